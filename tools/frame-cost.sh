#!/bin/sh
# The frame-cost model's table: jade's defaults (full mode, marble, the
# default asset) on every board of `jade info --boards`, for the default
# scene and a close-up (--distance 1.6), at 1280x720 and 1920x1080, and at
# 960x540: the frame of a board whose tier draws 1080p at that size when
# the display engine enlarges it (the kiosk with atomic modesetting, its
# default, where the plane's scaler takes it), with no GL pass at 1080p.
#
#   tools/frame-cost.sh [JADE] [--check EXPECTED | --update EXPECTED]
#
# Each row: board, scene, size, the estimated frame (ms) and its vertex and
# pixel parts, the shading pass's size (smaller where the board's tier
# draws smaller), fragments and cost per fragment in the compiler's unit,
# and the fragments of the passes at the picture's resolution ("main..."). With --check, a
# frame more than 10% slower than the committed table (or a row that is
# gone) fails; a faster one is said, so the table can be brought down with
# --update. Estimates, not measurements: docs/performance.md says what the
# model leaves out.
set -eu
cd "$(dirname "$0")/.."
jade=./build/jade
case "${1:-}" in ""|--*) ;; *) jade=$1; shift ;; esac
mode=print expected=""
case "${1:-}" in
    --check) mode=check expected=$2 ;;
    --update) mode=update expected=$2 ;;
    "") ;;
    *) echo "usage: $0 [JADE] [--check|--update tests/frame-cost.expected]"; exit 2 ;;
esac
[ -x "$jade" ] || { echo "frame-cost: $jade is not built"; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
boards=$("$jade" info --boards | awk 'NR > 1 && /^[a-z0-9]/ {print $1}')
table=$tmp/table
for b in $boards; do
    for scene in default closeup; do
        extra=""
        [ "$scene" = closeup ] && extra="--distance 1.6"
        for size in 960x540 1280x720 1920x1080; do
            # shellcheck disable=SC2086
            if ! "$jade" bench --device "$b" --size "$size" --frames 1 --mode full $extra >"$tmp/json" 2>"$tmp/err"; then
                echo "frame-cost: jade bench --device $b --size $size $extra failed: $(head -c 300 "$tmp/err")" >&2
                echo "frame-cost: 0 passed, 1 failed" >&2
                exit 1
            fi
            # The shading pass ("main", or "shade-scaled" where the tier
            # draws smaller) and the passes at the picture's resolution.
            tr ',' '\n' < "$tmp/json" | awk -v b="$b" -v sc="$scene" -v sz="$size" '
                function val() { split($0, a, ": "); gsub(/"/, "", a[2]); return a[2] }
                /"estimate"/ { est = 1 }
                !est { next }
                /"frame_ms"/ { frame = val() }
                /"vertex_ms"/ { vert = val() }
                /"fragment_ms"/ { frag = val() }
                /"pass": / { name = val(); sub(/^ *\{/, "", name) }
                /"size": / { size = val() }
                /"fragments": / { f = val(); if (name ~ /^main/) full += f; if (name == "main" || name == "shade-scaled") { sf = f; ss = size } }
                /"fs_cost": / { if (name == "main" || name == "shade-scaled") cost = val() }
                END { printf "%-12s %-8s %-10s frame_ms %8.2f vertex_ms %7.2f pixel_ms %8.2f shade %-9s fragments %7d cost %6.1f full_res_fragments %8d\n",
                             b, sc, sz, frame, vert, frag, ss, sf, cost, full }'
        done
    done
done > "$table"
echo "frame-cost: jade's defaults by the model (estimates; docs/performance.md):"
cat "$table"
case $mode in
    update) cp "$table" "$expected"; echo "frame-cost: wrote $expected" ;;
    check)
        awk '
            NR == FNR { want[$1 " " $2 " " $3] = $5; next }
            {
                key = $1 " " $2 " " $3; seen[key] = 1
                if (!(key in want)) { print "frame-cost: " key ": new row (update the table)"; next }
                if ($5 > want[key] * 1.1) { print "FAIL " key ": " want[key] " -> " $5 " ms (over 10% slower)"; bad++ }
                else { if ($5 < want[key] * 0.9) print "ok   " key ": " want[key] " -> " $5 " ms (faster: update the table)"
                       else print "ok   " key ": " $5 " ms (table " want[key] ")"; good++ }
            }
            END {
                for (k in want) if (!(k in seen)) { print "FAIL " k ": no longer estimated"; bad++ }
                printf "frame-cost: %d passed, %d failed\n", good, bad
                exit bad > 0
            }
        ' "$expected" "$table"
        ;;
esac
