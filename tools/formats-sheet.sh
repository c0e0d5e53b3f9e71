#!/bin/sh
# A contact sheet of every mesh format jade reads, from the public files in
# ../shared/testdata (glTF samples plain and Draco-compressed, Draco's own
# test files, the OBJ meshes) plus PLY and binary STL copies of the bunny and
# a 500,000-triangle sphere on the mali400 profile (16-bit chunks), all made
# here at run time and not kept. Prints one line per file (triangles, the
# whole render's wall time, the decode time); with Python's PIL, also
# writes the sheet: tools/formats-sheet.sh [JADE] [OUT.png]
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
jade=${1:-$here/build/jade}
out=${2:-formats-sheet.png}
shared=${JADE_SHARED:-$here/../shared}/testdata
[ -d "$shared" ] || { echo "formats-sheet: $shared is absent"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# PLY and binary STL of the bunny, and the big sphere, written with awk.
awk -v ply="$tmp/bunny.ply" -v stl="$tmp/bunny.stl.txt" '
    $1 == "v" { n++; x[n] = $2; y[n] = $3; z[n] = $4 }
    $1 == "f" { m++; split($2, a, "/"); split($3, b, "/"); split($4, c, "/"); f1[m] = a[1]; f2[m] = b[1]; f3[m] = c[1] }
    END {
        printf "ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n", n > ply
        printf "element face %d\nproperty list uchar int vertex_indices\nend_header\n", m > ply
        for (i = 1; i <= n; i++) printf "%s %s %s\n", x[i], y[i], z[i] > ply
        for (i = 1; i <= m; i++) printf "3 %d %d %d\n", f1[i] - 1, f2[i] - 1, f3[i] - 1 > ply
        print "solid bunny" > stl
        for (i = 1; i <= m; i++) printf "facet normal 0 0 0\nouter loop\nvertex %s %s %s\nvertex %s %s %s\nvertex %s %s %s\nendloop\nendfacet\n",
            x[f1[i]], y[f1[i]], z[f1[i]], x[f2[i]], y[f2[i]], z[f2[i]], x[f3[i]], y[f3[i]], z[f3[i]] > stl
        print "endsolid bunny" > stl }' "$shared/meshes/stanford-bunny.obj"
mv "$tmp/bunny.stl.txt" "$tmp/bunny.stl"
awk 'BEGIN { n = 500; m = 500; pi = 3.14159265358979
    for (i = 0; i <= n; i++) for (j = 0; j < m; j++) { t = pi * i / n; p = 2 * pi * j / m
        printf "v %.6f %.6f %.6f\n", sin(t) * cos(p), cos(t) * 1.6, sin(t) * sin(p) }
    for (i = 0; i < n; i++) for (j = 0; j < m; j++) { a = i * m + j + 1; b = i * m + (j + 1) % m + 1
        c = (i + 1) * m + j + 1; d = (i + 1) * m + (j + 1) % m + 1
        printf "f %d %d %d\nf %d %d %d\n", a, c, b, b, c, d } }' > "$tmp/sphere.obj"
"$jade" convert "$tmp/bunny.ply" "$tmp/bunny_from_ply.drc" >/dev/null
set -- "$shared"/gltf/*.glb "$shared/draco/bunny_gltf.drc" "$shared/draco/test_nm.obj.edgebreaker.cl10.2.2.drc" \
    "$shared"/meshes/*.obj "$tmp/bunny.ply" "$tmp/bunny.stl" "$tmp/bunny_from_ply.drc" "$tmp/sphere.obj"
i=0
: > "$tmp/list"
for f in "$@"; do
    [ -f "$f" ] || continue
    i=$((i + 1))
    prof=""
    [ "$(basename "$f")" = sphere.obj ] && prof="--profile mali400"
    start=$(date +%s%N)
    # shellcheck disable=SC2086
    if "$jade" render --mesh "$f" --size 256x256 $prof --out "$tmp/p$i.png" > "$tmp/o" 2>&1; then
        ms=$(( ($(date +%s%N) - start) / 1000000 ))
        tris=$(sed -n 's/.*: \([0-9]*\) triangles.*/\1/p' "$tmp/o")
        dec=$(sed -n 's/.*decode \([0-9.]*\) ms.*/\1/p' "$tmp/o")
        label="$(basename "$f")${prof:+ (mali400)}"
        printf '%-44s %8s triangles, render %5d ms, decode %6s ms\n' "$label" "$tris" "$ms" "$dec"
        printf '%s\t%s\t%s tris, %s ms\n' "$tmp/p$i.png" "$label" "$tris" "$ms" >> "$tmp/list"
    else
        echo "$(basename "$f"): FAILED: $(cat "$tmp/o")"
    fi
done
if python3 -c 'import PIL' 2>/dev/null; then
    python3 - "$tmp/list" "$out" <<'PY'
import sys
from PIL import Image, ImageDraw
rows = [l.rstrip('\n').split('\t') for l in open(sys.argv[1])]
cols = 4
W, H = 256, 256 + 30
sheet = Image.new('RGB', (cols * W, ((len(rows) + cols - 1) // cols) * H), (20, 20, 24))
d = ImageDraw.Draw(sheet)
for k, (path, label, info) in enumerate(rows):
    x, y = (k % cols) * W, (k // cols) * H
    sheet.paste(Image.open(path).convert('RGB'), (x, y))
    d.text((x + 4, y + 258), label, fill=(230, 230, 230))
    d.text((x + 4, y + 272), info, fill=(170, 170, 170))
sheet.save(sys.argv[2])
print('wrote', sys.argv[2])
PY
fi
