#!/bin/sh
# Installs what jade needs on Debian 12, skipping what is already there.
# As root it runs apt-get; otherwise it prints the exact command and stops.
set -eu
pkgs="build-essential cmake pkg-config libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri
      libdraco-dev draco libstb-dev libgbm-dev libdrm-dev libx11-dev glslang-tools xvfb"
# shellcheck disable=SC2086
missing=$("$(dirname "$0")/missing-packages.sh" $pkgs)
[ -z "$missing" ] && exit 0
if [ "$(id -u)" -ne 0 ]; then
    echo "jade needs these Debian packages:$missing"
    echo "run: sudo apt-get update && sudo apt-get install -y$missing"
    exit 1
fi
echo "installing:$missing"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
# shellcheck disable=SC2086
apt-get install -y -qq --no-install-recommends $missing >/dev/null
