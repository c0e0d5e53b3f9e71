#!/bin/sh
# Every mesh format jade reads, by content: one tetrahedron written here as
# OBJ, PLY, ASCII STL and binary STL (with a header that says "solid", as
# many exporters write it) and as a Draco file where draco_encoder exists,
# each renders the same picture (RMSE 0 against the PLY's, under 0.001 for
# the encoded Draco copy); a file named
# .obj that holds a PLY is read as a PLY; then the public OBJ meshes in
# ../shared/testdata/meshes render (said when absent).
jade=$1 shared=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); echo "ok   $1"; }
bad() { fail=$((fail + 1)); echo "FAIL $1"; }
render() { "$jade" render --mesh "$1" --size 96x96 --out "$2" >"$tmp/out" 2>&1; }
printf 'ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' > "$tmp/tet.ply"
printf '# a tetrahedron\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' > "$tmp/tet.obj"
facet() { printf 'facet normal 0 0 0\nouter loop\nvertex %s\nvertex %s\nvertex %s\nendloop\nendfacet\n' "$1" "$2" "$3"; }
{ echo "solid tet"; facet "0 0 0" "0 1 0" "1 0 0"; facet "0 0 0" "1 0 0" "0 0 1"; facet "0 0 0" "0 0 1" "0 1 0"
  facet "1 0 0" "0 1 0" "0 0 1"; echo "endsolid tet"; } > "$tmp/tet_ascii.stl"
# Binary: 80-byte header starting "solid", a count of 4, 50 bytes a facet.
{ printf 'solid binary'; head -c 68 /dev/zero | tr '\0' ' '; printf '\004\000\000\000'
  for t in "0 0 0 0 1 0 1 0 0" "0 0 0 1 0 0 0 0 1" "0 0 0 0 0 1 0 1 0" "1 0 0 0 1 0 0 0 1"; do
      head -c 12 /dev/zero
      for c in $t; do if [ "$c" = 1 ]; then printf '\000\000\200\077'; else printf '\000\000\000\000'; fi; done
      printf '\000\000'
  done; } > "$tmp/tet_binary.stl"
cp "$tmp/tet.ply" "$tmp/really_a_ply.obj"
set -- tet.obj tet_ascii.stl tet_binary.stl really_a_ply.obj
if command -v draco_encoder >/dev/null && draco_encoder -i "$tmp/tet.ply" -o "$tmp/tet.drc" -qp 0 >/dev/null 2>&1; then
    set -- "$@" tet.drc
else
    echo "no draco_encoder: the Draco copy is not tried"
fi
if render "$tmp/tet.ply" "$tmp/tet.ply.png"; then ok "tet.ply renders"; else bad "tet.ply: $(cat "$tmp/out")"; fi
for f in "$@"; do
    if ! render "$tmp/$f" "$tmp/$f.png"; then bad "$f: $(cat "$tmp/out")"; continue; fi
    rmse=$("$jade" metric "$tmp/$f.png" "$tmp/tet.ply.png" | sed -n 's/.*"rmse": \([0-9.]*\).*/\1/p')
    # The Draco copy went through an encoder: a few parts in a million.
    if [ "$rmse" = "0.000000" ] || { [ "$f" = tet.drc ] && awk "BEGIN { exit !($rmse < 0.001) }"; }; then
        ok "$f: the same picture as the PLY (RMSE $rmse)"
    else bad "$f: RMSE $rmse against the PLY"; fi
done
if [ -d "$shared/testdata/meshes" ]; then
    for f in "$shared"/testdata/meshes/*.obj; do
        start=$(date +%s%N)
        if render "$f" "$tmp/shared.png"; then
            ok "$(basename "$f"): $(sed -n 's/.*mesh [^:]*: \([0-9]* triangles\).*/\1/p' "$tmp/out") in $(( ($(date +%s%N) - start) / 1000000 )) ms"
        else bad "$(basename "$f"): $(cat "$tmp/out")"; fi
    done
else
    echo "$shared/testdata/meshes is absent: the public OBJ meshes are not tried"
fi
echo "formats: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
