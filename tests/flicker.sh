#!/bin/sh
# Flicker: the default asset, still, while the light orbits it by a degree a
# frame for 60 frames (azimuth 140 to 199, back-lit, no highlight, whose
# own motion is not the question), in full, none and the reference.
# tests/flicker_measure.c gives each sequence's `jerk`, the RMS of the
# second difference between frames: the light's motion changes shading
# smoothly and leaves little of it; a pixel that pops leaves it whole.
# The reference's jerk is what smooth looks like. The bound holds full's
# figure today (docs/quality.md: it flickers more than the reference) with
# a tenth to spare, so that it cannot grow unseen. Drawn without the
# anti-aliasing pass, as the boards with multisampling draw the object's
# inside (the pass, which only GPUs without multisampling run, took full's
# jerk from 0.0151 to 0.0137 on llvmpipe; an NVIDIA GPU under 4x
# multisampling gave 0.0155).
#
# The reference's 60 frames took 208 s of CPU a run (nearly all of this
# test), to give the same figure every time: they are made once, by
# `tests/flicker.sh --update JADE MEASURE tests/golden` (tools/update-goldens.sh
# runs it), which keeps the reference's measure (flicker_ref.json), its
# object mask and its first three frames with their own measure
# (flicker_ref3.json). Each run makes those three frames again (one run of
# jade reference, the samples placed once, the second and third relit:
# jd_ref_relight, which made the rest too) and holds them to the kept
# ones, and measures the kept three again: a change to the reference, to
# this orbit or to tests/flicker_measure.c fails here until they are made
# again, and the figure with them.
# Usage: flicker.sh JADE MEASURE GOLDEN_DIR IMGCMP (tests/CMakeLists.txt),
#        flicker.sh --update JADE MEASURE GOLDEN_DIR
update=0
if [ "${1:-}" = --update ]; then update=1; shift; fi
jade=$1 measure=$2 golden=$3 imgcmp=${4:-}
. "$(dirname "$0")/harness.sh"
scene="--size 128x128 --specular 0 --light-elevation 35 --light-azimuth 140 --light-step 1"
measure_seq() { # NAME N MASK: the N frames $tmp/NAME0.png...
    # shellcheck disable=SC2046
    "$measure" "$3" $(i=0; while [ $i -lt "$2" ]; do echo "$tmp/$1$i.png"; i=$((i + 1)); done)
}
if [ $update = 1 ]; then
    # shellcheck disable=SC2086
    "$jade" reference $scene --frames 60 --quiet --out "$tmp/ref%d.png" --mask "$tmp/mask.png" >/dev/null ||
        { echo "flicker --update: jade reference did not run"; exit 1; }
    measure_seq ref 60 "$tmp/mask.png" > "$golden/flicker_ref.json" || exit 1
    for i in 0 1 2; do cp "$tmp/ref$i.png" "$golden/flicker_ref$i.png"; done
    cp "$tmp/mask.png" "$golden/flicker_mask.png"
    measure_seq ref 3 "$tmp/mask.png" > "$golden/flicker_ref3.json" || exit 1
    echo "flicker --update: $(cat "$golden/flicker_ref.json")"
    exit 0
fi
# shellcheck disable=SC2086
"$jade" reference $scene --frames 3 --quiet --out "$tmp/now%d.png" --mask "$tmp/now_mask.png" >/dev/null ||
    bad "jade reference did not run"
# Within a level of 255 anywhere (another compiler's rounding), not bit
# for bit.
for f in 0 1 2 mask; do
    case $f in mask) now=now_mask kept=flicker_mask ;; *) now=now$f kept=flicker_ref$f ;; esac
    if "$imgcmp" "$tmp/$now.png" "$golden/$kept.png" --max-rmse 0.5 --max-bad-frac 0 --bad-threshold 1 \
        >"$tmp/cmp.txt" 2>&1; then
        ok "$kept.png is what jade reference makes today"
    else
        bad "$kept.png is not what jade reference makes today ($(tail -1 "$tmp/cmp.txt")): tools/update-goldens.sh makes the kept frames again"
    fi
done
for i in 0 1 2; do cp "$golden/flicker_ref$i.png" "$tmp/kept$i.png"; done
kept=$(measure_seq kept 3 "$golden/flicker_mask.png")
if [ "$kept" = "$(cat "$golden/flicker_ref3.json")" ]; then ok "the kept frames measure as when they were made"
else bad "the kept three frames measure $kept, not $(cat "$golden/flicker_ref3.json"): tests/flicker_measure.c changed? tools/update-goldens.sh"; fi
# Each of the two as one run, the light turning a degree a frame
# (--light-step, every frame written by its number): the same pictures as
# sixty runs of a frame each (tests/cli.sh holds that; so does the
# reference's, jd_ref_relight).
for m in none full; do
    # shellcheck disable=SC2086
    "$jade" render $scene --mode $m --antialias off --frames 60 --out "$tmp/$m%d.png" >/dev/null 2>&1 ||
        bad "jade render --mode $m did not run"
done
m_ref=$(cat "$golden/flicker_ref.json") m_none=$(measure_seq none 60 "$golden/flicker_mask.png")
m_full=$(measure_seq full 60 "$golden/flicker_mask.png")
ref=$(echo "$m_ref" | field jerk) none=$(echo "$m_none" | field jerk) full=$(echo "$m_full" | field jerk)
echo "jerk (RMS of the second difference between frames, linear luminance): reference $ref (its kept frames), none $none, full $full"
# What 8 bits alone leave on smooth ramps (no sequence goes much below it),
# and the share of the largest 1% of the second differences (a few edges
# stepping: near 1; pops spread over the surface: small).
echo "rounding to 8 bits alone: $(echo "$m_ref" | field rounding); largest 1% share: reference $(echo "$m_ref" | field top1), none $(echo "$m_none" | field top1), full $(echo "$m_full" | field top1)"
if awk -v r="$ref" -v n="$none" 'BEGIN { exit !(r != "" && r < n) }'; then ok "the reference is smoother than none ($ref < $none)"
else bad "the reference ($ref) is not smoother than none ($none): the measure sees nothing"; fi
# 0.0144 measured since full's soft shadow (light.glsl, jd_soft_lit; 0.0151
# with the 2x2 test before it), 0.0137 since its exponent is 0.25 a texel
# of depth, 0.0132 since half of the first level rides with the local
# part on lit points, 0.0128 since the levels count light within 3 sigma
# of a texel's own depth as its surface's (pass_light.c), 0.0133 since the
# light through thin parts' changes of 2026-12-07, 0.0141 since full sums
# the light scattered once along the camera ray (mesh.vert,
# jd_single_march; docs/quality.md, "Single scattering in full"): the goal, the
# reference's, is missed (docs/quality.md); the bound keeps it from growing
# unseen. It stays where it was: an NVIDIA
# H100 under 4x multisampling measured 0.0155 where llvmpipe gave 0.0151.
if awk -v f="$full" 'BEGIN { exit !(f != "" && f <= 0.0158) }'; then ok "full's jerk $full <= 0.0158 (measured 0.0141)"
else bad "full's jerk $full, over 0.0158 (measured 0.0141; the reference $ref)"; fi
finish flicker
