#!/bin/sh
# Installs jade into a temporary prefix and builds a small consumer against
# it twice: with find_package(jade) (static libjade) and with pkg-config
# (shared libjade.so). Both must render.
set -u
build=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null || { echo "install failed"; echo "consumer: 0 passed, 1 failed"; exit 1; }
mesh="$tmp/prefix/share/jade/default.drc"
# A sanitizer build's libraries need the sanitizer runtimes in the consumer.
san=""
grep -q '^JADE_SANITIZE:BOOL=ON' "$build/CMakeCache.txt" && san="-fsanitize=address,undefined"
if cmake -S "$src/consumer" -B "$tmp/cm" -DCMAKE_PREFIX_PATH="$tmp/prefix" -DCMAKE_C_FLAGS="$san" \
       -DCMAKE_EXE_LINKER_FLAGS="$san" >"$tmp/log" 2>&1 &&
   cmake --build "$tmp/cm" >>"$tmp/log" 2>&1 && "$tmp/cm/consumer" "$mesh" && "$tmp/cm/api"; then
    pass=$((pass + 1)); echo "ok   find_package(jade), static libjade: consumer.c, and api.cpp as C++17"
else
    fail=$((fail + 1)); echo "FAIL find_package(jade)"; tail -20 "$tmp/log"
fi
export PKG_CONFIG_PATH="$tmp/prefix/lib/pkgconfig"
if cc $san -o "$tmp/consumer_pc" "$src/consumer/consumer.c" $(pkg-config --cflags --libs jade-platform) >"$tmp/log" 2>&1 &&
   LD_LIBRARY_PATH="$tmp/prefix/lib" "$tmp/consumer_pc" "$mesh" && ldd "$tmp/consumer_pc" | grep -q 'libjade.so.0 =>'; then
    pass=$((pass + 1)); echo "ok   pkg-config jade-platform, shared libjade.so.0"
else
    fail=$((fail + 1)); echo "FAIL pkg-config"; cat "$tmp/log"
fi
# The same program as C++ (every installed header wraps itself in extern "C").
if command -v c++ >/dev/null; then
    if c++ -std=c++20 -x c++ $san -o "$tmp/consumer_cxx" "$src/consumer/consumer.c" -x none \
           $(pkg-config --cflags --libs jade-platform) >"$tmp/log" 2>&1 &&
       LD_LIBRARY_PATH="$tmp/prefix/lib" "$tmp/consumer_cxx" "$mesh"; then
        pass=$((pass + 1)); echo "ok   the same program as C++20"
    else
        fail=$((fail + 1)); echo "FAIL C++"; cat "$tmp/log"
    fi
fi
# api.cpp through pkg-config too, and it names every function the installed
# headers declare.
declared=$(cat "$tmp/prefix/include/jade/"*.h | grep -ohE "\bjd_[a-z0-9_]+ *\(" | sed 's/ *(//' | sort -u)
listed=$(sed -n 's/^ *FN(\(jd_[a-z0-9_]*\)),$/\1/p' "$src/consumer/api.cpp" | sort -u)
missing=$(printf '%s\n' "$declared" | grep -vxF "$listed")
if [ -z "$missing" ] && command -v c++ >/dev/null &&
   c++ -std=c++17 -Wall -Wextra $san -o "$tmp/api" "$src/consumer/api.cpp" $(pkg-config --cflags --libs jade-platform) >"$tmp/log" 2>&1 &&
   LD_LIBRARY_PATH="$tmp/prefix/lib" "$tmp/api" >"$tmp/out" 2>&1; then
    pass=$((pass + 1)); echo "ok   every public function ($(printf '%s\n' "$declared" | wc -l)) from C++, pkg-config: $(cat "$tmp/out")"
else
    fail=$((fail + 1)); echo "FAIL api.cpp: ${missing:+not in api.cpp: $(echo $missing)}"; cat "$tmp/log" "$tmp/out" 2>/dev/null
fi
# examples/embed.c, the README's embedding: its own EGL context, the mesh
# from memory; as C through find_package(jade) and as C++ through pkg-config.
ex=$src/../examples
if cmake -S "$ex" -B "$tmp/ex" -DCMAKE_PREFIX_PATH="$tmp/prefix" -DCMAKE_C_FLAGS="$san" \
       -DCMAKE_EXE_LINKER_FLAGS="$san" >"$tmp/log" 2>&1 && cmake --build "$tmp/ex" >>"$tmp/log" 2>&1 &&
   "$tmp/ex/embed" "$mesh" >"$tmp/out" 2>&1 && grep -q "^embed: " "$tmp/out"; then
    pass=$((pass + 1)); echo "ok   examples/embed.c as C, find_package(jade): $(cat "$tmp/out")"
else
    fail=$((fail + 1)); echo "FAIL examples/embed.c (C)"; tail -20 "$tmp/log"; cat "$tmp/out" 2>/dev/null
fi
if command -v c++ >/dev/null; then
    if c++ -std=c++17 -Wall -Wextra -x c++ $san -o "$tmp/embed_cxx" "$ex/embed.c" -x none \
           $(pkg-config --cflags --libs jade egl glesv2) >"$tmp/log" 2>&1 &&
       LD_LIBRARY_PATH="$tmp/prefix/lib" "$tmp/embed_cxx" "$mesh" >"$tmp/out" 2>&1; then
        pass=$((pass + 1)); echo "ok   examples/embed.c as C++17, pkg-config: $(cat "$tmp/out")"
    else
        fail=$((fail + 1)); echo "FAIL examples/embed.c (C++)"; cat "$tmp/log" "$tmp/out"
    fi
fi
# Every C block of the README and docs/*.md, compiled against the installed
# headers inside a function that declares what they use: code shown to
# users cannot go stale (tests/docs.sh checks that each is compiled here).
for md in "$src/../README.md" "$src"/../docs/*.md; do
    [ -f "$md" ] || continue
    awk '/^```c$/ { on = 1; k++; next } on && /^```$/ { on = 0 } on && !/^#include/ { print > ("'"$tmp"'/block." k) }' "$md"
    for b in "$tmp"/block.*; do
        [ -f "$b" ] || continue
        { echo '#include <jade/jade.h>'
          echo 'static unsigned char memory[1 << 20];'
          echo 'int doc_snippet(const void *bytes, size_t size, unsigned fbo, int w, int h);'
          echo 'int doc_snippet(const void *bytes, size_t size, unsigned fbo, int w, int h) {'
          echo '    jd_arena arena; jd_error err; jd_mesh mesh; jd_gl_caps caps; jd_renderer *r; jd_scene scene;'
          cat "$b"
          echo '    jd_renderer_destroy(r);'
          echo '    return err.code;'
          echo '}'; } > "$tmp/snippet.c"
        name="$(basename "$md"), C block $(basename "$b" | cut -d. -f2)"
        if cc -std=c11 -Wall -Wextra -Werror -c -o "$tmp/snippet.o" "$tmp/snippet.c" $(pkg-config --cflags jade) >"$tmp/log" 2>&1; then
            pass=$((pass + 1)); echo "ok   $name compiles against the installed headers ($(grep -c . "$b") lines)"
        else
            fail=$((fail + 1)); echo "FAIL $name"; cat "$tmp/log"
        fi
        rm -f "$b"
    done
done
echo "consumer: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
