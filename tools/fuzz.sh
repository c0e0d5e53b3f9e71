#!/bin/sh
# Fuzzes jade's parsers for a long time: tools/fuzz.sh [SECONDS] [TARGET...]
# (default: an hour, every target), one target per core at a time. Builds
# tests/fuzz with clang (ASan + UBSan + libFuzzer) in build-fuzz; the
# corpora grow in build-fuzz/tests/fuzz/corpus-<target> from run to run;
# crashes land in build-fuzz/tests/fuzz/findings. Prints, per target,
# executions and coverage from libFuzzer's final statistics.
set -eu
cd "$(dirname "$0")/.."
seconds=${1:-3600}
[ $# -gt 0 ] && shift
targets=${*:-fuzz_draco_header fuzz_metadata fuzz_mesh_load fuzz_mesh_text fuzz_gltf fuzz_image fuzz_options fuzz_texture}
if ! command -v clang >/dev/null || ! command -v clang++ >/dev/null; then
    echo "fuzz: clang is not installed (Debian: clang libclang-rt-14-dev)"
    exit 77
fi
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DJADE_FUZZ=ON -DJADE_TESTS=OFF \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
# shellcheck disable=SC2086
cmake --build build-fuzz -j"$(nproc)" --target $targets >/dev/null
dir=build-fuzz/tests/fuzz
mkdir -p "$dir/findings"
run() {
    t=$1
    mkdir -p "$dir/corpus-$t"
    # From the build folder: the decoder's child processes, whose stderr
    # libFuzzer closes, leave their sanitizer reports (.PID files) there.
    top=$(pwd)
    (cd "$dir" && "./$t" -max_total_time="$seconds" -timeout=60 -rss_limit_mb=2048 -close_fd_mask=3 \
        -print_final_stats=1 -artifact_prefix="findings/$t-" \
        "corpus-$t" "$top/tests/fuzz/corpus/$t") >"$dir/$t.log" 2>&1
    rc=$?
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/$t.log")
    cov=$(grep -o 'cov: [0-9]*' "$dir/$t.log" | tail -n 1)
    files=$(ls "$dir/corpus-$t" | wc -l)
    if [ "$rc" -eq 0 ]; then
        echo "$t: ${execs:-?} executions in $seconds s, ${cov:-cov: ?} edges, corpus $files inputs"
    else
        echo "$t: FAILED (exit $rc) after ${execs:-?} executions: $(grep -m1 -E 'ERROR|SUMMARY' "$dir/$t.log")"
        echo "    the input is in $dir/findings; the log in $dir/$t.log"
    fi
    return "$rc"
}
failed=0
running=0
jobs=$(nproc)
pids=""
for t in $targets; do
    run "$t" &
    pids="$pids $!"
    running=$((running + 1))
    if [ "$running" -ge "$jobs" ]; then
        for p in $pids; do wait "$p" || failed=1; done
        pids="" running=0
    fi
done
for p in $pids; do wait "$p" || failed=1; done
exit "$failed"
