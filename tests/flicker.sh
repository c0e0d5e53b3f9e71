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
jade=$1 measure=$2
. "$(dirname "$0")/harness.sh"
scene="--size 128x128 --specular 0 --light-elevation 35"
# Each of the three as one run, the light turning a degree a frame
# (--light-step, every frame written by its number): the same pictures as
# sixty runs of a frame each (tests/cli.sh holds that; the reference places
# its samples once, jd_ref_relight).
# shellcheck disable=SC2086
"$jade" reference $scene --light-azimuth 140 --light-step 1 --frames 60 --quiet --out "$tmp/ref%d.png" \
    --mask "$tmp/mask.png" >/dev/null || bad "jade reference did not run"
for m in none full; do
    # shellcheck disable=SC2086
    "$jade" render $scene --mode $m --antialias off --light-azimuth 140 --light-step 1 --frames 60 \
        --out "$tmp/$m%d.png" >/dev/null 2>&1 || bad "jade render --mode $m did not run"
done
measure_seq() {
    # shellcheck disable=SC2046
    "$measure" "$tmp/mask.png" $(i=0; while [ $i -lt 60 ]; do echo "$tmp/$1$i.png"; i=$((i + 1)); done)
}
m_ref=$(measure_seq ref) m_none=$(measure_seq none) m_full=$(measure_seq full)
ref=$(echo "$m_ref" | field jerk) none=$(echo "$m_none" | field jerk) full=$(echo "$m_full" | field jerk)
echo "jerk (RMS of the second difference between frames, linear luminance): reference $ref, none $none, full $full"
# What 8 bits alone leave on smooth ramps (no sequence goes much below it),
# and the share of the largest 1% of the second differences (a few edges
# stepping: near 1; pops spread over the surface: small).
echo "rounding to 8 bits alone: $(echo "$m_ref" | field rounding); largest 1% share: reference $(echo "$m_ref" | field top1), none $(echo "$m_none" | field top1), full $(echo "$m_full" | field top1)"
if awk -v r="$ref" -v n="$none" 'BEGIN { exit !(r != "" && r < n) }'; then ok "the reference is smoother than none ($ref < $none)"
else bad "the reference ($ref) is not smoother than none ($none): the measure sees nothing"; fi
# 0.0144 measured since full's soft shadow (light.glsl, jd_soft_lit; 0.0151
# with the 2x2 test before it), 0.0137 since its exponent is 0.25 a texel
# of depth, 0.0132 since half of the first level rides with the local
# part on lit points: the goal, the reference's, is missed (docs/quality.md); the
# bound keeps it from growing unseen. It stays where it was: an NVIDIA
# H100 under 4x multisampling measured 0.0155 where llvmpipe gave 0.0151.
if awk -v f="$full" 'BEGIN { exit !(f != "" && f <= 0.0158) }'; then ok "full's jerk $full <= 0.0158 (measured 0.0132)"
else bad "full's jerk $full, over 0.0158 (measured 0.0132; the reference $ref)"; fi
finish flicker
