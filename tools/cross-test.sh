#!/bin/sh
# Cross-builds jade for aarch64 and armhf with the toolchain files and runs
# the GL-free tests (units, the Draco reference comparison, hostile inputs,
# DRM selection, the image metric)
# under qemu-user; then builds each board's .deb (tools/package.sh --arch)
# and runs the unpacked program's --help, convert and metric under qemu. --sizes also reports the stripped size of the aarch64
# program with Draco linked dynamically and statically.
#
# An architecture whose packages could not be set up (setup-cross.sh says
# why: a broken package index, packages that cannot be installed) is
# skipped with that reason; a build or a test that fails on an architecture
# that was set up fails the run.
set -eu
cd "$(dirname "$0")/.."
status=build-cross/status
JADE_CROSS_STATUS=$status ./tools/setup-cross.sh
jobs=$(nproc)
ready() { grep -qx "ready $1" "$status"; }
for arch in arm64 armhf; do
    case $arch in arm64) triple=aarch64-linux-gnu ;; armhf) triple=arm-linux-gnueabihf ;; esac
    if ! ready "$arch"; then
        echo "skipped: $arch ($(sed -n "s/^skipped $arch //p" "$status" | head -1))"
        continue
    fi
    dir=build-$triple
    echo "== $triple"
    cmake -S . -B "$dir" -DCMAKE_TOOLCHAIN_FILE="toolchains/$triple.cmake" -DCMAKE_BUILD_TYPE=Release >/dev/null
    cmake --build "$dir" -j"$jobs" >/dev/null
    file "$dir/jade" | sed 's/, BuildID.*//'
    (cd "$dir" && ctest --output-on-failure -R '^(units|draco_reference|bad_inputs|drm_select|metric)$')
    # The board's package: built, unpacked into a throwaway root, and its
    # program's GL-free commands run under qemu-user from there.
    echo "== $triple package"
    deb=$(./tools/package.sh "build-pkg-$arch" --arch "$arch" | tail -1)
    echo "$(basename "$deb"): $(wc -c < "$deb") bytes, Architecture: $(dpkg-deb -f "$deb" Architecture), Depends: $(dpkg-deb -f "$deb" Depends)"
    root=$(mktemp -d)
    dpkg-deb -x "$deb" "$root"
    case $arch in arm64) qemu=qemu-aarch64 ;; armhf) qemu=qemu-arm ;; esac
    "$qemu" "$root/usr/bin/jade" --help > "$root/help.txt"
    grep -q "render a mesh in translucent material" "$root/help.txt" || { echo "packaged jade --help says: $(head -3 "$root/help.txt")"; exit 1; }
    printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' > "$root/tet.obj"
    "$qemu" "$root/usr/bin/jade" convert "$root/tet.obj" "$root/tet.drc"
    [ "$(head -c 5 "$root/tet.drc")" = DRACO ] || { echo "packaged jade convert wrote no Draco file"; exit 1; }
    m=$("$qemu" "$root/usr/bin/jade" metric tests/golden/knot_full_marble.png tests/golden/knot_full_marble.png)
    echo "$m" | grep -q '"rmse": 0.000000' || { echo "packaged jade metric says: $m"; exit 1; }
    echo "packaged jade under $qemu: --help, convert (tet.obj -> $(wc -c < "$root/tet.drc") bytes of Draco), metric (RMSE 0 against itself)"
    rm -rf "$root"
done
# The board-sysroot path: a sysroot made only of Debian's arm64 packages
# (what a Raspberry Pi OS image holds), no multiarch involved.
sysroot=${JADE_TEST_SYSROOT:-/tmp/jade-sysroot-arm64}
if ! ready arm64; then
    echo "skipped: arm64 sysroot build (no arm64 package index or cross compiler)"
    exit 0
fi
# (Made again when an older run's sysroot lacks a package added since.)
if [ ! -f "$sysroot/usr/lib/aarch64-linux-gnu/pkgconfig/draco.pc" ] ||
   [ ! -f "$sysroot/usr/lib/aarch64-linux-gnu/pkgconfig/libcjson.pc" ] ||
   [ ! -f "$sysroot/usr/lib/aarch64-linux-gnu/pkgconfig/libjpeg.pc" ] ||
   [ ! -d "$sysroot/usr/lib/aarch64-linux-gnu/cmake/meshoptimizer" ]; then
    mkdir -p "$sysroot.debs"
    # shellcheck disable=SC2046
    if ! err=$(cd "$sysroot.debs" && apt-get download $(for p in libc6 libc6-dev linux-libc-dev libgcc-s1 libgcc-12-dev \
        libstdc++6 libstdc++-12-dev libdraco7 libdraco-dev libegl1 libegl-dev libglvnd0 libgles2 libgles1 \
        libgles-dev libgl-dev libgl1 libglx0 libglx-dev libopengl0 libx11-dev libx11-6 libxcb1 libxau6 \
        libxdmcp6 libbsd0 libmd0 libstb0 libstb-dev libcjson1 libcjson-dev libpng16-16 libpng-dev \
        libjpeg62-turbo libjpeg62-turbo-dev zlib1g zlib1g-dev libmeshoptimizer2d libmeshoptimizer-dev; do
            echo "$p:arm64"; done) x11proto-dev 2>&1 >/dev/null); then
        echo "skipped: arm64 sysroot build (packages could not be downloaded: $(echo "$err" | grep '^E:' | tail -1))"
        rm -rf "$sysroot.debs"
        exit 0
    fi
    for f in "$sysroot.debs"/*.deb; do dpkg -x "$f" "$sysroot"; done
fi
echo "== aarch64-linux-gnu with the sysroot $sysroot"
cmake -S . -B build-aarch64-sysroot -DCMAKE_TOOLCHAIN_FILE=toolchains/aarch64-linux-gnu.cmake -DJADE_SYSROOT="$sysroot" \
    -DCMAKE_BUILD_TYPE=Release >/dev/null
grep -q "DRACO_LIBRARY_DIRS:INTERNAL=$sysroot" build-aarch64-sysroot/CMakeCache.txt ||
    { echo "pkg-config did not resolve Draco inside the sysroot"; exit 1; }
grep -q "meshoptimizer_DIR:PATH=$sysroot" build-aarch64-sysroot/CMakeCache.txt ||
    { echo "meshoptimizer (triangle order, --simplify) was not found inside the sysroot"; exit 1; }
cmake --build build-aarch64-sysroot -j"$jobs" >/dev/null
(cd build-aarch64-sysroot && ctest --output-on-failure -R '^(units|bad_inputs)$')
# The examples against that build installed into the sysroot, as a board's
# SDK would hold it (prefix /opt/jade inside it): examples/ with
# find_package(jade) and the toolchain file, and embed.c with the cross
# compiler and pkg-config pointed into the sysroot. Linked, not run: the
# sysroot has no GL driver.
rm -rf "$sysroot/opt/jade" build-aarch64-examples
DESTDIR="$sysroot" cmake --install build-aarch64-sysroot --prefix /opt/jade >/dev/null
cmake -S examples -B build-aarch64-examples -DCMAKE_TOOLCHAIN_FILE="$(pwd)/toolchains/aarch64-linux-gnu.cmake" \
    -DJADE_SYSROOT="$sysroot" -DCMAKE_PREFIX_PATH=/opt/jade >/dev/null
cmake --build build-aarch64-examples >/dev/null
echo "examples/ against the sysroot's jade, find_package(jade): $(file build-aarch64-examples/embed | sed 's/.*: //; s/, BuildID.*//')"
PKG_CONFIG_SYSROOT_DIR="$sysroot" \
PKG_CONFIG_LIBDIR="$sysroot/opt/jade/lib/pkgconfig:$sysroot/usr/lib/aarch64-linux-gnu/pkgconfig:$sysroot/usr/share/pkgconfig" \
    sh -c 'aarch64-linux-gnu-gcc --sysroot="$1" -std=c11 -Wall -Wextra -o build-aarch64-examples/embed_pc examples/embed.c \
        $(pkg-config --cflags --libs jade egl glesv2)' sh "$sysroot"
echo "examples/embed.c against the sysroot's jade, pkg-config: $(file build-aarch64-examples/embed_pc | sed 's/.*: //; s/, BuildID.*//')"

if [ "${1:-}" = "--sizes" ]; then
    cmake -S . -B build-aarch64-static -DCMAKE_TOOLCHAIN_FILE=toolchains/aarch64-linux-gnu.cmake \
        -DCMAKE_BUILD_TYPE=Release -DJADE_STATIC_DRACO=ON -DJADE_TESTS=OFF >/dev/null
    cmake --build build-aarch64-static -j"$jobs" >/dev/null
    for d in build-aarch64-linux-gnu build-aarch64-static; do
        aarch64-linux-gnu-strip -o "$d/jade.stripped" "$d/jade"
        echo "$d/jade stripped: $(wc -c < "$d/jade.stripped") bytes; needs: $(aarch64-linux-gnu-readelf -d "$d/jade" | grep NEEDED | sed 's/.*\[\(.*\)\]/\1/' | tr '\n' ' ')"
    done
fi
