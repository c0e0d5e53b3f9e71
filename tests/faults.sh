#!/bin/sh
# Faults injected, not imagined: a file-size limit standing in for a full
# disk (no root needed), SIGKILL while the picture is being written, and
# every output option pointed at a FIFO, a device, a symlink, a folder and
# the run's own input. Afterwards no output is truncated, no input changed,
# no temporary file left, and each refusal is one line with a non-zero exit.
jade=$1
. "$(dirname "$0")/harness.sh"
check() { if eval "$2"; then ok "$1"; else bad "$1"; fi; }
# refused NAME PATTERN -- command: exit 1 within 10 s, one line naming the problem
refused() {
    name=$1 pat=$2
    shift 3
    timeout 10 "$@" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    if [ "$rc" -eq 1 ] && [ "$(wc -l < "$tmp/err")" -eq 1 ] && grep -q -- "$pat" "$tmp/err"; then
        ok "$name: $(cat "$tmp/err")"
    else
        bad "$name: rc=$rc"; cat "$tmp/err"
    fi
}
only() { [ "$(ls -A "$1" | sort | tr '\n' ' ')" = "$2" ]; }
mesh=$(dirname "$0")/../assets/default.drc

# 1. The disk fills: writes past 40,000 bytes fail with EFBIG ("File too
#    large"), as a full disk fails with ENOSPC, at the same point in the code.
if command -v prlimit >/dev/null; then
    mkdir "$tmp/disk"
    "$jade" render --size 32x32 --out "$tmp/disk/pic.png" >/dev/null 2>&1
    cp "$tmp/disk/pic.png" "$tmp/prev.png"
    refused "disk full (file size limit)" "File too large" -- \
        sh -c 'trap "" XFSZ; exec prlimit --fsize=40000 -- "$@"' sh "$jade" render --size 512x512 --out "$tmp/disk/pic.png"
    check "the previous picture survives" 'cmp -s "$tmp/disk/pic.png" "$tmp/prev.png"'
    check "no temporary file is left" 'only "$tmp/disk" "pic.png "'
    refused "disk full for the sheet" "File too large" -- \
        sh -c 'trap "" XFSZ; exec prlimit --fsize=40000 -- "$@"' sh "$jade" render --size 256x256 --sheet "$tmp/disk/sheet.png"
    check "no sheet and no temporary file" 'only "$tmp/disk" "pic.png "'
    refused "disk full for the reference's PFM" "File too large" -- \
        sh -c 'trap "" XFSZ; exec prlimit --fsize=40000 -- "$@"' sh "$jade" reference --size 128x128 --samples 2000 --quiet \
        --out "$tmp/disk/ref.png" --pfm "$tmp/disk/ref.pfm"
    check "the reference left nothing half-written" 'only "$tmp/disk" "pic.png " || only "$tmp/disk" "pic.png ref.png "'
else
    echo "skip disk full: no prlimit (util-linux)"
fi

# 2. SIGKILL while the new picture is open for writing (found by watching
#    the process's descriptors), three times: the old picture stays whole.
mkdir "$tmp/kill"
"$jade" render --size 1024x1024 --budget-mb 128 --light-azimuth 30 --out "$tmp/kill/pic.png" >/dev/null 2>&1
cp "$tmp/kill/pic.png" "$tmp/old.png"
killed=0
for attempt in 1 2 3; do
    "$jade" render --size 1024x1024 --budget-mb 128 --out "$tmp/kill/pic.png" >/dev/null 2>&1 &
    pid=$!
    i=0
    while [ $i -lt 3000 ] && kill -0 $pid 2>/dev/null; do
        if ls -l /proc/$pid/fd 2>/dev/null | grep -q "$tmp/kill/"; then
            kill -9 $pid && killed=$((killed + 1))
            break
        fi
        i=$((i + 1))
        sleep 0.002
    done
    wait $pid 2>/dev/null
    check "killed mid-write ($attempt): the old picture is intact" 'cmp -s "$tmp/kill/pic.png" "$tmp/old.png"'
    check "killed mid-write ($attempt): nothing else in the folder" 'only "$tmp/kill" "pic.png "'
done
if [ "$killed" -gt 0 ]; then ok "$killed of 3 runs were killed with the output open"
else bad "no run was caught with its output open"; fi

# 3. Every output option at things that must not be written.
mkfifo "$tmp/fifo"
mkdir "$tmp/folder"
echo keep > "$tmp/target"
ln -s "$tmp/target" "$tmp/link"
cp "$mesh" "$tmp/m.drc"
for opt in --out --sheet; do
    refused "render $opt at a FIFO" "not a regular file" -- "$jade" render --size 32x32 "$opt" "$tmp/fifo"
    refused "render $opt at a device" "not a regular file" -- "$jade" render --size 32x32 "$opt" /dev/null
    refused "render $opt at a folder" "not a regular file" -- "$jade" render --size 32x32 "$opt" "$tmp/folder"
    refused "render $opt through a symlink" "symbolic link" -- "$jade" render --size 32x32 "$opt" "$tmp/link"
    refused "render $opt at the mesh" "one of this run's inputs" -- \
        "$jade" render --mesh "$tmp/m.drc" --size 32x32 "$opt" "$tmp/m.drc"
done
"$jade" render --size 32x32 --out "$tmp/ref.png" >/dev/null 2>&1
refused "sheet at its own reference picture" "one of this run's inputs" -- \
    "$jade" render --size 32x32 --sheet "$tmp/ref.png" --sheet-reference "$tmp/ref.png"
for opt in --out --pfm --mask; do
    refused "reference $opt at a FIFO" "not a regular file" -- "$jade" reference --size 16x16 --quiet "$opt" "$tmp/fifo"
    refused "reference $opt through a symlink" "symbolic link" -- "$jade" reference --size 16x16 --quiet "$opt" "$tmp/link"
    refused "reference $opt at the mesh" "one of this run's inputs" -- \
        "$jade" reference --mesh "$tmp/m.drc" --size 16x16 --quiet "$opt" "$tmp/m.drc"
done
check "/dev/null is still a device" '[ -c /dev/null ]'
check "the FIFO is still a FIFO" '[ -p "$tmp/fifo" ]'
check "the symlink's target is intact" '[ "$(cat "$tmp/target")" = keep ] && [ -L "$tmp/link" ]'
check "the mesh is intact" 'cmp -s "$mesh" "$tmp/m.drc"'
check "the sheet's reference is intact" '[ -s "$tmp/ref.png" ]'

# 4. Inputs that are not files.
refused "mesh is a device" "not a regular file" -- "$jade" render --mesh /dev/zero --out "$tmp/x.png"
refused "mesh is a folder" "" -- "$jade" render --mesh "$tmp/folder" --out "$tmp/x.png"
refused "picture is a device" "not a regular file" -- "$jade" metric /dev/zero "$tmp/ref.png"
refused "picture is a folder" "not a regular file" -- "$jade" metric "$tmp/folder" "$tmp/ref.png"

finish faults
