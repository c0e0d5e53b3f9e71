#!/bin/sh
# Prepares a Debian 12 machine to cross-build jade for aarch64 and armhf with
# Debian multiarch: the foreign architectures, the cross compilers, the
# target -dev packages and qemu-user to run target tests. As root it runs
# apt-get; otherwise it prints the commands and stops.
set -eu
archs=${JADE_CROSS_ARCHS:-"arm64 armhf"}
pkgs="qemu-user pkg-config cmake"
for a in $archs; do
    pkgs="$pkgs crossbuild-essential-$a libdraco-dev:$a libstb-dev:$a libegl-dev:$a libgles-dev:$a"
    pkgs="$pkgs libgbm-dev:$a libdrm-dev:$a libx11-dev:$a"
done
# shellcheck disable=SC2086
missing=$("$(dirname "$0")/missing-packages.sh" $pkgs)
[ -z "$missing" ] && exit 0
if [ "$(id -u)" -ne 0 ]; then
    echo "cross builds need:$missing"
    for a in $archs; do echo "run: sudo dpkg --add-architecture $a"; done
    echo "run: sudo apt-get update && sudo apt-get install -y --no-install-recommends$missing"
    exit 1
fi
for a in $archs; do dpkg --add-architecture "$a"; done
export DEBIAN_FRONTEND=noninteractive
# A mirror caught mid-sync fails one index: the others still serve.
apt-get update -qq || echo "apt-get update reported errors; going on with the indexes it has"
echo "installing:$missing"
# shellcheck disable=SC2086
if ! apt-get install -y -qq --no-install-recommends $missing >/dev/null; then
    # Multi-Arch: same libraries must have one version on every architecture;
    # when the security suite's indexes disagree between architectures, the
    # release suite has versions that exist for all of them.
    echo "retrying from the bookworm release suite (the architectures' security indexes disagree)"
    # shellcheck disable=SC2086
    apt-get install -y -qq --no-install-recommends -t bookworm $missing >/dev/null
fi
