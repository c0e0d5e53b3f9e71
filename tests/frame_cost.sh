#!/bin/sh
# The frame-cost model (jade bench --device): its committed table for jade's
# defaults on every board (tools/frame-cost.sh --check: 10% slower fails),
# and its counts held to what can be seen: the main pass shades at least
# the object's pixels of the same frame and not much more (overdraw), the
# passes of quads exactly their targets' areas.
#   frame_cost.sh JADE IMGCMP SOURCE_DIR [table|no-table]
# no-table (the sanitizer build) leaves the table to the release build.
jade=$1 imgcmp=$2 src=$3 table=${4:-table}
. "$(dirname "$0")/harness.sh"

if [ "$table" = no-table ]; then
    echo "the boards' table: left to the release build"
elif sh "$src/tools/frame-cost.sh" "$jade" --check "$src/tests/frame-cost.expected" >"$tmp/table" 2>&1; then
    ok "the boards' table within 10% of tests/frame-cost.expected ($(grep -c '^ok' "$tmp/table") rows)"
    cat "$tmp/table"
else
    bad "the boards' table (tools/frame-cost.sh --check)"
    cat "$tmp/table"
fi

# The same frame as a picture and as a count (anti-aliasing off, as on the boards).
"$jade" render --profile mali400 --size 320x240 --antialias off --mode full --out "$tmp/frame.png" >/dev/null 2>&1 &&
    "$jade" bench --device mali400-mp2 --size 320x240 --frames 1 --mode full >"$tmp/bench.json" 2>"$tmp/err" ||
    bad "render and bench --device mali400-mp2: $(head -c 300 "$tmp/err")"
covered=$("$imgcmp" --count "$tmp/frame.png")
tr '{' '\n' < "$tmp/bench.json" | grep '"pass"' > "$tmp/passes"
main=$(grep '"pass": "main"' "$tmp/passes" | sed 's/.*"fragments": \([0-9]*\).*/\1/')
if [ -n "$main" ] && [ -n "$covered" ] && [ "$main" -ge $((covered * 95 / 100)) ] && [ "$main" -le $((covered * 3 / 2)) ]; then
    ok "main pass: $main fragments shaded for $covered object pixels in the picture"
else
    bad "main pass: ${main:-no} fragments counted for ${covered:-?} object pixels"
fi
quads=$(grep -E '"pass": "(diffusion|sh-|irradiance|spread-a[12])' "$tmp/passes" |
        sed 's/.*"size": "\([0-9]*\)x\([0-9]*\)", "fragments": \([0-9]*\).*/\1 \2 \3/' |
        awk '{ n++; if ($1 * $2 != $3) bad++ } END { print n + 0, bad + 0 }')
set -- $quads
if [ "$1" -gt 0 ] && [ "$2" -eq 0 ]; then ok "$1 quad passes: fragments = target area"; else bad "quad passes: $2 of $1 off their area"; fi
if grep -q '"estimate": {"board": "mali400-mp2", "frame_ms": [0-9]' "$tmp/bench.json" &&
   grep -q '"device": "mali400-mp2"' "$tmp/bench.json"; then
    ok "bench --device prints the board and an estimate"
else
    bad "bench --device JSON"
fi
"$jade" bench --device no-such-board --frames 1 >/dev/null 2>"$tmp/err"
rc=$?
if [ "$rc" -eq 2 ] && grep -q "unknown board 'no-such-board' (have: mali400-mp2" "$tmp/err"; then
    ok "an unknown board: exit 2, the boards named"
else
    bad "an unknown board: exit $rc: $(cat "$tmp/err")"
fi
"$jade" bench --device vc4 --profile mali400 --frames 1 >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "draws with profile vc4" "$tmp/err" && ok "--device and a contrary --profile refused" ||
    bad "--device with a contrary --profile: $(cat "$tmp/err")"
finish frame_cost
