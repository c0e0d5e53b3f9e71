#!/bin/sh
# The calls that stall a tile-based GPU, counted from outside the process
# (tests/gl_count.c preloaded): no glReadPixels and no glFinish at all in
# the frames of any mode, the light moving or still, on the generic device
# and under the vc4, mali400, vivante and adreno3xx profiles (single and dual keep their SH
# coefficients on the GPU as an irradiance map). `kiosk` itself never
# finishes. Start-up makes none on llvmpipe, and exactly two with
# --program-probe on (the check that every program draws, which GPUs get:
# core/program_probe.c).
jade=$1 counter=$2
. "$(dirname "$0")/harness.sh"
preload_or_skip "$jade"
count() { # MODE PROFILE LIGHT_SPEED [OPTIONS] -> "readpixels finishes" in frames; $tmp/out keeps start-up's
    c_mode=$1 c_prof=$2 c_speed=$3
    shift 3
    JD_GL_COUNT_OUT=$tmp/out LD_PRELOAD=$counter "$jade" kiosk --platform headless --size 64x64 --frames 20 \
        --mode "$c_mode" ${c_prof:+--profile "$c_prof"} --light-speed "$c_speed" "$@" >/dev/null 2>"$tmp/err" ||
        { cat "$tmp/err"; echo "x x"; return; }
    echo "$(sed -n 's/^glReadPixels //p' "$tmp/out") $(sed -n 's/^glFinish //p' "$tmp/out")"
}
check() { # NAME GOT WANT
    if [ "$2" = "$3" ]; then pass=$((pass + 1)); echo "ok   $1: read-backs, glFinish = $2"
    else fail=$((fail + 1)); echo "FAIL $1: read-backs, glFinish = $2 (want $3)"; fi
}
for prof in "" vc4 mali400 vivante adreno3xx; do
    p=${prof:-generic}
    # The probe named: by default GPUs get it (two read-backs at start-up,
    # as below) and llvmpipe does not.
    check "none, $p, 20 frames" "$(count none "$prof" 30 --program-probe off)" "0 0"
    check "start-up, $p" "$(sed -n 's/^start-up glReadPixels //p' "$tmp/out") $(sed -n 's/^start-up glFinish //p' "$tmp/out")" "0 0"
    check "dual, $p, 20 frames, --program-probe on" "$(count dual "$prof" 30 --program-probe on)" "0 0"
    check "start-up, $p, --program-probe on" "$(sed -n 's/^start-up glReadPixels //p' "$tmp/out") $(sed -n 's/^start-up glFinish //p' "$tmp/out")" "2 0"
    check "full, $p, 20 frames" "$(count full "$prof" 30)" "0 0"
    check "single, $p, 20 frames, light moving" "$(count single "$prof" 30)" "0 0"
    check "dual, $p, 20 frames, light moving" "$(count dual "$prof" 30)" "0 0"
    check "dual, $p, 20 frames, light still" "$(count dual "$prof" 0)" "0 0"
    check "single, $p, 20 frames, light still" "$(count single "$prof" 0)" "0 0"
done
echo "frame_stalls: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
