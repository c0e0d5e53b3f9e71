#version 100
// One direction of one step of the full mode's diffusion, in the light's
// view. The light-depth map holds every directly lit point of the object
// (exactly the points a directional light reaches) with its irradiance S
// and depth z. Each step blurs S with a Gaussian whose variance adds to the
// previous level's, so level k holds S convolved with a Gaussian of sigma_k.
// The light gathered is kept in two parts by where it entered: near this
// texel's own lit surface (within u_near of its depth) and elsewhere (an
// occluder's lit face, a floor past a shadow's edge), each with the
// S-weighted mean depth of its entry points, which the shading pass compares
// with the receiver's depth: a point in a cast shadow is far below the
// occluder but level with the lit floor beside it. Output: sqrt(S) and Z of
// the shallower part in RG, of the deeper in BA, so that neighbouring texels
// on either side of a shadow's edge agree and filtering between them mixes
// like with like.
uniform sampler2D u_src;
uniform sampler2D u_ref;    // the light-depth map: each texel's own lit surface
uniform vec2 u_ref_scale;   // fragment coordinates to the light map's
uniform vec2 u_step;        // texel offset between taps, along the blur direction
uniform float u_w[JD_TAPS + 1]; // the Gaussian's weight 0, 1, ... taps away: an exp per tap
                            // and fragment kept more of lima's registers busy
uniform float u_near;       // light-depth units that still count as this texel's surface
varying vec2 v_uv;

// sqrt(S) and the mean depth of a part; `other`, the depth to give it where
// it holds no light: filtering between texels must not see a depth that no
// light came from (an interpolated depth would pass by every receiver's).
vec2 part(vec2 a, float wsum, float other)
{
    return vec2(sqrt(a.x / wsum), a.x > 0.0001 * wsum ? clamp(a.y / a.x, 0.0, 0.998) : other);
}

void main()
{
    float zr = jd_unpack(texture2D(u_ref, gl_FragCoord.xy * u_ref_scale));
    // Without branches, whole-vector sums: near w S, near w S z, far w S,
    // far w S z. (Written first with a branch per part and an exp per tap,
    // lima took 594 instructions and spilled 75:343; vc4 1,336.)
    vec4 acc = vec4(0.0);
    // Normalised convolution on the light's coverage: near the object's
    // outline as the light sees it there is lit surface on one side and
    // nothing (not dark surface) on the other.
    float wsum = 0.0;
    for (int i = -JD_TAPS; i <= JD_TAPS; i++) {
        float x = float(i);
        vec4 t = texture2D(u_src, v_uv + x * u_step);
        float w = u_w[i < 0 ? -i : i];
#if JD_FIRST
        float z = jd_unpack(t);
        float ws = w * t.a * t.a * step(z, 0.998), wn = ws * step(abs(z - zr), u_near);
        acc += vec4(wn, wn * z, ws - wn, (ws - wn) * z);
        wsum += w * step(z, 0.998);
#else
        float ws1 = w * t.r * t.r * step(t.g, 0.998), wn1 = ws1 * step(abs(t.g - zr), u_near);
        float ws2 = w * t.b * t.b * step(t.a, 0.998), wn2 = ws2 * step(abs(t.a - zr), u_near);
        acc += vec4(wn1 + wn2, wn1 * t.g + wn2 * t.a, ws1 - wn1 + ws2 - wn2, (ws1 - wn1) * t.g + (ws2 - wn2) * t.a);
        wsum += w * step(min(t.g, t.a), 0.998);
#endif
    }
    if (wsum <= 0.0) {
        gl_FragColor = vec4(0.0, 1.0, 0.0, 1.0);
    } else {
        float zn = acc.x > 0.0001 * wsum ? acc.y / acc.x : zr;
        float zf = acc.z > 0.0001 * wsum ? acc.w / acc.z : zn;
        vec2 n = part(acc.xy, wsum, clamp(zf, 0.0, 0.998)), f = part(acc.zw, wsum, clamp(zn, 0.0, 0.998));
        gl_FragColor = n.y <= f.y ? vec4(n, f) : vec4(f, n);
    }
}
