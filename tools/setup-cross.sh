#!/bin/sh
# Prepares a Debian 12 machine to cross-build jade with Debian multiarch: the
# foreign architectures, the cross compilers, the target -dev packages and
# qemu-user to run target tests. As root it runs apt-get; otherwise it prints
# the commands.
#
# A package source that fails is not jade's failure: an architecture whose
# package index cannot be fetched (a mirror caught mid-sync), or whose
# packages cannot be installed, is skipped with the reason, and the others
# are set up. The outcome goes to $JADE_CROSS_STATUS (default
# build-cross/status), one line per architecture, read by cross-test.sh:
#   ready ARCH
#   skipped ARCH REASON
# JADE_CROSS_ARCHS picks the architectures [arm64 armhf]; JADE_APT_OPTS adds
# options to every apt-get call (the script's own test points apt at a local
# repository with them); JADE_CROSS_DRY=1 says what it would install instead,
# JADE_CROSS_FORCE=1 as if nothing were installed.
set -eu
here=$(dirname "$0")
. "$here/apt-source.sh"
archs=${JADE_CROSS_ARCHS:-"arm64 armhf"}
status=${JADE_CROSS_STATUS:-build-cross/status}
mkdir -p "$(dirname "$status")"
: > "$status"
pkgs_of() { echo "crossbuild-essential-$1 libdraco-dev:$1 libpng-dev:$1 libjpeg62-turbo-dev:$1 libstb-dev:$1 libegl-dev:$1 libgles-dev:$1 libgbm-dev:$1 libdrm-dev:$1 libx11-dev:$1 libcjson-dev:$1 libinput-dev:$1 libmeshoptimizer-dev:$1"; }
skip() { echo "skipped $1 $2" >> "$status"; echo "skipped: $1 ($2)"; }

# Which architectures need anything.
need="" host_missing=$("$here/missing-packages.sh" qemu-user pkg-config cmake)
for a in $archs; do
    # shellcheck disable=SC2046
    if [ -n "${JADE_CROSS_FORCE:-}" ] || [ -n "$("$here/missing-packages.sh" $(pkgs_of "$a"))" ]; then
        need="$need $a"
    else
        echo "ready $a" >> "$status"
    fi
done
[ -z "$need" ] && [ -z "$host_missing" ] && exit 0

if [ "$(id -u)" -ne 0 ] && [ -z "${JADE_CROSS_DRY:-}" ]; then
    for a in $need; do echo "run: sudo dpkg --add-architecture $a"; done
    all="$host_missing"
    for a in $need; do all="$all $(pkgs_of "$a")"; done
    echo "run: sudo apt-get update && sudo apt-get install -y --no-install-recommends$all"
    for a in $need; do skip "$a" "needs root to install its packages"; done
    exit 0
fi
export DEBIAN_FRONTEND=noninteractive
if [ -z "${JADE_CROSS_DRY:-}" ]; then
    for a in $need; do dpkg --add-architecture "$a"; done
fi

# One update for all; the architectures whose index failed are left out of
# a second one, which apt needs: after a failed suite it keeps none of that
# suite's new indexes, so the healthy architectures' Multi-Arch libraries
# would not match the host's.
native=$(dpkg --print-architecture)
jd_apt_update "$native $need"
healthy=""
for a in $need; do
    reason=$(jd_apt_index_failure "$a")
    if [ -n "$reason" ]; then skip "$a" "package index unavailable: $reason"; else healthy="$healthy $a"; fi
done
if [ -n "$(jd_apt_index_failure "$native")" ]; then
    reason=$(jd_apt_index_failure "$native")
    for a in $healthy; do skip "$a" "host ($native) package index unavailable: $reason"; done
    exit 0
fi
restrict="-o APT::Architectures::=$native"
for a in $healthy; do restrict="$restrict -o APT::Architectures::=$a"; done
if [ "$healthy" != "$need" ] && [ -n "$healthy" ]; then jd_apt_update "$native $healthy"; fi

if [ -n "$host_missing" ]; then
    # shellcheck disable=SC2086
    if ! jd_apt_install "$restrict" $host_missing; then
        for a in $healthy; do skip "$a" "qemu-user or cmake not installable: $(jd_apt_last_error)"; done
        exit 0
    fi
fi
for a in $healthy; do
    # shellcheck disable=SC2046
    missing=$(if [ -n "${JADE_CROSS_FORCE:-}" ]; then pkgs_of "$a"; else "$here/missing-packages.sh" $(pkgs_of "$a"); fi)
    # shellcheck disable=SC2086
    if jd_apt_install "$restrict" $missing; then
        echo "ready $a" >> "$status"
    else
        skip "$a" "packages not installable: $(jd_apt_last_error)"
    fi
done
