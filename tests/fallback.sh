#!/bin/sh
# A device that cannot run one of jade's programs, played by a preloaded
# library (tests/gl_sabotage.c): a compiler that rejects a shader, or a
# driver that links one and then draws nothing with it. The running program
# must say so at start-up, draw the nearest cheaper mode instead (the same
# picture as that mode, compared with imgcmp) and exit 0, never show a frame
# with a pass missing; where the shading every mode needs is lost, it must
# fail with one line.
jade=$1 sabotage=$2 imgcmp=$3
. "$(dirname "$0")/harness.sh"
preload_or_skip "$jade"
sab_opts=
render() { # OUT MODE PROFILE SABOTAGE [OPTIONS] (sh has no local variables: r_*)
    r_out=$1 r_mode=$2 r_prof=$3 r_what=$4
    shift 4
    # The probe that finds a program drawing nothing is for GPUs; llvmpipe
    # (where this runs) gets it on request.
    JD_SABOTAGE=$r_what LD_PRELOAD=$sabotage "$jade" render --size 128x128 --mode "$r_mode" ${r_prof:+--profile "$r_prof"} \
        --program-probe on $sab_opts --out "$tmp/$r_out.png" "$@" >"$tmp/$r_out.out" 2>"$tmp/$r_out.err"
}
# NAME MODE PROFILE SABOTAGE SHOWN-AS WORDS [REFERENCE OPTIONS]: the run says
# WORDS and matches the picture of SHOWN-AS
falls_back() {
    name=$1 mode=$2 prof=$3 what=$4 shown=$5 words=$6
    shift 6
    render "ref-$name" "$shown" "$prof" "" "$@" || { bad "$name: the $shown reference run failed"; return; }
    if ! render "$name" "$mode" "$prof" "$what"; then bad "$name: exit $? ($(head -c 300 "$tmp/$name.err"))"; return; fi
    grep -q "gl_sabotage: [1-9]" "$tmp/$name.err" || { bad "$name: the sabotage did not happen"; return; }
    grep "$words" "$tmp/$name.err" >/dev/null || { bad "$name: no start-up line saying '$words':"; cat "$tmp/$name.err"; return; }
    if "$imgcmp" "$tmp/$name.png" "$tmp/ref-$name.png" >"$tmp/$name.cmp" 2>&1; then
        ok "$name: $(grep -o "$words.*" "$tmp/$name.err" | head -1 | cut -c1-150) | $(tail -1 "$tmp/$name.cmp" | sed 's/.*: rmse/rmse/')"
    else
        bad "$name: not $shown's picture: $(tail -1 "$tmp/$name.cmp")"
    fi
}
# Rejected by the compiler: full's diffusion blur (u_near is in no other shader).
falls_back "full, diffusion rejected" full "" "u_near:reject" dual "full frames are drawn as dual"
falls_back "full, diffusion rejected, mali400" full mali400 "u_near:reject" dual "full frames are drawn as dual"
# Linked, then nothing drawn (vc4's register-allocation failure): the SH projection.
falls_back "dual, SH projection drawing nothing, vc4" dual vc4 "u_atlas_texel:drop" none "draws nothing with it"
falls_back "single, SH projection drawing nothing" single "" "u_atlas_texel:drop" none "single frames are drawn as none"
# The spread's blur rejected: dual becomes single, single is untouched.
falls_back "dual, spread blur rejected" dual "" "u_inv_2s2:reject" single "dual frames are drawn as single"
# The anti-aliasing pass rejected: frames go without it. The pass asked
# for: a target with multisampling (an NVIDIA GPU's) builds none by default.
sab_opts="--antialias post"
falls_back "anti-aliasing pass rejected" full "" "float luma(vec3:reject" full "anti-aliasing pass unavailable" --antialias off
sab_opts=
# The light depth every mode needs: nothing cheaper, one line and exit 1.
if JD_SABOTAGE="v_depth:reject" LD_PRELOAD=$sabotage "$jade" render --size 64x64 --out "$tmp/x.png" >"$tmp/x.out" 2>"$tmp/x.err"; then
    bad "base rejected: exit 0"
elif [ "$(grep -v '^jade render: GL driver\|^gl_sabotage' "$tmp/x.err" | grep -c .)" = 1 ] && [ ! -e "$tmp/x.png" ]; then
    ok "base rejected: exit 1, $(grep -v '^jade render: GL driver\|^gl_sabotage' "$tmp/x.err" | cut -c1-160)"
else
    bad "base rejected: $(cat "$tmp/x.err")"
fi
finish fallback
