#!/bin/sh
# One command from a fresh Debian 12 clone to a rendered picture: installs the
# packages, builds, and renders the default scene (prints its path and the
# frame time). Extra arguments go to 'jade render'.
set -eu
cd "$(dirname "$0")/.."
./tools/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" >/dev/null
./build/jade render --out jade.png "$@"
echo "picture: $(pwd)/jade.png"
