#!/bin/sh
# No texel jade never wrote reaches the picture. GLES 2.0 leaves a new
# texture's contents undefined, and a driver that hands out freed buffers
# again (Mesa's lima keeps a cache of them) really fills them with another
# target's data: a kiosk that loads a second model would draw the first
# one's leftovers. Every texture made without data is filled with noise
# (tests/gl_sabotage.c, JD_POISON_TEXTURES) and each mode, under each
# device profile, must draw the same picture as without.
jade=$1 sabotage=$2 imgcmp=$3
. "$(dirname "$0")/harness.sh"
preload_or_skip "$jade"
for prof in generic mali400 vc4 vivante; do
    for mode in full dual single none; do
        # Back-lit from high up: the light map's top rows hold the object
        # (where the diffusion's vertical taps once read past what they wrote).
        set -- --size 192x192 --mode "$mode" --profile "$prof" --light-azimuth 170 --light-elevation 70
        name="$mode, $prof"
        "$jade" render "$@" --out "$tmp/clean.png" >/dev/null 2>"$tmp/clean.err" ||
            { bad "$name: the clean run failed: $(head -c 300 "$tmp/clean.err")"; continue; }
        JD_POISON_TEXTURES=1 LD_PRELOAD=$sabotage "$jade" render "$@" --out "$tmp/noise.png" >/dev/null 2>"$tmp/noise.err" ||
            { bad "$name: the run with noise failed: $(head -c 300 "$tmp/noise.err")"; continue; }
        grep -q "gl_sabotage: [1-9][0-9]* textures poisoned" "$tmp/noise.err" ||
            { bad "$name: no texture was filled with noise"; continue; }
        if "$imgcmp" "$tmp/noise.png" "$tmp/clean.png" --max-rmse 0 --bad-threshold 0 --max-bad-frac 0 >"$tmp/cmp" 2>&1; then
            ok "$name: $(grep -o '[0-9]* textures poisoned' "$tmp/noise.err"), the same picture"
        else
            bad "$name: the noise reached the picture: $(tail -1 "$tmp/cmp")"
        fi
    done
done
finish undefined_texels
