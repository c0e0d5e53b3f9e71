#version 100
// First SH reduction step. Output pixel (X, Y): X = face * NB + block column,
// Y = row * NB + block row, row = coefficient * 3 + channel. Each pixel
// averages L * Y_k * dw over a BxB block of the capture atlas, with dw scaled
// by 6N^2/(4 pi) so values stay within +-1.5, and packs the mean / 1.5.
uniform sampler2D u_atlas;     // 3N x 2N used, faces +X -X +Y / -Y +Z -Z
uniform vec2 u_atlas_texel;    // 1 / the atlas texture's (power-of-two) size
varying vec2 v_uv;
// JD_N (face size), JD_B (block), JD_NB = JD_N / JD_B come as defines.

void face_frame(float f, out vec3 a, out vec3 u, out vec3 v)
{
    if (f < 0.5)      { a = vec3(1.0, 0.0, 0.0);  u = vec3(0.0, 0.0, -1.0); v = vec3(0.0, 1.0, 0.0); }
    else if (f < 1.5) { a = vec3(-1.0, 0.0, 0.0); u = vec3(0.0, 0.0, 1.0);  v = vec3(0.0, 1.0, 0.0); }
    else if (f < 2.5) { a = vec3(0.0, 1.0, 0.0);  u = vec3(1.0, 0.0, 0.0);  v = vec3(0.0, 0.0, -1.0); }
    else if (f < 3.5) { a = vec3(0.0, -1.0, 0.0); u = vec3(1.0, 0.0, 0.0);  v = vec3(0.0, 0.0, 1.0); }
    else if (f < 4.5) { a = vec3(0.0, 0.0, 1.0);  u = vec3(1.0, 0.0, 0.0);  v = vec3(0.0, 1.0, 0.0); }
    else              { a = vec3(0.0, 0.0, -1.0); u = vec3(-1.0, 0.0, 0.0); v = vec3(0.0, 1.0, 0.0); }
}

void main()
{
    vec2 px = floor(gl_FragCoord.xy);
    float nb = float(JD_NB), n = float(JD_N);
    float face = floor(px.x / nb);
    float bx = px.x - face * nb;
    float row = floor(px.y / nb);
    float by = px.y - row * nb;
    float k = floor(row / 3.0);
    float ch = row - 3.0 * k;
    vec3 sel = vec3(ch < 0.5 ? 1.0 : 0.0, abs(ch - 1.0) < 0.5 ? 1.0 : 0.0, ch > 1.5 ? 1.0 : 0.0);
    vec4 ka = vec4(k < 0.5 ? 1.0 : 0.0, abs(k - 1.0) < 0.5 ? 1.0 : 0.0, abs(k - 2.0) < 0.5 ? 1.0 : 0.0, abs(k - 3.0) < 0.5 ? 1.0 : 0.0);
    vec4 kb = vec4(abs(k - 4.0) < 0.5 ? 1.0 : 0.0, abs(k - 5.0) < 0.5 ? 1.0 : 0.0, abs(k - 6.0) < 0.5 ? 1.0 : 0.0, abs(k - 7.0) < 0.5 ? 1.0 : 0.0);
    float kc = k > 7.5 ? 1.0 : 0.0;
    vec3 a, u, v;
    face_frame(face, a, u, v);
    vec2 origin = vec2(mod(face, 3.0) * n, floor(face / 3.0) * n) + vec2(bx, by) * float(JD_B);
    float scale = 6.0 / 3.14159265; // 4/N^2 * 6N^2/(4 pi), N folded in below
    float sum = 0.0;
    for (int j = 0; j < JD_B; j++) {
        for (int i = 0; i < JD_B; i++) {
            vec2 t = origin + vec2(float(i), float(j)) + 0.5;
            vec2 fuv = (t - vec2(mod(face, 3.0) * n, floor(face / 3.0) * n)) / n * 2.0 - 1.0;
            float q = 1.0 + dot(fuv, fuv);
            float dw = scale / (q * sqrt(q));
            vec3 w = normalize(a + fuv.x * u + fuv.y * v);
            vec4 ya = vec4(0.282095, 0.488603 * w.y, 0.488603 * w.z, 0.488603 * w.x);
            vec4 yb = vec4(1.092548 * w.x * w.y, 1.092548 * w.y * w.z, 0.315392 * (3.0 * w.z * w.z - 1.0), 1.092548 * w.x * w.z);
            float yc = 0.546274 * (w.x * w.x - w.y * w.y);
            float y = dot(ya, ka) + dot(yb, kb) + yc * kc;
            float l = dot(texture2D(u_atlas, t * u_atlas_texel).rgb, sel);
            // Accumulate the mean directly: a raw sum of B*B terms would lose
            // low bits in fp16.
            sum += l * y * dw / float(JD_B * JD_B);
        }
    }
    gl_FragColor = jd_pack_signed(sum / 1.5);
}
