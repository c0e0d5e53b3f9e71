#!/bin/sh
# encode_bunny.sh SHARED OUT.drc: the Stanford bunny from ../shared, encoded
# with Debian's draco_encoder at test time (never committed).
src="$1/testdata/meshes/stanford-bunny.obj"
if [ ! -f "$src" ]; then
    echo "SKIP: $src is absent (../shared beside the checkout holds the test meshes)"
    exit 77
fi
mkdir -p "$(dirname "$2")"
[ -f "$2" ] && [ "$2" -nt "$src" ] && exit 0
draco_encoder -i "$src" -o "$2" -cl 7 -qp 14 >/dev/null && echo "encoded $2 ($(wc -c < "$2") bytes)"
