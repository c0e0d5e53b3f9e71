#!/bin/sh
# Long-run check: tools/soak.sh [KIOSK_FRAMES] [BENCH_FRAMES] [LOG_SECONDS]
# (default 100000 kiosk frames, 10000 bench frames, a sample every 30 s).
# Runs `jade kiosk --platform headless` and `jade bench --mode all
# --cycle-materials` with health lines, then compares the last sample with
# the one at a fifth of the run (after the driver's caches have filled):
# resident memory must grow less than 1%, open descriptors and GL objects
# not at all. Prints each run's curve and the verdict; exits 1 on growth.
# JADE (the program), SOAK_SIZE (WxH, default 64x64) and SOAK_DIR (where the
# logs go) may be set.
set -eu
cd "$(dirname "$0")/.."
kframes=${1:-100000}
bframes=${2:-10000}
every=${3:-30}
jade=${JADE:-build/jade}
size=${SOAK_SIZE:-64x64}
dir=${SOAK_DIR:-build/soak}
mkdir -p "$dir"
[ -x "$jade" ] || { echo "soak: $jade not built"; exit 2; }

# verdict NAME LOG: the health lines' rss, fds and GL objects over time.
verdict() {
    awk -v name="$1" '
        BEGIN { n = 0 }
        / rss / {
            for (i = 1; i <= NF; i++) {
                if ($i == "rss") rss[n] = $(i + 1)
                if ($i == "fds") { f = $(i + 1); sub(",", "", f); fds[n] = f }
                if ($i == "objects") gl[n] = $(i + 1)
                if ($i == "at") t[n] = $(i + 1)
            }
            n++
        }
        END {
            if (n < 3) { printf "%s: only %d samples; run longer\n", name, n; exit 1 }
            b = int(n / 5)
            printf "%s: %d samples; t(s) rss(MiB) fds new-GL-objects:", name, n
            step = int(n / 8); if (step < 1) step = 1
            for (i = 0; i < n; i += step) printf " [%s %s %s %s]", t[i], rss[i], fds[i], gl[i]
            printf " [%s %s %s %s]\n", t[n-1], rss[n-1], fds[n-1], gl[n-1]
            growth = (rss[n-1] - rss[b]) / rss[b] * 100
            ok = growth < 1 && fds[n-1] == fds[b] && gl[n-1] == gl[b]
            printf "%s: from %s s to %s s: rss %s -> %s MiB (%+.2f%%), fds %s -> %s, new GL objects %s -> %s: %s\n",
                   name, t[b], t[n-1], rss[b], rss[n-1], growth, fds[b], fds[n-1], gl[b], gl[n-1],
                   ok ? "flat" : "GROWING"
            exit ok ? 0 : 1
        }' "$2"
}

echo "soak: kiosk, $kframes frames at $size, a sample every $every s"
start=$(date +%s)
"$jade" kiosk --platform headless --size "$size" --frames "$kframes" --log-every "$every" \
    >"$dir/kiosk.log" 2>"$dir/kiosk.err"
echo "soak: kiosk ran $(( $(date +%s) - start )) s: $(tail -n 1 "$dir/kiosk.log")"
rc=0
verdict kiosk "$dir/kiosk.log" || rc=1
per_mode=$((bframes / 4))
echo "soak: bench --mode all --cycle-materials, $per_mode frames per mode"
start=$(date +%s)
"$jade" bench --mode all --cycle-materials --size "$size" --frames "$per_mode" --log-every "$every" \
    >"$dir/bench.json" 2>"$dir/bench.log"
echo "soak: bench ran $(( $(date +%s) - start )) s"
verdict bench "$dir/bench.log" || rc=1
exit "$rc"
