#!/bin/sh
# Where full sums its levels (jd_renderer_desc.levels, --levels): on the
# GPUs whose vertex and fragment programs share their ALUs (Adreno 3xx,
# VideoCore IV, Vivante GC3000 and GC7000) per vertex on small meshes and
# per fragment on large ones
# (gl_caps.h, levels_per_fragment_from); per fragment on VideoCore IV with
# a colour texture, where per vertex full would lose its light scattered
# once (the light map is a sampler more); per vertex wherever else the
# vertex stage reads six textures; per fragment where it does not. Asked for, either way, where the GPU can;
# a one-line error where it cannot. The two ways give nearly one picture.
jade=$1
. "$(dirname "$0")/harness.sh"
here=$(dirname "$0")/..
knot=$here/assets/default.drc pebble=$here/assets/textured/pebble.gltf
levels() { # levels PROFILE MESH [options...]: bench's full_levels
    p=$1 m=$2
    shift 2
    "$jade" bench --profile "$p" --mode full --size 32x32 --frames 1 --mesh "$m" "$@" 2>/dev/null |
        sed -n 's/.*"full_levels": "\([^"]*\)".*/\1/p'
}
# The knot (46,080 vertices), the knot simplified to about 5,000 (--simplify
# 10000 triangles), 1,152 (2000) and 755 (1000), the textured pebble
# (1,225); the sizes from which the sum goes per fragment: Adreno 3xx
# 1,100, VideoCore IV 8,000, Vivante 1,350 (gl_caps.h).
while read -r prof name opts want; do
    mesh=$knot; [ "$name" = pebble ] && mesh=$pebble
    [ "$opts" = - ] && opts=
    want=$(echo "$want" | tr _ ' ')
    # shellcheck disable=SC2086
    got=$(levels "$prof" "$mesh" $opts)
    if [ "$got" = "$want" ]; then ok "$prof, the $name${opts:+ $opts}: $got"
    else bad "$prof, the $name${opts:+ $opts}: '$got', want '$want'"; fi
done <<'CASES'
adreno3xx knot - per_fragment
adreno3xx knot --simplify=10000 per_fragment
adreno3xx knot --simplify=1000 per_vertex
adreno3xx pebble - per_fragment
vc4 knot - per_fragment
vc4 knot --simplify=10000 per_vertex
vc4 pebble - per_fragment
gc7000l knot - per_fragment
gc7000l knot --simplify=2000 per_vertex
gc7000l pebble - per_vertex
vivante knot --simplify=2000 per_fragment
mali400 knot --simplify=2000 per_fragment
adreno3xx knot --levels=vertex per_vertex
vc4 pebble --levels=vertex per_vertex
gc7000l pebble --levels=fragment per_fragment
CASES
for p in adreno3xx vc4; do
    "$jade" render --profile $p --levels vertex --size 128x128 --light-azimuth 160 --out "$tmp/v_$p.png" >/dev/null 2>&1 &&
        "$jade" render --profile $p --levels fragment --size 128x128 --light-azimuth 160 --out "$tmp/f_$p.png" >/dev/null 2>&1 ||
        bad "$p: jade render --levels did not run"
    # 0.0096 while both took the slab's light through thin parts; 0.0133
    # since the sum per vertex takes the light scattered once along the
    # camera ray instead (mesh.vert, jd_single_march), which the sum per
    # fragment does not read.
    within "$p, the knot back-lit, per vertex against per fragment: RMSE" \
        "$("$jade" metric "$tmp/v_$p.png" "$tmp/f_$p.png" | field rmse)" 0.015
done
# Per vertex on VideoCore IV with a colour texture, asked for: drawn, without
# the light scattered once (render_program.c, JD_NO_SLAB: the light map is a
# sampler more).
if "$jade" render --profile vc4 --levels vertex --mesh "$pebble" --size 64x64 --out "$tmp/pv.png" >/dev/null 2>&1 &&
    [ -s "$tmp/pv.png" ]; then ok "vc4, the pebble per vertex, asked for: drawn"
else bad "vc4, the pebble per vertex, asked for: not drawn"; fi
# Where it cannot be: one line, non-zero.
for case in "mali400||under 6 vertex texture units" "vc4|--fragment-thickness|thickness is read per fragment"; do
    p=${case%%|*} rest=${case#*|} opt=${case#*|}
    opt=${opt%%|*} want=${rest#*|}
    # shellcheck disable=SC2086
    "$jade" render --profile "$p" --levels vertex $opt --size 32x32 --out "$tmp/no.png" >/dev/null 2>"$tmp/err"
    rc=$?
    if [ $rc -ne 0 ] && [ "$(wc -l < "$tmp/err")" -eq 1 ] && grep -q "$want" "$tmp/err" && [ ! -e "$tmp/no.png" ]; then
        ok "$p --levels vertex $opt: rc $rc, $(cat "$tmp/err")"
    else bad "$p --levels vertex $opt: rc $rc, $(cat "$tmp/err")"; fi
done
"$jade" render --levels sideways --size 32x32 --out "$tmp/no.png" >/dev/null 2>"$tmp/err"
rc=$?
if [ $rc -eq 2 ] && grep -q "expected auto, vertex or fragment, got 'sideways'" "$tmp/err"; then ok "--levels sideways: $(cat "$tmp/err")"
else bad "--levels sideways: rc $rc, $(cat "$tmp/err")"; fi
finish "levels"
