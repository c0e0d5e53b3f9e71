#version 100
// full's shadow, made once a frame in light space: an exponential shadow
// map (Annen, Mertens, Seidel, Flerackers and Kautz 2008). Each texel of the
// light map stands for exp2(c z) of its depth z; a Gaussian of 1.2
// light-map texels blurs that in two passes (this one direction at a time),
// and a point at depth zp is lit by min(1, blurred / exp2(c zp)): the
// weight of the texels near it that the light reaches at its depth or
// beyond, without the 2x2 test's stair steps a light-map texel tall. Each
// pass also halves the resolution in its direction (six taps, half a texel
// to two and a half either side of the new texel's centre, which is a
// corner of the light map's; the Gaussian's 1% beyond is left out): the
// Gaussian is wide enough for half as many texels, and a quarter of the
// fragments is what Mali-400's frame can pay. The sum spans more than any
// 8-bit channel holds, so it is kept as its log2 over c, a depth, packed as
// the light map packs depth (jd_pack): the largest tap is taken out before
// exp2, so nothing overflows fp16, and what is added back is at most
// log2(1 / 0.04) / c.
uniform sampler2D u_src;   // packed depth (RG): the light map, or this blur's first pass
uniform vec2 u_c;          // c, exp2's exponent per light-depth unit, and 1 / c
varying vec4 v_a, v_b, v_c; // the taps (soft_shadow.vert)

void main()
{
    // Read as the shadow test reads depth (jd_depth, pack.glsl).
    vec3 a = vec3(jd_depth(texture2D(u_src, v_a.xy)), jd_depth(texture2D(u_src, v_a.zw)), jd_depth(texture2D(u_src, v_b.xy)));
    vec3 b = vec3(jd_depth(texture2D(u_src, v_b.zw)), jd_depth(texture2D(u_src, v_c.xy)), jd_depth(texture2D(u_src, v_c.zw)));
    // Where nothing was drawn (depth 1, the cleared map) counts as the
    // deepest surface among the taps, not as a surface at the far end of
    // the light's box: exp2 of that far depth would outweigh every other
    // tap, and a point in a shadow would be lit wherever the occluder's
    // outline came within the blur's reach (bright slivers on thin parts
    // that the occluder's outline crosses, flickering as the light moves).
    // An empty tap drops out of the deepest (times 0) and is then held at
    // it (min), its exponent 0, where the exponent's factor was c (1 -
    // empty) and the deepest was taken of depth - empty: lima 48 -> 43
    // words, VideoCore IV 150 -> 140, Midgard 80 -> 70 (Adreno 3xx 135 ->
    // 143, ir3's schedule; with depth - empty kept, lima 44 and Adreno 143).
    vec3 mm = max(a * step(a, vec3(0.999)), b * step(b, vec3(0.999)));
    float m = max(max(mm.x, mm.y), mm.z);
    m = m > 0.0 ? m : 1.0; // all taps empty: empty
    // Gaussian weights exp(-x^2 / (2 1.2^2)) at x = 2.5, 1.5, 0.5, summing to 1.
    const vec3 w = vec3(0.038338, 0.153756, 0.307907);
    float s = dot(exp2((min(a, m) - m) * u_c.x), w) + dot(exp2((min(b, m) - m) * u_c.x), w.zyx);
    gl_FragColor = jd_pack(m + log2(s) * u_c.y);
}
