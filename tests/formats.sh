#!/bin/sh
# Every mesh format jade reads, by content: one tetrahedron written here as
# OBJ, PLY, ASCII STL and binary STL (with a header that says "solid", as
# many exporters write it) and as a Draco file where draco_encoder exists,
# each renders the same picture (RMSE 0 against the PLY's, under 0.001 for
# the encoded Draco copy); a file named
# .obj that holds a PLY is read as a PLY. The same tetrahedron as glTF: a
# .gltf with its buffer inline (data: URI), one with a .bin beside it and a
# .glb, each the same picture; a node's rotation placing it as the rotated
# OBJ does; two nodes instancing it (8 triangles); extras.jade_material
# choosing the material, and glTF's translucency extensions; hostile glTF
# refused by name. Then the public
# meshes in ../shared/testdata (glTF samples, plain and Draco-compressed,
# and OBJ) render (said when absent), and `jade convert` turns each format
# into a Draco file that renders the same.
jade=$1 shared=$2
. "$(dirname "$0")/harness.sh"
# The decode limit is raised: the public meshes under a sanitizer on a loaded
# machine can pass the default 1.5 s (the limit itself: test_bad_inputs).
render() { "$jade" render --mesh "$1" --size 96x96 --decode-timeout-ms 60000 --out "$2" >"$tmp/out" 2>&1; }
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
# glTF: the tetrahedron's 4 positions (floats) then 12 indices (uint16), 72 bytes.
le32() { printf "\\$(printf %03o $(($1 & 255)))\\$(printf %03o $(($1 >> 8 & 255)))\\$(printf %03o $(($1 >> 16 & 255)))\\$(printf %03o $(($1 >> 24 & 255)))"; }
{ for c in 0 0 0 1 0 0 0 1 0 0 0 1; do if [ "$c" = 1 ]; then printf '\000\000\200\077'; else printf '\000\000\000\000'; fi; done
  for i in 0 2 1 0 1 3 0 3 2 1 2 3; do printf "\\$(printf %03o "$i")\\000"; done; } > "$tmp/tet.bin"
# gltf_json URI [NODES] [MATERIAL]
gltf_json() {
    nodes=${2:-'{"mesh":0}'} roots=0 mat=""
    case "$nodes" in *'},{'*) roots="0,1";; esac
    [ -n "${3:-}" ] && mat=',"material":0'
    printf '{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[%s]}],"nodes":[%s],' "$roots" "$nodes"
    printf '"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1%s}]}],' "$mat"
    [ -n "${3:-}" ] && printf '"materials":[{"extras":{"jade_material":"%s"}}],' "$3"
    printf '"buffers":[{"byteLength":72%s}],' "$1"
    printf '"bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":24}],'
    printf '"accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},'
    printf '{"bufferView":1,"componentType":5123,"count":12,"type":"SCALAR"}]}'
}
gltf_json ",\"uri\":\"data:application/octet-stream;base64,$(base64 -w0 "$tmp/tet.bin")\"" > "$tmp/tet_inline.gltf"
gltf_json ',"uri":"tet.bin"' > "$tmp/tet_external.gltf"
gltf_json "" > "$tmp/glb.json"
while [ $(($(wc -c < "$tmp/glb.json") % 4)) -ne 0 ]; do printf ' ' >> "$tmp/glb.json"; done
jl=$(wc -c < "$tmp/glb.json")
{ printf 'glTF'; le32 2; le32 $((12 + 8 + jl + 8 + 72)); le32 "$jl"; printf 'JSON'; cat "$tmp/glb.json"
  le32 72; printf 'BIN\000'; cat "$tmp/tet.bin"; } > "$tmp/tet.glb"
cp "$tmp/tet.glb" "$tmp/glb_named.obj"
for f in tet_inline.gltf tet_external.gltf tet.glb glb_named.obj; do
    if ! render "$tmp/$f" "$tmp/$f.png"; then bad "$f: $(cat "$tmp/out")"; continue; fi
    rmse=$("$jade" metric "$tmp/$f.png" "$tmp/tet.ply.png" | sed -n 's/.*"rmse": \([0-9.]*\).*/\1/p')
    if [ "$rmse" = "0.000000" ]; then ok "$f: the same picture as the PLY (RMSE $rmse)"; else bad "$f: RMSE $rmse against the PLY"; fi
done
# A quarter turn about +Y (x' = z, z' = -x) by the node, against the OBJ turned by hand.
printf 'v 0 0 0\nv 0 0 -1\nv 0 1 0\nv 1 0 0\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' > "$tmp/tet_turned.obj"
gltf_json ',"uri":"tet.bin"' '{"mesh":0,"rotation":[0,0.70710678,0,0.70710678]}' > "$tmp/tet_turned.gltf"
if render "$tmp/tet_turned.gltf" "$tmp/turned_gltf.png" && render "$tmp/tet_turned.obj" "$tmp/turned_obj.png"; then
    rmse=$("$jade" metric "$tmp/turned_gltf.png" "$tmp/turned_obj.png" | sed -n 's/.*"rmse": \([0-9.]*\).*/\1/p')
    if awk "BEGIN { exit !($rmse < 0.002) }"; then ok "node rotation places the mesh as the turned OBJ (RMSE $rmse)"
    else bad "node rotation: RMSE $rmse against the turned OBJ"; fi
else bad "turned tetrahedron: $(cat "$tmp/out")"; fi
gltf_json ',"uri":"tet.bin"' '{"mesh":0},{"mesh":0,"translation":[3,0,0],"scale":[-1,1,1]}' > "$tmp/tet_twice.gltf"
if render "$tmp/tet_twice.gltf" "$tmp/twice.png" && grep -q ": 8 triangles" "$tmp/out"; then ok "two nodes, one mirrored: 8 triangles merged"
else bad "two instances: $(cat "$tmp/out")"; fi
gltf_json ',"uri":"tet.bin"' "" ketchup > "$tmp/tet_ketchup.gltf"
if render "$tmp/tet_ketchup.gltf" "$tmp/k.png" && grep -q ", ketchup," "$tmp/out"; then ok "extras.jade_material chooses ketchup"
else bad "extras.jade_material: $(cat "$tmp/out")"; fi
if "$jade" render --mesh "$tmp/tet_ketchup.gltf" --material skin1 --size 64x64 --out "$tmp/k2.png" 2>&1 | grep -q ", skin1,"; then
    ok "--material overrides the file's material"; else bad "--material does not override extras"; fi
# glTF's translucency extensions: the medium they describe, in metres, becomes
# jade's (docs/usage.md has the mapping); extras.jade_material and
# --material win; what jade cannot show is said.
gltf_mat() { # MATERIAL_JSON: the tetrahedron, a twentieth of a metre across, with that material
    gltf_json ',"uri":"tet.bin"' '{"mesh":0,"scale":[0.05,0.05,0.05]}' PLACEHOLDER |
        sed "s|\"materials\":\[{\"extras\":{\"jade_material\":\"PLACEHOLDER\"}}\]|\"materials\":[$1]|"
}
vol='"KHR_materials_volume":{"attenuationDistance":0.01,"attenuationColor":[0.5,0.3,0.2],"thicknessTexture":{"index":0}}'
scat='"KHR_materials_volume_scatter":{"multiscatterColor":[0.9,0.6,0.4],"scatterAnisotropy":0.2}'
gltf_mat "{\"extensions\":{$vol,$scat,\"KHR_materials_ior\":{\"ior\":1.4}}}" > "$tmp/tet_volume.gltf"
if render "$tmp/tet_volume.gltf" "$tmp/v.png" && grep -q ", gltf," "$tmp/out" &&
   grep -q "sigma_s' 0.05534 0.09162 0.1095, sigma_a 0.0001451 0.005878 0.02401 per mm, eta 1.4, 1000 mm a unit" "$tmp/out" &&
   grep -q "does not show the thickness texture" "$tmp/out"; then
    ok "KHR_materials_volume + _volume_scatter + _ior: $(grep 'the material of' "$tmp/out" | head -c 200)"
else bad "glTF volume material: $(cat "$tmp/out")"; fi
gltf_mat "{\"extensions\":{$vol,$scat},\"extras\":{\"jade_material\":\"ketchup\"}}" > "$tmp/tet_volume_k.gltf"
if render "$tmp/tet_volume_k.gltf" "$tmp/vk.png" && grep -q ", ketchup," "$tmp/out"; then ok "extras.jade_material wins over the extensions"
else bad "extras over extensions: $(cat "$tmp/out")"; fi
if "$jade" render --mesh "$tmp/tet_volume.gltf" --material skin1 --size 64x64 --out "$tmp/v2.png" 2>&1 | grep -q ", skin1,"; then
    ok "--material wins over the extensions"; else bad "--material does not override the extensions"; fi
gltf_mat "{\"extensions\":{$vol}}" > "$tmp/tet_clear.gltf"
if render "$tmp/tet_clear.gltf" "$tmp/c.png" && grep -q ", marble," "$tmp/out" && grep -q "nothing scatters" "$tmp/out"; then
    ok "a clear absorbing volume keeps the default material, and says why"
else bad "clear volume: $(cat "$tmp/out")"; fi
gltf_mat "{\"extensions\":{\"KHR_materials_volume\":{\"attenuationDistance\":1e-12,\"attenuationColor\":[1e-9,0,\"x\"]},$scat}}" > "$tmp/tet_absurd.gltf"
if render "$tmp/tet_absurd.gltf" "$tmp/a.png" && grep -q ", marble," "$tmp/out"; then
    ok "coefficients past jade's range are not taken (marble)"
else bad "absurd volume: $(cat "$tmp/out")"; fi
# Hostile glTF: each refused with its reason, exit 1.
refuse() {
    printf '%s' "$2" > "$tmp/$1"
    if "$jade" render --mesh "$tmp/$1" --size 64x64 --out "$tmp/r.png" > "$tmp/out" 2>&1; then bad "$1 was accepted"
    elif grep -q "$3" "$tmp/out"; then ok "$1 refused: $(head -c 160 "$tmp/out" | head -1)"
    else bad "$1: $(cat "$tmp/out")"; fi
}
refuse cyclic.gltf "$(gltf_json ',"uri":"tet.bin"' '{"mesh":0,"children":[1]},{"children":[0]}')" "cyclic"
refuse escape.gltf "$(gltf_json ',"uri":"../etc/passwd"')" "not a plain relative file name"
mkfifo "$tmp/pipe"
refuse fifo.gltf "$(gltf_json ',"uri":"pipe"')" "not a regular file"
refuse short.gltf "$(gltf_json ',"uri":"tet.bin"' | sed 's/"byteLength":24/"byteLength":240/')" "bufferView reaches"
refuse points.gltf "$(gltf_json ',"uri":"tet.bin"' | sed 's/"indices":1/"indices":1,"mode":0/')" "no triangles"
refuse badjson.gltf '{"asset":{"version":"2.0"},"meshes":[' "does not parse"
refuse index.gltf "$(gltf_json ',"uri":"tet.bin"' | sed 's/"count":4,/"count":2,/')" "past its"
refuse stride.gltf "$(gltf_json ',"uri":"tet.bin"' | sed 's/"byteLength":48}/"byteLength":48,"byteStride":4}/')" "byteStride of 4, smaller than its 12-byte elements"
refuse flat.gltf "$(gltf_json ',"uri":"tet.bin"' '{"mesh":0,"scale":[0,0,0]}')" "has no area"
refuse nodata.gltf "$(gltf_json ',"uri":"tet.bin"' | sed 's/{"bufferView":0,"componentType":5126/{"componentType":5126/')" "has no area"
# The other formats' gaps: said in words, exit 1.
refuse_file() { # NAME WANT: $tmp/NAME exists
    if "$jade" render --mesh "$tmp/$1" --size 64x64 --out "$tmp/r.png" > "$tmp/out" 2>&1; then bad "$1 was accepted"
    elif grep -q "$2" "$tmp/out"; then ok "$1 refused: $(head -c 200 "$tmp/out" | head -1)"
    else bad "$1: $(cat "$tmp/out")"; fi
}
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n' > "$tmp/cloud.ply"
refuse_file cloud.ply "no faces (a point cloud)"
# The tetrahedron as triangle strips (-1 between them), ASCII and binary,
# as the Stanford repository's scans are stored: the same picture as its faces.
strip_hdr() { printf 'ply\nformat %s 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n' "$1"; }
{ strip_hdr ascii; printf '0 0 0\n1 0 0\n0 1 0\n0 0 1\n15 0 2 1 -1 0 1 3 -1 0 3 2 -1 1 2 3\n'; } > "$tmp/strips_ascii.ply"
{ strip_hdr binary_little_endian
  for c in 0 0 0 1 0 0 0 1 0 0 0 1; do if [ "$c" = 1 ]; then printf '\000\000\200\077'; else printf '\000\000\000\000'; fi; done
  le32 15; for i in 0 2 1 -1 0 1 3 -1 0 3 2 -1 1 2 3; do le32 "$i"; done; } > "$tmp/strips_binary.ply"
for f in strips_ascii.ply strips_binary.ply; do
    if ! render "$tmp/$f" "$tmp/$f.png"; then bad "$f: $(cat "$tmp/out")"; continue; fi
    rmse=$("$jade" metric "$tmp/$f.png" "$tmp/tet.ply.png" | sed -n 's/.*"rmse": \([0-9.]*\).*/\1/p')
    if awk "BEGIN { exit !($rmse < 0.001) }" && grep -q ": 4 triangles" "$tmp/out"; then ok "$f (tristrips): 4 triangles, the same picture as the faces (RMSE $rmse)"
    else bad "$f: RMSE $rmse against the PLY's faces; $(cat "$tmp/out")"; fi
done
{ strip_hdr ascii; printf '0 0 0\n1 0 0\n0 1 0\n0 0 1\n5 0 2 1 9 3\n'; } > "$tmp/strips_bad.ply"
refuse_file strips_bad.ply "tristrips refer to a vertex past the vertex count"
sed 's/format ascii 1.0/format binary_big_endian 1.0/' "$tmp/tet.ply" > "$tmp/big.ply"
refuse_file big.ply "PLY is binary big-endian, which jade's reader (libdraco) does not read"
sed 's/format ascii 1.0/format binary_littl\xff_endian 1.0/' "$tmp/tet.ply" > "$tmp/mangled.ply"
refuse_file mangled.ply "PLY format line 'binary_littl?_endian 1.0' is not ascii"
printf 'v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n' > "$tmp/flat.obj"
refuse_file flat.obj "has no area"
# OBJ faces whose numbers libdraco would index with unchecked (found by
# fuzzing: they crashed its reader, contained by the decoder's child).
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//11\n' > "$tmp/normal_past.obj"
refuse_file normal_past.obj "OBJ line 5: a face refers to normal 11, but the file has 1"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1-1\n' > "$tmp/corner.obj"
refuse_file corner.obj "OBJ line 5: face corner '3/1-1' is not v, v/vt, v//vn or v/vt/vn"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2 # a comment\nf 1 2 4#another\nf 1 4 3\nf 2 3 4\n' > "$tmp/comments.obj"
if render "$tmp/comments.obj" "$tmp/cm.png" && grep -q ": 4 triangles" "$tmp/out"; then ok "an OBJ with comments after its faces reads"
else bad "comments.obj: $(cat "$tmp/out")"; fi
printf 'f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 4\n' > "$tmp/faces_first.obj"
if render "$tmp/faces_first.obj" "$tmp/ff.png" && grep -q ": 2 triangles" "$tmp/out"; then ok "an OBJ with a face before its vertices still reads (as libdraco reads it)"
else bad "faces_first.obj: $(cat "$tmp/out")"; fi
# The binary tetrahedron with a count of 5 in its header (it holds 4).
{ head -c 80 "$tmp/tet_binary.stl"; printf '\005\000\000\000'; tail -c +85 "$tmp/tet_binary.stl"; } > "$tmp/count.stl"
refuse_file count.stl "binary STL with a wrong triangle count: its header says 5, its 284 bytes hold 4"
# jade convert: every format to Draco, rendering as the original does.
for f in tet.ply tet.obj tet_binary.stl tet_inline.gltf tet.glb tet_turned.gltf; do
    if ! "$jade" convert "$tmp/$f" "$tmp/conv_$f.drc" > "$tmp/out" 2>&1; then bad "convert $f: $(cat "$tmp/out")"; continue; fi
    if ! render "$tmp/conv_$f.drc" "$tmp/conv_$f.png" || ! render "$tmp/$f" "$tmp/orig_$f.png"; then bad "converted $f: $(cat "$tmp/out")"; continue; fi
    rmse=$("$jade" metric "$tmp/conv_$f.png" "$tmp/orig_$f.png" | sed -n 's/.*"rmse": \([0-9.]*\).*/\1/p')
    if awk "BEGIN { exit !($rmse < 0.001) }"; then ok "convert $f: the Draco file renders the same (RMSE $rmse)"
    else bad "convert $f: RMSE $rmse"; fi
done
cp "$tmp/conv_tet.ply.drc" "$tmp/keep.drc"
if "$jade" convert "$tmp/conv_tet.ply.drc" "$tmp/conv_tet.ply.drc" > "$tmp/out" 2>&1; then bad "convert over its input"
elif cmp -s "$tmp/keep.drc" "$tmp/conv_tet.ply.drc"; then ok "convert refuses to write over its input: $(cat "$tmp/out")"
else bad "convert changed its input"; fi
if "$jade" convert "$tmp/tet.obj" "$tmp/x.png" > "$tmp/out" 2>&1; then bad "convert to .png accepted"
else ok "convert refuses a non-.drc output: $(cat "$tmp/out")"; fi
if [ -d "$shared/testdata/gltf" ]; then
    for f in "$shared"/testdata/gltf/*.glb "$shared"/testdata/gltf/*.gltf; do
        [ -f "$f" ] || continue
        start=$(date +%s%N)
        if render "$f" "$tmp/$(basename "$f").png"; then
            ok "$(basename "$f"): $(sed -n 's/.*mesh [^:]*: \([0-9]* triangles\).*/\1/p' "$tmp/out") in $(( ($(date +%s%N) - start) / 1000000 )) ms"
        else bad "$(basename "$f"): $(cat "$tmp/out")"; fi
    done
    if [ -f "$tmp/Box.glb.png" ] && [ -f "$tmp/Box_Draco.glb.png" ]; then
        rmse=$("$jade" metric "$tmp/Box.glb.png" "$tmp/Box_Draco.glb.png" | sed -n 's/.*"rmse": \([0-9.]*\).*/\1/p')
        if awk "BEGIN { exit !($rmse < 0.01) }"; then ok "Box_Draco.glb renders as Box.glb (RMSE $rmse)"
        else bad "Box_Draco.glb against Box.glb: RMSE $rmse"; fi
    fi
else
    echo "$shared/testdata/gltf is absent: the glTF samples are not tried"
fi
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
finish formats
