#!/bin/sh
# Runs inside tools/kms-test.sh's virtual machine, as root, in a chroot of
# the host's files (read-only): jade's kiosk on the vkms kernel driver.
# kms_guest.sh JADE VKMS.ko UINPUT_TOUCH OUT_DIR IMGCMP [SECONDS [STRESS_S
# STRESS]]; results in OUT_DIR/results, the checks' files beside them at the
# end. SECONDS (of the guest's uptime, 1300 unless given) bound the whole
# run: a check that would start too late to end in time is reported as not
# run, so that the results always arrive whole. STRESS_S above 0 runs the
# program STRESS (tests/kms_vblank_stress.c) that long in place of the checks.
jade=$1 vkms=$2 touch=$3 share=$4 imgcmp=$5 deadline=${6:-1300} stress_s=${7:-0} stress=${8:-}
res=$share/results
# The checks' own files (the programs' output, which the checks poll ten
# times a second, the pictures) on the guest's tmpfs, copied to the host's
# share at the end; the share takes the results as they come. Seen once in
# CI, cause unknown: the guest stopped making progress altogether between
# two checks while they polled their files on the 9p share.
out=/run/jade-work
mkdir -p "$out"
# Mesa's shader cache on that tmpfs too (the host's files are read-only
# here, so there was none), for the kiosks after the first: a kiosk run
# took 40 to 70 s under TCG, more than half of it before its first frame;
# with the cache 30 to 60 s (one run each, on different days).
MESA_SHADER_CACHE_DIR=$out/mesa-cache
export MESA_SHADER_CACHE_DIR
: > "$res"
pass=0 fail=0 notrun=0
ok() { pass=$((pass + 1)); echo "ok   $1" | tee -a "$res"; }
bad() { fail=$((fail + 1)); echo "FAIL $1" | tee -a "$res"; }
now() { cut -d. -f1 /proc/uptime; }
# The heartbeat tools/kms-test.sh watches: the guest's uptime every 5 s,
# and beside it the programs running (pid, name, state, the kernel function
# each waits in), which the host reports should the checks stop moving.
( while :; do
    now > "$share/heartbeat"
    { for d in /proc/[0-9]*; do
        [ -e "$d/exe" ] || continue # kernel threads have no program
        printf '%s %s %s %s, ' "${d#/proc/}" "$(cat "$d/comm")" "$(cut -d' ' -f3 "$d/stat" | head -c1)" "$(cat "$d/wchan")"
    done; } > "$share/blocked" 2>/dev/null
    sleep 5
done ) &
beating=$!
# A second guest, after the first stood still (tools/kms-test.sh), finds
# in the share the check that was under way and the time it has: the
# checks before that one ran in the first guest.
from=""
if [ -s "$share/from" ]; then read -r from deadline < "$share/from"; fi
# have SECONDS NAME: whether a check needing up to SECONDS can still end in
# the guest's time; if not it is reported as not run.
have() {
    if [ -n "$from" ]; then
        [ "$2" = "$from" ] || return 1
        from=""
    fi
    if [ $(( $(now) + $1 )) -le "$deadline" ]; then echo "  ($2: from $(now) s)" >> "$res"; return 0; fi
    notrun=$((notrun + 1))
    echo "not run: $2 (needs up to $1 s, the guest's time ends in $((deadline - $(now))) s)" | tee -a "$res"
    return 1
}
alive() { [ -d /proc/$1 ] && [ "$(cut -d' ' -f3 /proc/$1/stat 2>/dev/null)" != Z ]; }
# watch PID NAME LIMIT: waits for PID (a child writing $out/NAME) to end and
# returns its exit status. One still running LIMIT s from now, or 60 s after
# it printed its statistics, is recorded (each thread's wait channel, and
# the kernel stack where the kernel shows one: Debian's does not) and
# killed: a hang shows in the results instead of holding the guest until its
# time runs out (seen in CI: a kiosk that printed its statistics and never
# exited). One the kernel will not let die (state D) is
# left behind, not waited for.
watch() {
    wpid=$1 wname=$2 wend=$(( $(now) + $3 )) wdone=0
    while alive "$wpid"; do
        t=$(now)
        [ $wdone -eq 0 ] && grep -q "^kiosk: [0-9]* frames" "$out/$wname" 2>/dev/null && wdone=$t
        if [ "$t" -gt $wend ] || { [ $wdone -gt 0 ] && [ $((t - wdone)) -gt 60 ]; }; then
            bad "$wname: no exit $([ $wdone -gt 0 ] && echo '60 s after its statistics' || echo "in $3 s"): state $(cut -d' ' -f3 /proc/$wpid/stat), threads $(for th in /proc/$wpid/task/*; do printf '%s:%s ' "$(cat "$th/comm" 2>/dev/null)" "$(cat "$th/wchan" 2>/dev/null)"; done)$([ -r /proc/$wpid/stack ] && echo "stack $(tr '\n' ' ' < /proc/$wpid/stack | cut -c1-300)"); last: $(tail -2 "$out/$wname" 2>/dev/null | tr '\n' ' ')"
            kill -KILL "$wpid" 2>/dev/null
            i=0
            while [ $i -lt 50 ] && alive "$wpid"; do sleep 0.2; i=$((i + 1)); done
            if alive "$wpid"; then bad "$wname: not gone 10 s after SIGKILL (state $(cut -d' ' -f3 /proc/$wpid/stat)): left behind"; return 125; fi
            wait "$wpid"
            return 124
        fi
        sleep 0.5
    done
    wait "$wpid"
}
modprobe drm_kms_helper && modprobe drm_shmem_helper && insmod "$vkms" enable_writeback=1 ||
    { bad "vkms does not load"; exit 1; }
modprobe uinput 2>/dev/null; modprobe evdev 2>/dev/null
mount -t debugfs debugfs /sys/kernel/debug 2>/dev/null
i=0
while [ ! -e /dev/dri/card0 ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
# The kernel's functions and vkms's, for tools/kms-test.sh to name where
# the CPUs are should the guest stand still.
grep " [tT] " /proc/kallsyms > "$share/kallsyms" 2>/dev/null
[ -e /dev/dri/card0 ] && ok "vkms loaded at $(now) s: $(cat /sys/class/drm/card0-*/status 2>/dev/null | tr '\n' ' ')(/dev/dri/card0)" ||
    { bad "no /dev/dri/card0"; exit 1; }
if [ "$stress_s" -gt 0 ]; then
    echo "  (vblank_stress: from $(now) s)" >> "$res"
    if "$stress" /dev/dri/card0 "$stress_s" > "$out/vblank_stress" 2>&1; then ok "vblank stress: $(tr '\n' ' ' < "$out/vblank_stress")"
    else bad "vblank stress: $(tr '\n' ' ' < "$out/vblank_stress")"; fi
    kill "$beating" 2>/dev/null
    echo "kms guest: $pass passed, $fail failed, 0 not run (at $(now) s)" | tee -a "$res"
    exit 0
fi
state=/sys/kernel/debug/dri/0/state
crtc_state() { sed -n '/^crtc\[/,/^connector\[/p' "$state" | grep -v "^connector"; }
crtc_state > "$out/crtc_before"
# The checks of the display path show a cube (made here) in the cheapest
# mode without anti-aliasing: under TCG the default asset in full mode with
# 4x multisampling takes 15 s a frame and a minute to start. The default
# scene is shown once, by the writeback check, which compares it.
cube=$out/cube.obj
{
    for v in "-1 -1 -1" "1 -1 -1" "1 1 -1" "-1 1 -1" "-1 -1 1" "1 -1 1" "1 1 1" "-1 1 1"; do echo "v $v"; done
    for f in "1 3 2" "1 4 3" "5 6 7" "5 7 8" "1 2 6" "1 6 5" "4 8 7" "4 7 3" "1 5 8" "1 8 4" "2 3 7" "2 7 6"; do echo "f $f"; done
} > "$cube"
light="--display-mode 640x480 --decode-timeout-ms 60000 --mode none --antialias off --mesh $cube"
# bounded NAME LIMIT COMMAND...: runs COMMAND to its end (watch), its output
# in $out/NAME, and returns its exit status.
bounded() {
    name=$1 limit=$2
    shift 2
    start=$(now)
    "$@" > "$out/$name" 2>&1 &
    watch $! "$name" "$limit"
    rc=$?
    echo "  ($name: exit $rc after $(( $(now) - start )) s)" >> "$res"
    return $rc
}
# kiosk NAME LIMIT ARGS...: the kiosk on vkms, bounded.
kiosk() { k_name=$1 k_limit=$2; shift 2; bounded "$k_name" "$k_limit" "$jade" kiosk --drm-device /dev/dri/card0 "$@"; }
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
# stop PID NAME: SIGTERM, then at most 120 s for the exit (watch). Its exit status.
stop() {
    kill -TERM "$1" 2>/dev/null
    watch "$1" "$2" 120
}
# wait_for FILE TEXT SECONDS: SECONDS of the guest's uptime. (Counting ten
# polls a second made it last many times longer when the kiosk took both
# emulated CPUs and each poll's programs took a second to start.)
wait_for() {
    wf_end=$(( $(now) + $3 ))
    while [ "$(now)" -le $wf_end ] && ! grep -q "$2" "$1"; do sleep 0.1; done
    grep -q "$2" "$1"
}
if have 300 legacy; then
    if kiosk legacy 300 $light --frames 6 --kms legacy; then flips legacy 6; else bad "legacy: $(cat "$out/legacy")"; fi
    grep -q "; legacy modesetting (asked for)" "$out/legacy" || bad "legacy: not said: $(head -1 "$out/legacy")"
    restored legacy
fi
# Atomic unasked (--kms auto, the default), where the driver has it.
if have 300 atomic; then
    if kiosk atomic 300 $light --frames 6; then flips atomic 6; else bad "atomic: $(cat "$out/atomic")"; fi
    if grep -q "; atomic modesetting; fences" "$out/atomic"; then ok "atomic: chosen by default: $(grep -o 'atomic modesetting; fences' "$out/atomic")"
    else bad "atomic: not chosen by default: $(head -1 "$out/atomic")"; fi
    restored atomic
    # Explicit fences: every flip's OUT_FENCE_PTR fence waited on (vkms has the
    # property); the GPU's fence goes to the plane only where EGL has native
    # fences, which the guest's software GL has not: it must say so.
    if grep -q "fences in 0 out 5" "$out/atomic" && grep -q "fences: none to the plane (EGL has no native fences), the flip's waited on" "$out/atomic"; then
        ok "atomic: explicit fences: $(grep -o 'fences: [^;]*' "$out/atomic"); $(grep -o 'fences in [0-9]* out [0-9]*' "$out/atomic")"
    else bad "atomic: fences: $(grep -o 'fences[^;]*' "$out/atomic" | tr '\n' ' ')"; fi
fi
# A driver without atomic modesetting, and one whose atomic path refuses the
# modeset (vkms made to, by a preloaded library): the default falls back to
# legacy and says why; --atomic fails, naming the problem.
refuse="$(dirname "$touch")/kms_refuse_atomic.so"
# refusing NAME LIMIT WHAT ARGS...: the kiosk with JADE_REFUSE=WHAT preloaded.
refusing() {
    r_name=$1 r_limit=$2 r_what=$3
    shift 3
    bounded "$r_name" "$r_limit" env JADE_REFUSE="$r_what" LD_PRELOAD="$refuse" "$jade" kiosk --drm-device /dev/dri/card0 "$@"
}
if have 550 fallback; then
    if refusing no_atomic 150 cap $light --frames 4 &&
        grep -q "; legacy modesetting (the driver does not offer atomic modesetting);" "$out/no_atomic"; then flips no_atomic 4
    else bad "no atomic: $(cat "$out/no_atomic")"; fi
    restored no_atomic
    if refusing refused 150 modeset $light --frames 4 &&
        grep -q "the atomic modeset was refused: Invalid argument; legacy modesetting from here on" "$out/refused"; then
        flips refused 4
    else bad "atomic modeset refused: $(cat "$out/refused")"; fi
    restored refused
    if refusing must_atomic 60 cap $light --frames 1 --atomic; then bad "--atomic ran without atomic"
    elif grep -q "does not offer atomic modesetting (--kms auto falls back to legacy)" "$out/must_atomic"; then ok "--atomic without it: $(head -1 "$out/must_atomic")"
    else bad "--atomic without it: $(cat "$out/must_atomic")"; fi
    # A plane that refuses the GPU's fence (EGL made to offer native fences
    # whose fds the kernel cannot take): the first flip is refused, made
    # again without it, and every later one goes without, said once.
    if refusing fence 150 fence $light --frames 4 && grep -q "fences: the GPU's to the plane" "$out/fence" &&
        grep -q "the plane refused the GPU's fence (Invalid argument): flips without it from here on" "$out/fence" &&
        grep -q "fences in 0 out 3" "$out/fence"; then
        flips fence 4
        ok "fence refused: $(grep -o "the plane refused[^;]*" "$out/fence"); $(grep -o 'fences in [0-9]* out [0-9]*' "$out/fence")"
    else bad "fence refused: $(cat "$out/fence")"; fi
    restored fence
fi
# What was chosen is what was asked.
if have 200 choose; then
    if kiosk choose 200 $light --frames 2 --connector Virtual-1 --display-mode 800x600 && grep -q "Virtual-1 800x600" "$out/choose"; then
        ok "--connector Virtual-1 --display-mode 800x600: $(grep -o 'DRM/KMS [^,]*' "$out/choose")"
    else bad "connector and mode choice: $(cat "$out/choose")"; fi
fi
if have 150 rotate; then
    if kiosk rotate 150 $light --frames 3 --rotate 90; then ok "--rotate 90 runs: $(grep '^kiosk:' "$out/rotate")"; else bad "--rotate 90: $(cat "$out/rotate")"; fi
fi
if have 120 nomode; then
    if kiosk nomode 120 $light --frames 1 --display-mode 123x45 2>/dev/null; then bad "a mode the display lacks was accepted"
    else ok "a mode the display lacks is refused: $(head -1 "$out/nomode")"; fi
fi
# SIGTERM mid-run, the display given back; a second kiosk meanwhile is refused.
if have 300 SIGTERM; then
    "$jade" kiosk --drm-device /dev/dri/card0 $light > "$out/term" 2>&1 &
    pid=$!
    wait_for "$out/term" "anti-aliasing" 120
    sleep 4
    # Bounded as every other kiosk here: a refusal that blocked instead
    # would otherwise hold the guest's checks until the host gave up.
    if kiosk second 60 $light --frames 1; then bad "a second kiosk took the display"
    elif grep -q "held by jade (pid $pid)" "$out/second"; then ok "a second kiosk is refused, the holder named: $(cat "$out/second" | head -1)"
    else bad "second kiosk: $(cat "$out/second")"; fi
    sent=$(date +%s%N)
    stop "$pid" term
    rc=$?
    ms=$(( ($(date +%s%N) - sent) / 1000000 ))
    if [ "$rc" -eq 0 ] && grep -q "^kiosk: [0-9]* frames" "$out/term"; then ok "SIGTERM mid-run: exit 0 after $ms ms: $(grep '^kiosk: [0-9]* frames' "$out/term")"
    else bad "SIGTERM: exit $rc: $(cat "$out/term")"; fi
    restored SIGTERM
fi
# The default scene as the display scans it out, read back by vkms's
# writeback connector at the end (--screenshot), against jade's own render of
# the same still scene made here in the guest (llvmpipe's pictures depend on
# the CPU it sees).
if have 700 capture; then
    still="--light-speed 0 --antialias off"
    if kiosk capture 350 --display-mode 640x480 --decode-timeout-ms 60000 --frames 3 --atomic $still --screenshot "$out/scanout.png"; then
        if ! bounded render 300 "$jade" render --size 640x480 --decode-timeout-ms 60000 --antialias off --out "$out/render.png"; then
            bad "the guest's render: $(cat "$out/render")"
        # Not two blank pictures: the object is in the capture, whole.
        elif "$imgcmp" "$out/scanout.png" "$out/render.png" --max-rmse 0.5 --max-bad-frac 0.001 > "$out/cmp" 2>&1 &&
            "$imgcmp" --frame "$out/scanout.png" 0.3 >> "$out/cmp" 2>&1; then
            ok "the scanned-out picture (writeback) is jade's render: $(cat "$out/cmp" | tr '\n' ' ')"
        else bad "the scanned-out picture differs from the render: $(cat "$out/cmp")"; fi
    else bad "writeback capture: $(cat "$out/capture")"; fi
    restored capture
fi
# The same through the pass after the frame (no multisampled config asked
# for), which marks its flat pixels in the display surface's own depth
# buffer and then smooths the edges alone: the scan-out is jade's render
# through the same pass, which marks them in the headless target's.
if have 500 capture_post; then
    post="--light-speed 0 --antialias post"
    if kiosk capture_post 350 --display-mode 640x480 --decode-timeout-ms 60000 --frames 3 --atomic $post \
        --screenshot "$out/scanout_post.png" &&
        grep -q "^anti-aliasing: a pass after the frame (the target has no multisampling), on the edges its test marks" \
            "$out/capture_post"; then
        if ! bounded render_post 300 "$jade" render --size 640x480 --decode-timeout-ms 60000 --antialias post \
            --out "$out/render_post.png"; then
            bad "the guest's render through the pass: $(cat "$out/render_post")"
        elif "$imgcmp" "$out/scanout_post.png" "$out/render_post.png" --max-rmse 0.5 --max-bad-frac 0.001 > "$out/pcmp" 2>&1 &&
            "$imgcmp" --frame "$out/scanout_post.png" 0.3 >> "$out/pcmp" 2>&1; then
            ok "the pass after the frame on KMS, its marks in the surface's depth: $(grep '^anti-aliasing' "$out/capture_post"); $(cat "$out/pcmp" | tr '\n' ' ')"
        else bad "the scan-out through the pass differs from the render: $(cat "$out/pcmp")"; fi
    else bad "writeback capture through the pass: $(cat "$out/capture_post")"; fi
    restored capture_post
fi
# The display engine enlarging the picture: under the mali400 profile the
# tier draws 1280x720 at 960x540, and with atomic modesetting (the default
# where the driver has it) the kiosk asks the plane's scaler to enlarge it
# (vkms scales here, nearest pixel: tools/kms/vkms-plane-scaling.patch), not
# a GL pass. What the writeback reads back is the whole picture at the
# mode's size, as jade's render enlarges it (bilinear: the outline's pixels
# differ). With legacy modesetting the GPU enlarges it, and says why.
tier="--display-mode 1280x720 --profile mali400 --decode-timeout-ms 60000 --mode none --antialias off --mesh $cube"
if have 600 scale; then
    if kiosk scale 300 $tier --frames 3 --light-speed 0 --screenshot "$out/scaled.png" &&
        grep -q "^kiosk: the display engine enlarges 960x540 to 1280x720" "$out/scale"; then
        ok "the plane's scaler enlarges the tier's picture: $(grep '^kiosk: the display' "$out/scale"); $(grep '^kiosk: [0-9]* frames' "$out/scale")"
        if bounded scaled_render 200 "$jade" render --size 1280x720 --profile mali400 --decode-timeout-ms 60000 --mode none --antialias off \
            --mesh "$cube" --out "$out/scaled_render.png" &&
            "$imgcmp" "$out/scaled.png" "$out/scaled_render.png" --max-rmse 4 --max-bad-frac 0.01 > "$out/scmp" 2>&1 &&
            "$imgcmp" --frame "$out/scaled.png" 0.3 >> "$out/scmp" 2>&1; then
            ok "the scanned-out picture is the render, enlarged: $(cat "$out/scmp" | tr '\n' ' ')"
        else bad "the enlarged scan-out differs from the render: $(cat "$out/scmp" "$out/scaled_render" 2>/dev/null | tr '\n' ' ')"; fi
    else bad "plane scaling: $(cat "$out/scale")"; fi
    restored scale
    # With the display's multisampled config (no --antialias off): under the
    # scaler the picture is drawn into the multisampled surface itself;
    # enlarged by the GPU (the guest's GL has no
    # EXT_multisampled_render_to_texture) its edges are smoothed by the pass
    # after the frame at 960x540, and it says so.
    tier_aa=$(echo "$tier" | sed 's/ --antialias off//')
    if kiosk scale_aa 150 $tier_aa --frames 2 --light-speed 0 && grep -q "^kiosk: the display engine enlarges" "$out/scale_aa" &&
        grep -q "^anti-aliasing: 4x multisampling in the target" "$out/scale_aa"; then
        ok "under the scaler the picture is multisampled: $(grep '^anti-aliasing' "$out/scale_aa")"
    else bad "scaler and multisampling: $(cat "$out/scale_aa")"; fi
    if kiosk scale_gpu 150 $tier_aa --frames 2 --kms legacy && grep -q "^kiosk: the GPU enlarges 960x540 to 1280x720 (legacy" "$out/scale_gpu" &&
        grep -q "^anti-aliasing: a pass after the frame on the picture drawn at 960x540, on the edges its test marks, then enlarged (the target's 4x" "$out/scale_gpu"; then
        ok "with legacy modesetting the GPU enlarges it: $(grep '^kiosk: the GPU' "$out/scale_gpu"); $(grep '^anti-aliasing' "$out/scale_gpu")"
    else bad "legacy with the tier: $(cat "$out/scale_gpu")"; fi
fi
# Hotplug: the display unplugged and plugged back in. vkms makes no hotplug
# of its own, so the connector is forced off and on through debugfs and the
# kernel's uevent is asked for by hand, as a real hotplug would send it.
# hotplug NAME ARGS...: the kiosk with ARGS through it.
force=$(ls -d /sys/kernel/debug/dri/0/Virtual-1 2>/dev/null)/force
# forcing WHAT: writes WHAT to the connector's force file, at most 30 s.
# Once in a local run the checks stopped right where the first write was
# due (cause unknown): a write the kernel does not finish fails the check
# instead of holding the guest's shell.
forcing() {
    ( printf %s "$1" > "$force" ) &
    fpid=$! i=0
    while [ $i -lt 300 ] && alive $fpid; do sleep 0.1; i=$((i + 1)); done
    if alive $fpid; then
        bad "$h: writing '$1' to $force did not return in 30 s: state $(cut -d' ' -f3 /proc/$fpid/stat), waiting in $(cat /proc/$fpid/wchan 2>/dev/null)"
        return 1
    fi
    wait $fpid
}
hotplug() {
    h=$1
    shift
    "$jade" kiosk --drm-device /dev/dri/card0 "$@" > "$out/$h" 2>&1 &
    pid=$!
    wait_for "$out/$h" "anti-aliasing" 120
    sleep 3
    forcing off && echo change > /sys/class/drm/card0/uevent
    # Under TCG on a loaded host a frame can take 25 s, and uevents are read
    # between frames.
    if wait_for "$out/$h" "the display went away" 90 && sleep 2 && kill -0 "$pid"; then
        ok "$h: unplugged: the kiosk waits: $(grep 'went away' "$out/$h")"
    else bad "$h: unplug: $(cat "$out/$h")"; fi
    forcing on && echo change > /sys/class/drm/card0/uevent
    if wait_for "$out/$h" "the display is back" 90 && wait_for "$out/$h" "set again" 90; then
        ok "$h: plugged back: $(grep -e 'is back' -e 'set again' "$out/$h" | tr '\n' ' ')"
    else bad "$h: plug back: $(cat "$out/$h")"; fi
    # The plane as the kernel has it now (its source and its place on the CRTC).
    sed -n '/^plane\[/,/^crtc\[/p' "$state" | grep -e 'src-pos=' -e 'crtc-pos=' | head -2 | tr -d '\t' | tr '\n' ' ' > "$out/${h}_plane"
    forcing unspecified # 11 bytes: the kernel's buffer has no room for a newline too
    stop "$pid" "$h"
    rc=$?
    line=$(grep "^kiosk: [0-9]* frames" "$out/$h")
    if [ "$rc" -eq 0 ] && echo "$line" | grep -q "modesets 2"; then
        ok "$h: a frame shown again by a second modeset, exit 0 at SIGTERM: $line"
    else bad "$h: after the hotplug: exit $rc: $(cat "$out/$h")"; fi
    restored "$h"
}
if [ ! -w "$force" ]; then
    echo "no debugfs force file for Virtual-1: hotplug is not tried" | tee -a "$res"
else
    if have 450 hotplug; then hotplug hotplug $light --kms legacy; fi
    # The same with the plane's scaler enlarging the picture: the display
    # comes back with the same mode, and the plane still enlarges 960x540.
    if have 450 hotplug_scaled; then
        hotplug hotplug_scaled $tier --light-speed 0
        if grep -q "crtc-pos=1280x720+0+0" "$out/hotplug_scaled_plane" &&
            grep -q "src-pos=960.000000x540.000000+0.000000+0.000000" "$out/hotplug_scaled_plane"; then
            ok "hotplug_scaled: after the second modeset the plane still enlarges: $(cat "$out/hotplug_scaled_plane")"
        else bad "hotplug_scaled: the plane after the hotplug: $(cat "$out/hotplug_scaled_plane")"; fi
    fi
fi
# A touch screen: udev tags it, libinput finds it, a swipe turns the object.
if [ ! -e /dev/uinput ] || [ ! -x /lib/systemd/systemd-udevd ]; then
    echo "no /dev/uinput or systemd-udevd: the touch screen is not tried" | tee -a "$res"
elif have 380 touch; then
    /lib/systemd/systemd-udevd --daemon 2>/dev/null
    "$touch" 120000 > "$out/touch_dev" 2>&1 &
    tpid=$!
    sleep 1
    udevadm trigger --subsystem-match=input --action=add 2>/dev/null
    udevadm settle -t 10 2>/dev/null
    "$jade" kiosk --drm-device /dev/dri/card0 $light --idle 2 > "$out/touch" 2>&1 &
    pid=$!
    # The swipe once the kiosk has started (its input found, its display
    # set): a swipe made before would go by unseen.
    wait_for "$out/touch" "anti-aliasing" 120
    kill -USR1 "$tpid" 2>/dev/null
    wait_for "$out/touch" "touched at" 50
    wait_for "$out/touch" "back in place" 60
    stop "$pid" touch
    kill "$tpid" 2>/dev/null
    if grep -q "input: 1 touch or pointer device" "$out/touch"; then ok "libinput finds the touch screen: $(grep -o 'input: [^;]*' "$out/touch")"
    else bad "touch screen not found: $(head -3 "$out/touch")"; fi
    if grep -q "^kiosk: touched at" "$out/touch" && grep -q "^kiosk: back in place" "$out/touch"; then
        ok "a swipe turns the object and it turns back: $(grep '^kiosk: touched' "$out/touch"); $(grep '^kiosk: back' "$out/touch")"
    else bad "swipe: $(cat "$out/touch" "$out/touch_dev")"; fi
    restored touch
fi
kill "$beating" 2>/dev/null
cp "$out"/* "$share"/ 2>/dev/null
echo "kms guest: $pass passed, $fail failed, $notrun not run (at $(now) s)" | tee -a "$res"
