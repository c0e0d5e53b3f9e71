#!/bin/sh
# Runs inside tools/kms-test.sh's virtual machine, as root, in a chroot of
# the host's files (read-only): jade's kiosk on the vkms kernel driver.
# kms_guest.sh JADE VKMS.ko UINPUT_TOUCH OUT_DIR IMGCMP; results in OUT_DIR/results.
jade=$1 vkms=$2 touch=$3 out=$4 imgcmp=$5
res=$out/results
: > "$res"
pass=0 fail=0
ok() { pass=$((pass + 1)); echo "ok   $1" | tee -a "$res"; }
bad() { fail=$((fail + 1)); echo "FAIL $1" | tee -a "$res"; }
modprobe drm_kms_helper && modprobe drm_shmem_helper && insmod "$vkms" enable_writeback=1 ||
    { bad "vkms does not load"; exit 1; }
modprobe uinput 2>/dev/null; modprobe evdev 2>/dev/null
mount -t debugfs debugfs /sys/kernel/debug 2>/dev/null
i=0
while [ ! -e /dev/dri/card0 ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
[ -e /dev/dri/card0 ] && ok "vkms loaded: $(cat /sys/class/drm/card0-*/status 2>/dev/null | tr '\n' ' ')(/dev/dri/card0)" ||
    { bad "no /dev/dri/card0"; exit 1; }
state=/sys/kernel/debug/dri/0/state
crtc_state() { sed -n '/^crtc\[/,/^connector\[/p' "$state" | grep -v "^connector"; }
crtc_state > "$out/crtc_before"
# Under TCG a frame takes seconds and a decode may pass the usual 1.5 s.
mode="--display-mode 640x480 --decode-timeout-ms 60000"
# kiosk NAME ARGS...: runs the kiosk to its end; its output in $out/NAME.
# A kiosk that has not exited 60 s after printing its statistics (or 600 s
# after it started) is recorded (each thread's wait channel, the kernel
# stack) and killed: a hang at exit shows in the results instead of holding
# the guest until its time runs out (seen once in CI: a run that printed
# its statistics and then never exited).
kiosk() {
    name=$1
    shift
    start=$(date +%s)
    "$jade" kiosk --drm-device /dev/dri/card0 $mode "$@" > "$out/$name" 2>&1 &
    kpid=$!
    done_at=0
    while [ -d /proc/$kpid ] && [ "$(cut -d' ' -f3 /proc/$kpid/stat 2>/dev/null)" != Z ]; do
        now=$(date +%s)
        [ $done_at -eq 0 ] && grep -q "^kiosk: [0-9]* frames" "$out/$name" && done_at=$now
        if [ $((now - start)) -gt 600 ] || { [ $done_at -gt 0 ] && [ $((now - done_at)) -gt 60 ]; }; then
            bad "$name: no exit $([ $done_at -gt 0 ] && echo '60 s after its statistics' || echo 'in 600 s'): threads $(for t in /proc/$kpid/task/*; do printf '%s:%s ' "$(cat "$t/comm" 2>/dev/null)" "$(cat "$t/wchan" 2>/dev/null)"; done)stack $(tr '\n' ' ' < /proc/$kpid/stack 2>/dev/null | cut -c1-200)"
            kill -KILL $kpid
            break
        fi
        sleep 0.5
    done
    wait $kpid
    rc=$?
    echo "  ($name: exit $rc after $(( $(date +%s) - start )) s)" >> "$res"
    return $rc
}
restored() {
    crtc_state > "$out/crtc_after"
    if cmp -s "$out/crtc_before" "$out/crtc_after"; then ok "$1: the CRTC is as it was before ($(grep -m1 'enable=' "$out/crtc_after" | tr -d '\t'))"
    else bad "$1: the CRTC is not restored: $(diff "$out/crtc_before" "$out/crtc_after" | head -5 | tr '\n' ' ')"; fi
}
flips() { # NAME FRAMES: every frame after the modeset was a page flip the kernel confirmed
    line=$(grep "^kiosk: [0-9]* frames" "$out/$1")
    f=$(echo "$line" | sed -n 's/^kiosk: \([0-9]*\) frames.*/\1/p')
    p=$(echo "$line" | sed -n 's/.*page flips \([0-9]*\).*/\1/p')
    if [ "$f" = "$2" ] && [ "$p" = "$(( $2 - 1 ))" ] && echo "$line" | grep -q "modesets 1"; then ok "$1: $f frames drawn, $p page flips confirmed: $line"
    else bad "$1: frames $f, flips $p (want $2 and $(( $2 - 1 ))): $(cat "$out/$1")"; fi
}
if kiosk legacy --frames 6; then flips legacy 6; else bad "legacy: $(cat "$out/legacy")"; fi
restored legacy
if kiosk atomic --frames 6 --atomic --mode none; then flips atomic 6; else bad "atomic: $(cat "$out/atomic")"; fi
restored atomic
# Explicit fences: every flip's OUT_FENCE_PTR fence waited on (vkms has the
# property); the GPU's fence goes to the plane only where EGL has native
# fences, which the guest's software GL has not: it must say so.
if grep -q "fences in 0 out 5" "$out/atomic" && grep -q "fences: none to the plane (EGL has no native fences), the flip's waited on" "$out/atomic"; then
    ok "atomic: explicit fences: $(grep -o 'fences: [^;]*' "$out/atomic"); $(grep -o 'fences in [0-9]* out [0-9]*' "$out/atomic")"
else bad "atomic: fences: $(grep -o 'fences[^;]*' "$out/atomic" | tr '\n' ' ')"; fi
# What was chosen is what was asked.
if kiosk choose --frames 2 --mode none --connector Virtual-1 --display-mode 800x600 && grep -q "Virtual-1 800x600" "$out/choose"; then
    ok "--connector Virtual-1 --display-mode 800x600: $(grep -o 'DRM/KMS [^,]*' "$out/choose")"
else bad "connector and mode choice: $(cat "$out/choose")"; fi
# What the display scans out, read back by vkms's writeback connector at the
# end (--screenshot), against jade's own render of the same still scene made
# here in the guest (llvmpipe's pictures depend on the CPU it sees).
still="--light-speed 0 --antialias off"
if kiosk capture --frames 3 --atomic $still --screenshot "$out/scanout.png" &&
    "$jade" render --size 640x480 --decode-timeout-ms 60000 --antialias off --out "$out/render.png" > "$out/render" 2>&1; then
    # Not two blank pictures: the object is in the capture, whole.
    if "$imgcmp" "$out/scanout.png" "$out/render.png" --max-rmse 0.5 --max-bad-frac 0.001 > "$out/cmp" 2>&1 &&
        "$imgcmp" --frame "$out/scanout.png" 0.3 >> "$out/cmp" 2>&1; then
        ok "the scanned-out picture (writeback) is jade's render: $(cat "$out/cmp" | tr '\n' ' ')"
    else bad "the scanned-out picture differs from the render: $(cat "$out/cmp")"; fi
else bad "writeback capture: $(cat "$out/capture" "$out/render" 2>/dev/null)"; fi
restored capture
# The rest need no translucency: the cheapest mode keeps the guest quick.
mode="--display-mode 640x480 --decode-timeout-ms 60000 --mode none"
if kiosk rotate --frames 3 --rotate 90; then ok "--rotate 90 runs: $(grep '^kiosk:' "$out/rotate")"; else bad "--rotate 90: $(cat "$out/rotate")"; fi
if kiosk nomode --frames 1 --display-mode 123x45 2>/dev/null; then bad "a mode the display lacks was accepted"
else ok "a mode the display lacks is refused: $(head -1 "$out/nomode")"; fi
# SIGTERM mid-run, the display given back; a second kiosk meanwhile is refused.
"$jade" kiosk --drm-device /dev/dri/card0 $mode > "$out/term" 2>&1 &
pid=$!
i=0
while [ $i -lt 600 ] && ! grep -q "anti-aliasing" "$out/term"; do sleep 0.1; i=$((i + 1)); done
sleep 4
if "$jade" kiosk --drm-device /dev/dri/card0 $mode --frames 1 > "$out/second" 2>&1; then bad "a second kiosk took the display"
elif grep -q "held by jade (pid $pid)" "$out/second"; then ok "a second kiosk is refused, the holder named: $(cat "$out/second" | head -1)"
else bad "second kiosk: $(cat "$out/second")"; fi
kill -TERM "$pid"
sent=$(date +%s%N)
wait "$pid"
rc=$?
ms=$(( ($(date +%s%N) - sent) / 1000000 ))
if [ "$rc" -eq 0 ] && grep -q "^kiosk: [0-9]* frames" "$out/term"; then ok "SIGTERM mid-run: exit 0 after $ms ms: $(grep '^kiosk: [0-9]* frames' "$out/term")"
else bad "SIGTERM: exit $rc: $(cat "$out/term")"; fi
restored SIGTERM
# Hotplug: the display unplugged and plugged back in. vkms makes no hotplug
# of its own, so the connector is forced off and on through debugfs and the
# kernel's uevent is asked for by hand, as a real hotplug would send it.
# stop PID NAME: SIGTERM, then at most 120 s for the exit; a process still
# there is recorded (where the kernel says it waits) and killed, so that a
# hang shows in the results instead of stopping the guest. Its exit status.
stop() {
    kill -TERM "$1" 2>/dev/null
    i=0
    while [ $i -lt 1200 ] && [ -d /proc/$1 ] && [ "$(cut -d' ' -f3 /proc/$1/stat 2>/dev/null)" != Z ]; do
        sleep 0.1; i=$((i + 1))
    done
    if [ -d /proc/$1 ] && [ "$(cut -d' ' -f3 /proc/$1/stat 2>/dev/null)" != Z ]; then
        bad "$2: still running 120 s after SIGTERM, in $(cat /proc/$1/wchan 2>/dev/null): $(tr '\n' ' ' < /proc/$1/stack 2>/dev/null | cut -c1-300); $(tail -2 "$out/$2" | tr '\n' ' ')"
        kill -KILL "$1" 2>/dev/null
    fi
    wait "$1"
}
# wait_for FILE TEXT SECONDS
wait_for() {
    i=0
    while [ $i -lt $(( $3 * 10 )) ] && ! grep -q "$2" "$1"; do sleep 0.1; i=$((i + 1)); done
    grep -q "$2" "$1"
}
force=$(ls -d /sys/kernel/debug/dri/0/Virtual-1 2>/dev/null)/force
if [ -w "$force" ]; then
    "$jade" kiosk --drm-device /dev/dri/card0 $mode > "$out/hotplug" 2>&1 &
    pid=$!
    wait_for "$out/hotplug" "anti-aliasing" 120
    sleep 3
    echo off > "$force" && echo change > /sys/class/drm/card0/uevent
    # Under TCG on a loaded host a frame can take 25 s, and uevents are read
    # between frames.
    if wait_for "$out/hotplug" "the display went away" 90 && sleep 2 && kill -0 "$pid"; then
        ok "unplugged: the kiosk waits: $(grep 'went away' "$out/hotplug")"
    else bad "unplug: $(cat "$out/hotplug")"; fi
    echo on > "$force" && echo change > /sys/class/drm/card0/uevent
    if wait_for "$out/hotplug" "the display is back" 90 && wait_for "$out/hotplug" "set again" 90; then
        ok "plugged back: $(grep -e 'is back' -e 'set again' "$out/hotplug" | tr '\n' ' ')"
    else bad "plug back: $(cat "$out/hotplug")"; fi
    printf unspecified > "$force" # 11 bytes: the kernel's buffer has no room for a newline too
    stop "$pid" hotplug
    rc=$?
    line=$(grep "^kiosk: [0-9]* frames" "$out/hotplug")
    if [ "$rc" -eq 0 ] && echo "$line" | grep -q "modesets 2"; then
        ok "a frame shown again by a second modeset, exit 0 at SIGTERM: $line"
    else bad "after the hotplug: exit $rc: $(cat "$out/hotplug")"; fi
    restored hotplug
else
    echo "no debugfs force file for Virtual-1: hotplug is not tried" | tee -a "$res"
fi
# A touch screen: udev tags it, libinput finds it, a swipe turns the object.
if [ -e /dev/uinput ] && [ -x /lib/systemd/systemd-udevd ]; then
    /lib/systemd/systemd-udevd --daemon 2>/dev/null
    "$touch" 25000 > "$out/touch_dev" 2>&1 &
    tpid=$!
    sleep 1
    udevadm trigger --subsystem-match=input --action=add 2>/dev/null
    udevadm settle -t 10 2>/dev/null
    "$jade" kiosk --drm-device /dev/dri/card0 $mode --idle 2 > "$out/touch" 2>&1 &
    pid=$!
    i=0
    while [ $i -lt 500 ] && ! grep -q "touched at" "$out/touch"; do sleep 0.1; i=$((i + 1)); done
    i=0
    while [ $i -lt 600 ] && ! grep -q "back in place" "$out/touch"; do sleep 0.1; i=$((i + 1)); done
    stop "$pid" touch
    kill "$tpid" 2>/dev/null
    if grep -q "input: 1 touch or pointer device" "$out/touch"; then ok "libinput finds the touch screen: $(grep -o 'input: [^;]*' "$out/touch")"
    else bad "touch screen not found: $(head -3 "$out/touch")"; fi
    if grep -q "^kiosk: touched at" "$out/touch" && grep -q "^kiosk: back in place" "$out/touch"; then
        ok "a swipe turns the object and it turns back: $(grep '^kiosk: touched' "$out/touch"); $(grep '^kiosk: back' "$out/touch")"
    else bad "swipe: $(cat "$out/touch" "$out/touch_dev")"; fi
    restored touch
else
    echo "no /dev/uinput or systemd-udevd: the touch screen is not tried" | tee -a "$res"
fi
echo "kms guest: $pass passed, $fail failed" | tee -a "$res"
