# Sourced by the shell tests: a scratch folder removed on exit ($tmp), and
# ok/bad, which print one line each and count; `finish NAME` prints the
# totals and sets the exit status.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); echo "ok   $1"; }
bad() { fail=$((fail + 1)); echo "FAIL $1"; }
finish() { echo "$1: $pass passed, $fail failed"; [ "$fail" -eq 0 ]; }
# Tests that preload a library into jade (gl_count, gl_sabotage): ASan
# must come first in a sanitized build, so they skip there.
preload_or_skip() {
    if ldd "$1" | grep -q libasan; then
        echo "skipped: a sanitized build cannot take a preloaded library first"
        exit 77
    fi
}
