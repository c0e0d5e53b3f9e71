#!/bin/sh
# The quality table: how far jade's none, single, dual and full modes are from the
# CPU reference (the full dipole BSSRDF), for the bunny in marble, skin1,
# ketchup and whole milk, front-lit and back-lit, and the bunny given
# jade's veined colour texture (tools/textured-mesh.sh) in the material its
# colours give and in skin1, whose references take 2 x 2 rays a pixel (the
# texture's edges). Long (a reference per case): run on demand, not by the
# tests.
#
#   tools/quality-table.sh [OUT_DIR]      (SIZE=512x512, BUILD=build by default)
#   cmake --build build --target quality  (the same, into build/quality)
#
# Writes OUT_DIR/table.md (the metrics of `jade metric`, each mode against
# the reference over the object's pixels) and a contact sheet per material
# and light: reference | none | single | dual | full.
#
# RENDER="--profile mali400 --antialias off" renders the modes with those
# options too (a board's profile, its quality tier); MODES="full" only
# those modes (no verdicts or sheets then); KEEP=1 reuses references
# already in OUT_DIR (the same scene at the same size).
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD:-$root/build}
out=${1:-$build/quality}
size=${SIZE:-512x512}
modes=${MODES:-none single dual full}
render_opts=${RENDER:-}
jade=$build/jade
bunny=$build/testdata/bunny.drc
[ -x "$jade" ] || { echo "quality-table: $jade is not built (run tools/quickstart.sh or cmake --build build)" >&2; exit 1; }
sh "$root/tests/encode_bunny.sh" "$root/../shared" "$bunny" || { echo "quality-table: needs the bunny from ../shared" >&2; exit 1; }
mkdir -p "$out"

# front: the light 45 degrees to the camera's left and above; back: behind.
lights="front:-30:40 back:170:35"
materials="marble skin1 ketchup wholemilk"
table=$out/table.md
field() { sed -n "s/.*\"$1\": \([-0-9.e]*\).*/\1/p"; }

{
    echo "| material | light | mode | RMSE | PSNR dB | SSIM | best k | RMSE at k | SSIM at k |"
    echo "|---|---|---|---|---|---|---|---|---|"
} > "$table.tmp"
verdicts=""
# one_case NAME MESH MATERIAL_OPTIONS REFERENCE_OPTIONS: its two lights.
one_case() {
    cname=$1 mesh=$2 matopt=$3 refopt=$4
    for l in $lights; do
        name=${l%%:*}; rest=${l#*:}; az=${rest%%:*}; el=${rest#*:}
        scene="--mesh $mesh --size $size $matopt --light-azimuth $az --light-elevation $el"
        base=$out/${cname}_$name
        echo "== $cname, $name-lit" >&2
        if [ "${KEEP:-0}" != 1 ] || [ ! -f "$base.reference.png" ] || [ ! -f "$base.mask.png" ]; then
            # shellcheck disable=SC2086
            "$jade" reference $scene $refopt --out "$base.reference.png" --pfm "$base.reference.pfm" --mask "$base.mask.png" --quiet >&2
        fi
        rmse_of=""
        for mode in $modes; do
            # shellcheck disable=SC2086
            "$jade" render $scene $render_opts --mode $mode --out "$base.$mode.png" >/dev/null 2>&1
            m=$("$jade" metric "$base.$mode.png" "$base.reference.png" --mask "$base.mask.png")
            echo "$m" > "$base.$mode.json"
            rmse=$(echo "$m" | field rmse); psnr=$(echo "$m" | field psnr_db); ssim=$(echo "$m" | field ssim)
            k=$(echo "$m" | field best_scale); rk=$(echo "$m" | field rmse_scaled); sk=$(echo "$m" | field ssim_scaled)
            printf '| %s | %s | %s | %.4f | %.2f | %.4f | %.3f | %.4f | %.4f |\n' \
                "$cname" "$name" "$mode" "$rmse" "$psnr" "$ssim" "$k" "$rk" "$sk" >> "$table.tmp"
            rmse_of="$rmse_of $rmse:$rk:$ssim"
        done
        [ "$modes" = "none single dual full" ] || continue
        # shellcheck disable=SC2086
        "$jade" render $scene $render_opts --sheet "$out/sheet_${cname}_$name.png" --sheet-reference "$base.reference.png" >/dev/null 2>&1
        # The paper's claims, per case: single closer than none, dual closer
        # than single; and jade's: full closer than dual and than none, its
        # structure (SSIM) closer than dual's.
        verdicts="$verdicts$(echo "$rmse_of" | awk -v c="$cname, $name-lit" '
            function v(x) { return x ? "yes" : "**no**" }
            { split($1, n, ":"); split($2, s, ":"); split($3, d, ":"); split($4, f, ":");
              printf "| %s | %s | %s | %s | %s | %s | %.2f |\n", c, v(s[1] < n[1]), v(d[1] < s[1]), v(f[1] < d[1]),
                     v(f[1] < n[1]), v(f[3] > d[3]), f[1] / n[1] }')
"
    done
}
for mat in $materials; do one_case "$mat" "$bunny" "--material $mat" ""; done
if [ "${TEXTURED:-1}" = 1 ]; then
    textured=$out/textured/bunny_tex.obj
    sh "$root/tools/textured-mesh.sh" "$root/../shared/testdata/meshes/stanford-bunny.obj" "$textured"
    one_case "textured-colour" "$textured" "" "--pixel-samples 2"
    one_case "textured-skin1" "$textured" "--material skin1" "--pixel-samples 2"
fi
{
    cat "$table.tmp"
    echo
    echo "| case | single closer than none | dual closer than single | full closer than dual | full closer than none | full's SSIM above dual's | full / none (RMSE) |"
    echo "|---|---|---|---|---|---|---|"
    printf '%s' "$verdicts"
} > "$table"
rm -f "$table.tmp"
cat "$table"
echo "wrote $table and the sheets in $out" >&2
