#!/bin/sh
# Regenerates assets/default.drc from tools/gen_asset.c (needs cc and draco_encoder).
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cc -O2 -o "$tmp/gen_asset" "$here/tools/gen_asset.c" -lm
"$tmp/gen_asset" > "$tmp/knot.obj"
draco_encoder -i "$tmp/knot.obj" -o "$tmp/default.drc" -cl 7 -qp 14 >/dev/null
mv "$tmp/default.drc" "$here/assets/default.drc"
echo "wrote assets/default.drc ($(wc -c < "$here/assets/default.drc") bytes)"
