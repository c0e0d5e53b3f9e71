#!/bin/sh
# One command from a fresh Debian 12 clone to a full test run: installs the
# packages, builds, runs every test, then builds again with ASan and UBSan and
# runs the tests once more. Tests that need ../shared skip when it is absent.
set -eu
cd "$(dirname "$0")/.."
# Each stage's time, to $JADE_CI_TIMES when set (.ci/run prints them).
lap_t=$(date +%s)
lap() {
    now=$(date +%s)
    [ -z "${JADE_CI_TIMES:-}" ] || echo "$1 $((now - lap_t))" >> "$JADE_CI_TIMES"
    lap_t=$now
}
./tools/setup.sh
lap setup
jobs=$(nproc)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$jobs" >/dev/null
lap "release build"
echo "== tests (release build)"
(cd build && ctest -j"$jobs" --output-on-failure)
lap "release tests"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DJADE_SANITIZE=ON >/dev/null
cmake --build build-asan -j"$jobs" >/dev/null
lap "sanitizer build"
echo "== tests (ASan + UBSan build)"
# The GL driver (Mesa, LLVM) keeps allocations until exit: leak reports would
# be about it, not jade. Everything else ASan and UBSan check stays on.
(cd build-asan && ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest -j"$jobs" --output-on-failure)
lap "sanitizer tests"
# The fuzz targets, briefly, over their seed corpora and what earlier runs
# found (tools/fuzz.sh runs them for hours). Needs clang and libFuzzer.
fuzz_probe=$(mktemp)
if command -v clang >/dev/null && command -v clang++ >/dev/null &&
   echo 'int LLVMFuzzerTestOneInput(const char *d, unsigned long n) { return d && n; }' |
   clang -fsanitize=fuzzer -x c - -o "$fuzz_probe" 2>/dev/null; then
    rm -f "$fuzz_probe"
    echo "== fuzz smoke (libFuzzer, ${JADE_FUZZ_SECONDS:-10} s per target)"
    CC=clang CXX=clang++ cmake -S . -B build-fuzz -DJADE_FUZZ=ON -DJADE_TESTS=OFF \
        -DJADE_FUZZ_SECONDS="${JADE_FUZZ_SECONDS:-10}" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
    cmake --build build-fuzz -j"$jobs" >/dev/null
    (cd build-fuzz && ctest -j"$jobs" -L fuzz --output-on-failure)
    lap "fuzz smoke"
else
    rm -f "$fuzz_probe"
    echo "== fuzz smoke skipped: clang with libFuzzer is not installed (Debian: clang libclang-rt-14-dev)"
fi
# Every shader program through the real Mali-400 (lima), VideoCore IV (vc4)
# and Mali Midgard (panfrost) compilers, against the committed budget. The
# first run builds Mesa from Debian's source package (about 6 minutes).
echo "== device compilers (tools/device-shaders.sh)"
set +e
./tools/device-shaders.sh --check tests/device-shaders.expected
rc=$?
set -e
lap "device compilers"
[ "$rc" -eq 0 ] || [ "$rc" -eq 77 ] || exit "$rc"
