#!/bin/sh
# full's highlight, as the picture shows it: the strength it adds (RMSE of
# --specular 1 against 0) under the mali400 profile, where it is read from
# a table (pass_screen.c, jdr_update_spec), within 10% of the desktop's,
# which takes the power per fragment. On a 12-triangle box (culled: the
# table's normal is the interpolated one as it comes) and on an open sheet
# drawn with --no-cull from either side, lit from the side it is seen from
# (the back's normal turned to the eye: without it the back had no
# highlight, RMSE 0). Here: box 0.109 / 0.110, sheet 0.152 / 0.153 and
# 0.154 / 0.154.
jade=$1
. "$(dirname "$0")/harness.sh"
box_obj "$tmp/box.obj"
printf 'v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3\nf 1 3 4\n' > "$tmp/sheet.obj"
# strength NAME PROFILE SCENE...: the RMSE the highlight adds, in $s
strength() {
    name=$1 prof=$2; shift 2
    opt="--profile $prof"; [ "$prof" = desktop ] && opt=""
    for k in 0 1; do
        # shellcheck disable=SC2086
        "$jade" render "$@" $opt --size 128x128 --specular $k --out "$tmp/$name.$prof.$k.png" >/dev/null 2>&1 ||
            { bad "$name, $prof: jade render did not run"; s=""; return; }
    done
    s=$("$jade" metric "$tmp/$name.$prof.0.png" "$tmp/$name.$prof.1.png" | sed -n 's/.*"rmse": \([0-9.]*\).*/\1/p')
}
check() {
    name=$1; shift
    strength "$name" desktop "$@"; d=$s
    strength "$name" mali400 "$@"; m=$s
    if awk -v d="$d" -v m="$m" 'BEGIN { exit !(d != "" && m != "" && d > 0.05 && m > 0.9 * d && m < 1.1 * d) }'; then
        ok "$name: the highlight adds $m (mali400, its table) and $d (desktop)"
    else bad "$name: the highlight adds $m (mali400, its table) and $d (desktop): not within 10%"; fi
}
check "box" --mesh "$tmp/box.obj" --distance 2 --light-azimuth 40 --light-elevation 30
check "sheet, front" --mesh "$tmp/sheet.obj" --no-cull --yaw 0 --pitch 10 --light-azimuth 0 --light-elevation 30
check "sheet, back" --mesh "$tmp/sheet.obj" --no-cull --yaw 180 --pitch 10 --light-azimuth 180 --light-elevation 30
finish "highlight"
