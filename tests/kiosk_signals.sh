#!/bin/sh
# The running kiosk, sent real signals: SIGTERM (systemctl stop) and SIGINT
# (Ctrl-C) end it within a frame or two, with its statistics line and exit
# status 0, on the headless platform and on X11 (Xvfb, started here when it
# is installed). A kiosk that keeps running is killed after 10 s and fails.
jade=$1 out=$2
pass=0 fail=0
run() { # run PLATFORM SIGNAL[+SIGNAL: a second one right after] [env...]
    plat=$1 sig=${2%+*} again=
    case $2 in *+*) again=${2#*+} ;; esac
    shift 2
    env "$@" "$jade" kiosk --platform "$plat" --size 160x120 > "$out/kiosk_$plat.$sig$again.txt" 2>&1 &
    pid=$!
    # Until it has drawn frames: start-up (decode, shaders) is not the point.
    i=0
    while [ $i -lt 100 ] && ! grep -q "anti-aliasing" "$out/kiosk_$plat.$sig$again.txt"; do sleep 0.1; i=$((i + 1)); done
    sleep 0.5
    kill -"$sig" "$pid"
    sent=$(date +%s%N)
    # A second signal while it shuts down (systemd's stop, then an impatient
    # operator): it must not cut the shutdown short.
    [ -n "$again" ] && kill -"$again" "$pid" 2>/dev/null
    ( sleep 10; kill -KILL "$pid" 2>/dev/null ) &
    guard=$!
    wait "$pid"
    rc=$?
    ms=$(( ($(date +%s%N) - sent) / 1000000 ))
    kill "$guard" 2>/dev/null
    if [ "$rc" -eq 0 ] && [ "$ms" -lt 5000 ] && grep -q "^kiosk: [0-9]* frames in" "$out/kiosk_$plat.$sig$again.txt"; then
        pass=$((pass + 1)); echo "ok   $plat SIG$sig${again:+ then SIG$again}: exit 0 after $ms ms: $(grep '^kiosk:' "$out/kiosk_$plat.$sig$again.txt")"
    else
        fail=$((fail + 1)); echo "FAIL $plat SIG$sig: exit $rc after $ms ms"; cat "$out/kiosk_$plat.$sig$again.txt"
    fi
}
run headless TERM
run headless INT
run headless TERM+TERM
run headless INT+TERM
# --wait-display with no display: it waits (systemd may start it before the
# panel), says so once, and a signal ends the wait cleanly.
"$jade" kiosk --wait-display --drm-device "$out/no-such-card" > "$out/kiosk_wait.txt" 2>&1 &
pid=$!
sleep 1.5
kill -TERM "$pid"
( sleep 10; kill -KILL "$pid" 2>/dev/null ) &
guard=$!
wait "$pid"
rc=$?
kill "$guard" 2>/dev/null
if [ "$rc" -eq 0 ] && [ "$(grep -c ': waiting for a display' "$out/kiosk_wait.txt")" -eq 1 ] &&
   grep -q "stopped while waiting" "$out/kiosk_wait.txt"; then
    pass=$((pass + 1)); echo "ok   --wait-display waits, says so once, and SIGTERM ends the wait: exit 0"
else
    fail=$((fail + 1)); echo "FAIL --wait-display: exit $rc"; cat "$out/kiosk_wait.txt"
fi
if command -v Xvfb >/dev/null; then
    xvfb_first=95
    . "$(dirname "$0")/xvfb.sh"
    d=$DISPLAY_NUM
    run x11 TERM DISPLAY=":$d"
    run x11 INT DISPLAY=":$d"
else
    echo "Xvfb missing: the X11 kiosk is not tried"
fi
echo "kiosk signals: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
