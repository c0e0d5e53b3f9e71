#!/bin/sh
# Every code block in README.md and docs/*.md is run or checked by a test,
# so that none goes stale:
#   c      compiled against the installed headers by tests/consumer.sh
#   sh     each command line is one that CI runs: the table below names the
#          script that runs it and a line of that script that must still be
#          there; a command line the table does not know fails
#   text   jade's own output: run here (a device that cannot run full's
#          diffusion, played by tests/gl_sabotage.c) and compared
#   (none) the command synopsis, checked against `jade CMD --help` (every
#          command and option in it exists), or the source tree's folders,
#          checked against the tree (each one listed exists, each one tracked
#          is listed)
# Anything else is a code block no test runs, and fails.
jade=$1 src=$2 sabotage=$3
. "$(dirname "$0")/harness.sh"

# Command line (comment and sudo taken off) | script that runs it | a line of that script
claims='./tools/quickstart.sh|.ci/run|./tools/quickstart.sh
./tools/test.sh|.ci/run|./tools/test.sh
./tools/setup-cross.sh|tools/cross-test.sh|JADE_CROSS_STATUS=$status ./tools/setup-cross.sh
cmake -S . -B build-aarch64 -DCMAKE_TOOLCHAIN_FILE=toolchains/aarch64-linux-gnu.cmake|tools/cross-test.sh|cmake -S . -B "$dir" -DCMAKE_TOOLCHAIN_FILE="toolchains/$triple.cmake"
cmake --build build-aarch64|tools/cross-test.sh|cmake --build "$dir"
cmake -S . -B build-board -DCMAKE_TOOLCHAIN_FILE=toolchains/aarch64-linux-gnu.cmake -DJADE_SYSROOT=/path/to/sysroot|tools/cross-test.sh|cmake -S . -B build-aarch64-sysroot -DCMAKE_TOOLCHAIN_FILE=toolchains/aarch64-linux-gnu.cmake -DJADE_SYSROOT="$sysroot"
./tools/package.sh|tests/package.sh|deb=$("$src/tools/package.sh"
./tools/package.sh build-pkg-arm64 --arch arm64|tools/cross-test.sh|deb=$(./tools/package.sh "build-pkg-$arch" --arch "$arch"
./tools/package.sh build-pkg-armhf --arch armhf|tools/cross-test.sh|deb=$(./tools/package.sh "build-pkg-$arch" --arch "$arch"
apt install ./build-pkg/jade_*.deb|tests/package.sh|dpkg-deb -x "$deb" "$root"
sudoedit /etc/jade/kiosk.conf|tests/package.sh|if grep -qx /etc/jade/kiosk.conf "$root/DEBIAN/conffiles"
systemctl enable --now jade-kiosk|tests/package.sh|if systemd-analyze verify --man=no "$tmp/unit/jade-kiosk.service"'

# The fenced blocks: FILE<TAB>LINE<TAB>LANG, each block's text in $tmp/N.
n=0
for f in "$src/README.md" "$src"/docs/*.md; do
    awk -v f="${f#"$src"/}" -v dir="$tmp" -v start="$n" '
        /^```/ { if (!on) { on = 1; lang = substr($0, 4); k++; out = dir "/" (start + k); printf "" > out
                            printf "%s\t%d\t%s\n", f, NR, lang > (dir "/index." (start + k)) }
                 else { on = 0; close(out) } next }
        on { print > out }
        END { print start + k > (dir "/count") }' "$f"
    n=$(cat "$tmp/count")
done
[ "$n" -gt 0 ] || { echo "FAIL no code blocks found under $src"; exit 1; }

helps=""
help_of() { # the --help text of a jade command, cached
    [ -f "$tmp/help.$1" ] || "$jade" "$1" --help > "$tmp/help.$1" 2>&1
    cat "$tmp/help.$1"
}
synopsis() { # FILE:LINE BLOCK: every "jade CMD" and each --option after it
    where=$1 block=$2 bad_before=$fail
    cmd=""
    while IFS= read -r line; do
        case $line in jade\ *) cmd=$(echo "$line" | awk '{print $2}') ;; esac
        [ -n "$cmd" ] || continue
        if ! help_of "$cmd" | grep -q "^usage: jade $cmd"; then bad "$where: jade $cmd is not a command"; cmd=""; continue; fi
        for opt in $(echo "$line" | grep -oE -- '--[a-z][a-z0-9-]*'); do
            help_of "$cmd" | grep -qE -- "^ +$opt( |$)" || bad "$where: jade $cmd has no $opt"
        done
    done < "$block"
    [ "$fail" -eq "$bad_before" ] && ok "$where: the synopsis ($(grep -c '^jade ' "$block") commands) matches jade's --help"
}
tree() { # FILE:LINE BLOCK: the folders listed against the tracked ones
    where=$1 block=$2 bad_before=$fail
    listed=$(sed -n 's|^\([a-z_]*\)/ .*|\1|p' "$block" | sort -u)
    for d in $listed; do [ -d "$src/$d" ] || bad "$where: $d/ is listed but not in the tree"; done
    tracked=$(cd "$src" && git ls-files 2>/dev/null | sed -n 's|^\([a-z_]*\)/.*|\1|p' | sort -u)
    for d in $tracked; do echo "$listed" | grep -qx "$d" || bad "$where: $d/ is in the tree but not listed"; done
    [ "$fail" -eq "$bad_before" ] && ok "$where: the $(echo "$listed" | wc -w) folders listed are the tree's"
}
output() { # FILE:LINE BLOCK: a line jade prints, "..." standing for the rest
    where=$1 block=$2
    want=$(head -1 "$block")
    case $want in
    "jade kiosk: on this GPU: full's diffusion unavailable:"*)
        # A sanitized build cannot take the preloaded library first: the
        # release build's run checks this block.
        if ldd "$jade" | grep -q libasan; then ok "$where: checked in the release build (preloading)"; return; fi
        JD_SABOTAGE=u_near:reject LD_PRELOAD=$sabotage "$jade" kiosk --platform headless --size 64x64 --frames 1 \
            > "$tmp/out" 2> "$tmp/err"
        got=$(grep "on this GPU" "$tmp/err")
        head=${want%%...*} tail=${want##*...}
        case $got in
        "$head"*"$tail") ok "$where: jade prints it: $(echo "$got" | cut -c1-110)..." ;;
        *) bad "$where: jade prints '$got', the docs '$want'" ;;
        esac ;;
    *) bad "$where: a text block no test produces: $want" ;;
    esac
}
commands() { # FILE:LINE BLOCK: each command line claimed by a CI script that still runs it
    where=$1 block=$2
    sed 's/ *#.*//; s/^sudo //' "$block" | grep . | while IFS= read -r line; do
        claim=$(printf '%s\n' "$claims" | awk -F'|' -v l="$line" '$1 == l { print; exit }')
        if [ -z "$claim" ]; then echo "FAIL $where: '$line': no test runs it (tests/docs.sh names who does)"; continue; fi
        script=$(echo "$claim" | cut -d'|' -f2) needle=$(echo "$claim" | cut -d'|' -f3-)
        if grep -qF -- "$needle" "$src/$script"; then echo "ok   $where: '$line': run by $script"
        else echo "FAIL $where: '$line': $script no longer has: $needle"; fi
    done > "$tmp/claims"
    cat "$tmp/claims"
    pass=$((pass + $(grep -c '^ok' "$tmp/claims"))) fail=$((fail + $(grep -c '^FAIL' "$tmp/claims")))
}

i=1
while [ "$i" -le "$n" ]; do
    IFS='	' read -r file line lang < "$tmp/index.$i"
    where="$file:$line"
    case $lang in
    c) if grep -qF '"$src"/../docs/*.md' "$src/tests/consumer.sh"; then ok "$where: C, compiled by tests/consumer.sh"
       else bad "$where: C block, but tests/consumer.sh compiles none"; fi ;;
    sh) commands "$where" "$tmp/$i" ;;
    text) output "$where" "$tmp/$i" ;;
    "") if grep -q '^jade ' "$tmp/$i"; then synopsis "$where" "$tmp/$i"
        elif grep -q '^[a-z_]*/ ' "$tmp/$i"; then tree "$where" "$tmp/$i"
        else bad "$where: a code block no test runs: $(head -1 "$tmp/$i")"; fi ;;
    *) bad "$where: a '$lang' block no test runs" ;;
    esac
    i=$((i + 1))
done
echo "($n code blocks)"
finish docs
