// What the shading passes ask of the light-depth map and of the full mode's
// light-space levels, the same in the vertex and the fragment stage.

// The Fresnel transmittance Ft of light entering or leaving at the cosine
// cosv, over its mean under diffuse light: the reference's factor
// (ref_render.c, entry_t), as ab.x - ab.y (1 - cosv)^5 fitted to the true
// curve at the scene's eta (jd_fresnel_fit, core/material.c: 1 and 0 at
// eta 1, where no boundary reflects). Schlick's form, 1.05 - 1.05 x^5 at
// every eta, darkened an index-matched rim 15-40% and put full 7-12%
// further from Cycles than none on held-out meshes front-lit.
// jd_fresnel_x takes x = 1 - cosv from a caller that knows it lies in
// [0, 1] (full's vertex stage: its clamps cost lima's vertex words there).
float jd_fresnel_x(float x, vec2 ab)
{
    float x2 = x * x;
    return ab.x - ab.y * (x2 * x2 * x);
}
float jd_fresnel_tc(float cosv, vec2 ab)
{
    return jd_fresnel_x(1.0 - clamp(cosv, 0.0, 1.0), ab);
}

// Percentage-closer filtering: the four nearest texels of the light depth
// compared with the point l (light-map xy, depth), the answers (not the
// depths) mixed bilinearly. size: texels per side and their inverse.
#if defined(JD_ALBEDO) && defined(JD_FULL)
#if JD_ALBEDO && !JD_FULL
#define JD_PCF_SCALAR 1
#endif
#endif
#if JD_PACK_HIGHP
#define JD_PCF_EXACT 1
#elif defined(JD_SPREAD)
#if JD_SPREAD
#define JD_PCF_EXACT 1
#endif
#endif
float jd_lit_fraction(sampler2D depth, vec3 l, vec2 size)
{
    vec2 tc = l.xy * size.x - 0.5;
    vec2 f = fract(tc);
    float d = size.y;
    // The nearest texel centre below l is l less f texels: no floor (2 of
    // lima's words, 8 of vc4's). Dual's shading keeps the floor: with it
    // gone lima spilled there (1:1).
#if defined(JD_SPREAD) && JD_SPREAD
    vec2 b = (floor(tc) + 0.5) * d;
#else
    vec2 b = l.xy - f * d;
#endif
    // Under the two-byte packing each depth is read as high byte + low
    // byte / 255, without jd_unpack's exact recovery of the bytes (8 of
    // lima's instruction words fewer): a texture unit's error of 1e-5 is
    // nothing beside the shadow test's bias, and fp16 holds no more. Dual's
    // shading keeps jd_unpack (its other order spilled on lima).
#ifdef JD_PCF_EXACT
    float s00 = step(l.z, jd_unpack(texture2D(depth, b)));
    float s10 = step(l.z, jd_unpack(texture2D(depth, b + vec2(d, 0.0))));
    float s01 = step(l.z, jd_unpack(texture2D(depth, b + vec2(0.0, d))));
    float s11 = step(l.z, jd_unpack(texture2D(depth, b + vec2(d, d))));
    return mix(mix(s00, s10, f.x), mix(s01, s11, f.x), f.y);
#else
#ifdef JD_PCF_SCALAR
    // none's and single's with a colour: the vector form below spilled on
    // lima there (1:1, the colour held from the shader's start).
    float s00 = step(l.z, jd_depth(texture2D(depth, b)));
    float s10 = step(l.z, jd_depth(texture2D(depth, b + vec2(d, 0.0))));
    float s01 = step(l.z, jd_depth(texture2D(depth, b + vec2(0.0, d))));
    float s11 = step(l.z, jd_depth(texture2D(depth, b + vec2(d, d))));
    return mix(mix(s00, s10, f.x), mix(s01, s11, f.x), f.y);
#else
    // The four tests and the first mix as vector operations: 2 of lima's
    // instruction words fewer than one texel at a time.
    vec4 z = vec4(jd_depth(texture2D(depth, b)), jd_depth(texture2D(depth, b + vec2(d, 0.0))),
                  jd_depth(texture2D(depth, b + vec2(0.0, d))), jd_depth(texture2D(depth, b + vec2(d, d))));
    vec4 s = step(vec4(l.z), z);
    vec2 m = mix(s.xz, s.yw, f.x);
    return mix(m.x, m.y, f.y);
#endif
#endif
}

// full's shadow test: the exponential shadow map (soft_shadow.frag) read at
// the point p (light-map xy; z its depth, not moved towards the light: the
// exponential is its own slack, as the exponent z c - 0.25, which the
// vertex stage gives). c: exp2's exponent per light-depth unit,
// 0.25 per texel of depth, soft enough that the stair steps of the light
// map's texels do not show at a shallow angle, sharp enough that an
// occluder 20 texels in front keeps 4% of the light (10 texels: 21%); the
// point is taken a texel nearer the light (exp2(0.25)), or a crease's own
// walls darken it. At 0.35 a texel the edge of a cast shadow strayed more:
// the lit taps of the blur lie at other depths than the point on a floor
// slanted to the light, and exp2 weighs the deeper ones more by where the
// edge falls among the texels (docs/quality.md, "Artifacts, measured").
// Declared in both stages at one precision, as GLSL ES asks of a uniform
// they share.
uniform mediump vec2 u_soft_c; // c and c / 255: the two bytes' weights
float jd_soft_lit(sampler2D soft, vec3 p)
{
    // By one dot product where depth is packed in two bytes (jd_depth_by):
    // lima's full shading 26 -> 25 words, Midgard 31 -> 30 cycles.
    return min(exp2(jd_depth_by(texture2D(soft, p.xy), u_soft_c) - p.z), 1.0);
}

// The light a point takes from the levels and through thin parts, as one
// signed value (lima holds no more through the levels' loop without
// spilling): where n.l > 0 the lit face's ramp over the terminator's first
// quarter times its shadow (jd_level takes the positive part); where
// n.l < 0 minus the ramp of a face turned from the light, which takes
// what crossed a thin part (jd_slab_light; none at the terminator, whose
// light the levels bring).
float jd_lit_ramp(float nl, float vis)
{
    return nl > 0.0 ? vis * min(4.0 * nl, 1.0) : max(4.0 * nl, -1.0);
}

// A level at a point p of light depth p.z: its shallower and its deeper
// part (l: sqrt(S / (21/20)) and the S-weighted mean depth where that light
// entered, of each). Each part is S convolved with the level's Gaussian in
// the light's plane times the Gaussian of the depth between the point and
// where the light entered: G(r) of a 3-D distance factors into the two. s:
// light-depth units over sigma sqrt(2), times sqrt(log2 e), so that exp2
// takes it a multiply fewer (pass_screen.c); slack: the map's own error in
// depth. A point the light reaches (lit = 1) is itself on the map's
// surface, the part nearer its depth; that surface runs away from the light
// by sigma tan(theta) within the level's reach: no path through the
// material, so that part's depth term goes to 1 with lit, which adds what
// the term took off that part. The two parts side by side in the vector
// lanes, and only that gain chosen by which part is nearer, not each
// part's sum of two (lima's levels' sum 267 -> 245 words, Adreno 3xx's
// vertex stage 525 -> 485 instructions, Vivante GC3000 359 -> 337).
float jd_level(vec4 l, vec3 p, float s, float slack, float lit)
{
    vec2 dz = abs(p.z - l.ga), ee = l.rb * l.rb;
    vec2 q = max(dz - slack, 0.0) * s;
    vec2 ab = ee * exp2(-q * q), gain = ee - ab;
    return ab.x + ab.y + max(lit, 0.0) * (dz.x < dz.y ? gain.x : gain.y);
}

// A level read at p texel by texel, each texel's parts weighed against the
// point's depth before they are mixed: filtering the texels' depths first
// would make depths that no light entered at, and where one passes through
// the point's depth a bright line would follow it. d: its texel size.
float jd_level_at(sampler2D lv, vec3 p, float d, float s, float slack, float lit)
{
    // Texel i of the 2x2 around p lies at p + g d, g = o - f (o: its
    // offset, 0 or 1 each way; f: p's place between the texel centres), and
    // its bilinear weight is 1 - |g|: nothing but f is held through the
    // loop (with the texel centres held as well, lima's wide pass took 12
    // instruction words more).
    vec2 f = fract(p.xy / d - 0.5);
    // A loop over the four texels, unrolled where the program is built with
    // JD_TRIPS (render_program.c: every GPU but Vivante GC400-GC2000, whose
    // 256 instructions it would not fit; each trip's own test and branches
    // cost lima 16 words). Kept a loop, its count must not look constant, or
    // Mesa's NIR unrolls it: d > 0, so the break comes after 4. A vertex
    // stage unrolls it (as a loop, vc4's vertex shader doubled in length).
    // JD_UNROLL (the device-compiler tool only): a constant trip count, so
    // the compilers' counts say what one more trip costs.
    float l = 0.0;
#if defined(JD_UNROLL)
    for (int i = 0; i < JD_UNROLL; i++) {
#elif defined(JD_FRAGMENT) && !defined(JD_TRIPS)
    for (int i = 0; i < 64; i++) {
        if (float(i) >= 4.0 * step(0.0, d)) break;
#else
    for (int i = 0; i < 4; i++) {
#endif
        vec2 g = vec2(mod(float(i), 2.0), floor(float(i) * 0.5)) - f;
        vec2 wt = 1.0 - abs(g);
        l += wt.x * wt.y * jd_level(texture2D(lv, p.xy + g * d), p, s, slack, lit);
    }
    return l;
}

// The light that crossed a thin part to a point the light does not reach
// itself (pass_light.c, update_slab): the slab's transmission T for the
// part's thickness (the table's first row), less what the levels already
// bring for the depth between the point and the lit face above it (its second
// row), times the light that entered there. Both from the second level, one
// filtered read: the light crossing a part spreads about as wide as the part
// is thick (the reference's carried profile), and a light-map texel read
// point by point mottles an ear with the proxy's facets. The depth from its
// shallower part (the mean depth that light entered at); the light from that
// part and half of the deeper one's where it too lies above the point: where
// the lit face is steep to the light, a level texel's entries span many
// depths and the blurs' sort leaves much of that face's light in the deeper
// part ("Where the top arc's streaks come from", docs/quality.md). From the
// shallower part alone a thick back-lit tube got 0.4 of the light the
// reference carries across it. Half, not all, of the deeper part: whole, it
// came closer to the reference but flickered 2.3% more as the light turns
// (docs/quality.md, "The light through thin parts from both parts of the
// level"). The test is made in the point's own light-depth units: on the
// scaled depth VideoCore IV's summing pass fell to one thread.
// pz: the point's light depth; scale: light-depth units to the table's
// coordinate; tn: the part's own thickness under the point along its normal,
// in the table's coordinate (mesh_thickness.c); lit: the point's own light
// (jd_lit_ramp), negative past the terminator; sd: the shadow map's depth at
// xy (jd_soft_lit's map, read as the light map is); through: the shadow test
// where the point's normal leaves the part (mesh.vert).
vec3 jd_slab_light(sampler2D level, sampler2D slab, vec2 xy, float pz, float scale, float sd, float tn, float lit,
                   float through)
{
    vec4 m = texture2D(level, xy);
    // The lit face's depth above the point: the shallower of two estimates
    // that each lie too deep where that face slants across the light. The
    // level's mean depth of the light that entered within a level texel (a
    // few millimetres: on an ear slanted to the light it lay level with
    // the far face, or below it, and the far face took nothing), and the
    // shadow map's, whose exponential blur leans to the deepest texel
    // within a light-map texel or two.
    float z = (pz - min(m.y, sd)) * scale;
    // The reference carries the light across a part along the normal,
    // which a slanted light crosses longer: the part's own thickness where
    // the depth is up to three times it (a light 70 degrees off the
    // normal), the depth from 7 times it on, a ramp between. Farther, the
    // lit face above is another part's; where that part shades the
    // normal's far end (a foot under the body, whose own thickness lit
    // ketchup's feet from the back in streaks), through, the shadow test
    // there, takes the term away. Until 2026-12-07 the ramp alone did
    // that, and reached the depth at 3.67 times the thickness: where a
    // part thins towards an edge it dropped T(t) to nothing within a few
    // vertices (the fandisk's dark triangle). With the test and no ramp
    // the triangle went, but the default asset's blotches grew 2%
    // (docs/quality.md, "The light through thin parts where it does not
    // come through").
    float t = min(z, max(tn, 1.5 * z - 3.5 * tn));
    // Where it applies: a face turned from the light, over the first
    // quarter of n.l past the terminator (lit: jd_lit_ramp); and, whatever
    // its n.l, a face not lit itself (the rest of 1 - lit) whose lit face
    // above lies a quarter to three times the part's thickness away: a
    // thin part's far side. The reference carries the light across a part
    // whatever the angle of the face it leaves by; the ramp alone left a
    // dark dashed streak down the back-lit bunny's ear, where a wrinkle's
    // normal turns to the light in the ear's own shadow. A thick body's
    // terminator, which the ramp is for, has its lit surface at the point
    // itself (z far below tn) and takes the ramp alone.
    float r = z / max(tn, 0.001);
    float w = max(-lit, clamp(min(4.0 * r - 1.0, 6.0 - 2.0 * r), 0.0, 1.0) * (1.0 - max(lit, 0.0)));
    // sqrt(S / (21/20)): the table holds the 21/20. Its two rows come as
    // square roots (pass_light.c, update_slab: their difference is small
    // on a far face, and 8 bits of it made patches there).
    vec3 ta = texture2D(slab, vec2(t, 0.25)).rgb, tb = texture2D(slab, vec2(z, 0.75)).rgb;
    // The light that entered above the point (m.xz: the two parts' square
    // roots; the deeper one's at half, and only where it lies above).
    float e = dot(m.xz, m.xz * vec2(1.0, 0.5 * step(m.w, pz)));
    return (w * through * e) * max(ta * ta - tb * tb, 0.0);
}

// The levels' sum at light-map position p (xy, depth): Rd's weight on each
// level's Gaussian (w, per channel, times the 21/20 the levels were divided
// by, pass_screen.c) times the level's light. The two
// narrowest levels are read texel by texel (d: the first one's texel size,
// the second's twice that); the wider ones forgive a filtered depth and
// take one filtered read. On a lit point half of the first level's
// Gaussian (a level texel wide) is taken by the local part, from the point's
// own light (that half's weight is there, pass_screen.c); the level gives
// the other half there, and all of it as the point leaves the light
// (lit < 1: a shadow, the terminator, a face turned away). Read texel by
// texel, the level's grid, which turns with the light, makes a still
// object's lit pixels pop from frame to frame; taking all of it locally
// pops less still but sharpens the shadow's edge and moves full away from
// Cycles on the held-out meshes (docs/quality.md, "Artifacts, measured").
vec3 jd_diffused(sampler2D lv0, sampler2D lv1, sampler2D lv2, sampler2D lv3, sampler2D lv4, vec3 p, vec3 w[5],
                 vec3 s[2], float d, float slack, float lit)
{
    // w[0] comes halved (pass_screen.c): (2 - lit) w[0] / 2 is the share
    // above with a multiply fewer. With the 21/20 in w as well, lima's wide
    // pass 276 -> 273 words a fragment.
    return w[0] * jd_level_at(lv0, p, d, s[0].x, slack, lit) * (2.0 - max(lit, 0.0))
         + w[1] * jd_level_at(lv1, p, 2.0 * d, s[0].y, slack, lit)
         + w[2] * jd_level(texture2D(lv2, p.xy), p, s[0].z, slack, lit)
         + w[3] * jd_level(texture2D(lv3, p.xy), p, s[1].x, slack, lit)
         + w[4] * jd_level(texture2D(lv4, p.xy), p, s[1].y, slack, lit);
}
