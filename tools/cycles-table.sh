#!/bin/sh
# cycles-table.sh [OUT_DIR]: the quality table's bunny cases held to Cycles
# (tools/cycles-reference.sh) instead of to jade's own dipole reference: RMSE
# of jade reference, none, single, dual and full against the path-traced
# picture, over jade's object mask, in linear light (jade metric), and of
# jade reference with one bounce of light between the object's parts
# (--bounces 1), solved in the volume (--volume, ref_volume.h), and with one
# bounce and single scattering traced (--bounces 1 --single-scatter,
# ref_single.h), last.
# jade reference takes 3 x 3 rays a pixel, as Cycles
# averages over each pixel, and jade's modes 3 x 3 samples (jade render
# --pixel-samples 3; until 2026-12-07 one, with the pass after the frame).
#
# The scenes are the quality table's (bunny; marble, skin1, ketchup, whole
# milk; front-lit az -30 el 40, back-lit az 170 el 35) with the boundary that
# Cycles converges on: index-matched (--eta 1), no ambient light, no
# highlight (--ambient 0 --specular 0), for jade as for Cycles. Long (Cycles:
# about 90 s a case at 128x128 and 1024 samples on 2 cores): on demand, never
# by the tests. KEEP=1 reuses Cycles pictures already in OUT_DIR; BOUNDARY=walk
# renders Cycles' random-walk subsurface scattering instead of the matched
# medium (tools/cycles-reference.sh --boundary); MESH=FILE holds another mesh
# to the same cases (the held-out meshes of ../shared, say), MATERIALS the
# materials to take.
#
#   SIZE=128x128 SAMPLES=1024 [BOUNDARY=walk] [MESH=FILE] tools/cycles-table.sh [OUT_DIR]   (default build/cycles)
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD:-$root/build}
out=${1:-$build/cycles}
size=${SIZE:-128x128}
samples=${SAMPLES:-1024}
boundary=${BOUNDARY:-matched}
jade=$build/jade
bunny=${MESH:-$root/../shared/testdata/meshes/stanford-bunny.obj}
[ -x "$jade" ] || { echo "cycles-table: $jade is not built" >&2; exit 1; }
[ -f "$bunny" ] || { echo "cycles-table: needs $bunny (../shared, or MESH=FILE)" >&2; exit 1; }
mkdir -p "$out"
field() { sed -n "s/.*\"$1\": \([-0-9.e]*\).*/\1/p"; }
common="--eta 1 --ambient 0 --specular 0"
echo "| material | light | jade reference | none | single | dual | full | full / none | full / reference | reference, 1 bounce | reference, volume | reference, 1 bounce, single scattering |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for mat in ${MATERIALS:-marble skin1 ketchup wholemilk}; do
    for l in front:-30:40 back:170:35; do
        name=${l%%:*}; rest=${l#*:}; az=${rest%%:*}; el=${rest#*:}
        base=$out/${mat}_$name
        scene="--mesh $bunny --size $size --material $mat --light-azimuth $az --light-elevation $el"
        if [ "${KEEP:-0}" != 1 ] || [ ! -f "$base.pfm" ]; then
            # shellcheck disable=SC2086
            "$root/tools/cycles-reference.sh" $scene --eta 1 --ambient 0 --samples "$samples" --seed 7 --boundary "$boundary" --out "$base" >&2
        fi
        # shellcheck disable=SC2086
        "$jade" reference $scene $common --pixel-samples 3 --out "$base.jade_reference.png" --mask "$base.jade_mask.png" --quiet >/dev/null 2>&1
        # shellcheck disable=SC2086
        "$jade" reference $scene $common --bounces 1 --pixel-samples 3 --out "$base.jade_bounced.png" --quiet >/dev/null 2>&1
        # shellcheck disable=SC2086
        "$jade" reference $scene $common --volume --pixel-samples 3 --out "$base.jade_volume.png" --quiet >/dev/null 2>&1
        # shellcheck disable=SC2086
        "$jade" reference $scene $common --bounces 1 --single-scatter --pixel-samples 3 --out "$base.jade_scattered.png" --quiet >/dev/null 2>&1
        row=""
        for m in reference none single dual full bounced volume scattered; do
            pic=$base.jade_reference.png
            if [ "$m" = bounced ] || [ "$m" = volume ] || [ "$m" = scattered ]; then
                pic=$base.jade_$m.png
            elif [ "$m" != reference ]; then
                pic=$base.jade_$m.png
                # shellcheck disable=SC2086
                "$jade" render $scene $common --mode "$m" --pixel-samples 3 --out "$pic" >/dev/null 2>&1
            fi
            row="$row $("$jade" metric "$pic" "$base.pfm" --mask "$base.jade_mask.png" | field rmse)"
        done
        echo "$row" | awk -v c="$mat" -v l="$name" '{ printf "| %s | %s | %.4f | %.4f | %.4f | %.4f | %.4f | %.2f | %.2f | %.4f | %.4f | %.4f |\n", c, l, $1, $2, $3, $4, $5, $5 / $2, $5 / $1, $6, $7, $8 }'
    done
done
