#!/bin/sh
# jade's kiosk on a real kernel KMS driver: tools/kms-test.sh [JADE [IMGCMP]]
#
# Boots Debian's own kernel in qemu (TCG: no KVM needed) with a busybox
# initramfs made here, the host's files shared read-only over 9p, and runs
# tests/kms_guest.sh in a chroot of them: the vkms virtual display driver
# (built here out of tree from linux-source, which Debian's kernel lacks),
# Mesa's software rendering through GBM, a touch screen made with uinput.
# Needs root to install what is missing (qemu-system-x86, linux-image-amd64,
# linux-headers-amd64, linux-source-6.1, busybox-static, systemd); exits 77
# with the reason where they cannot be had. The module, the kernel and the
# initramfs are kept in build-kms/ for the next run. vkms gets three
# changes (tools/kms/*.patch): a fix so that its writeback connector can
# read back what the kiosk shows, compared with IMGCMP (tests/imgcmp),
# plane scaling, which no driver that runs in qemu has, for the kiosk's use
# of a display engine's scaler, and a fix for the deadlock of its vblank
# timer that froze two-CPU guests in CI.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
jade=$(readlink -f "${1:-$here/build/jade}")
imgcmp=$(readlink -f "${2:-$(dirname "$jade")/tests/imgcmp}")
work=${JADE_KMS_WORK:-$here/build-kms}
mkdir -p "$work"
work=$(cd "$work" && pwd)
[ -x "$jade" ] || { echo "kms-test: $jade is not built"; exit 1; }
[ -x "$imgcmp" ] || { echo "kms-test: $imgcmp (tests/imgcmp) is not built"; exit 1; }
[ "$(uname -m)" = x86_64 ] || { echo "SKIP: kms-test runs on x86_64 hosts"; exit 77; }
. "$here/tools/apt-source.sh"
pkgs="qemu-system-x86 linux-image-amd64 linux-headers-amd64 linux-source-6.1 busybox-static systemd udev make gcc bc
      libelf-dev flex bison xz-utils cpio kmod patch socat"
missing=$("$here/tools/missing-packages.sh" $pkgs)
if [ -n "$missing" ]; then
    if [ "$(id -u)" -ne 0 ]; then echo "SKIP: kms-test needs:$missing (run as root to install them)"; exit 77; fi
    export DEBIAN_FRONTEND=noninteractive
    jd_apt_update "$(dpkg --print-architecture)"
    # shellcheck disable=SC2086
    if ! jd_apt_install "--no-install-recommends" $missing >/dev/null; then
        echo "SKIP: kms-test: the package source failed for$missing: $(jd_apt_last_error)"
        exit 77
    fi
fi
[ "$(id -u)" -eq 0 ] || { echo "SKIP: kms-test needs root (9p sharing of / and the guest's chroot)"; exit 77; }
# The newest Debian kernel with headers.
kver=""
for v in $(ls /boot | sed -n 's/^vmlinuz-//p' | sort -V); do
    [ -d "/usr/src/linux-headers-$v" ] && [ -d "/lib/modules/$v" ] && kver=$v
done
[ -n "$kver" ] || { echo "SKIP: no /boot/vmlinuz-* with its linux-headers"; exit 77; }
# vkms, out of tree, against that kernel, with its writeback fix, plane
# scaling and the vblank timer's deadlock fixed (tools/kms/*.patch); the
# module kept is named by the patches, so a changed one is built again.
fixes="vkms-writeback-clones vkms-plane-scaling vkms-vblank-cancel"
ko=$work/vkms-$kver-$(for fix in $fixes; do cat "$here/tools/kms/$fix.patch"; done | cksum | cut -d' ' -f1).ko
if [ ! -f "$ko" ]; then
    src=$(ls /usr/src/linux-source-*.tar.xz | sort -V | tail -1)
    rm -rf "$work/vkms-src"
    mkdir -p "$work/vkms-src"
    tar -xJf "$src" -C "$work/vkms-src" --strip-components=5 --wildcards '*/drivers/gpu/drm/vkms/*'
    for fix in $fixes; do
        patch -s -p5 -d "$work/vkms-src" < "$here/tools/kms/$fix.patch" ||
            { echo "kms-test: tools/kms/$fix.patch does not apply to $src"; exit 1; }
    done
    make -C "/usr/src/linux-headers-$kver" M="$work/vkms-src" CONFIG_DRM_VKMS=m modules > "$work/vkms-build.log" 2>&1 ||
        { echo "kms-test: vkms does not build against $kver: $(tail -3 "$work/vkms-build.log")"; exit 1; }
    cp "$work/vkms-src/vkms.ko" "$ko"
fi
cc -O2 -Wall -Wextra "$here/tests/uinput_touch.c" -o "$work/uinput_touch"
# JADE_KMS_VBLANK_STRESS=SECONDS: the guest runs tests/kms_vblank_stress.c
# for that long in place of the checks (what showed vkms's vblank-timer
# deadlock and its fix); not part of ctest's run.
stress_s=${JADE_KMS_VBLANK_STRESS:-0}
case $stress_s in *[!0-9]*|"") echo "kms-test: JADE_KMS_VBLANK_STRESS=$stress_s is not a number of seconds"; exit 1 ;; esac
if [ "$stress_s" -gt 0 ]; then
    # shellcheck disable=SC2046
    cc -O2 -Wall -Wextra "$here/tests/kms_vblank_stress.c" -o "$work/kms_vblank_stress" $(pkg-config --cflags --libs libdrm)
fi
# Beside it, what the guest preloads to make vkms refuse atomic modesetting.
cc -O2 -Wall -Wextra -shared -fPIC "$here/tests/kms_refuse_atomic.c" -o "$work/kms_refuse_atomic.so" -ldl
# The guest stops starting checks at guest_s seconds of its uptime, so that
# its results come back whole before qemu's time (host_s) runs out.
guest_s=1000 host_s=1100
# A second guest, after the first stood still, may run until all_s of the
# test's time (ctest stops it at 1300).
all_s=1250
# The initramfs: busybox, the virtio and 9p modules in load order, and an
# init that mounts the host, prepares a chroot and runs the guest's tests.
ird=$work/initrd
rm -rf "$ird"
mkdir -p "$ird/bin" "$ird/mod" "$ird/proc" "$ird/sys" "$ird/dev" "$ird/host"
cp /bin/busybox "$ird/bin/"
order=$(for m in virtio_pci 9pnet_virtio 9p; do modprobe -S "$kver" --show-depends "$m"; done |
        awk '$1 == "insmod" && !seen[$2]++ { print $2 }')
for f in $order; do cp "$f" "$ird/mod/"; done
cat > "$ird/init" <<EOI
#!/bin/busybox sh
/bin/busybox --install -s /bin
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
for f in $(for f in $order; do printf '%s ' "$(basename "$f")"; done); do insmod /mod/\$f; done
mount -t 9p -o trans=virtio,version=9p2000.L,ro,msize=262144 host /host || echo "GUEST: the host's files cannot be mounted"
for d in proc sys dev; do mount --bind /\$d /host/\$d; done
# Writable places on top of the read-only host: /run only. Not /tmp, whose
# host files (a checkout under /tmp, the program) the guest must still see.
mount -t tmpfs run /host/run
mkdir -p /host/run/jade-out
mount -t 9p -o trans=virtio,version=9p2000.L,msize=262144 out /host/run/jade-out
echo "GUEST: up in \$(cut -d' ' -f1 /proc/uptime) s"
chroot /host /bin/sh "$here/tests/kms_guest.sh" "$jade" "$ko" "$work/uinput_touch" /run/jade-out "$imgcmp" $guest_s $stress_s "$work/kms_vblank_stress"
sync
poweroff -f
EOI
chmod +x "$ird/init"
(cd "$ird" && find . | cpio -o -H newc 2>/dev/null | gzip -1) > "$work/initrd.gz"
out=$work/out
rm -rf "$out"
mkdir -p "$out"
echo "kms-test: kernel $kver, vkms built here, $(basename "$jade") from $(dirname "$jade")"
# The guest's heartbeat (its uptime, written to the share every 5 s) is
# watched from here. Twice in CI the guest's checks stopped with their own
# bounds never firing and nothing on its console (once while they polled
# the 9p share, once between two kiosk runs), and once here its shell was
# held while the guest lived. The watch below then named where a frozen
# CI guest's CPUs were: one in hrtimer_cancel, the other spinning on a
# lock, vkms's vblank-timer deadlock, which an off-and-on modeset loop
# beside vblank waits brought about here within 30 s and which
# tools/kms/vkms-vblank-cancel.patch removes. The watch stays for what
# else may freeze an emulated guest. When the heartbeat stops for 90 s, the kernel function each
# CPU is in is recorded through qemu's monitor (named by the guest's own
# /proc/kallsyms, which it copies to the share; native_safe_halt is an
# idle CPU), then a key press is sent, whose interrupt would wake CPUs
# halted for a timer interrupt that never came. A guest that does not beat again within
# 60 s is stopped, and a second one runs the checks from the one that was
# under way: the checks judge jade's kiosk, not qemu's emulation, and the
# freeze is reported with where the CPUs were. One that stands still too
# fails the test. The same when the guest beats but no check begins or
# ends for 450 s: its shell is held (its programs and where each waits
# are reported).
mon=$work/monitor.sock
start=$(date +%s)
# monitor COMMAND: what qemu's human monitor answers, without its banner and prompts.
monitor() {
    printf '%s\n' "$1" | socat -t 3 - UNIX-CONNECT:"$mon" 2>/dev/null | tr -d '\r' |
        sed -e 's/\x1b\[[0-9;]*[A-Za-z]//g' | grep -v -e '^QEMU [0-9]' -e '^(qemu)' -e '^ *$'
}
# cpus: each guest CPU's state and the kernel function it is in.
cpus() {
    monitor "info cpus" | tr '\n' ' '
    for rip in $(monitor "info registers -a" | grep -o 'RIP=[0-9a-f]*' | cut -d= -f2); do
        case $rip in
            0000*) fn="(a program)" ;;
            *) fn=$(awk -v a="$rip" '($1 "") <= a && ($1 "") > b { b = $1; f = $3 " " $4 } END { print f }' "$out/kallsyms" 2>/dev/null) ;;
        esac
        printf 'at %s %s; ' "$rip" "${fn:-?}"
    done
}
# boot SECONDS: a guest, watched, until it powers off, stands still or
# SECONDS pass; 2 when it stood still and was stopped.
boot() {
    rm -f "$mon" "$out/heartbeat"
    bstart=$(date +%s)
    qemu-system-x86_64 -machine q35 -cpu qemu64 -smp 2 -m 2048 -nographic -no-reboot \
        -kernel "/boot/vmlinuz-$kver" -initrd "$work/initrd.gz" -append "console=ttyS0 panic=-1 quiet" \
        -virtfs local,path=/,mount_tag=host,security_model=none,readonly=on,multidevs=remap \
        -virtfs local,path="$out",mount_tag=out,security_model=none \
        -monitor unix:"$mon",server=on,wait=off < /dev/null >> "$work/console.log" 2>&1 &
    qpid=$!
    stood=0
    while kill -0 "$qpid" 2>/dev/null; do
        sleep 5
        t=$(date +%s)
        if [ $((t - bstart)) -ge "$1" ]; then echo "kms-test: the guest ran out of its $1 s"; kill "$qpid"; break; fi
        hb=$(stat -c %Y "$out/heartbeat" 2>/dev/null || echo "$bstart")
        # Beating, but no check has begun or ended for 450 s (none runs
        # longer than 380 s between two lines): the checks' shell is held.
        rs=$(stat -c %Y "$out/results" 2>/dev/null || echo "$bstart")
        if [ $((t - hb)) -le 90 ] && [ $((t - rs)) -gt 450 ]; then
            echo "kms-test: the guest's checks stopped at $((t - start)) s (no result for $((t - rs)) s); its programs (pid, name, state, wait): $(cat "$out/blocked" 2>/dev/null)"
            kill "$qpid"
            stood=1
            break
        fi
        [ $((t - hb)) -gt 90 ] || continue
        # Results already whole: the guest is shutting down.
        grep -q "^kms guest: [0-9]* passed" "$out/results" 2>/dev/null && continue
        echo "kms-test: the guest stood still at $((t - start)) s (no heartbeat for $((t - hb)) s, the last at its uptime $(cat "$out/heartbeat" 2>/dev/null) s): $(cpus)"
        monitor "sendkey shift" > /dev/null
        i=0
        while [ $i -lt 12 ] && [ "$(stat -c %Y "$out/heartbeat" 2>/dev/null)" = "$hb" ]; do sleep 5; i=$((i + 1)); done
        if [ "$(stat -c %Y "$out/heartbeat" 2>/dev/null)" = "$hb" ]; then
            echo "kms-test: a key press did not wake it in 60 s; its CPUs: $(cpus)"
            kill "$qpid"
            stood=1
            break
        fi
        echo "kms-test: a key press woke it (a heartbeat at its uptime $(cat "$out/heartbeat") s); its CPUs: $(cpus)"
    done
    wait "$qpid" 2>/dev/null
    [ $stood -eq 0 ] || return 2
}
: > "$work/console.log"
rm -f "$out/from"
if ! boot $host_s; then
    # The check under way when it stood still (the last one begun), and
    # the time left for the second guest (a minute kept for its start).
    from=$(sed -n 's/^  (\([a-zA-Z_]*\): from [0-9]* s)$/\1/p' "$out/results" | tail -1)
    left=$(( all_s - ($(date +%s) - start) ))
    mv "$out/results" "$out/results.first"
    second="no time was left for a second one ($left s)"
    if [ -n "$from" ] && [ $left -gt 300 ]; then
        echo "$from $((left - 60))" > "$out/from"
        echo "kms-test: a second guest runs the checks from $from on, in $left s"
        boot $left || echo "kms-test: the second guest stood still too"
        second="a second one ran what follows"
    fi
    # Both guests' results as one list: the first's up to the check that
    # did not end, which the second ran again. (Without a second guest
    # there are no second results: once in CI, cat's failure then ended
    # this script under set -e before it printed any.)
    { sed "/^  ($from: from /,\$d" "$out/results.first"; echo "(the first guest stood still here; $second)"; cat "$out/results" 2>/dev/null || true; } > "$out/results.all"
    mv "$out/results.all" "$out/results"
fi
echo "kms-test: the guest ran $(( $(date +%s) - start )) s"
if [ ! -s "$out/results" ]; then
    echo "kms-test: the guest wrote no results; its console:"
    tail -30 "$work/console.log"
    exit 1
fi
cat "$out/results"
if ! grep -q "^kms guest: [0-9]* passed" "$out/results"; then
    echo "kms-test: the guest did not finish (its last check above had not ended); its console:"
    tail -15 "$work/console.log"
    exit 1
fi
# Checks the guest had no time for (a slow or loaded host) are said above
# and do not fail the test; a check that ran and failed does.
grep -q "^kms guest: [0-9]* passed, 0 failed" "$out/results" && ! grep -q "^FAIL" "$out/results"
