#!/bin/sh
# The default camera frames the object: a standing figure (a box 10 times
# taller than wide), a lying one and the default asset, rendered at square,
# wide, tall and 90-degree-rotated outputs, never touch the picture's edge
# and span at least half of it (imgcmp --frame prints the margins);
# --distance and --fit override it; 1920x1080 and 3840x2160 render with no
# budget flag.
jade=$1 imgcmp=$2
. "$(dirname "$0")/harness.sh"
# box X Y Z: a closed box of that size, as OBJ.
box() {
    printf 'v 0 0 0\nv %s 0 0\nv %s %s 0\nv 0 %s 0\nv 0 0 %s\nv %s 0 %s\nv %s %s %s\nv 0 %s %s\n' \
        "$1" "$1" "$2" "$2" "$3" "$1" "$3" "$1" "$2" "$3" "$2" "$3"
    printf 'f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n'
}
box 0.2 2 0.2 > "$tmp/standing.obj"
box 2 0.2 0.3 > "$tmp/lying.obj"
for mesh in standing.obj lying.obj default; do
    m="--mesh $tmp/$mesh"
    [ "$mesh" = default ] && m=""
    for case in "512x512" "1280x320" "320x1024" "320x1024 --rotate 90" "512x512 --pitch 80" "512x512 --yaw 90"; do
        set -- $case
        size=$1
        shift
        out="$tmp/$mesh-$size-$#.png"
        # shellcheck disable=SC2086
        if ! "$jade" render $m --size "$size" --mode none "$@" --out "$out" > "$tmp/out" 2>&1; then
            bad "$mesh $case: $(cat "$tmp/out")"
            continue
        fi
        if line=$("$imgcmp" --frame "$out" 0.5); then ok "$mesh $case: ${line#*: }"; else bad "$mesh $case: ${line#*: }"; fi
    done
done
# Overrides: a near camera crops the standing box; --fit 0.5 halves its span.
"$jade" render --mesh "$tmp/standing.obj" --size 256x256 --mode none --distance 1.3 --out "$tmp/near.png" >/dev/null 2>&1
if line=$("$imgcmp" --frame "$tmp/near.png" 0.1); then bad "--distance 1.3 did not come closer: $line"
else ok "--distance 1.3 comes close enough to crop: ${line#*: }"; fi
"$jade" render --mesh "$tmp/standing.obj" --size 256x256 --mode none --fit 0.45 --out "$tmp/half.png" >/dev/null 2>&1
line=$("$imgcmp" --frame "$tmp/half.png" 0.3)
span=$(echo "$line" | sed -n 's/.*spans \([0-9.]*\).*/\1/p')
if awk "BEGIN { exit !($span > 0.3 && $span <= 0.46) }"; then ok "--fit 0.45: spans $span"; else bad "--fit 0.45: $line"; fi
# Large outputs need no flag: the budget and the targets follow the size.
for size in 1920x1080 3840x2160; do
    if "$jade" render --size "$size" --mode dual --out "$tmp/big.png" > "$tmp/out" 2>&1; then
        ok "$size renders without flags: $(sed -n 's/.*\(arena peak [0-9]* bytes, render targets [0-9]* bytes\).*/\1/p' "$tmp/out")"
    else bad "$size: $(cat "$tmp/out")"; fi
done
finish framing
