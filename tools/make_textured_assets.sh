#!/bin/sh
# Regenerates assets/textured/ (jade's own textured test models) from
# tools/gen_textured.c. Needs cc and libstb-dev.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cc -O2 -o "$tmp/gen_textured" "$here/tools/gen_textured.c" $(pkg-config --cflags --libs stb) -lm
mkdir -p "$here/assets/textured"
"$tmp/gen_textured" "$here/assets/textured"
ls -l "$here/assets/textured"
