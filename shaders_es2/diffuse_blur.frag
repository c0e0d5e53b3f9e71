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
uniform vec2 u_ref_scale;   // the source's coordinates to the light map's (from gl_FragCoord lima took 5 words more)
uniform vec2 u_step;        // texel offset between taps, along the blur direction
uniform int u_taps;         // taps on each side of the centre for this level, 1..JD_TAPS
uniform float u_w[JD_TAPS + 1]; // the Gaussian's weights by distance: the centre tap, then each pair u_w[k] at -k and +k taps
uniform float u_near;       // light-depth units that still count as this texel's surface
#if JD_BOX
// JD_BOX_SIDE: light-map texels a side of the square one output texel
// gathers (a power of two, or 1), fixed when the renderer is made.
#endif
varying vec2 v_uv;

// The light map's depths are read by two bytes (jd_bytes, pack.glsl): the
// levels keep their depths in one byte.

// sqrt(S) and the mean depth of a part; `other`, the depth to give it where
// it holds no light: filtering between texels must not see a depth that no
// light came from (an interpolated depth would pass by every receiver's).
vec2 part(vec2 a, float wsum, float other)
{
    return vec2(sqrt(a.x / wsum), a.x > 0.0001 * wsum ? clamp(a.y / a.x, 0.0, 0.998) : other);
}

#if JD_FIRST
// Four light-map texels, a square of 2 x 2 (t0 at its origin, t1 across,
// t2 up, t3 both), into the near and far sums, (S, S z) of each part (the
// other three weigh `more`: none where a square of one is asked for). The
// four are worked side by side in the vector lanes: one texel at a time,
// as the later steps' tap(), lima spilled 8:22 at four a trip.
void square(vec4 t0, vec4 t1, vec4 t2, vec4 t3, float more, float zr, inout vec4 acc, inout float wsum)
{
    vec4 za = vec4(t0.xy, t1.xy);
    vec2 a01 = vec2(t0.a, t1.a);
    vec4 zb = vec4(t2.xy, t3.xy);
    vec4 z = vec4(za.xz, zb.xz) + vec4(za.yw, zb.yw) * jd_bytes.y;
    vec4 a = vec4(a01, t2.a, t3.a);
    vec4 lit = step(z, vec4(0.998)) * vec4(1.0, more, more, more);
    vec4 ws = lit * a * a, wn = ws * step(abs(z - zr), vec4(u_near)), wf = ws - wn;
    acc += vec4(dot(wn, vec4(1.0)), dot(wn, z), dot(wf, vec4(1.0)), dot(wf, z));
    wsum += dot(lit, vec4(1.0));
}
#ifdef JD_BOX_COORDS
// Every texel's coordinates from the vertex stage (quad.vert): the first
// step's squares unrolled, at most four of them (render_program.c). Made
// per fragment, the sixteen coordinates and the offsets they came from
// were what lima spilled (210 words, 32:81 spills:fills; from here 175,
// 16:37). v_uv, the squares' centre, is not among the varyings (eight at
// most on Mali-400 and VideoCore IV): the middle of the first and last
// texels stands in for it.
varying vec4 v_sq[2 * JD_TRIPS];
#endif
#else
// One tap of weight w into the near and far sums: (w S, w S z) of each
// part, written as whole-vector operations (lima spilled where NIR built
// vectors out of scalars). Each texel holds two parts, (sqrt S, z,
// sqrt S, z): the sums keep them apart, (part 1, part 2), and are added at
// the end. A part's weight takes no test of its depth (lima 2 words a
// tap): the texels with no light (this pass's depth 1, below; the band past
// the rows written and a target's first clear, pass_light.c and
// render_target.c) hold S = 0 in both parts, and every other part's depth
// is at most 0.998. Only a tap that a level's filtering mixes mostly of
// such a texel keeps the little light it has, at a depth near 1: the
// default asset's pictures within 0.00013 RMSE of the test's.
void tap(vec2 uv, float w, float zr, inout vec4 acc, inout float wsum)
{
    vec4 t = texture2D(u_src, uv), z = t.yyww;
    vec4 ws = (w * t.xxzz * t.xxzz) * (t * vec4(0.0, 1.0, 0.0, 1.0) + vec4(1.0, 0.0, 1.0, 0.0));
    vec4 wn = ws * step(abs(z - zr), vec4(u_near)), wf = ws - wn;
    acc += vec4(wn.xy + wn.zw, wf.xy + wf.zw);
    wsum += w * step(min(t.y, t.w), 0.998);
}

// Two taps of one weight w, at uv - o and uv + o, their four parts worked
// side by side in the vector lanes as square() works its texels: what
// tap() does for one, the same sums in another order.
void pair(vec2 uv, vec2 o, float w, float zr, inout vec4 acc, inout float wsum)
{
    vec4 t0 = texture2D(u_src, uv - o), t1 = texture2D(u_src, uv + o);
    vec4 s = vec4(t0.xz, t1.xz), z = vec4(t0.yw, t1.yw);
    vec4 ws = w * s * s, wn = ws * step(abs(z - zr), vec4(u_near)), wf = ws - wn;
    acc += vec4(dot(wn, vec4(1.0)), dot(wn, z), dot(wf, vec4(1.0)), dot(wf, z));
    wsum += w * dot(step(vec2(min(t0.y, t0.w), min(t1.y, t1.w)), vec2(0.998)), vec2(1.0));
}
#endif

void main()
{
#if defined(JD_BOX_COORDS) && JD_BOX_SIDE > 1
    float zr = jd_depth(texture2D(u_ref, (v_sq[0].xy + v_sq[2 * JD_TRIPS - 1].zw) * 0.5 * u_ref_scale));
#elif defined(JD_BOX_COORDS)
    float zr = jd_depth(texture2D(u_ref, v_sq[0].xy * u_ref_scale));
#else
    float zr = jd_depth(texture2D(u_ref, v_uv * u_ref_scale));
#endif
    // Normalised convolution on the light's coverage: near the object's
    // outline as the light sees it there is lit surface on one side and
    // nothing (not dark surface) on the other.
    vec4 acc = vec4(0.0); // the near part's (S, S z), the far part's
    float wsum = 0.0;
    // A loop the compilers keep as a loop: its trip count is a uniform, and
    // its constant bound (GLSL ES 1.00 wants one) is past what Mesa's NIR
    // unrolls (32). Unrolled, every tap's texel and coordinates were live
    // at once and lima spilled 12:80 of its 6 vec4 registers (322
    // instructions); one tap per pass round the loop, 0 spills and 69.
    // The blur takes its centre first and then a pair of taps a trip, the
    // Gaussian's two at the same distance (one weight), their four parts in
    // the vector lanes: lima's blur of 5 taps 149 words a fragment as one
    // tap a trip (24 a trip, 7 of them the loop's own tests and branches),
    // 120 as pairs, still without a spill.
#if !JD_BOX
    tap(v_uv, u_w[0], zr, acc, wsum);
#endif
#ifdef JD_UNROLL
    for (int i = 0; i < JD_UNROLL; i++) { // the device-compiler tool: the cost of one trip more
#elif defined(JD_TRIPS)
    // The renderer's trip count, constant, where the GPU runs the loop
    // shorter unrolled (every one but Utgard: render_program.c).
    for (int i = 0; i < JD_TRIPS; i++) {
#else
    // At most 65 squares of 2 x 2 (renderer.c refuses a box over 16 a
    // side), or JD_TAPS pairs of taps.
    for (int i = 0; i <= 64; i++) {
        if (i >= u_taps) break;
#endif
#if JD_BOX
        // The first level's first step: every light-map texel under this
        // output texel (JD_BOX_SIDE a side, a power of two) with the same weight,
        // at a quarter of the fragments a first pass along one axis writes;
        // a square of 2 x 2 a trip, u_taps trips (a side of 1: one tap, the
        // others weigh 0). One texel a trip, the loop's own words came 16
        // times; two a trip, lima's 8 trips at the default sizes cost 536
        // instruction words a fragment, the four in vector lanes 326 (with
        // 6 spills, which the count holds); the side a constant, 310 (no
        // reciprocal of it a trip).
#ifdef JD_BOX_COORDS
        vec4 c01 = v_sq[2 * i], c23 = v_sq[2 * i + 1];
#else
        const float hb = 0.5 * float(JD_BOX_SIDE);
        float fi = float(i), row = floor(fi * (1.0 / hb));
        vec2 o = 2.0 * vec2(fi - hb * row, row) - 0.5 * (float(JD_BOX_SIDE) - 1.0);
        vec2 uv = v_uv + o * u_step;
        vec4 c01 = vec4(uv, uv + vec2(u_step.x, 0.0)), c23 = vec4(uv + vec2(0.0, u_step.y), uv + u_step);
#endif
        square(texture2D(u_src, c01.xy), texture2D(u_src, c01.zw), texture2D(u_src, c23.xy), texture2D(u_src, c23.zw),
               JD_BOX_SIDE > 1 ? 1.0 : 0.0, zr, acc, wsum);
#else
        pair(v_uv, float(i + 1) * u_step, u_w[i + 1], zr, acc, wsum);
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
