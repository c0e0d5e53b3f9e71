#!/bin/sh
# --rotate N turns the picture N degrees counter-clockwise (DRM's rotation
# convention), done in the projection: compare with the unrotated frame
# turned on the CPU.
jade=$1 imgcmp=$2 out=$3
pass=0 fail=0
"$jade" render --size 128x128 --out "$out/rot0.png" >/dev/null || fail=$((fail + 1))
for r in 90 180 270; do
    "$jade" render --size 128x128 --rotate $r --out "$out/rot$r.png" >/dev/null &&
        "$imgcmp" "$out/rot$r.png" "$out/rot0.png" --rotate-b $((360 - r)) --max-rmse 1.0 --max-bad-frac 0.01 \
            && pass=$((pass + 1)) || fail=$((fail + 1))
done
echo "rotation: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
