# Sourced by the shell tests: a scratch folder removed on exit ($tmp), and
# ok/bad, which print one line each and count; `finish NAME` prints the
# totals and sets the exit status.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); echo "ok   $1"; }
bad() { fail=$((fail + 1)); echo "FAIL $1"; }
finish() { echo "$1: $pass passed, $fail failed"; [ "$fail" -eq 0 ]; }
