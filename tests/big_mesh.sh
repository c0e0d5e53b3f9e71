#!/bin/sh
# A mesh far over 16-bit indices (a 500x500 sphere: 250,500 vertices,
# 500,000 triangles, written here as OBJ) on GPUs without 32-bit indices:
# the vc4 profile draws it in 16-bit chunks and must give the very picture
# the adreno3xx profile gives with 32-bit indices (no seam: both sum full's
# levels per fragment, gl_caps.h, and vc4's other limits change nothing in
# full mode here); the device and the mali400 and generic profiles render
# it; the default memory budget grows to hold it. The same with a colour
# texture: the chunks carry its coordinates and colours.
jade=$1 imgcmp=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
awk 'BEGIN { n = 500; m = 500; pi = 3.14159265358979
    for (i = 0; i <= n; i++) for (j = 0; j < m; j++) {
        t = pi * i / n; p = 2 * pi * j / m
        printf "v %.6f %.6f %.6f\n", sin(t) * cos(p), cos(t) * 1.6, sin(t) * sin(p) }
    for (i = 0; i < n; i++) for (j = 0; j < m; j++) {
        a = i * m + j + 1; b = i * m + (j + 1) % m + 1; c = (i + 1) * m + j + 1; d = (i + 1) * m + (j + 1) % m + 1
        printf "f %d %d %d\nf %d %d %d\n", a, c, b, b, c, d } }' > "$tmp/sphere.obj"
for prof in device vc4 adreno3xx mali400 generic; do
    start=$(date +%s%N)
    # The decode limit is raised: this test is about the chunks, and half a
    # million faces under a sanitizer on a loaded machine pass 1.5 s.
    if "$jade" render --mesh "$tmp/sphere.obj" --size 256x256 --decode-timeout-ms 60000 $([ "$prof" = device ] || echo --profile "$prof") \
        --out "$tmp/$prof.png" >"$tmp/out" 2>&1; then
        pass=$((pass + 1))
        echo "ok   $prof: $(head -n 1 "$tmp/out" | sed 's/.*mesh [^:]*: //') in $(( ($(date +%s%N) - start) / 1000000 )) ms; $(sed -n 's/.*\(arena peak [0-9]* bytes\).*/\1/p' "$tmp/out")"
    else
        fail=$((fail + 1)); echo "FAIL $prof: $(cat "$tmp/out")"
    fi
done
if cmp -s "$tmp/adreno3xx.png" "$tmp/vc4.png"; then
    pass=$((pass + 1)); echo "ok   16-bit chunks (vc4) give the 32-bit picture (adreno3xx) byte for byte"
else
    fail=$((fail + 1)); echo "FAIL the chunked picture differs: $("$jade" metric "$tmp/vc4.png" "$tmp/adreno3xx.png")"
fi
# Simplified as it loads (--simplify: meshoptimizer's edge collapses in the
# decoder), the sphere comes to at most the triangles asked for, and its
# picture stays that of the whole mesh: a Mali-400 draws it in a seventh of
# the vertex processor's time (docs/usage.md).
simplified() { # NAME MESH REFERENCE [render options]
    name=$1 mesh=$2 ref=$3
    shift 3
    if "$jade" render --mesh "$mesh" --simplify 20000 --size 256x256 --decode-timeout-ms 60000 "$@" --out "$tmp/$name.png" \
        >"$tmp/out" 2>&1 && n=$(sed -n 's/.*500000 triangles, simplified to \([0-9]*\)).*/\1/p' "$tmp/out" | head -1) &&
        [ -n "$n" ] && [ "$n" -le 20000 ] && [ "$n" -ge 10000 ] &&
        "$imgcmp" "$tmp/$name.png" "$ref" --max-rmse 1.5 --max-bad-frac 0.005 --bad-threshold 8 >"$tmp/cmp" 2>&1; then
        pass=$((pass + 1)); echo "ok   $name: 500,000 triangles simplified to $n, the picture the whole mesh's: $(tail -1 "$tmp/cmp")"
    elif grep -q "built without meshoptimizer" "$tmp/out"; then
        echo "skip $name: $(cat "$tmp/out")"
    else
        fail=$((fail + 1)); echo "FAIL $name: $(cat "$tmp/out") $(tail -1 "$tmp/cmp" 2>/dev/null)"
    fi
}
simplified simplified "$tmp/sphere.obj" "$tmp/mali400.png" --profile mali400
# The same sphere with jade's veined texture (texture coordinates and an
# MTL): the chunks carry the coordinates and colours too, no seam.
cp "$(dirname "$0")/../assets/textured/pebble.png" "$tmp/veined.png"
printf 'newmtl veined\nmap_Kd veined.png\n' > "$tmp/veined.mtl"
{ echo "mtllib veined.mtl"; grep '^v ' "$tmp/sphere.obj"
  awk 'BEGIN { n = 500; m = 500
      for (i = 0; i <= n; i++) for (j = 0; j < m; j++) printf "vt %.6f %.6f\n", 3 * j / m, 1 - i / n
      print "usemtl veined"
      for (i = 0; i < n; i++) for (j = 0; j < m; j++) {
          a = i * m + j + 1; b = i * m + (j + 1) % m + 1; c = (i + 1) * m + j + 1; d = (i + 1) * m + (j + 1) % m + 1
          printf "f %d/%d %d/%d %d/%d\nf %d/%d %d/%d %d/%d\n", a, a, c, c, b, b, b, b, c, c, d, d } }'; } > "$tmp/textured.obj"
for prof in vc4 adreno3xx; do
    if "$jade" render --mesh "$tmp/textured.obj" --size 256x256 --decode-timeout-ms 60000 --profile "$prof" \
        --out "$tmp/tex_$prof.png" >"$tmp/out" 2>&1 && grep -q "colour texture" "$tmp/out"; then :
    else fail=$((fail + 1)); echo "FAIL textured $prof: $(cat "$tmp/out")"; fi
done
if [ -f "$tmp/tex_vc4.png" ] && cmp -s "$tmp/tex_adreno3xx.png" "$tmp/tex_vc4.png"; then
    pass=$((pass + 1)); echo "ok   textured: 16-bit chunks (vc4) give the 32-bit picture (adreno3xx) byte for byte"
else
    fail=$((fail + 1)); echo "FAIL the textured chunked picture differs: $("$jade" metric "$tmp/tex_vc4.png" "$tmp/tex_adreno3xx.png" 2>&1)"
fi
# The frame-cost model says when the vertices bind a board's frame, and
# what to ask for: the sphere's 250,500 vertices on a Mali-400 MP2.
if "$jade" bench --mesh "$tmp/sphere.obj" --mode full --device mali400-mp2 --size 1920x1080 --frames 1 \
        --decode-timeout-ms 60000 >"$tmp/bench.json" 2>"$tmp/bench.err" &&
    n=$(sed -n 's/.*vertices bind the frame.*--simplify \([0-9]*\) would.*/\1/p' "$tmp/bench.err") && [ -n "$n" ] &&
    "$jade" bench --mesh "$tmp/sphere.obj" --simplify "$n" --mode full --device mali400-mp2 --size 1920x1080 --frames 1 \
        --decode-timeout-ms 60000 >"$tmp/bench2.json" 2>"$tmp/bench2.err" && ! grep -q "vertices bind" "$tmp/bench2.err"; then
    pass=$((pass + 1))
    echo "ok   bench --device mali400-mp2: $(grep "vertices bind" "$tmp/bench.err" | sed 's/^jade bench: //'); with it the frame $(grep -o '"frame_ms": [0-9.]*' "$tmp/bench2.json" | head -1)"
else
    fail=$((fail + 1)); echo "FAIL bench's --simplify hint: $(cat "$tmp/bench.err" "$tmp/bench2.err" 2>/dev/null)"
fi
# Simplified with its texture: the coordinates and colours follow the
# vertices kept.
[ -f "$tmp/tex_device.png" ] && simplified simplified_textured "$tmp/textured.obj" "$tmp/tex_device.png" \
    --light-azimuth 15 --light-elevation 35
echo "big mesh: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
