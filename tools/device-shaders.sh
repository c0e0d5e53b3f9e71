#!/bin/sh
# Every jade shader program through the real device compilers, with no GPU:
# Mesa's lima (Mali-400/450), vc4 (VideoCore IV), panfrost (Mali Midgard
# T720/T860), etnaviv (Vivante GC400, GC2000, GC3000, GC7000L) and
# freedreno (Adreno 306, 320) drivers built from Debian's own source
# package, run behind Mesa's drm-shim (a preloaded library that fakes the
# kernel device, as Mesa's shader-db does).
#
#   tools/device-shaders.sh [--check EXPECTED] [--update EXPECTED]
#
# Prints one table row per driver and program: compiled, linked,
# instructions, registers/threads, spills and fills, and the compiler's
# message on failure. With --check, exits 1 when a program stops compiling
# or linking, or its instruction count or spills grow more than 10% over
# the committed table (tests/device-shaders.expected), or comes within 10%
# of a hard limit of its GPU (Vivante cores without an instruction cache,
# GC400 to GC2000, run only programs of at most 256 instructions per stage:
# 230 is the most a program may have); --update rewrites it.
#
# The Mesa build (376 s on 2 cores the first time, 2026-11-29) is cached in
# $JADE_DEVICE_CACHE (default: build-device). Exits 77 (skip) when the
# source package or the build tools cannot be had.
set -eu
cd "$(dirname "$0")/.."
root=$(pwd)
cache=${JADE_DEVICE_CACHE:-$root/build-device}
jade=${JADE:-$root/build/jade}
mode=print expected=""
case "${1:-}" in
    --check) mode=check expected=$2 ;;
    --update) mode=update expected=$2 ;;
    "") ;;
    *) echo "usage: $0 [--check|--update tests/device-shaders.expected]"; exit 2 ;;
esac
mkdir -p "$cache"
skip() { echo "device-shaders: skipped: $*"; exit 77; }
[ -x "$jade" ] || skip "$jade is not built"

# 1. Mesa's source, from a deb-src entry derived from this machine's own
#    apt sources (never a host name written here), in a private apt state.
mesa=$cache/mesa
if [ ! -f "$mesa/.extracted" ]; then
    for t in dpkg-source meson ninja bison flex; do command -v $t >/dev/null || skip "$t is missing (apt: dpkg-dev meson ninja-build bison flex python3-mako)"; done
    /usr/bin/python3 -c 'import mako' 2>/dev/null || skip "python3-mako is missing"
    apt=$cache/apt
    mkdir -p "$apt/sources.list.d" "$apt/lists/partial" "$cache/src"
    : > "$apt/sources.list.d/src.sources"
    for f in /etc/apt/sources.list.d/*.sources; do
        [ -f "$f" ] && sed -n '/^Types:/,$p' "$f" | sed 's/^Types:.*/Types: deb-src/' >> "$apt/sources.list.d/src.sources" &&
            echo >> "$apt/sources.list.d/src.sources"
    done
    list=$apt/sources.list
    : > "$list"
    for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
        [ -f "$f" ] && grep -E '^deb ' "$f" | grep -v 'cdrom:' | sed 's/^deb /deb-src /' >> "$list" || true
    done
    aptopt="-o Dir::Etc::SourceParts=$apt/sources.list.d -o Dir::Etc::SourceList=$list -o Dir::State::Lists=$apt/lists"
    # shellcheck disable=SC2086
    apt-get -q $aptopt update >"$cache/apt.log" 2>&1 || true
    version=$(dpkg-query -W -f '${Version}' libgl1-mesa-dri 2>/dev/null || true)
    # shellcheck disable=SC2086
    (cd "$cache/src" && { apt-get -q $aptopt source --download-only "mesa=$version" ||
                          apt-get -q $aptopt source --download-only mesa; } >>"$cache/apt.log" 2>&1) ||
        skip "apt-get source mesa failed: $(grep -E '^(E|W):' "$cache/apt.log" | head -1)"
    rm -rf "$mesa"
    # apt checked the files against the signed Sources index; dpkg-source
    # would only complain that no Debian keyring is installed.
    dpkg-source -x "$(ls "$cache"/src/mesa_*.dsc | head -1)" "$mesa" >>"$cache/apt.log" 2>&1
    (cd "$mesa" && patch -p1 -s < "$root/tools/device/vc4-shim.patch")
    touch "$mesa/.extracted"
fi

# 2. The drivers, their compilers and the shims.
build=$cache/mesa-build
drivers=lima,vc4,panfrost,kmsro,etnaviv,freedreno
# Unoptimised (-O0) but without assertions: the build took 376 s here
# against 801 s at meson's release -O3 (one generated format table alone
# takes 30-40 s at -O3, 3 s at -O0), and the 33 compiles of step 3 58 s
# against 38 s (2026-11-29). The table is the same, line for line: it is the
# compilers' output, not their speed. Only what step 3 loads is built: no
# standalone tools, no other drivers, no XA, VA or VDPAU.
opt=-O0
# A cache built for another driver list or options is built again.
if [ "$(cat "$build/.built" 2>/dev/null)" != "$drivers $opt" ]; then
    start=$(date +%s)
    rm -rf "$build"
    # Debian's own python3 (with python3-mako), not one a version manager put first.
    PATH=/usr/bin:$PATH meson setup "$build" "$mesa" --buildtype=plain -Dc_args=$opt -Dcpp_args=$opt -Db_ndebug=true \
        -Dgallium-drivers=$drivers -Dgallium-xa=disabled -Dgallium-vdpau=disabled -Dgallium-va=disabled \
        -Dvulkan-drivers= -Dllvm=disabled -Dplatforms= -Dglx=disabled -Degl=enabled -Dgbm=enabled \
        -Dgles1=disabled -Dgles2=enabled -Dopengl=true -Dtools=drm-shim -Dshared-glapi=enabled \
        -Dvalgrind=disabled -Dlibunwind=disabled -Dzstd=disabled >"$cache/meson.log" 2>&1 ||
        { tail -20 "$cache/meson.log"; skip "meson setup failed (see $cache/meson.log)"; }
    targets="src/egl/libEGL.so.1.0.0 src/mapi/es2api/libGLESv2.so.2.0.0 src/mapi/shared-glapi/libglapi.so.0.0.0
             src/gbm/libgbm.so.1.0.0 src/gallium/drivers/lima/drm-shim/liblima_noop_drm_shim.so
             src/broadcom/drm-shim/libvc4_noop_drm_shim.so src/panfrost/drm-shim/libpanfrost_noop_drm_shim.so
             src/etnaviv/drm-shim/libetnaviv_noop_drm_shim.so src/freedreno/drm-shim/libfreedreno_noop_drm_shim.so"
    for d in lima vc4 panfrost etnaviv msm; do targets="$targets src/gallium/targets/dri/${d}_dri.so"; done
    # shellcheck disable=SC2086
    PATH=/usr/bin:$PATH ninja -C "$build" $targets >"$cache/ninja.log" 2>&1 || { tail -20 "$cache/ninja.log"; echo "device-shaders: Mesa build failed"; exit 1; }
    echo "device-shaders: Mesa built in $(( $(date +%s) - start )) s"
    echo "$drivers $opt" > "$build/.built"
fi

# 3. jade info --compile through each driver: every program of every mode
#    for that GPU's profile, compiled at link time (the drivers' precompile
#    switches), nothing drawn (the shims never signal a fence). The
#    compilers' statistics arrive as GL_KHR_debug messages after the
#    "compiling program N" line they belong to.
lib_dir() { dirname "$(find "$build" -name "$1" -print -quit)"; }
egl=$(lib_dir 'libEGL.so.1') gles=$(lib_dir 'libGLESv2.so.2') glapi=$(lib_dir 'libglapi.so.0') gbm=$(lib_dir 'libgbm.so.1')
dri=$(lib_dir 'lima_dri.so')
shim() { find "$build" -name "lib$1_noop_drm_shim.so" -print -quit; }
run_driver() { # NAME PROFILE SHIM ENV... (PROFILE "-": none, the device's own limits)
    name=$1 profile=$2 lib=$3
    shift 3
    [ "$profile" = - ] && profile=""
    # Three builds: as shipped, then with every dynamic loop at a constant
    # trip count of 1 and of 2 (jade info --unroll-loops): what one more
    # trip costs, for the frame-cost model (core/frame_cost.c). The
    # drivers run side by side, as many at a time as there are cores (each
    # is one single-threaded process: the 33 took 58 s so on 2 cores, 2026-11-29).
    [ "$running" -lt "$cores" ] || { wait; running=0; }
    running=$((running + 1))
    for unroll in 0 1 2; do
        # A failed program makes jade exit 1: the table still gets its row.
        rc=0
        env LD_LIBRARY_PATH="$egl:$gles:$glapi:$gbm" LIBGL_DRIVERS_PATH="$dri" EGL_PLATFORM=surfaceless \
            MESA_SHADER_CACHE_DISABLE=true LD_PRELOAD="$lib" "$@" \
            timeout 300 "$jade" info --compile ${profile:+--profile "$profile"} --unroll-loops $unroll \
            >"$cache/$name.$unroll.log" 2>&1 || rc=$?
        echo "$rc" > "$cache/$name.$unroll.rc"
    done &
}
cores=$(nproc) running=0
run_driver lima mali400 "$(shim lima)" LIMA_DEBUG=precompile
run_driver vc4 vc4 "$(shim vc4)" VC4_DEBUG=shaderdb
run_driver panfrost-t720 generic "$(shim panfrost)" PAN_MESA_DEBUG=precompile PAN_GPU_ID=720
run_driver panfrost-t860 generic "$(shim panfrost)" PAN_MESA_DEBUG=precompile PAN_GPU_ID=860
# Vivante: GC400 (STM32MP1) and GC2000 (i.MX6 Quad) under the vivante
# profile, which is GC2000's limits (GC400's own, lower, still apply);
# GC3000 (i.MX6 QuadPlus) and GC7000L (i.MX8M) with their own limits.
for gpu in GC400 GC2000; do
    run_driver "etnaviv-$(echo $gpu | tr A-Z a-z)" vivante "$(shim etnaviv)" ETNA_MESA_DEBUG=shaderdb ETNA_SHIM_GPU=$gpu
done
for gpu in GC3000 GC7000L; do
    run_driver "etnaviv-$(echo $gpu | tr A-Z a-z)" - "$(shim etnaviv)" ETNA_MESA_DEBUG=shaderdb ETNA_SHIM_GPU=$gpu
done
# Adreno 306 (Snapdragon 410; the kernel and the shim call it 307 after
# its chip id 3.0.6.0) and Adreno 320 (Snapdragon 600), their own limits.
run_driver freedreno-a306 adreno3xx "$(shim freedreno)" FD_MESA_DEBUG=shaderdb FD_GPU_ID=307
run_driver freedreno-a320 adreno3xx "$(shim freedreno)" FD_MESA_DEBUG=shaderdb FD_GPU_ID=320
wait

# 4. One row per driver and program. The cost columns are what the
#    frame-cost model charges per vertex and per fragment, in each
#    compiler's own unit: lima's instruction words; vc4's estimated cycles
#    (its scheduler counts the texture waits a single-threaded shader
#    stalls on) or, for a two-threaded fragment shader, its instructions;
#    panfrost's bundles; etnaviv's instructions (its compiler prints 32-bit
#    words, four to an instruction); freedreno's instructions with their
#    repeats and nops (ir3 issues one per clock, the nops being the waits
#    its scheduler could not fill). fc: the program as built; f1, f2: with its dynamic
#    loops at 1 and 2 trips (equal to fc where it has none).
rows() { # DRIVER UNROLL
    awk -v drv="$1" -v rc="$(cat "$cache/$1.$2.rc")" '
        function flush() {
            if (label == "") return
            if (again) { label = ""; return }
            if (status == "") status = "ok"
            printf "%-14s %-62s vs %4s fs %4s spills %3d fills %3d %s %s %-9s %s\n", drv, label, vs == "" ? "-" : vs,
                   fs == "" ? "-" : fs, spills, fills, vc == "" ? "-" : vc, fc == "" ? "-" : fc, extra == "" ? "-" : extra, status
            label = ""
        }
        # A program built again (jade info --compile builds the colour
        # variants with a second renderer) keeps its first row.
        /^jade: compiling program / { flush(); label = $4 $5; vs = fs = vc = fc = extra = status = ""; spills = fills = 0
                                      again = ($5 in seen); seen[$5] = 1; open = 1; next }
        # The program is built: what the driver compiles after it (its own
        # internal shaders: lima and panfrost build clear and resolve
        # programs when a target takes samples) belongs to no program.
        /^program +[0-9]+ / { if ($0 ~ /FAILED/) { status = "FAILED:" $0; gsub(/ /, "_", status) } open = 0; next }
        /shader compiler: / {
            if (!open) next
            line = $0; sub(/.*shader compiler: /, "", line)
            if (line ~ /COORD|^BVERT/) next   # vc4, freedreno: the binning copy of the vertex shader
            n = split(line, w, /[ ,]+/)
            inst = cyc = bdl = thr = ""
            for (i = 1; i < n; i++) {
                if (w[i + 1] == "inst") inst = w[i]
                if (w[i + 1] == "instructions") inst = w[i] / 4   # etnaviv: words
                if (w[i + 1] == "estimated-cycles") cyc = w[i]
                if (w[i + 1] == "bundles") bdl = w[i]
                if (w[i + 1] == "threads") thr = w[i]
            }
            cost = bdl != "" ? bdl : cyc != "" && thr == 1 ? cyc : inst
            for (i = 1; i < n; i++) {
                if (w[i + 1] == "spills:fills") { split(w[i], sf, ":"); spills += sf[1]; fills += sf[2] }
                if (w[i + 1] == "threads") extra = extra (extra == "" ? "" : "/") w[i] "thr"
                if (w[i + 1] == "registers") extra = extra (extra == "" ? "" : "/") w[i] "reg"
                if (w[i + 1] == "temps") extra = extra (extra == "" ? "" : "/") w[i] "temp"
                if (w[i + 1] == "full" || w[i + 1] == "half") extra = extra (extra == "" ? "" : "/") w[i] w[i + 1]
                if (w[i + 1] == "uniforms" && line !~ /VERTEX|vertex/) extra = extra (extra == "" ? "" : "/") w[i] "unif"
            }
            if (line ~ /^(VS|vertex|MESA_SHADER_VERTEX|vs)/ || line ~ /^VERT/) { vs = inst; vc = cost } else { fs = inst; fc = cost }
            next
        }
        /Failed to register allocate/ { status = "FAILED:register-allocation" }
        END { flush(); if (rc != 0 && rc != 1) printf "%-14s %-62s exit %s (see the log)\n", drv, "(run)", rc }
    ' "$cache/$1.$2.log"
}
table=$cache/device-shaders.table
for d in lima vc4 panfrost-t720 panfrost-t860 etnaviv-gc400 etnaviv-gc2000 etnaviv-gc3000 etnaviv-gc7000l \
         freedreno-a306 freedreno-a320; do
    rows "$d" 0 > "$cache/$d.rows0"
    rows "$d" 1 > "$cache/$d.rows1"
    rows "$d" 2 > "$cache/$d.rows2"
    # Row by row (the same programs in the same order): the costs of the
    # two unrolled builds join the shipped build's row.
    awk '
        FILENAME == ARGV[1] { f1[FNR] = $12; next }
        FILENAME == ARGV[2] { f2[FNR] = $12; next }
        $3 != "vs" { print; next }
        { printf "%-14s %-62s vs %4s fs %4s spills %3d fills %3d cost vc %4s fc %4s f1 %4s f2 %4s %-9s %s\n",
                 $1, $2, $4, $6, $8, $10, $11, $12, f1[FNR] == "" ? "-" : f1[FNR], f2[FNR] == "" ? "-" : f2[FNR], $13, $14 }
    ' "$cache/$d.rows1" "$cache/$d.rows2" "$cache/$d.rows0"
done > "$table"
echo "device-shaders: one row per driver and program (instructions per stage as each compiler counts them):"
cat "$table"
# 5. The picture drawn smaller (info --compile's render scale 0.5) into a
#    texture with the headless target's samples: the driver's framebuffer
#    made complete with them (EXT_multisampled_render_to_texture), or why not.
#    Mesa 22.3.6's lima and panfrost list the extension (panfrost runs under
#    the generic profile here, which promises no extension); lima listing it
#    and refusing the framebuffer would leave Mali-400's enlarged pictures
#    without anti-aliased edges, and --check fails on it.
ms_bad=0
for d in lima vc4 panfrost-t720 panfrost-t860 etnaviv-gc2000 freedreno-a306; do
    line=$(grep -m1 '^anti-aliasing' "$cache/$d.0.log" || echo "no anti-aliasing line (see $cache/$d.0.log)")
    echo "device-shaders: $d: $line"
    case $d in lima) case $line in *"multisampling in the picture drawn at"*) ;; *) ms_bad=1 ;; esac ;; esac
done
case $mode in
    update) cp "$table" "$expected"; echo "device-shaders: wrote $expected" ;;
    check)
        # Programs are matched by driver and name, not by their place in the
        # list (a program added in the middle must not make every later one
        # "new"); a name that repeats counts its occurrences. A GPU's hard
        # limit (limit[]) is checked with 10% to spare: a program nearer
        # than that fails whatever the committed table says.
        budget_bad=0
        awk '
            BEGIN { limit["etnaviv-gc400"] = 256; limit["etnaviv-gc2000"] = 256 }
            function name(drv, prog,   n) {
                sub(/^[0-9]+:/, "", prog)
                n = ++seen[FILENAME, drv, prog]
                return drv " " prog (n > 1 ? " #" n : "")
            }
            NR == FNR { key = name($1, $2); want_vs[key] = $4; want_fs[key] = $6; want_sp[key] = $8; next }
            {
                key = name($1, $2); st = $NF
                if (st != "ok") { print "device-shaders: " key ": " st; bad = 1; next }
                if ($1 in limit) {
                    # etnaviv prints no count for a shader it failed to compile
                    # (the link still succeeds: the draw would fail).
                    if ($4 == "-" || $6 == "-") { print "device-shaders: " key ": no instruction count (the compiler failed?)"; bad = 1 }
                    if ($4 > limit[$1] * 0.9 || $6 > limit[$1] * 0.9) {
                        printf "device-shaders: %s: VS %s, FS %s instructions: over %d, within 10%% of the %d this GPU can hold\n",
                               key, $4, $6, limit[$1] * 0.9, limit[$1]
                        bad = 1
                    }
                }
                if (!(key in want_fs)) { print "device-shaders: " key ": new program (update the table)"; next }
                if (want_vs[key] != "-" && $4 > want_vs[key] * 1.1) { print "device-shaders: " key ": VS " want_vs[key] " -> " $4 " instructions (over 10%)"; bad = 1 }
                if (want_fs[key] != "-" && $6 > want_fs[key] * 1.1) { print "device-shaders: " key ": FS " want_fs[key] " -> " $6 " instructions (over 10%)"; bad = 1 }
                if ($8 > want_sp[key]) { print "device-shaders: " key ": spills " want_sp[key] " -> " $8; bad = 1 }
            }
            END { exit bad }
        ' "$expected" "$table" || budget_bad=1
        # The budget's verdict is the exit status: the check after it must
        # not replace it (it did: a program over the budget printed its line
        # and the script still exited 0).
        [ "$budget_bad" -eq 0 ] && echo "device-shaders: within the committed budget and the GPUs' limits ($expected)"
        [ "$ms_bad" -eq 0 ] || { echo "device-shaders: lima drew the smaller picture without samples (above)"; exit 1; }
        [ "$budget_bad" -eq 0 ] || exit 1
        ;;
esac
