# Sourced by the shell tests: a scratch folder removed on exit ($tmp), and
# ok/bad, which print one line each and count; `finish NAME` prints the
# totals and sets the exit status.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); echo "ok   $1"; }
bad() { fail=$((fail + 1)); echo "FAIL $1"; }
finish() { echo "$1: $pass passed, $fail failed"; [ "$fail" -eq 0 ]; }
# A number from the one-line JSON on stdin (jade metric, bench, the
# measuring tools): `field KEY`.
field() { sed -n "s/.*\"$1\": \([-0-9.e]*\).*/\1/p"; }
# A figure held to a bound: `within WHAT VALUE BOUND` (VALUE <= BOUND) and
# `closer WHAT A B` (A < B); an empty value fails.
within() { if awk -v v="$2" -v b="$3" 'BEGIN { exit !(v != "" && v <= b) }'; then ok "$1 $2 <= $3"; else bad "$1 $2, over $3"; fi; }
closer() { if awk -v a="$2" -v b="$3" 'BEGIN { exit !(a != "" && a < b) }'; then ok "$1 ($2 < $3)"; else bad "$1: $2, not below $3"; fi; }
# Tests that preload a library into jade (gl_count, gl_sabotage): ASan
# must come first in a sanitized build, so they skip there.
preload_or_skip() {
    if ldd "$1" | grep -q libasan; then
        echo "skipped: a sanitized build cannot take a preloaded library first"
        exit 77
    fi
}
# A box of 12 triangles, two to a face, its corners' normals shared (the
# file has none: the loader makes them from the faces), into FILE.
box_obj() {
    cat > "$1" <<'OBJ'
v -1 -1 -1
v 1 -1 -1
v 1 1 -1
v -1 1 -1
v -1 -1 1
v 1 -1 1
v 1 1 1
v -1 1 1
f 1 3 2
f 1 4 3
f 5 6 7
f 5 7 8
f 1 2 6
f 1 6 5
f 4 8 7
f 4 7 3
f 1 5 8
f 1 8 4
f 2 3 7
f 2 7 6
OBJ
}
