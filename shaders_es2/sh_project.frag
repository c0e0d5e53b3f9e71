#version 100
// First SH reduction step. Output pixel (X, Y): X = face * NB + block column,
// Y = row * NB + block row, row = coefficient * 3 + channel. Each pixel
// averages L * Y_k * dw over a BxB block of the capture atlas, with dw scaled
// by 6N^2/(4 pi) so values stay within +-1.5, and packs the mean / 1.5.
//
// On a face, the direction is w = (a + fx u + fy v) / sqrt(q), q = 1 + fx^2
// + fy^2, so every Y_k is a quadratic polynomial in (fx, fy) over q^(d/2),
// d = 0, 1 or 2; dw is 4/N^2 / q^(3/2). The rectangle's attributes carry
// the polynomial and the power of q, poly1.z = (3 + d) / 2, taken as
// exp2(-poly1.z log2 q): two operations per sample, as a reciprocal and a
// square root were, but one value live instead of two (lima spilled 1:4);
// the polynomial already holds 6/pi (4/N^2 * 6N^2/(4 pi)), 1/(B*B) for the
// mean and 1/1.5 for the packing.
uniform sampler2D u_atlas;     // 3N x 2N used, faces +X -X +Y / -Y +Z -Z
uniform vec2 u_atlas_texel;    // 1 / the atlas texture's (power-of-two) size
varying vec4 v_poly0;
varying vec4 v_poly1;
varying vec3 v_channel;
varying vec4 v_texel;
// JD_N (face size), JD_B (block), JD_NB = JD_N / JD_B come as defines.

void main()
{
    float step = 2.0 / float(JD_N);
    vec2 t0 = floor(v_texel.xy) + 0.5;          // snapped: varyings may be interpolated in fp16
    vec2 f0 = (t0 - v_texel.zw) * step - 1.0;   // the first sample's face coordinates
#if JD_B == 2
    // The four samples of a 2x2 block as the lanes of vec4s (VideoCore IV
    // and Mali-400 take 2x2 blocks): one vector expression instead of four
    // scalar ones kept lima's registers from spilling.
    vec4 fx = f0.x + vec4(0.0, step, 0.0, step), fy = f0.y + vec4(0.0, 0.0, step, step);
    vec4 power = exp2(-v_poly1.z * log2(1.0 + fx * fx + fy * fy));
    vec4 w = (v_poly0.x + v_poly0.y * fx + v_poly0.z * fy + v_poly0.w * fx * fx + (v_poly1.x * fy + v_poly1.y * fx) * fy) * power;
    vec3 c = texture2D(u_atlas, t0 * u_atlas_texel).rgb * w.x;
    c += texture2D(u_atlas, (t0 + vec2(1.0, 0.0)) * u_atlas_texel).rgb * w.y;
    c += texture2D(u_atlas, (t0 + vec2(0.0, 1.0)) * u_atlas_texel).rgb * w.z;
    c += texture2D(u_atlas, (t0 + vec2(1.0, 1.0)) * u_atlas_texel).rgb * w.w;
    float sum = dot(c, v_channel);
#else
    float sum = 0.0;
    for (int j = 0; j < JD_B; j++) {
        for (int i = 0; i < JD_B; i++) {
            vec2 o = vec2(float(i), float(j));
            vec2 f = f0 + o * step;
            float y = v_poly0.x + dot(v_poly0.yz, f) + v_poly0.w * f.x * f.x + (v_poly1.x * f.y + v_poly1.y * f.x) * f.y;
            float power = exp2(-v_poly1.z * log2(1.0 + dot(f, f)));
            float l = dot(texture2D(u_atlas, (t0 + o) * u_atlas_texel).rgb, v_channel);
            // Accumulate the mean directly: a raw sum of B*B terms would lose
            // low bits in fp16.
            sum += l * y * power;
        }
    }
#endif
    gl_FragColor = jd_pack_signed(sum);
}
