# Sourced by the tests that need an X server: starts Xvfb on a free display
# number from $xvfb_first (90) up, sets DISPLAY_NUM, and stops it when the
# test exits. (Sourced: a POSIX shell passes the caller's arguments on.)
d=${xvfb_first:-90}
while [ -e "/tmp/.X$d-lock" ] || [ -e "/tmp/.X11-unix/X$d" ]; do d=$((d + 1)); done
Xvfb ":$d" -screen 0 640x480x24 -nolisten tcp >/dev/null 2>&1 &
xvfb_pid=$!
trap 'kill $xvfb_pid 2>/dev/null' EXIT
i=0
while [ ! -e "/tmp/.X11-unix/X$d" ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
DISPLAY_NUM=$d
