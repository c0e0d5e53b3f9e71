#version 100
// One direction of a separable Gaussian on premultiplied A0 + coverage. Taps
// are spaced by u_step texels so one fixed loop serves every width.
uniform sampler2D u_src;
uniform vec2 u_step;        // texel offset between taps, along the blur direction
uniform float u_inv_2s2;    // 1 / (2 sigma^2), sigma in taps
varying vec2 v_uv;
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
    gl_FragColor = acc / wsum;
}
