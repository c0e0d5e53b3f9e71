#!/bin/sh
# Builds the Debian package: tools/package.sh [BUILD_DIR] [--arch arm64|armhf]
# -> BUILD_DIR/jade_VERSION_ARCH.deb (the program, its default asset, the
# manual page, /etc/jade/kiosk.conf and the jade-kiosk systemd unit;
# postinst adds the user "jade" in the video, render and input groups).
# --arch cross-builds it for a board with toolchains/ (the cross packages
# of tools/setup-cross.sh), for Raspberry Pi OS and Armbian. Install it
# with: sudo apt install ./jade_*.deb
set -eu
cd "$(dirname "$0")/.."
dir=build-pkg arch=""
while [ $# -gt 0 ]; do
    case $1 in
        --arch) arch=${2:-}; shift 2 ;;
        -*) echo "usage: $0 [BUILD_DIR] [--arch arm64|armhf]" >&2; exit 2 ;;
        *) dir=$1; shift ;;
    esac
done
toolchain=""
case $arch in
    "") ;;
    arm64) toolchain=-DCMAKE_TOOLCHAIN_FILE=toolchains/aarch64-linux-gnu.cmake ;;
    armhf) toolchain=-DCMAKE_TOOLCHAIN_FILE=toolchains/arm-linux-gnueabihf.cmake ;;
    *) echo "$0: --arch: '$arch' is not arm64 or armhf" >&2; exit 2 ;;
esac
# shellcheck disable=SC2086
cmake -S . -B "$dir" $toolchain -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr -DJADE_PACKAGE=ON -DJADE_TESTS=OFF >/dev/null
cmake --build "$dir" -j"$(nproc)" >/dev/null
(cd "$dir" && cpack -G DEB >/dev/null)
ls "$dir"/jade_*.deb
