#!/bin/sh
# jade held to ground truth it did not write: jade's own asset (the knot,
# tools/gen_asset.c) path-traced by Blender's Cycles in the quality table's
# eight cases (marble, skin1, ketchup, whole milk; front-lit: light azimuth
# -30, elevation 40; back-lit: the default 170, 35), committed as
# assets/cycles/default-MATERIAL-front.png and -back.png (128x128, 4096
# samples, 1024 bounces: their noise is about 0.01 RMSE, docs/quality.md),
# each made by
#   tools/gen_asset.c > knot.obj (the asset before Draco's quantization)
#   tools/cycles-reference.sh --mesh knot.obj --size 128x128 --material MATERIAL \
#       --eta 1 --ambient 0 [--light-azimuth -30 --light-elevation 40] \
#       --samples 4096 --seed 11 --out default-MATERIAL-LIGHT
# and the same medium behind Cycles' random-walk boundary (diffuse entry and
# exit), assets/cycles/walk-MATERIAL-LIGHT.png, by the same command with
# --boundary walk --out walk-MATERIAL-LIGHT (noise about 0.004).
# The boundary is index-matched (Cycles converges on nothing else under a
# directional light), so jade runs with --eta 1 --ambient 0 --specular 0.
# The bounds hold today's figures (RMSE in linear light over jade's mask)
# with a tenth to spare: a change that takes jade's reference or full
# further from the path tracer fails here, with the figure printed.
# Back-lit, both are closer than none to either picture. Front-lit, both
# are closer than none to the medium (the reference since light crosses thin
# parts, reference/ref_slab.h; full since its Fresnel factor is the true
# transmittance's, jd_fresnel_fit, not Schlick's, which at eta 1 darkened
# the rim: full's RMSE 13-24% lower, 0.0734 -> 0.0560 for marble), neither
# to the walk in most cases, which the test prints and does not hide (the
# walk's diffuse boundary darkens the rim as Schlick's form did: full front-
# lit moved away from it, 0.0556 -> 0.0661 for skin1).
jade=$1 src=$2
. "$(dirname "$0")/harness.sh"
rmse() { "$jade" metric "$1" "$2" --mask "$tmp/mask.png" | sed -n 's/.*"rmse": \([0-9.e-]*\).*/\1/p'; }
gain() { "$jade" metric "$1" "$2" --mask "$tmp/mask.png" | sed -n 's/.*"best_scale": \([0-9.e-]*\).*/\1/p'; }
# jade's albedo is the transport equation's (the half-space's exact albedo,
# jade_albedo_ratio; in the reference the light's beam by its angle), not the
# dipole's Rd_total: the last columns hold what the dipole's reference
# measured, and in geometric mean over the sixteen comparisons today's must
# stay under 0.9 of it; for the absorbing materials (skin1, ketchup) closer
# to the walk in every case.
logsum=0 thinsum=0
# material light azimuth elevation, then today's RMSE of the reference and
# full against the matched medium, then against the random walk, then the
# dipole-albedo reference's against each (before the exact albedo), then the
# half-space reference's against the medium (before light crossed thin
# parts, reference/ref_slab.h), then the reference with one bounce of the
# light between the knot's parts (--bounces 1) against the medium and the
# walk: closer to both in all sixteen than without, which is held. Those
# take 20,000 samples (0.6 mm apart; 4 s a case, not 13-17 s at the default
# 81,652, whose figures docs/quality.md gives: within 0.0010 of these).
# Last, the reference's against the medium when its light left every point
# as from a Lambertian surface (Schlick's transmittance, normalised, at
# entry and exit), before it took the half-space's exit laws
# (jd_halfspace_exit): in geometric mean today's must stay under 0.85 of it
# (measured 0.80). Against the walk, whose boundary is diffuse, skin1 and
# ketchup front-lit moved away (0.0513 -> 0.0703, 0.0587 -> 0.0656).
# Then the reference with a bounce and single scattering traced along each
# camera ray in place of the light carried across thin parts
# (--single-scatter, reference/ref_single.h): held within a tenth, closer to
# the medium than the bounced reference without it in every back-lit case,
# and in geometric mean over the eight under 0.8 of it (measured 0.74).
# Front-lit marble and whole milk come out 4% and 7% further (the light the
# slab carried away from the lit side now stays there): printed.
bouncesum=0 exitsum=0 ratiosum=0 singlesum=0
while read -r mat light az el ref_today full_today wref_today wfull_today dref dwref href bref_today bwref_today lref sref_today; do
    truth=$src/assets/cycles/default-$mat-$light.png walk=$src/assets/cycles/walk-$mat-$light.png
    scene="--mesh $src/assets/default.drc --size 128x128 --material $mat --eta 1 --ambient 0 --specular 0"
    scene="$scene --light-azimuth $az --light-elevation $el"
    # shellcheck disable=SC2086
    "$jade" reference $scene --pixel-samples 3 --quiet --out "$tmp/reference.png" --mask "$tmp/mask.png" >/dev/null ||
        { bad "jade reference did not run ($mat, $light)"; continue; }
    # none and full at 3 x 3 samples a pixel, as the reference's rays and
    # Cycles' box filter average it (jade render --pixel-samples): drawn
    # with one sample and the pass after the frame, the knot's outlines (a
    # quarter of its pixels at 128x128) took full 21% further from Cycles
    # in geometric mean and none 6% (full over none 0.662, not 0.583).
    for m in none full; do
        # shellcheck disable=SC2086
        "$jade" render $scene --mode $m --pixel-samples 3 --out "$tmp/$m.png" >/dev/null 2>&1 || bad "jade render --mode $m did not run"
    done
    ref=$(rmse "$tmp/reference.png" "$truth") none=$(rmse "$tmp/none.png" "$truth") full=$(rmse "$tmp/full.png" "$truth")
    echo "$mat, $light-lit: RMSE against Cycles: jade reference $ref (best gain $(gain "$tmp/reference.png" "$truth")), none $none, full $full"
    within "$mat $light: jade reference (measured $ref_today)" "$ref" "$(awk -v v="$ref_today" 'BEGIN { printf "%.4f", 1.1 * v }')"
    within "$mat $light: full (measured $full_today)" "$full" "$(awk -v v="$full_today" 'BEGIN { printf "%.4f", 1.1 * v }')"
    wref=$(rmse "$tmp/reference.png" "$walk") wnone=$(rmse "$tmp/none.png" "$walk") wfull=$(rmse "$tmp/full.png" "$walk")
    echo "$mat, $light-lit: RMSE against the random walk: jade reference $wref (best gain $(gain "$tmp/reference.png" "$walk")), none $wnone, full $wfull"
    within "$mat $light: jade reference against the walk (measured $wref_today)" "$wref" "$(awk -v v="$wref_today" 'BEGIN { printf "%.4f", 1.1 * v }')"
    within "$mat $light: full against the walk (measured $wfull_today)" "$wfull" "$(awk -v v="$wfull_today" 'BEGIN { printf "%.4f", 1.1 * v }')"
    logsum=$(awk -v s="$logsum" -v a="$ref" -v b="$dref" -v c="$wref" -v d="$dwref" 'BEGIN { print s + log(a / b) + log(c / d) }')
    thinsum=$(awk -v s="$thinsum" -v a="$ref" -v b="$href" 'BEGIN { print s + log(a / b) }')
    exitsum=$(awk -v s="$exitsum" -v a="$ref" -v b="$lref" 'BEGIN { print s + log(a / b) }')
    ratiosum=$(awk -v s="$ratiosum" -v a="$full" -v b="$none" 'BEGIN { print s + log(a / b) }')
    # shellcheck disable=SC2086
    if "$jade" reference $scene --bounces 1 --samples 20000 --pixel-samples 3 --quiet --out "$tmp/bounced.png" >/dev/null; then
        bref=$(rmse "$tmp/bounced.png" "$truth") bwref=$(rmse "$tmp/bounced.png" "$walk")
        echo "$mat, $light-lit: jade reference with light between parts: RMSE $bref against Cycles (best gain $(gain "$tmp/bounced.png" "$truth")), $bwref against the walk"
        within "$mat $light: the reference with a bounce (measured $bref_today)" "$bref" "$(awk -v v="$bref_today" 'BEGIN { printf "%.4f", 1.1 * v }')"
        within "$mat $light: the reference with a bounce, against the walk (measured $bwref_today)" "$bwref" "$(awk -v v="$bwref_today" 'BEGIN { printf "%.4f", 1.1 * v }')"
        closer "$mat $light: a bounce brings the reference closer to the medium" "$bref" "$ref"
        closer "$mat $light: a bounce brings the reference closer to the walk" "$bwref" "$wref"
        # full carries the light between parts too (core/mesh_bounce.c),
        # and where it sums the levels per vertex, as here, the light
        # scattered once (mesh.vert, jd_single_march): the reference that
        # has both is the one to be closer than full (below). The one with
        # the bounce alone was, until full took the light scattered once:
        # printed.
        if awk -v a="$bref" -v b="$full" 'BEGIN { exit !(a < b) }'; then echo "$mat $light: the reference with light between parts closer than full"
        else echo "$mat $light: full closer than the reference with light between parts (it lacks single scattering)"; fi
        # Without the bounce the reference is closer than full in the
        # absorbing materials (skin1, ketchup), not in marble or whole milk,
        # whose light between parts full has and it lacks: printed, not
        # held. (With full drawn at one sample a pixel, its outlines took it
        # further, and the reference without the bounce was closer in all
        # eight since its entry moved along the refracted ray, 2026-12-07.)
        # Against the walk, whose entry is diffuse (no ray to move along),
        # that move took the reference further in five of the eight and the
        # bounced one in seven: its bounds there are today's.
        if awk -v a="$ref" -v b="$full" 'BEGIN { exit !(a < b) }'; then echo "$mat $light: the reference without light between parts closer than full"
        else echo "$mat $light: full closer than the reference without light between parts"; fi
        bouncesum=$(awk -v s="$bouncesum" -v a="$bref" -v b="$ref" -v c="$bwref" -v d="$wref" 'BEGIN { print s + log(a / b) + log(c / d) }')
        # shellcheck disable=SC2086
        if "$jade" reference $scene --bounces 1 --single-scatter --samples 20000 --pixel-samples 3 --quiet --out "$tmp/single.png" >/dev/null; then
            sref=$(rmse "$tmp/single.png" "$truth") swref=$(rmse "$tmp/single.png" "$walk")
            echo "$mat, $light-lit: jade reference with light between parts and single scattering: RMSE $sref against Cycles (best gain $(gain "$tmp/single.png" "$truth")), $swref against the walk"
            within "$mat $light: the reference with single scattering (measured $sref_today)" "$sref" "$(awk -v v="$sref_today" 'BEGIN { printf "%.4f", 1.1 * v }')"
            [ "$light" = back ] && closer "$mat back: single scattering brings the reference closer to the medium" "$sref" "$bref"
            closer "$mat $light: jade reference with light between parts and single scattering closer than full to the medium" "$sref" "$full"
            singlesum=$(awk -v s="$singlesum" -v a="$sref" -v b="$bref" 'BEGIN { print s + log(a / b) }')
        else bad "jade reference --single-scatter did not run ($mat, $light)"; fi
    else bad "jade reference --bounces 1 did not run ($mat, $light)"; fi
    case $mat in skin1 | ketchup) closer "$mat $light: the exact albedo brings the reference closer to the walk than the dipole's" "$wref" "$dwref" ;; esac
    # Since light crosses thin parts the reference is closer than none to
    # the medium front-lit as well (before: not for milk).
    if [ "$light" = front ]; then
        closer "$mat front: jade reference closer than none" "$ref" "$none"
        closer "$mat front: full closer than none" "$full" "$none"
    fi
    if [ "$light" = back ]; then
        closer "$mat back: jade reference closer than none" "$ref" "$none"
        closer "$mat back: full closer than none" "$full" "$none"
        closer "$mat back: jade reference closer than none to the walk" "$wref" "$wnone"
        closer "$mat back: full closer than none to the walk" "$wfull" "$wnone"
    fi
done <<'CASES'
marble front -30 40 0.0341 0.0296 0.0507 0.0330 0.0673 0.0493 0.0679 0.0221 0.0428 0.0663 0.0230
marble back 170 35 0.0474 0.0391 0.0408 0.0257 0.0721 0.0561 0.0678 0.0281 0.0238 0.0669 0.0210
skin1 front -30 40 0.0220 0.0312 0.0747 0.0471 0.0529 0.0838 0.0396 0.0180 0.0727 0.0403 0.0123
skin1 back 170 35 0.0331 0.0330 0.0243 0.0227 0.0711 0.0494 0.0528 0.0288 0.0215 0.0504 0.0195
ketchup front -30 40 0.0142 0.0163 0.0622 0.0629 0.0324 0.0811 0.0171 0.0129 0.0608 0.0160 0.0077
ketchup back 170 35 0.0248 0.0200 0.0302 0.0281 0.0443 0.0508 0.0329 0.0240 0.0289 0.0277 0.0120
wholemilk front -30 40 0.0338 0.0287 0.0453 0.0285 0.0672 0.0499 0.0677 0.0218 0.0375 0.0653 0.0234
wholemilk back 170 35 0.0466 0.0370 0.0407 0.0244 0.0689 0.0545 0.0652 0.0260 0.0230 0.0649 0.0198
CASES
# full against none, the issue's measure (#28: 0.25 the target): 0.764
# before full carried the light between parts, 0.693 then, 0.662 since its
# local part is smoothed over the terminator (2026-12-07); those with one
# sample a pixel. 0.583 with both at 3 x 3 samples (2026-12-07, later);
# 0.505 since full sums the light scattered once along the camera ray
# (mesh.vert, jd_single_march; 2026-12-08).
gm=$(awk -v s="$ratiosum" 'BEGIN { printf "%.3f", exp(s / 8) }')
echo "full's RMSE over none's against the medium, geometric mean of 8: $gm (the target 0.25)"
closer "full over none, geometric mean of 8" "$gm" 0.56
gm=$(awk -v s="$logsum" 'BEGIN { printf "%.3f", exp(s / 16) }')
closer "the reference's RMSE over the dipole-albedo reference's, geometric mean of 16" "$gm" 0.9
# Light carried across thin parts (Donner & Jensen's multipole, measured
# 0.958 of the half-space reference's RMSE against the medium).
gm=$(awk -v s="$thinsum" 'BEGIN { printf "%.3f", exp(s / 8) }')
closer "the reference's RMSE over the half-space reference's against the medium, geometric mean of 8" "$gm" 0.97
# One bounce of light between the parts (measured 0.847 of the reference's
# RMSE without it, geometric mean over medium and walk).
gm=$(awk -v s="$bouncesum" 'BEGIN { printf "%.3f", exp(s / 16) }')
closer "the reference with a bounce over without, geometric mean of 16" "$gm" 0.92
gm=$(awk -v s="$singlesum" 'BEGIN { printf "%.3f", exp(s / 8) }')
closer "the reference with single scattering over without, geometric mean of 8 (with a bounce, against the medium)" "$gm" 0.8
gm=$(awk -v s="$exitsum" 'BEGIN { printf "%.3f", exp(s / 8) }')
closer "the reference's RMSE over the Lambertian exit's against the medium, geometric mean of 8" "$gm" 0.85
finish cycles_truth
