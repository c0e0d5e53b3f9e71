#!/bin/sh
# Builds the Debian package: tools/package.sh [BUILD_DIR] -> BUILD_DIR/jade_VERSION_ARCH.deb
# (the program, its default asset, the manual page, /etc/jade/kiosk.conf and
# the jade-kiosk systemd unit; postinst adds the user "jade" in the video,
# render and input groups). Install it with: sudo apt install ./jade_*.deb
set -eu
cd "$(dirname "$0")/.."
dir=${1:-build-pkg}
cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr -DJADE_PACKAGE=ON -DJADE_TESTS=OFF >/dev/null
cmake --build "$dir" -j"$(nproc)" >/dev/null
(cd "$dir" && cpack -G DEB >/dev/null)
ls "$dir"/jade_*.deb
