#version 100
// Shared vertex stage of the shading passes. The parallax-corrected
// refraction direction is found here, per vertex; the fragment stage looks
// the SH irradiance up along it in the map the reduction left on the GPU.
attribute vec4 a_position; // w: the part's thickness under the vertex (render_target.c)
attribute vec3 a_normal;   // unit length
uniform mat4 u_mvp;
// The light's view to light-map coordinates: xy in the map and depth in
// [0, 1] (its clip space with the 0.5 scale and offset folded in on the
// CPU: 8 of lima's vertex words fewer). The light is orthographic: its w
// is 1, and a direction's z comes out halved.
uniform mat4 u_light_tex;
uniform mediump vec3 u_eye; // shared with the fragment stage: precisions must match
uniform vec2 u_shadow_bias;  // light-depth units: per unit of the surface's slope to the light, and always
#if JD_WIDE_ONLY
varying vec2 v_pos;          // x: n.l, signed as the face is seen; y: the part's thickness, half (light-depth units)
varying vec3 v_exit;         // where the normal leaves the part, in the light map (below; light.glsl, jd_slab_light)
varying vec3 v_keep;        // the levels' share a lit face keeps (below)
uniform mediump vec3 u_light_dir; // shared with the fragment stage: precisions must match
#else
varying vec3 v_view;        // towards the eye, unit length: the fragment stage takes it as it comes
varying vec3 v_normal;      // (the summing pass takes n.l in v_pos instead)
#endif
// Where the point falls in the light-depth map, moved towards the light so
// that the map (drawn from a coarser proxy, in texels) does not shadow the
// surface it was drawn from: by the proxy's error, and by the depth a texel
// spans where the surface slopes away from the light (tan theta). Only in
// depth: moving it sideways would move the edges of cast shadows.
// w: the surface's own light depth.
varying vec4 v_shadow;
#if JD_ALBEDO
// The model's own colour (docs/textures.md): the vertex's reflectance over
// the surface's mean, and the texture's weight; the texture's coordinates.
attribute vec4 a_color;        // sqrt of the reflectance, texture weight
uniform vec3 u_albedo_norm;    // 1 / the surface's mean reflectance (2/3 of it with a texture: shade.frag)
varying vec4 v_col;
#if JD_ALBEDO_MAP
attribute vec2 a_uv;
uniform float u_albedo_reach;  // the entry's radius in pixels, times the depth it is seen at
varying vec3 v_uv;             // texture coordinates, the entry's mip bias
#endif
#endif
#if JD_FULL && !JD_WIDE_ONLY
// full's two Fresnel factors per vertex (the fragment stage keeps the
// normal's detail for the highlight and the shadow): the light's
// transmitted in, times n.l and the share a thin part keeps (below, green's
// for all channels: pass_light.c); and the view's out. Meshes are dense beside
// the pixels the boards shade (the default asset at 960x540: about one
// vertex a fragment), and both factors are smooth. The highlight's half
// vector too, for the same reason: the fragment stage normalised it from
// the light and the interpolated view at 4 of lima's 37 words; a mesh
// coarse beside the highlight is split by the loader (mesh_subdivide.c),
// and the interpolated vector is short by the cosine of half the angle
// between its vertices' (a 12-triangle cube close up: 2 of 255 at most).
uniform mediump vec3 u_light_dir; // shared with the fragment stage: precisions must match
uniform vec2 u_fresnel;      // jd_fresnel_tc's fit at the scene's eta
uniform vec2 u_wrap;        // the terminator's smoothing (below; pass_screen.c)
attribute vec2 a_curve;      // the surface's curvature k and 1 / k (mesh_curvature.h)
#if JD_WIDE_BUFFER
// Where the levels' sum comes from its buffer (Utgard; Vivante GC400 to
// GC2000; Adreno 3xx since 2026-12-06), the local part's light is made
// here too, times its colour and weight (u_local_x), and the highlight's
// side test rides in the half vector's w: lima's shading one word shorter
// (27 -> 26; with a texture 32 -> 31), its vertex stage 2 longer; Vivante
// GC2000 35 -> 33 (Midgard, on the same path, 29 -> 31 cycles). Where the
// levels are summed per vertex (VideoCore IV and Adreno 3xx then) that form
// made the shading longer (118 -> 122 and 119 -> 126 instructions).
uniform vec3 u_local_x;
varying vec4 v_fresnel;      // u_local_x n.l Ft(l)/c keep, Ft(v)/c
varying vec4 v_half;         // w: n.l Ft(l)/c keep, > 0 where the vertex is lit
#else
varying vec2 v_fresnel;
varying vec3 v_half;
#endif
#endif
#if JD_FULL
uniform vec3 u_keep[2];     // a lit face's light kept by a part t thick: 1 - a 2^(-b t) (pass_light.c)
// The light between parts: what the rest of the object's lit surface sends
// this vertex across the air, G(l) = max(0, a_bounce . (l, 1)) of the
// light's irradiance (core/mesh_bounce.c, made once at set-up), given out
// again by both albedos (u_bounce_rd: Rd_total squared, per channel). A
// per-vertex value that the fragment stage takes with the levels' light.
attribute vec4 a_bounce;
uniform vec3 u_bounce_rd;
#if JD_WIDE_ONLY
varying vec3 v_bounce;
#endif
#endif
#if JD_FULL && JD_VERTEX_DIFFUSION
// Where the vertex stage can read textures, the full mode's light-space
// levels (smooth by construction: their finest Gaussian is a level texel
// wide) are summed per vertex; the fragment stage keeps the local part.
uniform sampler2D u_depth_v;
uniform sampler2D u_lv0_v;
uniform sampler2D u_lv1_v;
uniform sampler2D u_lv2_v;
uniform sampler2D u_lv3_v;
uniform sampler2D u_lv4_v;
uniform vec4 u_light_map_v;  // as the fragment stage's u_light_map
uniform vec3 u_light_dir_v;
uniform vec3 u_lw[5];
uniform vec3 u_ls[2];
#ifndef JD_NO_SLAB
// The light scattered once on its way to the camera (jd_single_march).
uniform sampler2D u_light_depth_v; // the light map itself (depth.frag), not the shadow map
uniform vec3 u_march_st;     // sigma_t, per mm
uniform vec3 u_march_ss;     // sigma_s / 4, per mm, times the light's way in through the boundary
uniform vec4 u_march;        // mm per world unit, mm per light-depth unit, the march's reach and its start under a lit point (mm)
#endif
varying vec3 v_wide;
#endif
#if JD_FULL && JD_WIDE_BUFFER
// Where the point falls in the levels' half-resolution sum, before the
// division by w (the fragment stage reads it with texture2DProj): from
// gl_FragCoord there it took lima 6 instruction words more (84, not 78).
uniform vec2 u_wide_scale;   // half the used corner of that layer's texture
varying vec3 v_screen;
#endif
#if JD_TRANSLUCENT
uniform vec3 u_box_min;
uniform vec3 u_box_max;
uniform float u_inv_eta;
uniform float u_inset;
uniform float u_f0;          // Schlick reflectance at normal incidence
uniform vec3 u_a0_scale;     // K (1-Fdr)/pi alpha'/2, per channel
#if JD_VERTEX_THICKNESS
// Where the GPU can fetch textures in the vertex stage, the thickness and
// its dipole tail are read per vertex: the fragment stage then has no
// texture to fetch for A0. (Mali-400 has no vertex texture units: there the
// fragment stage does it.)
uniform sampler2D u_depth_v;
uniform sampler2D u_tail_v;
#else
varying vec3 v_light;
#endif
varying vec3 v_trans;        // A0 but the irradiance and (per fragment) the thickness term
varying vec3 v_dir;          // where the irradiance is looked up
#endif

#if JD_FULL && JD_VERTEX_DIFFUSION && !defined(JD_NO_SLAB)
// The light that reached the point l (light-map xy, depth) through the
// medium, e^(-sigma_t d) per channel, d its depth below the light map's
// surface in mm: over the four nearest texels, each texel's light weighed
// bilinearly, and none from a texel whose surface lies behind the point
// (the point is in the air there, outside the part; tol: how far behind
// counts as on it, mm). The transmittances are mixed, not the depths: the
// depths mixed (a tube's with what lies past its outline in the light's
// view) were blotchier still, and one texel's depth at each point stepped
// from vertex to vertex: the default asset's blotches 59% larger and its
// flicker 56% (docs/quality.md, "Single scattering in full").
vec3 jd_through(vec3 l, float tol)
{
    vec2 tc = l.xy * u_light_map_v.x - 0.5;
    vec2 f = fract(tc);
    vec2 b = l.xy - f * u_light_map_v.y;
    float d = u_light_map_v.y;
    vec4 dd = (l.z - vec4(jd_depth(texture2D(u_light_depth_v, b)), jd_depth(texture2D(u_light_depth_v, b + vec2(d, 0.0))),
                          jd_depth(texture2D(u_light_depth_v, b + vec2(0.0, d))),
                          jd_depth(texture2D(u_light_depth_v, b + vec2(d, d))))) * u_march.y;
    vec2 g = 1.0 - f;
    vec4 w = vec4(g.x * g.y, f.x * g.y, g.x * f.y, f.x * f.y) * step(vec4(-tol), dd);
    dd = max(dd, 0.0);
    return vec3(dot(w, exp(-u_march_st.r * dd)), dot(w, exp(-u_march_st.g * dd)), dot(w, exp(-u_march_st.b * dd)));
}

// The light scattered once on its way through the part to the camera
// (Jensen et al. 2001's first order; jade reference --single-scatter
// traces it): sigma_s / 4 times the integral along the camera ray, into the
// part from the vertex, of e^(-sigma_t s) times the light that reached
// the ray's point through the medium (jd_through): the translucent shadow
// maps of Dachsbacher and Stamminger 2003, in the vertex stage. Three
// steps to the reach, min(the part's thickness / |n.v|, 5 mean free paths
// of the clearest channel): four gave the same figures, two a blotchier
// default asset; between two steps the integrand taken as exponential
// (exact where the depth to the light changes linearly along the ray: the
// midpoint rule overshot marble's first millimetre). Less what the point's
// own half-space scatters once, keep alpha / 4 mu0 / (mu0 + mu), which the
// local part's albedo already holds. On a lit point the march starts a
// little under it (u_march.w, two light-map texels) and the half-space's
// figure is taken off only past there: finer than a texel the light map's
// depths say nothing, and a millimetre of error in d is a factor 9 of
// marble's light. In place of the slab's light through thin parts
// (jd_slab_light), whose diffusion put the light that crosses a part in
// patches where Cycles has it even (docs/quality.md, "Single scattering in
// full": every back-lit case of the knot closer to Cycles, ketchup's most).
vec3 jd_single_march(vec3 pos, vec3 vf, float thick, float ndv, float ndl, float lit, vec3 keep)
{
    float reach = min(thick * u_march.x / max(ndv, 0.25), u_march.z);
    float s0 = min(u_march.w * max(lit, 0.0), reach), h = (reach - s0) / 3.0;
    float tol = 0.5 * u_march.w;
    // The light map's coordinates are affine in the world's: a step along
    // the ray is a constant step there.
    vec3 l = (u_light_tex * vec4(pos - vf * (s0 / u_march.x), 1.0)).xyz;
    vec3 dl = (u_light_tex * vec4(-vf * (h / u_march.x), 0.0)).xyz;
    vec3 f0 = max(exp(-u_march_st * s0) * jd_through(l, tol), 1e-6), sum = vec3(0.0);
    for (int k = 1; k <= 3; k++) {
        vec3 f1 = max(exp(-u_march_st * (s0 + float(k) * h)) * jd_through(l + float(k) * dl, tol), 1e-6);
        vec3 x = log(f0 / f1);
        sum += mix(f0, (f0 - f1) / x, step(vec3(1e-3), abs(x)));
        f0 = f1;
    }
    float mu0 = max(ndl, 0.0);
    vec3 own = max(lit, 0.0) * keep * (u_march_ss / max(u_march_st, 1e-6)) * mu0 / max(mu0 + ndv, 0.01) *
               exp(-u_march_st * s0 * (1.0 + ndv / max(mu0, 0.05)));
    return max(u_march_ss * sum * h - own, 0.0);
}
#endif

void main()
{
#if JD_ALBEDO
    // Grouped as lima's vertex compiler took it shortest: (a_color (a_color
    // norm)) in full (67 words, 72 the other way), (a_color a_color) norm
    // elsewhere (the translucent modes 125, 134 the other way).
#if JD_FULL
    v_col = vec4(a_color.rgb * (a_color.rgb * u_albedo_norm), a_color.a);
#else
    v_col = vec4(a_color.rgb * a_color.rgb * u_albedo_norm, a_color.a);
#endif
#endif
    // The part's thickness under the vertex rides in the position's w
    // (render_target.c, mesh_thickness.c).
    vec3 pos = a_position.xyz;
    vec3 an = a_normal;
    float thick = a_position.w;
#if JD_FULL
    // On a lit face, the share of the light that a part this thick keeps
    // (its slab's R(t) of the half-space's, pass_light.c: 1 - a 2^(-b t),
    // per channel, fitted on the CPU), the local part's and the levels'.
    vec3 lose = u_keep[0] * exp2(-u_keep[1] * thick);
#if !JD_WIDE_ONLY
    vec3 keep = 1.0 - lose;
#endif
#endif
#if JD_FULL
#if JD_WIDE_ONLY
    // G(l) as a three-lane dot and an add, not a four-lane dot of (l, 1):
    // the same value; the levels' sum's vertex stage on lima 48 -> 45
    // words, Midgard 64 -> 61. Where the vertex stage sums the levels the
    // four-lane dot is the shorter (Vivante GC3000/GC7000L and Adreno 3xx
    // one instruction).
    vec3 bounce = u_bounce_rd * max(dot(a_bounce.xyz, u_light_dir) + a_bounce.w, 0.0);
#else
    vec3 bounce = u_bounce_rd * max(dot(a_bounce, vec4(u_light_dir, 1.0)), 0.0);
#endif
#endif
#if JD_WIDE_ONLY
    // The face seen is lit where n.v and n.l have the same sign: one
    // product, not the normal turned towards the eye (three selects)
    // before the dot. And the share is written 1/2 - lit/2 (1 - keep), not
    // mix(1, keep, lit) / 2, the same value. lima's vertex stage: 64 words
    // as the other passes write it, 61 with the product, 57 with the form,
    // 56 with both (Midgard 32 -> 31 bundles).
    // Halved (the light between parts and the share's a by their
    // uniforms: pass_screen.c): the buffer holds sqrt(wide / 2)
    // (shade.frag), and the halving here is a multiply fewer there.
    float dv = dot(an, u_eye - pos), dl = dot(an, u_light_dir);
    float lit_face = step(0.0, dv * dl);
    v_keep = 0.5 - lit_face * lose;
    v_bounce = bounce;
#endif
#if JD_WIDE_ONLY
    // n.l as the face is seen, for the summing pass's ramp (shade.frag).
    v_pos = vec2(dv < 0.0 ? -dl : dl, 0.5 * thick);
#else
    vec3 vf = normalize(u_eye - pos);
    v_view = vf;
    v_normal = an;
#endif
    gl_Position = u_mvp * vec4(pos, 1.0);
#if JD_ALBEDO_MAP
    // The entry's mip bias (shade.frag): the radius in pixels here, nearer
    // or further than the object's centre, and less the slant. The GPU
    // picks a level by the footprint's longer side, which a surface seen
    // at a slant stretches by 1 / |n.v|: the bias takes that back, else
    // the entry near the silhouette was read levels too coarse (at most
    // 4.3 levels here, at |n.v| 0.05).
    v_uv = vec3(a_uv, log2(max(max(abs(dot(an, vf)), 0.05) * u_albedo_reach / gl_Position.w, 1e-6)));
#endif
    vec4 sp = u_light_tex * vec4(pos, 1.0);
    v_shadow = sp.xyzz;
#if JD_FULL
    // full's shadow test takes the depth as its exponential's exponent
    // (light.glsl, jd_soft_lit): scaled and offset here, not per fragment;
    // full moves no depth towards the light (the bias below is the 2x2
    // test's). With JD_LIGHT_Z_SCALED the matrix's depth row comes scaled and
    // offset from the CPU (pass_screen.c): the picture's pass with the
    // levels from their buffer, which reads no w of this stage (lima's
    // vertex stage 55 -> 54 words with the light factor grouped as below,
    // with a colour 63 -> 58; Midgard 89 -> 82 and 105 -> 99 bundles,
    // Vivante 2 fewer).
#ifndef JD_LIGHT_Z_SCALED
    v_shadow.z = sp.z * u_soft_c.x - 0.250;
#endif
#if JD_WIDE_ONLY && !defined(JD_NO_SLAB)
    // Where the normal leaves the part (the far end of the thickness under
    // the vertex, mesh_thickness.c) in the light map, as the shadow test
    // takes it: the light that crossed a thin part comes only where that
    // end is lit (light.glsl, jd_slab_light). Taken half the thickness
    // nearer the light (a light-depth unit is two of the world's: 0.25),
    // or on a far face slanted to the light the test failed in patches (a
    // dark blotch on the back-lit ketchup bunny's thigh, and that case 1.7%
    // further from the reference); 0.3, 0.5, 0.7 or 1 times the thickness
    // moved the bunny's back-lit cases by 0.8% at most (with the ramp of
    // 3 to 3.67 times the thickness, light.glsl). This program takes the
    // depth row unscaled (JD_LIGHT_Z_SCALED is the picture's pass alone),
    // so the exponent's scale is applied here. The form is lima's shortest
    // of those tried: 52 words in the summing pass, 54, 57, 62. (The levels
    // summed per vertex take the light scattered once instead,
    // jd_single_march.)
    v_exit = v_shadow.xyz -
             thick * ((u_light_tex * vec4(an, 0.0)).xyz + vec3(0.0, 0.0, 0.25)) * vec3(1.0, 1.0, u_soft_c.x);
#endif
#else
    // The light looks down its +z: a normal facing it has a negative z there.
    float cl = clamp(abs(2.0 * (u_light_tex * vec4(an, 0.0)).z), 0.2, 1.0);
    v_shadow.z -= u_shadow_bias.y + u_shadow_bias.x * (1.0 + sqrt(1.0 - cl * cl) / cl);
#endif
#if JD_FULL && !JD_WIDE_ONLY
    // The face as seen: n.v and n.l with their signs turned where n.v < 0,
    // not the normal turned (three selects) and both dots taken again. The
    // same values, bit for bit; lima's vertex stage 60 -> 50 words (with a
    // colour 69 -> 65), and this stage runs on every vertex of the mesh.
    float dvf = dot(an, vf), dlf = dot(an, u_light_dir);
    float xl = dvf < 0.0 ? -dlf : dlf;
    // The local part's n.l smoothed over the terminator: light that enters
    // on the lit side diffuses round a curved surface into its shade, as far
    // as the part's width (sigma, millimetres) is an angle at the surface's
    // radius (1 / k, the attribute's; Penner and Borshukov's pre-integrated
    // skin shading tabulates the same). The ramp max(n.l, 0) averaged over
    // +-e, a box of the Gaussian's variance (e = sqrt(3) sigma k, at most 1):
    // (n.l + e)^2 / 4e within e of the terminator, n.l beyond. u_wrap: e / k
    // and 1 / 4e times k (pass_screen.c); a_curve: k and 1 / k. A thin
    // tube's or a leg's shaded side is no longer dark from the terminator
    // on, where Cycles' is not: the knot 0.693 -> 0.662 of none's error
    // against Cycles, the cow back-lit 10-12% closer (docs/quality.md,
    // "The terminator"). lima's vertex stage 50 -> 55 words, in the form
    // its compiler took shortest (JD_UTGARD): t (t q); the Fresnel factors
    // without the clamps that their arguments' ranges make idle (ndl_v >=
    // 0, and |n.v| <= 1 but for rounding, where x^5 is then -1e-35 or so);
    // the wide buffer's coordinates as (xy + w) s. 57 with the clamps, 60
    // left to right; searches over 420 equivalent forms (2026-12-07): none
    // shorter than 55 (its scheduler is not monotonic: with no lower clamp
    // on the light's factor either, 59; dropping keep entirely gave 64);
    // 54 since the depth row comes scaled (JD_LIGHT_Z_SCALED, above).
    // Elsewhere the clamps stay: Midgard, Vivante and Adreno clamp to
    // [0, 1] for free, and the Utgard form took them 1, 1 and 4
    // instructions more.
    float e = min(a_curve.x * u_wrap.x, 1.0), q = max(a_curve.y * u_wrap.y, 0.25);
    float t = max(xl + e, 0.0);
    float ndl_v = xl < e ? t * (t * q) : xl;
    // n.l is 0 on a face turned from the light: keep counts only where lit.
#if JD_UTGARD
    // n.l (F keep): with the depth row scaled on the CPU (above), the
    // shortest of lima's (54 words; left to right 59, (n.l keep) F 55).
    float fl = ndl_v * (jd_fresnel_x(1.0 - min(ndl_v, 1.0), u_fresnel) * keep.g);
    float fv = jd_fresnel_x(1.0 - abs(dvf), u_fresnel);
#else
    float fl = ndl_v * (jd_fresnel_tc(ndl_v, u_fresnel) * keep.g), fv = jd_fresnel_tc(abs(dvf), u_fresnel);
#endif
    vec3 hv = normalize(u_light_dir + vf);
#if JD_WIDE_BUFFER
    v_fresnel = vec4(u_local_x * fl, fv);
    v_half = vec4(hv, fl);
#else
    v_fresnel = vec2(fl, fv);
    v_half = hv;
#endif
#if JD_ALBEDO
    // The view's Fresnel factor rides on the colour, which multiplies the
    // same light in the fragment stage (shade.frag): a vector multiply
    // fewer a fragment there (lima 33 -> 32 words, Adreno 3xx 136 -> 126).
    v_col.rgb *= fv;
#endif
#endif
#if JD_FULL && JD_VERTEX_DIFFUSION
    float ndl = dot(an, u_light_dir_v);
    if (dvf < 0.0) ndl = -ndl;
    // The shadow test without a branch round it: jd_lit_ramp takes it only
    // where ndl > 0 (VideoCore IV's vertex stage 330 -> 286 instructions,
    // 614 -> 477 cycles; Adreno 3xx 628 -> 554).
    float lit = jd_lit_ramp(ndl, jd_soft_lit(u_depth_v, v_shadow.xyz));
    v_wide = jd_diffused(u_lv0_v, u_lv1_v, u_lv2_v, u_lv3_v, u_lv4_v, v_shadow.xyw, u_lw, u_ls, u_ls[1].z, u_light_map_v.w, lit);
    // A lit face of a thin part returns the slab's R(t), not the
    // half-space's: what went deep left through the far side.
    v_wide *= mix(vec3(1.0), keep, step(0.0, ndl));
#ifndef JD_NO_SLAB
    // The light scattered once on its way through the part to the camera.
    v_wide += jd_single_march(pos, vf, thick, abs(dvf), ndl, lit, keep);
#endif
    v_wide += bounce;
#endif
#if JD_TRANSLUCENT
    vec3 n = an;
    vec3 view = vf;
    if (dot(n, view) < 0.0) n = -n;
    // Thickness is read at a point moved inward, so the surface does not
    // measure itself.
    vec3 light = (u_light_tex * vec4(pos - u_inset * n, 1.0)).xyz;
    vec3 r = refract(-view, n, u_inv_eta);
    if (dot(r, r) < 1e-6) r = -n;
    // Box projection: where the refracted ray leaves the bounding cube, seen
    // from the capture centre (the origin).
    // No zero components: 0/0 would poison the lookup with NaN.
    r = vec3(r.x < 0.0 ? min(r.x, -1e-4) : max(r.x, 1e-4),
             r.y < 0.0 ? min(r.y, -1e-4) : max(r.y, 1e-4),
             r.z < 0.0 ? min(r.z, -1e-4) : max(r.z, 1e-4));
    vec3 s1 = (u_box_max - pos) / r;
    vec3 s2 = (u_box_min - pos) / r;
    vec3 sf = max(s1, s2);
    float s = min(min(sf.x, sf.y), sf.z);
    v_dir = pos + s * r; // the lookup normalises
    float x = clamp(1.0 - dot(n, view), 0.0, 1.0);
    float x2 = x * x;
    float ft = 1.0 - (u_f0 + (1.0 - u_f0) * x2 * x2 * x); // Fresnel transmittance
    // With the fragment stage's constant factors: RGBM's 4 and, where the
    // thickness is taken per fragment, the tail's 2 (left there, lima's
    // compiler moved the whole product after its last texture read and held
    // every operand live; it spilled).
#if JD_VERTEX_THICKNESS
    v_trans = ft * u_a0_scale * 4.0;
#else
    v_trans = ft * u_a0_scale * 8.0;
#endif
#if JD_VERTEX_THICKNESS
    float t = clamp(light.z - jd_unpack(texture2DLod(u_depth_v, light.xy, 0.0)), 0.0, 1.0);
    vec3 m = texture2DLod(u_tail_v, vec2(t, 0.5), 0.0).rgb;
    v_trans *= 2.0 * m * m;
#else
    v_light = light;
#endif
#endif
#if JD_FULL && JD_WIDE_BUFFER
#if JD_UTGARD
    v_screen = vec3((gl_Position.xy + gl_Position.w) * u_wide_scale, gl_Position.w);
#else
    v_screen = vec3(gl_Position.xy * u_wide_scale + gl_Position.w * u_wide_scale, gl_Position.w);
#endif
#endif
}
