#!/bin/sh
# One command from a fresh Debian 12 clone to a full test run: installs the
# packages, builds, runs every test, then builds again with ASan and UBSan and
# runs the tests once more. Tests that need ../shared skip when it is absent.
set -eu
cd "$(dirname "$0")/.."
./tools/setup.sh
jobs=$(nproc)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$jobs" >/dev/null
echo "== tests (release build)"
(cd build && ctest -j"$jobs" --output-on-failure)
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DJADE_SANITIZE=ON >/dev/null
cmake --build build-asan -j"$jobs" >/dev/null
echo "== tests (ASan + UBSan build)"
# The GL driver (Mesa, LLVM) keeps allocations until exit: leak reports would
# be about it, not jade. Everything else ASan and UBSan check stays on.
(cd build-asan && ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest -j"$jobs" --output-on-failure)
