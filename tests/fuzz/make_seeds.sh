#!/bin/sh
# Writes the fuzz targets' seed corpora (tests/fuzz/corpus/<target>), all
# from jade's own tiny shapes: a tetrahedron encoded by Debian's
# draco_encoder both ways, with and without metadata, and small pictures.
# Run again after a format change; the results are committed.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
c=$here/corpus
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$c/fuzz_draco_header" "$c/fuzz_metadata" "$c/fuzz_mesh_load" "$c/fuzz_mesh_text" "$c/fuzz_gltf" "$c/fuzz_image" "$c/fuzz_options" \
    "$c/fuzz_texture"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1/1 3/3/1 2/2/1\nf 1/1/1 2/2/1 4/3/1\nf 1/1/1 4/3/1 3/2/1\nf 2/2/1 3/3/1 4/1/1\n' > "$tmp/tet.obj"
draco_encoder -i "$tmp/tet.obj" -o "$tmp/seq.drc" -cl 0 >/dev/null
draco_encoder -i "$tmp/tet.obj" -o "$tmp/eb.drc" -cl 7 >/dev/null
draco_encoder -i "$tmp/tet.obj" -o "$tmp/raw.drc" -cl 0 -qp 0 -qt 0 -qn 0 >/dev/null
python3 - "$tmp" "$c" <<'PY'
import sys, os
tmp, c = sys.argv[1], sys.argv[2]
def varint(v):
    out = b''
    while True:
        b = v & 0x7f; v >>= 7
        if v: out += bytes([b | 0x80])
        else: return out + bytes([b])
def nested(depth):
    m = varint(1) + b'\x04name' + varint(3) + b'tet' + varint(0)
    for _ in range(depth):
        m = varint(0) + varint(1) + b'\x03sub' + m
    return varint(1) + varint(0) + varint(0) + varint(0) + m   # one (empty) attribute metadata, then the file's
meshes = {n: open(f'{tmp}/{n}.drc', 'rb').read() for n in ('seq', 'eb', 'raw')}
for n, b in meshes.items():
    for d in ('fuzz_draco_header', 'fuzz_mesh_load'):
        open(f'{c}/{d}/{n}.drc', 'wb').write(b)
    meta = bytearray(b[:11]); meta[10] |= 0x80
    for depth in (0, 3):
        for d in ('fuzz_draco_header', 'fuzz_mesh_load'):
            open(f'{c}/{d}/{n}-meta{depth}.drc', 'wb').write(bytes(meta) + nested(depth) + b[11:])
        open(f'{c}/fuzz_metadata/{n}-meta{depth}', 'wb').write(nested(depth) + b[11:])
PY
# The other mesh formats, for the sandboxed load: OBJ, PLY, ASCII and binary STL.
cp "$tmp/tet.obj" "$c/fuzz_mesh_load/tet.obj"
# Faces with numbers past their arrays and a malformed corner: libdraco's
# OBJ reader crashed on such (core/obj_check.c names them now).
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//11\n' > "$c/fuzz_mesh_load/normal_past.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1-1\n' > "$c/fuzz_mesh_load/corner.obj"
printf 'ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' > "$c/fuzz_mesh_load/tet.ply"
printf 'ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n7 0 2 1 3 -1 1 2\n' > "$c/fuzz_mesh_load/strips.ply"
python3 - "$c/fuzz_mesh_load/strips_binary.ply" <<'PY'
import struct, sys
h = (b'ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n'
     b'element tristrips 1\nproperty list int int vertex_indices\nend_header\n')
s = [0, 2, 1, 3, -1, 1, 2, 3]
open(sys.argv[1], 'wb').write(h + struct.pack('<12f', 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1) + struct.pack('<i', len(s)) +
                              struct.pack('<%di' % len(s), *s))
PY
printf 'solid t\nfacet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid t\n' > "$c/fuzz_mesh_load/tri.stl"
python3 - "$c/fuzz_mesh_load/tri_binary.stl" <<'PY'
import struct, sys
open(sys.argv[1], 'wb').write(b'solid binary'.ljust(80, b' ') + struct.pack('<I', 1) +
                              struct.pack('<12fH', 0, 0, -1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0))
PY
# The text meshes again for jade's own checks on them, in process.
for f in tet.obj tet.ply strips.ply strips_binary.ply normal_past.obj corner.obj; do
    cp "$c/fuzz_mesh_load/$f" "$c/fuzz_mesh_text/$f"
done
# glTF: the tetrahedron as .gltf (inline buffer, a node with TRS, a
# material's extras; another with the translucency extensions), as .glb, and as a .glb whose primitive is the Draco
# encoding above (KHR_draco_mesh_compression), for both the reader and the load.
python3 - "$tmp" "$c" <<'PY'
import sys, struct, json, base64
tmp, c = sys.argv[1], sys.argv[2]
pos = struct.pack('<12f', 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1)
idx = struct.pack('<12H', 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3)
def doc(uri, blen, views, accessors, prim, extra={}):
    d = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
         "nodes": [{"children": [1], "rotation": [0, 0.7071068, 0, 0.7071068]}, {"mesh": 0, "scale": [1, 2, 1]}],
         "meshes": [{"primitives": [prim]}], "materials": [{"extras": {"jade_material": "skin1"}}],
         "buffers": [dict({"byteLength": blen}, **({"uri": uri} if uri else {}))],
         "bufferViews": views, "accessors": accessors}
    d.update(extra)
    return json.dumps(d).encode()
plain_views = [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 24}]
plain_acc = [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
             {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}]
plain_prim = {"attributes": {"POSITION": 0}, "indices": 1, "material": 0}
def glb(j, b):
    j += b' ' * (-len(j) % 4)
    b += b'\0' * (-len(b) % 4)
    return (b'glTF' + struct.pack('<II', 2, 28 + len(j) + len(b)) + struct.pack('<I', len(j)) + b'JSON' + j +
            struct.pack('<I', len(b)) + b'BIN\0' + b)
inline = doc('data:application/octet-stream;base64,' + base64.b64encode(pos + idx).decode(), 72, plain_views,
             plain_acc, plain_prim)
binary = glb(doc(None, 72, plain_views, plain_acc, plain_prim), pos + idx)
drc = open(f'{tmp}/eb.drc', 'rb').read()
draco = glb(doc(None, len(drc), [{"buffer": 0, "byteLength": len(drc)}],
                [{"componentType": 5126, "count": 4, "type": "VEC3"},
                 {"componentType": 5123, "count": 12, "type": "SCALAR"}],
                {"attributes": {"POSITION": 0}, "indices": 1, "material": 0,
                 "extensions": {"KHR_draco_mesh_compression": {"bufferView": 0, "attributes": {"POSITION": 0}}}},
                {"extensionsUsed": ["KHR_draco_mesh_compression"], "extensionsRequired": ["KHR_draco_mesh_compression"]}),
            drc)
# A material with glTF's translucency extensions.
medium = {"KHR_materials_volume": {"attenuationDistance": 0.01, "attenuationColor": [0.5, 0.3, 0.2]},
          "KHR_materials_volume_scatter": {"multiscatterColor": [0.9, 0.6, 0.4], "scatterAnisotropy": 0.2},
          "KHR_materials_ior": {"ior": 1.4}}
volume = doc('data:application/octet-stream;base64,' + base64.b64encode(pos + idx).decode(), 72, plain_views,
             plain_acc, plain_prim, {"materials": [{"extensions": medium}]})
for d in ('fuzz_gltf', 'fuzz_mesh_load'):
    open(f'{c}/{d}/tet.gltf', 'wb').write(inline)
    open(f'{c}/{d}/tet_volume.gltf', 'wb').write(volume)
    open(f'{c}/{d}/tet.glb', 'wb').write(binary)
    open(f'{c}/{d}/tet_draco.glb', 'wb').write(draco)
PY
# Pictures: a 2x2 PFM with LF and with CR LF ends, a PPM, a BMP and a PNG
# (the PNG written by python's zlib, no image library needed).
python3 - "$c/fuzz_image" <<'PY'
import sys, struct, zlib
d = sys.argv[1]
px = struct.pack('<12f', 0, 0, 0, 1, 1, 1, 0.5, 0.25, 0.125, 2, 2, 2)
open(f'{d}/lf.pfm', 'wb').write(b'PF\n2 2\n-1.0\n' + px)
open(f'{d}/crlf.pfm', 'wb').write(b'PF\r\n2 2\r\n-1.0\r\n' + px)
open(f'{d}/tiny.ppm', 'wb').write(b'P6\n2 2\n255\n' + bytes(range(12)))
row = b'\x00\x00\xff\xff\xff\x00\x00'
bmp_px = (b'\x00\x00\xff\xff\xff\xff' + b'\x00\x00') * 2
open(f'{d}/tiny.bmp', 'wb').write(b'BM' + struct.pack('<IHHI', 54 + len(bmp_px), 0, 0, 54) +
                                  struct.pack('<IiiHHIIiiII', 40, 2, 2, 1, 24, 0, len(bmp_px), 2835, 2835, 0, 0) + bmp_px)
def chunk(t, b): return struct.pack('>I', len(b)) + t + b + struct.pack('>I', zlib.crc32(t + b) & 0xffffffff)
raw = b''.join(b'\x00' + bytes([x * 60, y * 60, 90, 255]) * 1 + bytes([200, 10, 10, 255]) for y in range(2) for x in range(1))
png = b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', 2, 2, 8, 6, 0, 0, 0)) + \
      chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b'')
open(f'{d}/tiny.png', 'wb').write(png)
PY
# Colour textures: the PNG above, and a JPEG (baseline and progressive)
# written by stb_image_write; a glTF tetrahedron with the PNG as its base
# colour texture in a data: URI.
cp "$c/fuzz_image/tiny.png" "$c/fuzz_texture/tiny.png"
cat > "$tmp/jpg.c" <<'C'
#include <stb_image_write.h>
int main(int argc, char **argv)
{
    unsigned char px[8 * 8 * 3];
    for (int i = 0; i < 8 * 8 * 3; i++) px[i] = (unsigned char)(i * 37);
    (void)argc;
    return !stbi_write_jpg(argv[1], 8, 8, 3, px, 80);
}
C
cc -o "$tmp/jpg" "$tmp/jpg.c" $(pkg-config --cflags --libs stb) && "$tmp/jpg" "$c/fuzz_texture/tiny.jpg"
python3 - "$c" <<'PY'
import sys, base64, json
c = sys.argv[1]
g = json.load(open(f'{c}/fuzz_gltf/tet.gltf'))
png = open(f'{c}/fuzz_texture/tiny.png', 'rb').read()
g['materials'] = [{'pbrMetallicRoughness': {'baseColorTexture': {'index': 0}, 'baseColorFactor': [1, 0.5, 0.5, 1]}}]
g['textures'] = [{'source': 0}]
g['images'] = [{'uri': 'data:image/png;base64,' + base64.b64encode(png).decode()}]
open(f'{c}/fuzz_gltf/tet_texture.gltf', 'w').write(json.dumps(g))
# The same as gltfpack writes it: the extensions its quantization needs
# required, the texture's coordinates through KHR_texture_transform.
g['materials'][0]['pbrMetallicRoughness']['baseColorTexture']['extensions'] = {
    'KHR_texture_transform': {'offset': [0.5, 0], 'rotation': 0.3, 'scale': [2, 2]}}
g['extensionsUsed'] = g['extensionsRequired'] = ['KHR_mesh_quantization', 'KHR_texture_transform']
open(f'{c}/fuzz_gltf/tet_quant.gltf', 'w').write(json.dumps(g))
PY
# Argument lists: the first byte picks the command (0 render, 1 bench,
# 2 info, 3 view, 4 kiosk, 5 reference, 6 metric), then NUL-separated words.
o=$c/fuzz_options
printf '\000--size\000640x480\000--mode\000dual\000--sigma-s=1,2,3' > "$o/render"
printf '\001--mode=all\000--frames\00010\000--material\000skin1' > "$o/bench"
printf '\002--profile\000mali400' > "$o/info"
printf '\004--platform\000headless\000--rotate\00090\000--atomic' > "$o/kiosk"
printf '\005--samples\00020000\000--error\0000.02\000--quiet' > "$o/reference"
printf '\006a.png\000b.png\000--mask\000m.png' > "$o/metric"
echo "seeds written under $c"
