#!/bin/sh
# Regenerates core/albedo_table.c from tools/gen_albedo_table.c (the exact
# half-space albedo over the dipole's, reference/halfspace_albedo.c). Needs cc.
# (material.c links against the table in the tree, which the generator does
# not read: only the dipole's own Rd_total.)
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cc -O2 -I"$here/core" -I"$here/reference" -o "$tmp/gen" "$here/tools/gen_albedo_table.c" \
    "$here/reference/halfspace_albedo.c" "$here/core/material.c" "$here/core/albedo_table.c" -lm
"$tmp/gen" > "$tmp/albedo_table.c"
mv "$tmp/albedo_table.c" "$here/core/albedo_table.c"
echo "wrote $here/core/albedo_table.c"
