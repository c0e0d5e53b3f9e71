#!/bin/sh
# Light through thin parts in full (docs/quality.md, "Kept: the light
# through thin parts in full"), where the levels are summed per fragment
# (the mali400 and vivante profiles): faces turned from the light take what
# a slab as thick as the part lets through (the multipole's T(d), the same
# as jade reference carries across its thin parts), less what full's levels
# already bring. The default asset back-lit in ketchup, whose lobes glow
# red from behind: full against jade's reference. Measured 0.0143 with it,
# 0.0161 without (0.0135 and 0.0158 before the reference took the
# half-space's exit laws, 2026-11-28; 0.0134 and 0.0133 since 2026-12-07):
# the bound lies between, nearer today's.
# Where the levels are summed per vertex (this GPU) full takes the light
# scattered once along the camera ray instead (mesh.vert, jd_single_march;
# docs/quality.md, "Single scattering in full"), and is held to the
# reference that traces it (--single-scatter, which needs eta 1): measured
# 0.0224, where the slab's term had 0.0340 (against the reference that
# carries the light across instead, at eta 1.3, 0.0172 and 0.0143: that
# reference has no single scattering, and Cycles sides with the march).
jade=$1
. "$(dirname "$0")/harness.sh"
scene="--size 128x128 --material ketchup"
# shellcheck disable=SC2086
"$jade" reference $scene --quiet --out "$tmp/ref.png" --mask "$tmp/mask.png" >/dev/null || bad "jade reference did not run"
for p in mali400 vivante; do
    # shellcheck disable=SC2086
    "$jade" render $scene --profile $p --out "$tmp/$p.png" >/dev/null 2>&1 || bad "jade render ($p) did not run"
    r=$("$jade" metric "$tmp/$p.png" "$tmp/ref.png" --mask "$tmp/mask.png" | sed -n 's/.*"rmse": \([0-9.]*\).*/\1/p')
    if awk -v r="$r" 'BEGIN { exit !(r != "" && r <= 0.0149) }'; then ok "$p: full's RMSE against the reference $r <= 0.0149 (0.0161 without the light through thin parts)"
    else bad "$p: full's RMSE against the reference $r, over 0.0149 (measured 0.0134; 0.0161 without the light through thin parts)"; fi
done
# shellcheck disable=SC2086
"$jade" reference $scene --eta 1 --single-scatter --quiet --out "$tmp/ref1.png" --mask "$tmp/mask1.png" >/dev/null ||
    bad "jade reference --single-scatter did not run"
# shellcheck disable=SC2086
"$jade" render $scene --eta 1 --out "$tmp/device1.png" >/dev/null 2>&1 || bad "jade render (eta 1) did not run"
r=$("$jade" metric "$tmp/device1.png" "$tmp/ref1.png" --mask "$tmp/mask1.png" | sed -n 's/.*"rmse": \([0-9.]*\).*/\1/p')
if awk -v r="$r" 'BEGIN { exit !(r != "" && r <= 0.0245) }'; then ok "device: full's RMSE against the reference with single scattering $r <= 0.0245 (0.0340 with the slab's light)"
else bad "device: full's RMSE against the reference with single scattering $r, over 0.0245 (measured 0.0224; 0.0340 with the slab's light)"; fi
# A mesh past 2^17 triangles, where jade takes each vertex's thickness from
# the light map's proxy round it instead of a ray a vertex (renderer.c):
# tests/wall.awk's wall and floor gridded at 0.5 mm (283,840 triangles)
# against the same gridded at 2 mm (17,740, a ray a vertex), full and the
# mali400 profile. Measured 0.029 and 0.031; 0.119 and 0.115 when such a
# mesh counted as thick everywhere (the 2 mm floor as bright as a
# half-space, 0.58 where the reference has 0.48).
awk -v dense=1 -f "$(dirname "$0")/wall.awk" > "$tmp/wall2.obj"
awk -v dense=1 -v step=0.5 -f "$(dirname "$0")/wall.awk" > "$tmp/wall05.obj"
wall="--mm-per-unit 1 --pitch 89 --yaw 0 --light-azimuth -60 --light-elevation 45 --size 128x128 --decode-timeout-ms 60000"
for p in device mali400; do
    for w in wall2 wall05; do
        # shellcheck disable=SC2086,SC2046
        "$jade" render --mesh "$tmp/$w.obj" $wall $([ $p = device ] || echo --profile $p) --out "$tmp/$p-$w.png" >/dev/null 2>&1 ||
            bad "jade render $w ($p) did not run"
    done
    r=$("$jade" metric "$tmp/$p-wall05.png" "$tmp/$p-wall2.png" | sed -n 's/.*"rmse": \([0-9.]*\).*/\1/p')
    if awk -v r="$r" 'BEGIN { exit !(r != "" && r <= 0.06) }'; then ok "$p: the 283,840-triangle wall within $r <= 0.06 of the 17,740-triangle one (0.119 when it counted as thick)"
    else bad "$p: the 283,840-triangle wall $r from the 17,740-triangle one, over 0.06 (measured 0.029; 0.119 when it counted as thick everywhere)"; fi
done
finish thin_parts
