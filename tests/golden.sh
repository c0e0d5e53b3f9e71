#!/bin/sh
# golden.sh JADE IMGCMP MESH GOLDEN.png OUT.png [render options...]
# Renders MESH and compares it with a stored golden image, with a tolerance.
# Exit 77 (skipped) when the mesh is absent (one encoded from ../shared at
# test time may be).
jade=$1 imgcmp=$2 mesh=$3 golden=$4 out=$5
shift 5
if [ ! -f "$mesh" ]; then
    echo "SKIP: $mesh is absent"
    exit 77
fi
"$jade" render --mesh "$mesh" --out "$out" "$@" || exit 1
"$imgcmp" "$out" "$golden" --max-rmse 2.5 --max-bad-frac 0.01 --bad-threshold 24
