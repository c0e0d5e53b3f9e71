#!/bin/sh
# The setup scripts against a package source that fails: a local file
# repository whose armhf index does not match its Release file (what a
# mirror caught mid-sync serves). setup-cross.sh must name armhf, say why,
# go on with arm64 and exit 0; with every index healthy it skips nothing.
# apt is pointed at the local repository and private state folders only.
root=$(cd "$(dirname "$0")/.." && pwd)
t=$(mktemp -d)
trap 'rm -rf "$t"' EXIT
pass=0 fail=0
check() { if eval "$2"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL $1"; fi; }
if ! command -v apt-get >/dev/null || [ "$(id -u)" -ne 0 ]; then echo "SKIP: needs apt-get and root"; exit 77; fi

native=$(dpkg --print-architecture)
repo() { # repo DIR BROKEN_ARCH: a repository whose BROKEN_ARCH index has the wrong size
    mkdir -p "$1/dists/fake/main"
    for a in $native arm64 armhf; do mkdir -p "$1/dists/fake/main/binary-$a"; : > "$1/dists/fake/main/binary-$a/Packages"; done
    {
        echo "Origin: jade-test"; echo "Suite: fake"; echo "Codename: fake"
        echo "Architectures: $native arm64 armhf"; echo "Components: main"
        echo "Date: $(LC_ALL=C date -u '+%a, %d %b %Y %H:%M:%S UTC')"
        echo "SHA256:"
        for a in $native arm64 armhf; do
            f=$1/dists/fake/main/binary-$a/Packages
            if [ "$a" = "$2" ]; then
                echo " 0000000000000000000000000000000000000000000000000000000000000000 100 main/binary-$a/Packages"
            else
                echo " $(sha256sum "$f" | cut -d' ' -f1) $(wc -c < "$f") main/binary-$a/Packages"
            fi
        done
    } > "$1/dists/fake/Release"
}
run() { # run REPO: setup-cross.sh in a dry run against REPO
    mkdir -p "$t/lists/partial" "$t/cache/archives/partial" "$t/parts"
    rm -f "$t/lists/"*Packages* "$t/lists/"*Release* 2>/dev/null
    echo "deb [trusted=yes] file:$1 fake main" > "$t/sources.list"
    JADE_APT_OPTS="-o Dir::Etc::SourceList=$t/sources.list -o Dir::Etc::SourceParts=$t/parts -o Dir::State::Lists=$t/lists
        -o Dir::Cache=$t/cache -o Debug::NoLocking=1 -o APT::Sandbox::User=$(id -un)" \
    JADE_CROSS_DRY=1 JADE_CROSS_FORCE=1 JADE_CROSS_STATUS=$t/status \
        sh "$root/tools/setup-cross.sh" > "$t/out" 2>&1
    echo $? > "$t/rc"
}

repo "$t/broken" armhf
run "$t/broken"
cat "$t/out"
check "exit 0 when a package index fails" '[ "$(cat "$t/rc")" = 0 ]'
check "armhf named, with the reason" 'grep -q "^skipped: armhf (package index unavailable: ." "$t/out"'
check "arm64 goes on" 'grep -q "would install: .*crossbuild-essential-arm64" "$t/out"'
check "arm64 set up" 'grep -qx "ready arm64" "$t/status"'
check "the status file says armhf was skipped" 'grep -q "^skipped armhf package index unavailable" "$t/status"'

repo "$t/healthy" none
run "$t/healthy"
cat "$t/out"
check "exit 0 with healthy indexes" '[ "$(cat "$t/rc")" = 0 ]'
check "nothing skipped with healthy indexes" '! grep -q skipped "$t/out"'
check "both architectures would be installed" \
    '[ "$(grep -c "would install: .*crossbuild-essential-arm" "$t/out")" = 2 ]'
echo "setup scripts: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
