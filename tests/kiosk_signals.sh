#!/bin/sh
# The running kiosk, sent real signals: SIGTERM (systemctl stop) and SIGINT
# (Ctrl-C) end it within a frame or two, with its statistics line and exit
# status 0, on the headless platform and on X11 (Xvfb, started here when it
# is installed). A kiosk that keeps running is killed after 10 s and fails.
jade=$1 out=$2 drag=${3:-none}
pass=0 fail=0
run() { # run PLATFORM SIGNAL[+SIGNAL: a second one right after] [env...]
    plat=$1 sig=${2%+*} again=
    case $2 in *+*) again=${2#*+} ;; esac
    shift 2
    rm -f "$out/kiosk_$plat.$sig$again.txt" # the last run's: see the SIGHUP check
    env "$@" "$jade" kiosk --platform "$plat" --size 160x120 > "$out/kiosk_$plat.$sig$again.txt" 2>&1 &
    pid=$!
    # Until it has drawn frames: start-up (decode, shaders) is not the point.
    # Up to 60 s: on a loaded machine a start took over 10 s, and a SIGHUP
    # sent before main() installs its handlers ends any process.
    i=0
    while [ $i -lt 600 ] && ! grep -qs "anti-aliasing" "$out/kiosk_$plat.$sig$again.txt"; do sleep 0.1; i=$((i + 1)); done
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
# SIGHUP re-reads --config: a new material and mesh take effect, a broken
# file leaves the kiosk as it was, a display option waits for a restart;
# the live GL objects stay as many after 6 mesh changes as before.
conf="$out/kiosk_hup.conf"
printf '# test\nplatform = headless\nsize = 96x72\nmaterial = skin1\nlog-every = 0.3\n' > "$conf"
# The last run's log goes first: the shell truncates it in the child, and a
# grep here could read the old one's start line before that.
rm -f "$out/kiosk_hup.out" "$out/kiosk_hup.err"
"$jade" kiosk --config "$conf" > "$out/kiosk_hup.out" 2> "$out/kiosk_hup.err" &
pid=$!
i=0
while [ $i -lt 600 ] && ! grep -qs "anti-aliasing" "$out/kiosk_hup.err" && kill -0 "$pid" 2>/dev/null; do sleep 0.1; i=$((i + 1)); done
# A kiosk that did not start is said, with where it is, not sent SIGHUPs
# (which would end a process that has no handler yet).
if ! grep -q "anti-aliasing" "$out/kiosk_hup.err"; then
    if kill -0 "$pid" 2>/dev/null; then
        echo "FAIL SIGHUP: the kiosk did not start in $((i / 10)) s: state $(sed -n 's/^State:\t//p' /proc/$pid/status), in $(cat /proc/$pid/wchan 2>/dev/null)"
        cat /proc/$pid/stack 2>/dev/null | head -8
        command -v gdb >/dev/null && timeout 30 gdb -p "$pid" -batch -ex "thread apply all bt 12" 2>&1 | grep '^#\|^Thread' | head -40
        kill -KILL "$pid"
    else
        wait "$pid"
        echo "FAIL SIGHUP: the kiosk ended before it started, status $?: $(cat "$out/kiosk_hup.err" "$out/kiosk_hup.out" | head -5)"
    fi
    exit 1
fi
hup() { printf "$1" > "$conf"; kill -HUP "$pid"; i=0; n=$2
        while [ $i -lt 300 ] && [ "$(grep -c SIGHUP "$out/kiosk_hup.err")" -lt "$n" ]; do sleep 0.1; i=$((i + 1)); done; }
base='platform = headless\nsize = 96x72\nlog-every = 0.3\n'
hup "${base}material = ketchup\n" 1
hup "${base}material = ketchup\nbogus = 1\n" 3
hup "${base}material = ketchup\nconnector = HDMI-A-9\n" 5
k=6
for m in tet cube tet cube tet cube; do
    if [ $m = tet ]; then printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' > "$out/kiosk_hup.obj"
    else printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 5\nf 2 5 4\nf 3 4 5\n' > "$out/kiosk_hup.obj"; fi
    hup "${base}mesh = $out/kiosk_hup_$m.obj\n" $k
    cp "$out/kiosk_hup.obj" "$out/kiosk_hup_$m.obj"
    hup "${base}mesh = $out/kiosk_hup_$m.obj\n" $((k + 1))
    k=$((k + 2))
done
# A glTF whose material names ketchup: its material holds through a
# re-read that leaves the mesh as it is (the file is not read again).
{ for c in 0 0 0 1 0 0 0 1 0 0 0 1; do if [ "$c" = 1 ]; then printf '\000\000\200\077'; else printf '\000\000\000\000'; fi; done
  for i in 0 2 1 0 1 3 0 3 2 1 2 3; do printf "\\$(printf %03o "$i")\\000"; done; } > "$out/kiosk_hup.bin"
printf '{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0}]}],"materials":[{"extras":{"jade_material":"ketchup"}}],"buffers":[{"byteLength":72,"uri":"data:application/octet-stream;base64,%s"}],"bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":24}],"accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},{"bufferView":1,"componentType":5123,"count":12,"type":"SCALAR"}]}' \
    "$(base64 -w0 "$out/kiosk_hup.bin")" > "$out/kiosk_hup.gltf"
hup "${base}mesh = $out/kiosk_hup.gltf\n" $k
hup "${base}mesh = $out/kiosk_hup.gltf\nlight-speed = 10\n" $((k + 1))
# jade's textured pebble: its colour texture is made and, at the next mesh,
# deleted with the renderer (the GL object count below); the material its
# colours give holds through a re-read that keeps it.
peb=$(cd "$(dirname "$0")/.." && pwd)/assets/textured/pebble.gltf
hup "${base}mesh = $peb\n" $((k + 2))
hup "${base}mesh = $peb\nlight-speed = 5\n" $((k + 3))
hup "${base}mesh = $out/kiosk_hup.gltf\n" $((k + 4))
sleep 1
kill -TERM "$pid"
wait "$pid"
rc=$?
e="$out/kiosk_hup.err"
check() { if grep -q "$2" "$e"; then pass=$((pass + 1)); echo "ok   SIGHUP: $1: $(grep -m1 "$2" "$e")"
          else fail=$((fail + 1)); echo "FAIL SIGHUP: $1"; cat "$e"; fi; }
check "the new material" "re-read from .*material ketchup"
check "a broken file is named and changes nothing" "line 5: unknown option '--bogus'"
check "a display option waits for a restart" "connector changed; that takes effect at the next start"
check "a new mesh is drawn" "mesh $out/kiosk_hup_cube.obj"
check "the file's material holds when the mesh stays" "mesh $out/kiosk_hup.gltf, material ketchup, light speed 10"
check "a model's colours give its material, and it holds when the mesh stays" "mesh $peb, material colour, light speed 5"
gl_first=$(grep -m1 "new GL objects" "$out/kiosk_hup.out" | sed 's/.*new GL objects //')
gl_last=$(grep "new GL objects" "$out/kiosk_hup.out" | tail -1 | sed 's/.*new GL objects //')
if [ "$rc" -eq 0 ] && [ "$gl_last" = "0/0/0/0" ]; then
    pass=$((pass + 1)); echo "ok   SIGHUP: after $(grep -c 're-read' "$e") re-reads, exit 0, live GL objects beyond the first sample: $gl_first -> $gl_last"
else
    fail=$((fail + 1)); echo "FAIL SIGHUP: exit $rc, GL objects $gl_first -> $gl_last"; tail -3 "$out/kiosk_hup.out"
fi
if command -v Xvfb >/dev/null; then
    xvfb_first=95
    . "$(dirname "$0")/xvfb.sh"
    d=$DISPLAY_NUM
    run x11 TERM DISPLAY=":$d"
    run x11 INT DISPLAY=":$d"
    # Full screen, no pointer, and a drag turns the object until --idle
    # seconds without input bring it back.
    if [ "$drag" != none ]; then
        rm -f "$out/kiosk_drag.out" "$out/kiosk_drag.err"
        DISPLAY=":$d" "$jade" kiosk --platform x11 --idle 1 --log-every 0.5 > "$out/kiosk_drag.out" 2> "$out/kiosk_drag.err" &
        pid=$!
        i=0
        while [ $i -lt 600 ] && ! grep -qs "anti-aliasing" "$out/kiosk_drag.err"; do sleep 0.1; i=$((i + 1)); done
        sleep 0.3
        DISPLAY=":$d" "$drag" jade 200 -60 > "$out/kiosk_drag.send" 2>&1
        i=0
        while [ $i -lt 150 ] && ! grep -q "back in place" "$out/kiosk_drag.out"; do sleep 0.1; i=$((i + 1)); done
        kill -TERM "$pid"
        wait "$pid"
        rc=$?
        if grep -q "window 640x480, full screen" "$out/kiosk_drag.err" &&
           grep -q "_NET_WM_STATE: .*_NET_WM_STATE_FULLSCREEN" "$out/kiosk_drag.send"; then
            pass=$((pass + 1)); echo "ok   x11 kiosk fills the 640x480 screen: $(grep -o 'window .*' "$out/kiosk_drag.err"), $(grep -o '_NET_WM_STATE: .*' "$out/kiosk_drag.send")"
        else fail=$((fail + 1)); echo "FAIL x11 kiosk is not full screen: $(head -1 "$out/kiosk_drag.err")"; fi
        if [ "$rc" -eq 0 ] && grep -q "^kiosk: touched at" "$out/kiosk_drag.out" && grep -q "^kiosk: back in place" "$out/kiosk_drag.out"; then
            pass=$((pass + 1)); echo "ok   x11 drag: $(grep '^kiosk: touched' "$out/kiosk_drag.out"); $(grep '^kiosk: back in place' "$out/kiosk_drag.out")"
        else
            fail=$((fail + 1)); echo "FAIL x11 drag (exit $rc): $(cat "$out/kiosk_drag.send")"; cat "$out/kiosk_drag.out" "$out/kiosk_drag.err"
        fi
    fi
else
    echo "Xvfb missing: the X11 kiosk is not tried"
fi
echo "kiosk signals: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
