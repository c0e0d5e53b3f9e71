#version 100
// One direction of a separable Gaussian on premultiplied A0 + coverage. Taps
// are spaced by u_step texels so one fixed loop serves every width.
uniform sampler2D u_src;
uniform vec2 u_step;        // texel offset between taps, along the blur direction
uniform float u_inv_2s2;    // 1 / (2 sigma^2), sigma in taps
varying vec2 v_uv;
#if JD_COMBINE
// The last pass also folds both spread layers into one texture, so the
// full-resolution pass reads one texel: S = w1 A1 + w2 A2, after dividing
// each by its blurred coverage (normalised convolution), stored as sqrt(S/2)
// for precision in the dark glow; alpha says whether any coverage reached.
uniform sampler2D u_a1;
uniform vec3 u_w1;
uniform vec3 u_w2;
#endif
void main()
{
    vec4 acc = vec4(0.0);
    float wsum = 0.0;
    for (int i = -JD_TAPS; i <= JD_TAPS; i++) {
        float x = float(i);
        float w = exp(-x * x * u_inv_2s2);
        acc += w * texture2D(u_src, v_uv + x * u_step);
        wsum += w;
    }
#if JD_COMBINE
    vec4 b2 = acc / wsum;
    vec4 b1 = texture2D(u_a1, v_uv);
    if (b1.a < 0.004 || b2.a < 0.004) {
        gl_FragColor = vec4(0.0);
    } else {
        vec3 s = u_w1 * (2.0 * b1.rgb / b1.a) + u_w2 * (2.0 * b2.rgb / b2.a);
        gl_FragColor = vec4(sqrt(clamp(0.5 * s, 0.0, 1.0)), 1.0);
    }
#else
    gl_FragColor = acc / wsum;
#endif
}
