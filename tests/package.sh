#!/bin/sh
# The .deb as an operator gets it: tools/package.sh builds it; it is
# unpacked into a throwaway root (dpkg-deb -x, no install on this machine);
# its contents, its conffile, its maintainer scripts' syntax and the unit
# (systemd-analyze verify, any message fails) are checked; the unpacked
# program renders the default scene from another folder, finding its asset
# beside itself, and the picture equals the build tree's. Skips (77) without
# cpack, dpkg-deb or systemd-analyze.
jade=$1
src=$(cd "$(dirname "$0")/.." && pwd)
for t in cpack dpkg-deb systemd-analyze; do
    command -v "$t" >/dev/null || { echo "SKIP: $t is not installed"; exit 77; }
done
. "$(dirname "$0")/harness.sh"
start=$(date +%s)
if ! deb=$("$src/tools/package.sh" "$tmp/build" 2>"$tmp/err" | tail -1) || [ ! -f "$deb" ]; then
    echo "FAIL tools/package.sh: $(tail -5 "$tmp/err")"
    exit 1
fi
ok "tools/package.sh built $(basename "$deb") ($(wc -c < "$deb") bytes) in $(( $(date +%s) - start )) s"
root=$tmp/root
dpkg-deb -x "$deb" "$root" && dpkg-deb -e "$deb" "$root/DEBIAN"
for f in usr/bin/jade usr/share/jade/default.drc usr/share/man/man1/jade.1.gz etc/jade/kiosk.conf \
         lib/systemd/system/jade-kiosk.service DEBIAN/postinst DEBIAN/prerm DEBIAN/conffiles; do
    if [ -f "$root/$f" ]; then ok "holds /$f"; else bad "no /$f in the package"; fi
done
if grep -qx /etc/jade/kiosk.conf "$root/DEBIAN/conffiles"; then ok "kiosk.conf is a conffile (kept across upgrades)"
else bad "kiosk.conf is not a conffile"; fi
if dpkg-deb -f "$deb" Depends | grep -q adduser; then ok "depends on adduser (postinst makes the jade user): $(dpkg-deb -f "$deb" Depends | cut -c1-120)..."
else bad "no adduser dependency"; fi
for s in postinst prerm; do
    if sh -n "$root/DEBIAN/$s"; then ok "$s parses"; else bad "$s has a syntax error"; fi
done
if grep -q "adduser --system" "$root/DEBIAN/postinst" && grep -q "video render input" "$root/DEBIAN/postinst"; then
    ok "postinst makes a system user jade in video, render and input"
else bad "postinst does not make the jade user"; fi
# The unit, as systemd reads it (ExecStart pointed at the unpacked program,
# which is not installed here).
mkdir -p "$tmp/unit"
sed "s|/usr/bin/jade|$root/usr/bin/jade|" "$root/lib/systemd/system/jade-kiosk.service" > "$tmp/unit/jade-kiosk.service"
if systemd-analyze verify --man=no "$tmp/unit/jade-kiosk.service" > "$tmp/verify" 2>&1 && [ ! -s "$tmp/verify" ]; then
    ok "systemd-analyze verify: jade-kiosk.service is clean"
else bad "systemd-analyze verify: $(cat "$tmp/verify")"; fi
for k in "User=jade" "Restart=on-failure" "ExecReload=" "--config /etc/jade/kiosk.conf"; do
    if grep -q -- "$k" "$root/lib/systemd/system/jade-kiosk.service"; then ok "unit has $k"; else bad "unit lacks $k"; fi
done
# The configuration the package ships is one the kiosk accepts.
if "$root/usr/bin/jade" kiosk --config "$root/etc/jade/kiosk.conf" --platform headless --frames 2 --size 64x48 \
    > "$tmp/kiosk" 2>&1; then ok "the shipped kiosk.conf is accepted: $(tail -1 "$tmp/kiosk")"
else bad "the shipped kiosk.conf: $(cat "$tmp/kiosk")"; fi
# Run from elsewhere: the asset is found beside the program.
mkdir "$tmp/elsewhere"
if (cd "$tmp/elsewhere" && "$root/usr/bin/jade" render --size 128x128 --out pkg.png > "$tmp/render" 2>&1) &&
   "$jade" render --size 128x128 --out "$tmp/tree.png" > /dev/null 2>&1; then
    rmse=$("$jade" metric "$tmp/elsewhere/pkg.png" "$tmp/tree.png" | sed -n 's/.*"rmse": \([0-9.]*\).*/\1/p')
    if [ "$rmse" = "0.000000" ] && grep -q "$root/usr/bin/../share/jade/default.drc" "$tmp/render"; then
        ok "the unpacked program renders from another folder, its asset found beside it (RMSE $rmse against the tree's)"
    else bad "unpacked render: RMSE $rmse; $(head -1 "$tmp/render")"; fi
else bad "unpacked render: $(cat "$tmp/render")"; fi
if zcat "$root/usr/share/man/man1/jade.1.gz" | grep -q "kiosk.conf"; then ok "the manual page documents kiosk.conf"
else bad "manual page"; fi
finish package
