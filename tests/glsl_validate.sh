#!/bin/sh
# Every shader source jade hands the driver, for both packings, must be valid
# GLSL ES 1.00 to glslangValidator (Debian glslang-tools), not just to Mesa.
dir=$1
if ! command -v glslangValidator >/dev/null; then
    echo "SKIP: glslangValidator missing: install glslang-tools (tools/setup.sh does, and says when it cannot)"
    exit 77
fi
pass=0 fail=0
for f in "$dir"/*; do
    case "$f" in *.vert|*.frag) ;; *) continue ;; esac
    if ! head -1 "$f" | grep -qx '#version 100'; then
        echo "FAIL $f does not start with #version 100"; fail=$((fail + 1)); continue
    fi
    if out=$(glslangValidator "$f" 2>&1); then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL $f"; echo "$out"; fi
done
echo "validated $pass shader sources as GLSL ES 1.00 (#version 100) in $dir"
echo "glsl: $pass passed, $fail failed"
[ "$fail" -eq 0 ] && [ "$pass" -gt 10 ]
