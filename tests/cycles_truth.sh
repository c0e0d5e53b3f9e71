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
# Back-lit, both are closer than none to either picture; front-lit on this
# knot they mostly are not (docs/quality.md: jade's reference is darker than
# the medium), which the test prints and does not hide.
jade=$1 src=$2
. "$(dirname "$0")/harness.sh"
rmse() { "$jade" metric "$1" "$2" --mask "$tmp/mask.png" | sed -n 's/.*"rmse": \([0-9.e-]*\).*/\1/p'; }
gain() { "$jade" metric "$1" "$2" --mask "$tmp/mask.png" | sed -n 's/.*"best_scale": \([0-9.e-]*\).*/\1/p'; }
# within WHAT VALUE BOUND
within() { if awk -v v="$2" -v b="$3" 'BEGIN { exit !(v != "" && v <= b) }'; then ok "$1 $2 <= $3"; else bad "$1 $2, over $3"; fi; }
closer() { if awk -v a="$2" -v b="$3" 'BEGIN { exit !(a != "" && a < b) }'; then ok "$1 ($2 < $3)"; else bad "$1: $2, not below $3"; fi; }
# jade reference --exact-albedo (the half-space's albedo for the dipole's, at
# eta 1: the light's beam by its angle, the ambient as diffuse light) is held
# as well: in geometric mean over the sixteen comparisons it is closer to
# Cycles than the dipole's reference (0.815 when measured; held under 0.9),
# and for the absorbing materials (skin1, ketchup) closer to the walk in
# every case.
logsum=0
# material light azimuth elevation, then today's RMSE of the reference and
# full against the matched medium, then against the random walk, then the
# exact-albedo reference's against each
while read -r mat light az el ref_today full_today wref_today wfull_today xref_today xwref_today; do
    truth=$src/assets/cycles/default-$mat-$light.png walk=$src/assets/cycles/walk-$mat-$light.png
    scene="--mesh $src/assets/default.drc --size 128x128 --material $mat --eta 1 --ambient 0 --specular 0"
    scene="$scene --light-azimuth $az --light-elevation $el"
    # shellcheck disable=SC2086
    "$jade" reference $scene --pixel-samples 3 --quiet --out "$tmp/reference.png" --mask "$tmp/mask.png" >/dev/null ||
        { bad "jade reference did not run ($mat, $light)"; continue; }
    # shellcheck disable=SC2086
    "$jade" reference $scene --pixel-samples 3 --quiet --exact-albedo --out "$tmp/exact.png" >/dev/null ||
        bad "jade reference --exact-albedo did not run ($mat, $light)"
    for m in none full; do
        # shellcheck disable=SC2086
        "$jade" render $scene --mode $m --out "$tmp/$m.png" >/dev/null 2>&1 || bad "jade render --mode $m did not run"
    done
    ref=$(rmse "$tmp/reference.png" "$truth") none=$(rmse "$tmp/none.png" "$truth") full=$(rmse "$tmp/full.png" "$truth")
    echo "$mat, $light-lit: RMSE against Cycles: jade reference $ref (best gain $(gain "$tmp/reference.png" "$truth")), none $none, full $full"
    within "$mat $light: jade reference (measured $ref_today)" "$ref" "$(awk -v v="$ref_today" 'BEGIN { printf "%.4f", 1.1 * v }')"
    within "$mat $light: full (measured $full_today)" "$full" "$(awk -v v="$full_today" 'BEGIN { printf "%.4f", 1.1 * v }')"
    wref=$(rmse "$tmp/reference.png" "$walk") wnone=$(rmse "$tmp/none.png" "$walk") wfull=$(rmse "$tmp/full.png" "$walk")
    echo "$mat, $light-lit: RMSE against the random walk: jade reference $wref (best gain $(gain "$tmp/reference.png" "$walk")), none $wnone, full $wfull"
    within "$mat $light: jade reference against the walk (measured $wref_today)" "$wref" "$(awk -v v="$wref_today" 'BEGIN { printf "%.4f", 1.1 * v }')"
    within "$mat $light: full against the walk (measured $wfull_today)" "$wfull" "$(awk -v v="$wfull_today" 'BEGIN { printf "%.4f", 1.1 * v }')"
    xref=$(rmse "$tmp/exact.png" "$truth") xwref=$(rmse "$tmp/exact.png" "$walk")
    echo "$mat, $light-lit: the exact-albedo reference: $xref against the medium, $xwref against the walk"
    within "$mat $light: exact-albedo reference (measured $xref_today)" "$xref" "$(awk -v v="$xref_today" 'BEGIN { printf "%.4f", 1.1 * v }')"
    within "$mat $light: exact-albedo reference against the walk (measured $xwref_today)" "$xwref" "$(awk -v v="$xwref_today" 'BEGIN { printf "%.4f", 1.1 * v }')"
    logsum=$(awk -v s="$logsum" -v a="$xref" -v b="$ref" -v c="$xwref" -v d="$wref" 'BEGIN { print s + log(a / b) + log(c / d) }')
    case $mat in skin1 | ketchup) closer "$mat $light: the exact albedo brings the reference closer to the walk" "$xwref" "$wref" ;; esac
    if [ "$light" = back ]; then
        closer "$mat back: jade reference closer than none" "$ref" "$none"
        closer "$mat back: full closer than none" "$full" "$none"
        closer "$mat back: jade reference closer than none to the walk" "$wref" "$wnone"
        closer "$mat back: full closer than none to the walk" "$wfull" "$wnone"
    fi
done <<'CASES'
marble front -30 40 0.0673 0.0704 0.0493 0.0665 0.0679 0.0470
marble back 170 35 0.0721 0.0839 0.0561 0.0699 0.0678 0.0530
skin1 front -30 40 0.0529 0.0587 0.0838 0.0958 0.0396 0.0493
skin1 back 170 35 0.0711 0.0731 0.0494 0.0544 0.0528 0.0323
ketchup front -30 40 0.0324 0.0391 0.0811 0.0889 0.0171 0.0611
ketchup back 170 35 0.0443 0.0470 0.0508 0.0532 0.0329 0.0400
wholemilk front -30 40 0.0672 0.0719 0.0499 0.0655 0.0677 0.0486
wholemilk back 170 35 0.0689 0.0822 0.0545 0.0691 0.0652 0.0519
CASES
gm=$(awk -v s="$logsum" 'BEGIN { printf "%.3f", exp(s / 16) }')
closer "the exact-albedo reference's RMSE over the dipole's, geometric mean of 16" "$gm" 0.9
finish cycles_truth
