#!/bin/sh
# Re-renders the golden images after a deliberate change to the picture.
# Look at them before committing: a golden image is a claim that it is right.
set -eu
cd "$(dirname "$0")/.."
cmake --build build >/dev/null
# jade's own meshes only: nothing made from ../shared's is committed.
for mode in none single dual full; do
    for mat in marble skin1 ketchup; do
        ./build/jade render --mesh assets/default.drc --out "tests/golden/knot_${mode}_${mat}.png" \
            --size 256x256 --mode "$mode" --material "$mat" --cam-azimuth 20 --precision highp >/dev/null
    done
done
for mode in none single dual full; do
    ./build/jade render --mesh assets/textured/pebble.gltf --out "tests/golden/pebble_${mode}.png" --size 256x256 \
        --mode "$mode" --light-azimuth 150 --light-elevation 30 --precision highp >/dev/null 2>&1
done
# The flicker test's reference frames (tests/flicker.sh keeps three of them,
# the mask and the measure of all 60): about 2 minutes on 2 cores.
sh tests/flicker.sh --update ./build/jade ./build/tests/flicker_measure tests/golden
ls -la tests/golden
