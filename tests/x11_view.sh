#!/bin/sh
# jade view in a real X server (Xvfb, started here) renders what headless
# renders; under the mali400 profile it renders the mediump / per-fragment
# path, as the render command's explicit flags do.
jade=$1 imgcmp=$2 out=$3
if ! command -v Xvfb >/dev/null; then
    echo "SKIP: Xvfb is missing: install xvfb (tools/setup.sh does, and says when it cannot)"; exit 77
fi
xvfb_first=90
. "$(dirname "$0")/xvfb.sh"
d=$DISPLAY_NUM
pass=0 fail=0
check() { if "$@"; then pass=$((pass + 1)); else fail=$((fail + 1)); fi; }
# The same picture both ways: edges without anti-aliasing (the window may
# have multisampling, the headless target has not).
args="--size 200x160 --cam-azimuth 30 --material skin1 --antialias off"
check env DISPLAY=":$d" "$jade" view --frames 60 --screenshot "$out/view.png" $args
# By default the window's edges are anti-aliased, one way or the other.
env DISPLAY=":$d" "$jade" view --frames 2 --size 200x160 > "$out/view_aa.txt" 2>&1
check grep -Eq "anti-aliasing: ([0-9]+x multisampling|a pass after the frame)" "$out/view_aa.txt"
grep anti-aliasing "$out/view_aa.txt"
# Drawn smaller and enlarged (the mali400 tier at 1280x720): multisampled
# in its own texture where the GPU can draw one so; otherwise the window's
# multisampling sees only the enlarging quad, and the pass after the frame
# smooths the picture at its own size first.
env DISPLAY=":$d" "$jade" view --frames 1 --size 1280x720 --profile mali400 --mode none > "$out/view_tier.txt" 2>&1
check grep -Eq "anti-aliasing: (a pass after the frame on the picture drawn at 960x540, on the edges its test marks, then enlarged \(the target's [0-9]+x multisampling sees only the enlarging[^)]*\)|4x multisampling in the picture drawn at 960x540|a pass after the frame \(the target has no multisampling)" "$out/view_tier.txt"
grep anti-aliasing "$out/view_tier.txt"
# The pass after the frame into the window, which marks its flat pixels in
# the window's own depth buffer first: the headless pass's picture.
env DISPLAY=":$d" "$jade" view --frames 3 --screenshot "$out/view_post.png" --size 200x160 --cam-azimuth 30 \
    --antialias post > "$out/view_post.txt" 2>&1
check grep -q "anti-aliasing: a pass after the frame (the target has no multisampling), on the edges its test marks" \
    "$out/view_post.txt"
check "$jade" render --out "$out/post_headless.png" --size 200x160 --cam-azimuth 30 --antialias post
check "$imgcmp" "$out/view_post.png" "$out/post_headless.png" --max-rmse 0.01 --max-bad-frac 0 --bad-threshold 2
check "$jade" render --out "$out/view_headless.png" $args
check "$imgcmp" "$out/view.png" "$out/view_headless.png" --max-rmse 1.0 --max-bad-frac 0.001 --bad-threshold 16
check env DISPLAY=":$d" "$jade" view --frames 5 --screenshot "$out/view_mali.png" --profile mali400 $args
check "$jade" render --out "$out/mali_path.png" --precision mediump --fragment-thickness $args
check "$imgcmp" "$out/view_mali.png" "$out/mali_path.png" --max-rmse 1.0 --max-bad-frac 0.001 --bad-threshold 16
env -u DISPLAY "$jade" view --frames 1 >/dev/null 2>"$out/nodisplay.err"
if [ $? -ne 0 ] && grep -q "DISPLAY is not set" "$out/nodisplay.err" && [ "$(wc -l < "$out/nodisplay.err")" -eq 1 ]; then
    pass=$((pass + 1)); echo "ok   no display: $(cat "$out/nodisplay.err")"
else
    fail=$((fail + 1)); echo "FAIL no display"; cat "$out/nodisplay.err"
fi
echo "x11: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
