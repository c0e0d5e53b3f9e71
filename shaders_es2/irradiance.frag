#version 100
// The last step of the SH reduction, kept on the GPU: the irradiance of the
// nine coefficients for every direction of a small cube map (one face per
// draw), which the shading pass looks up along its refraction vector. Reading the 27 packed
// texels back to the CPU instead would stall a tile-based GPU's frame.
// Stored RGBM (rgb * a * 4), so faint light keeps its relative precision.
uniform sampler2D u_src;  // the reduction's result: 1 x 27 packed texels, row k * 3 + c, in a
                          // JD_SRC_W x JD_SRC_H texture
uniform vec2 u_size;      // a face's texels per side, and 2 / that
uniform mat3 u_face;      // the face: its axis, and the directions of s and t across it

// One colour channel of the irradiance: the nine coefficients of that
// channel (rows c, c + 3, ... c + 24), each weighted by its basis function
// at the direction. The rows' coordinates are constants: computed from a
// uniform, lima kept them live and spilled (Mali-400's fragment processor
// has six vec4 registers).
#define JD_COEF(c, k) jd_unpack_signed(texture2D(u_src, vec2(0.5 / JD_SRC_W, (float(c + 3 * k) + 0.5) / JD_SRC_H)))
float channel0(vec4 w0, vec4 w1, float w8)
{
    return w0.x * JD_COEF(0, 0) + w0.y * JD_COEF(0, 1) + w0.z * JD_COEF(0, 2) + w0.w * JD_COEF(0, 3) + w1.x * JD_COEF(0, 4) +
           w1.y * JD_COEF(0, 5) + w1.z * JD_COEF(0, 6) + w1.w * JD_COEF(0, 7) + w8 * JD_COEF(0, 8);
}
float channel1(vec4 w0, vec4 w1, float w8)
{
    return w0.x * JD_COEF(1, 0) + w0.y * JD_COEF(1, 1) + w0.z * JD_COEF(1, 2) + w0.w * JD_COEF(1, 3) + w1.x * JD_COEF(1, 4) +
           w1.y * JD_COEF(1, 5) + w1.z * JD_COEF(1, 6) + w1.w * JD_COEF(1, 7) + w8 * JD_COEF(1, 8);
}
float channel2(vec4 w0, vec4 w1, float w8)
{
    return w0.x * JD_COEF(2, 0) + w0.y * JD_COEF(2, 1) + w0.z * JD_COEF(2, 2) + w0.w * JD_COEF(2, 3) + w1.x * JD_COEF(2, 4) +
           w1.y * JD_COEF(2, 5) + w1.z * JD_COEF(2, 6) + w1.w * JD_COEF(2, 7) + w8 * JD_COEF(2, 8);
}

void main()
{
    vec2 st = gl_FragCoord.xy * u_size.y - 1.0;
    vec3 n = normalize(u_face[0] + st.x * u_face[1] + st.y * u_face[2]);
    // Stored: the mean of L Y dw 6N^2/(4 pi) over 1.5, so a coefficient is
    // the value times 1.5 * 4 pi; Ramamoorthi and Hanrahan's constants.
    const float k = 18.849556;
    const float c1 = 0.429043 * k, c2 = 0.511664 * k, c3 = 0.743125 * k, c4 = 0.886227 * k, c5 = 0.247708 * k;
    // Coefficients in the order stored: L00, L1-1 (y), L10 (z), L11 (x),
    // L2-2 (xy), L2-1 (yz), L20, L21 (xz), L22.
    vec4 w0 = vec4(c4, 2.0 * c2 * n.y, 2.0 * c2 * n.z, 2.0 * c2 * n.x);
    vec4 w1 = vec4(2.0 * c1 * n.x * n.y, 2.0 * c1 * n.y * n.z, c3 * n.z * n.z - c5, 2.0 * c1 * n.x * n.z);
    float w8 = c1 * (n.x * n.x - n.y * n.y);
    vec3 e = vec3(channel0(w0, w1, w8), channel1(w0, w1, w8), channel2(w0, w1, w8));
    e = clamp(e, 0.0, 4.0) * 0.25;
    // The shared scale rounded up to a byte, so rgb stays within [0, 1].
    float a = max(ceil(max(max(e.r, e.g), max(e.b, 1e-3)) * 255.0) / 255.0, 1.0 / 255.0);
    gl_FragColor = vec4(e / a, a);
}
