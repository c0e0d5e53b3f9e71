#!/bin/sh
# A box of 12 triangles in full against jade reference: the per-vertex terms
# (the levels summed at the vertices where the vertex stage reads textures,
# the Fresnel factors everywhere) need vertices about as close as the
# levels' texels, which the loader now makes (core/mesh_subdivide.c).
# Before it the box's faces came out a quarter to a third too dark here
# (RMSE 0.30-0.32; 0.047-0.049 split, full's own error on a box made
# dense: the same box with flat normals split 8 x 8 in the file, 0.038),
# the levels' light read only at the corners.
jade=$1
. "$(dirname "$0")/harness.sh"
box_obj "$tmp/box.obj"
scene="--mesh $tmp/box.obj --yaw 30 --pitch 25 --light-azimuth 20 --light-elevation 35 --size 96x96"
# shellcheck disable=SC2086
"$jade" reference $scene --quiet --out "$tmp/ref.png" --mask "$tmp/mask.png" >/dev/null || bad "jade reference did not run"
for p in desktop mali400 vc4; do
    opt="--profile $p"; [ $p = desktop ] && opt=""
    # shellcheck disable=SC2086
    "$jade" render $scene $opt --out "$tmp/$p.png" >/dev/null 2>&1 || { bad "jade render $opt did not run"; continue; }
    r=$("$jade" metric "$tmp/$p.png" "$tmp/ref.png" --mask "$tmp/mask.png" | sed -n 's/.*"rmse": \([0-9.]*\).*/\1/p')
    if awk -v r="$r" 'BEGIN { exit !(r != "" && r < 0.08) }'; then ok "full, $p profile, on a 12-triangle box: RMSE $r (under 0.08)"
    else bad "full, $p profile, on a 12-triangle box: RMSE $r (over 0.08)"; fi
done
finish "coarse mesh"
