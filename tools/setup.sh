#!/bin/sh
# Installs what jade needs on Debian 12, skipping what is already there.
# As root it runs apt-get; otherwise it prints the exact command and stops.
#
# A package source that fails is reported as such, by name. What jade cannot
# build without (compiler, EGL/GLES, Draco, libpng, libjpeg-turbo, stb) stops the run; the rest
# (the X11 and DRM/KMS platforms, meshoptimizer's triangle order, glTF through cJSON, the GLSL
# validator, Xvfb, Python for the JSON checks, clang for the fuzz targets,
# Mesa's build tools for the device compilers) is left out with the reason,
# and the build and tests that do not need it go on: CMake
# leaves out a platform whose library is missing, and the tests that need a
# missing tool say they are skipped.
set -eu
here=$(dirname "$0")
. "$here/apt-source.sh"
required="build-essential cmake pkg-config libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri libdraco-dev draco
          libpng-dev libjpeg62-turbo-dev libstb-dev"
optional="libgbm-dev libdrm-dev libinput-dev libudev-dev libx11-dev libmeshoptimizer-dev libcjson-dev glslang-tools xvfb python3 clang libclang-rt-14-dev
          dpkg-dev meson ninja-build bison flex python3-mako libexpat1-dev zlib1g-dev"
# shellcheck disable=SC2086
missing_req=$("$here/missing-packages.sh" $required)
# shellcheck disable=SC2086
missing_opt=$("$here/missing-packages.sh" $optional)
[ -z "$missing_req$missing_opt" ] && exit 0
if [ "$(id -u)" -ne 0 ]; then
    echo "jade needs these Debian packages:$missing_req$missing_opt"
    echo "run: sudo apt-get update && sudo apt-get install -y$missing_req$missing_opt"
    exit 1
fi
export DEBIAN_FRONTEND=noninteractive
jd_apt_update "$(dpkg --print-architecture)"
broken=$(jd_apt_index_failure "$(dpkg --print-architecture)")
[ -n "$broken" ] && echo "setup: a package index failed ($broken); going on with the indexes apt has"
if [ -n "$missing_req" ]; then
    # shellcheck disable=SC2086
    if ! jd_apt_install "" $missing_req; then
        echo "setup: the package source failed for packages jade cannot build without:$missing_req"
        echo "setup: apt says: $(jd_apt_last_error)"
        exit 1
    fi
fi
for p in $missing_opt; do
    jd_apt_install "" "$p" >/dev/null ||
        echo "skipped: $p (package source failed: $(jd_apt_last_error)); what needs it is left out"
done
