#!/bin/sh
# Blotches and streaks that RMSE forgives: the high-pass error of full
# against jade's reference (`jade metric`'s highpass_rmse: the difference's
# luminance less its mean over the 9x9 pixels around, where all 81 lie on
# the object), in the default scene (the knot, marble, back-lit, 384x384).
# The reference is committed, made once by
#   jade reference --size 384x384 --pixel-samples 3 \
#       --out assets/reference/default-marble-back.png \
#       --mask assets/reference/default-marble-back-mask.png
# (58 s on 2 cores). 3 x 3 rays a pixel, because full's picture is
# anti-aliased: against the reference's one ray a pixel, whose edges are
# stair steps, every contour inside the object (a tube in front of
# another) counted as high-pass error that no blotch made. The one-ray
# reference itself is 0.0035 from the 3 x 3 one; the 3 x 3 one with another
# sample placement (--seed 1) 0.00134, the reference's own noise
# (docs/quality.md, "Artifacts, measured").
# That reference has no light between parts, which full carries since
# 2026-12-03 (core/mesh_bounce.c): against it full's RMSE rose from 0.0238
# to 0.0304, and its high-pass from 0.00567 to 0.00580; against the same
# reference with one bounce (--bounces 1, 3 x 3, 86 s, not committed) full
# went from 0.0351 to 0.0258 and 0.00596 to 0.00584.
# The bounds hold today's figures with a tenth to spare. They are not the
# goal: the goal is within twice the reference's noise, 0.0027, which full
# misses by about 2.1 times (the streaks on the knot's top arc), and the
# test prints by how much.
jade=$1 src=$2
. "$(dirname "$0")/harness.sh"
ref=$src/assets/reference/default-marble-back.png mask=$src/assets/reference/default-marble-back-mask.png
[ -f "$ref" ] && [ -f "$mask" ] || { bad "the committed reference $ref or its mask is missing"; finish blotches; exit; }
metric() { "$jade" metric "$1" "$ref" --mask "$mask" > "$tmp/m.json" || return 1; }

# The committed picture must still be what jade's reference makes: one ray a
# pixel (8 s, not 58) differs from it by its stair-stepped edges alone,
# RMSE 0.0065 and high-pass 0.0035 today; a change to the reference's model
# of 0.004 RMSE or more takes it over the bound, and the picture is to be
# made again by the command above.
if "$jade" reference --size 384x384 --out "$tmp/ref1.png" > "$tmp/log" 2>&1 && metric "$tmp/ref1.png"; then
    within "jade reference today, one ray a pixel, against the committed picture: RMSE" "$(field rmse < "$tmp/m.json")" 0.0075
    within "the same, high-pass" "$(field highpass_rmse < "$tmp/m.json")" 0.0040
else
    bad "jade reference failed: $(tail -1 "$tmp/log")"
fi

# profile (the machine's own GL: none), today's RMSE, today's high-pass;
# the generic profile's figures are mali400's on llvmpipe. vc4 sums the
# levels per fragment at half resolution as mali400 does (gl_caps.h), at
# fp32: until 2026-12-06 it summed them per vertex, 0.03039 / 0.00580.
# Since 2026-12-07 full's local part is smoothed over the terminator, which
# the reference lacks and Cycles has (docs/quality.md, "The terminator"):
# the RMSE against the reference 0.03039 -> 0.03528 on the machine's GL
# (mali400 0.03017 -> 0.03494, vc4 0.03065 -> 0.03552), the high-pass
# 0.00580 -> 0.00561 (0.00608 -> 0.00597, 0.00606 -> 0.00597). The same
# day the reference's light moved along its refracted ray before it
# scatters (reference/ref_render.c; docs/quality.md, "The light's entry,
# moved along its ray"), and the committed picture was made again: full's
# RMSE against it 0.03528 -> 0.03435 (mali400 0.03494 -> 0.03389, vc4
# 0.03552 -> 0.03438), the high-pass 0.00561 -> 0.00556 (0.00597 ->
# 0.00595, 0.00597 -> 0.00595). Since full sums the light scattered once
# along the camera ray where it sums the levels per vertex (the machine's
# own GL here; mesh.vert, jd_single_march; 2026-12-08) that path's high-pass
# 0.00551 -> 0.00586 and its RMSE 0.0339 -> 0.0336 (docs/quality.md,
# "Single scattering in full"); the profiles, which sum them per fragment,
# the same.
while read -r profile rmse_today hp_today; do
    set -- --profile "$profile"
    name="$profile profile"
    [ "$profile" = none ] && set -- && name="the machine's own GL"
    if ! "$jade" render --size 384x384 "$@" --out "$tmp/full-$profile.png" > "$tmp/log" 2>&1 ||
        ! metric "$tmp/full-$profile.png"; then
        bad "full, $name: $(tail -1 "$tmp/log")"
        continue
    fi
    rmse=$(field rmse < "$tmp/m.json") hp=$(field highpass_rmse < "$tmp/m.json")
    within "full, $name: RMSE" "$rmse" "$(awk -v t="$rmse_today" 'BEGIN { printf "%.5f", 1.1 * t }')"
    within "full, $name: high-pass" "$hp" "$(awk -v t="$hp_today" 'BEGIN { printf "%.5f", 1.1 * t }')"
    echo "note full, $name: high-pass $hp is $(awk -v h="$hp" 'BEGIN { printf "%.1f", h / 0.0027 }') times the goal (0.0027, twice the reference's own noise)"
    [ "$profile" = none ] && full_hp=$hp
done <<'CASES'
none 0.03361 0.00586
mali400 0.03389 0.00595
vc4 0.03438 0.00595
CASES

# The measure must tell a blotchy picture: none (no diffusion of the light
# in the light's view) is 0.0108 today, almost twice full's.
if "$jade" render --size 384x384 --mode none --out "$tmp/none.png" > "$tmp/log" 2>&1 && metric "$tmp/none.png"; then
    closer "full's high-pass below none's" "${full_hp:-}" "$(field highpass_rmse < "$tmp/m.json")"
else
    bad "none: $(tail -1 "$tmp/log")"
fi
finish blotches
