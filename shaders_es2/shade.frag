#version 100
// The visible surface. none, single, dual: Lambert + Blinn-Phong with the
// direct light shadowed by the light-depth map, plus in translucent modes the
// transmitted layer A0 = K Ft (1-Fdr)/pi M(t) E(d), and in dual mode the two
// spread layers, blended per channel before tone mapping. full: the
// reference's model, Ft(wo)/c * Mo with Mo the directly lit irradiance
// diffused with the dipole's profile (a local part here, the wider Gaussians
// from the light-space levels).
precision mediump float;
uniform vec3 u_light_dir;
uniform vec3 u_eye;
uniform vec3 u_albedo;       // Rd_total
uniform vec3 u_light_color;
uniform vec4 u_shading;      // ambient, specular, shininess, exposure
uniform vec4 u_light_map;    // light-depth texels per side, their inverse, Schlick F0, depth slack of the proxy
uniform sampler2D u_depth;   // light depth, packed; irradiance in alpha (full: the exponential shadow map)
#if JD_WIDE_ONLY
varying vec2 v_pos;          // x: n.l, signed as the face is seen; y: the part's thickness, half (light-depth units: mesh.vert)
varying vec3 v_exit;         // where the normal leaves the part, in the light map (mesh.vert)
varying vec3 v_keep;         // the levels' share a lit face of a thin part keeps, halved (mesh.vert)
varying vec3 v_bounce;       // the light between parts, halved (mesh.vert)
#else
varying vec3 v_view;         // towards the eye, unit length at the vertices (mesh.vert)
varying vec3 v_normal;       // (the summing pass takes n.l from the vertices instead)
#endif
varying vec4 v_shadow;
#if JD_TRANSLUCENT
#if !JD_VERTEX_THICKNESS
uniform sampler2D u_tail;    // sqrt of the dipole tail M(t)/M-scale, t across [0, range]
varying vec3 v_light;
#endif
varying vec3 v_trans;
varying vec3 v_dir;
uniform samplerCube u_irr;   // the SH irradiance by direction, RGBM: rgb * a * 4 (irradiance.frag)
#endif
#if JD_SPREAD
uniform vec2 u_inv_viewport; // screen position to the used corner of the low-resolution layer
#endif
#if JD_SPREAD
uniform sampler2D u_spread;  // sqrt((w1 A1 + w2 A2) / 2), alpha = covered
uniform vec3 u_w0;
#endif
#if JD_FULL
#if !JD_WIDE_ONLY
// The picture's constant factors, multiplied together on the CPU
// (pass_screen.c): lima's compiler multiplied the uniforms in every
// fragment (4 instruction words).
uniform vec3 u_amb_x;        // Rd_total x ambient x exposure
uniform vec3 u_wide_x;       // light colour x exposure (x 2 where the levels' sum is read halved)
uniform vec3 u_spec_x;       // light colour x specular x exposure
#ifdef JD_SPEC_TABLE
// The highlight, (n.h / |n|)^shininess, by n.n and n.h of the interpolated
// normal (pass_screen.c, jdr_update_spec).
uniform sampler2D u_spec;
#endif
// Per vertex (mesh.vert): n.l Ft(l)/c times a thin part's keep (fl), the
// view's Ft(v)/c, the highlight's half vector, unit length at the vertices.
#if JD_WIDE_BUFFER
varying vec4 v_fresnel;      // the local part's light, u_local_x fl; Ft(v)/c
varying vec4 v_half;         // w: fl, the highlight's side test
#define JD_LIT_V v_half.w
#define JD_FT_V max(v_fresnel.w, 0.15)
#else
uniform vec3 u_local_x;      // light colour x Rd's weight on the Gaussians finer than a level texel x exposure
varying vec2 v_fresnel;      // fl, Ft(v)/c
varying vec3 v_half;
#define JD_LIT_V v_fresnel.x
#define JD_FT_V max(v_fresnel.y, 0.15)
#endif
#endif
#if JD_VERTEX_DIFFUSION
varying vec3 v_wide;         // the levels' light, per vertex (jd_diffused)
#elif JD_WIDE_BUFFER
// Where the vertex stage cannot read textures, the levels' light is summed
// per fragment at half resolution (it is smooth: its finest Gaussian is a
// level texel wide), its outline filled (wide_fill.frag), and read here
// once: sqrt(wide / 2).
uniform sampler2D u_wide;
varying vec3 v_screen;       // where in it (mesh.vert), before the division by w
#else
// The five light-space levels: sqrt(S / (21/20)) and mean depth of the
// light that entered near the map's surface (RG) and elsewhere (BA).
uniform sampler2D u_lv0;
uniform sampler2D u_lv1;
uniform sampler2D u_lv2;
uniform sampler2D u_lv3;
uniform sampler2D u_lv4;
uniform vec3 u_lw[5];        // Rd's weight on each level's Gaussian, per channel
uniform vec3 u_ls[2];        // per level: depth units to sigma_k sqrt(2), levels 1-3 and 4-5; the first level's size
#ifndef JD_NO_SLAB
uniform sampler2D u_slab;    // the light through thin parts, by thickness (jd_slab_light)
uniform float u_slab_scale;  // light-depth units to its coordinate
#endif
#endif
#endif

#if JD_ALBEDO
varying vec4 v_col;          // reflectance / mean at the vertex (2/3 of it with the texture), texture weight
#if JD_ALBEDO_MAP
uniform sampler2D u_albedo_map; // sqrt of the reflectance
varying vec3 v_uv;           // texture coordinates, mip levels from the exit's texel to the profile's reach
#endif
// The light under the surface scaled by its colour where it leaves and
// where it entered, sqrt(A_out) sqrt(A_in) / mean A (d'Eon, Luebke and
// Enderton 2007, pre- and post-scatter texturing). The entry's sqrt(A) is
// the profile-weighted mean around the point: a third the colour at the
// point (the profile's peak), two thirds the texture's mean over its 60%
// radius (a coarser mip level), as jade reference measured it
// (docs/textures.md).
vec3 albedo_factor()
{
#if JD_ALBEDO_MAP
    vec3 t0 = texture2D(u_albedo_map, v_uv.xy).rgb;
    // (t0 + 2 t1) / 3 as (t0 / 2 + t1) with the 2/3 in u_albedo_norm:
    // lima had a word more for the 2 t1.
    vec3 t = t0 * (0.5 * t0 + texture2D(u_albedo_map, v_uv.xy, v_uv.z).rgb);
#if JD_ALBEDO_PARTIAL
    // Some materials untextured: their vertices' weight 0 takes the
    // texture out (1.5: the uniform's 2/3 undone).
    return v_col.rgb * mix(vec3(1.5), t, v_col.a);
#else
    return v_col.rgb * t;
#endif
#else
    return v_col.rgb;
#endif
}
#endif

#if JD_TRANSLUCENT
// A0: the per-vertex part times the dipole tail of the thickness, which comes
// from a lookup table (two exp and two sqrt per channel, per fragment, cost
// more than the rest of the shader on small GPUs).
vec3 translucency()
{
    vec4 e = textureCube(u_irr, v_dir);
    vec3 trans = v_trans * e.rgb * e.a; // v_trans carries the factors
#if JD_VERTEX_THICKNESS
    return trans;
#else
    float shadow = jd_unpack(texture2D(u_depth, v_light.xy));
    float t = clamp(v_light.z - shadow, 0.0, 1.0);
    vec3 m = texture2D(u_tail, vec2(t, 0.5)).rgb;
    return m * m * trans;
#endif
}
#endif

void main()
{
#if JD_SPREAD && !JD_A0_ONLY
    // The spread layers are read first: read where they are used, the
    // screen position's registers and theirs were live beside the
    // translucency's reads and lima spilled 2:6. (Orders tried on lima's
    // compiler, tools/device-shaders.sh; this one holds every variant
    // within its six registers.)
    vec4 sp = texture2D(u_spread, gl_FragCoord.xy * u_inv_viewport);
#endif
#if JD_ALBEDO && !JD_SPREAD
    // Read first, where no other value is live yet (lima spilled 1:3 with
    // the reads where they are used); dual reads its spread layer first
    // instead, and these where they are used.
    vec3 alb = albedo_factor();
#endif
#if JD_WIDE_ONLY
    // The summing pass takes only n.l's sign and its first quarter (the
    // terminator's ramp), with the normal turned to the eye: made per
    // vertex (mesh.vert), as n.l of the interpolated normal is the
    // interpolated n.l. Turned per vertex, a triangle across the
    // silhouette has a vertex each way, where per fragment it took the
    // side of each fragment; its three dot products, the turn and the
    // varyings of the normal and the position cost lima 4 words here
    // (271 -> 267) and Vivante GC400/GC2000 7 instructions; Midgard's
    // scheduler packs the shorter program into 4 bundles more (125 -> 129),
    // its vertex stage 5 fewer.
    float nl = v_pos.x;
#else
    vec3 n = normalize(v_normal);
    // The direction to the eye as the vertices had it, not normalised
    // again: between unit vectors 5 degrees apart as the eye sees them the
    // interpolated one is at most 0.1% short, and only the highlight's
    // half vector (normalised below) and a sign take it (lima 4
    // instruction words fewer in every mode, vc4 10-39 instructions). On a
    // face spanning tens of degrees close up its direction, and the
    // highlight, move a little (a 12-triangle cube: 0.03 RMSE).
    vec3 v = v_view;
    if (dot(n, v) < 0.0) n = -n;
#endif
#if JD_A0_ONLY
    // The spread funnel's input: A0 premultiplied by coverage (alpha 1), at
    // half range so values up to 2 survive RGBA8.
    gl_FragColor = vec4(0.5 * translucency(), 1.0);
#else
#if !JD_WIDE_ONLY
    float ndl = max(dot(n, u_light_dir), 0.0);
#endif
#if JD_FULL
    // full's own test, soft (light.glsl, jd_soft_lit): u_depth holds the
    // exponential shadow map here. v_shadow.z: the depth not moved
    // towards the light, as the exponent (mesh.vert).
    float vis = jd_soft_lit(u_depth, v_shadow.xyz);
#elif JD_SPREAD || (JD_TRANSLUCENT && JD_ALBEDO)
    float vis = ndl > 0.0 ? jd_lit_fraction(u_depth, v_shadow.xyz, u_light_map.xy) : 0.0;
#else
    // The shadow test without a branch round it: what vis multiplies is
    // already nothing where the surface faces away from the light (ndl, the
    // highlight's own test; full's per-vertex n.l Ft, which reaches 0 at
    // the terminator). Branchless, lima took 3 instruction words fewer,
    // Midgard 3-11 bundles, Adreno 3xx 20-60 instructions, and VideoCore IV
    // runs it in two threads (where one thread cost 410 cycles). Kept where
    // it was: dual (lima spilled 2:2 without it) and single with a colour
    // (VideoCore IV back to one thread).
    float vis = jd_lit_fraction(u_depth, v_shadow.xyz, u_light_map.xy);
#endif
#if !JD_WIDE_ONLY
#if JD_FULL
    // full's half vector as the vertices made it, unit length there and
    // not normalised again (mesh.vert): lima 4 words fewer (37 -> 33),
    // VideoCore IV 20 instructions; the default asset, the bunny, the
    // pebble and a 12-triangle cube at 512x512 no pixel more than 8 of 255
    // from the per-fragment one.
    vec3 h = v_half.xyz;
#else
    vec3 h = normalize(u_light_dir + v);
#endif
#if JD_FULL
    // The normal turns to the eye only where back faces are drawn: culled,
    // a visible face's normal faces the eye but in the silhouette's last
    // pixels (the normals follow the winding, mesh_load.c). The side test
    // is the vertices' n.l (JD_LIT_V: > 0 where any vertex of the triangle
    // is lit), a word fewer than the fragment's own on lima; where there
    // is no table, the fragment's n.l, the turn and the eye's varying took
    // VideoCore IV 19 of full's 124 instructions, GC3000 7 of 40, Adreno
    // 3xx 14 of 119.
    vec3 ns = v_normal;
#if JD_TWO_SIDED
    if (dot(ns, v) < 0.0) ns = -ns;
#endif
#ifdef JD_SPEC_TABLE
    // The highlight read from a table by the two dot products, where the
    // normal's normalising, the power and the side tests took lima 14 of
    // full's 33 instruction words (a chain of scalar steps: rsqrt, log2,
    // exp2 each a word of their own); from the table 27. n.h < 0 reads the
    // table's first row, 0. Read outside the test: inside it, lima
    // branched round the read.
    float st = texture2D(u_spec, vec2(dot(v_normal, v_normal) * JD_SPEC_SCALE.x + JD_SPEC_OFFSET.x,
                                      dot(ns, h) * JD_SPEC_SCALE.y + JD_SPEC_OFFSET.y)).r;
#else
    // Where there is no table (the levels summed per vertex: desktops, and
    // small meshes on the GPUs whose vertices and fragments share their
    // ALUs, gl_caps.h), (n.h / |n|)^shininess.
    float st = pow(max(dot(normalize(ns), h), 0.0), u_shading.z);
#endif
    float spec = JD_LIT_V > 0.0 ? vis * st : 0.0;
#else
    float spec = ndl > 0.0 ? vis * pow(max(dot(n, h), 0.0), u_shading.z) : 0.0;
#endif
#endif
#if JD_FULL
#if JD_VERTEX_DIFFUSION
    vec3 wide = v_wide;
#elif JD_WIDE_BUFFER
    // Its outline filled (wide_fill.frag): a pixel on the silhouette takes
    // the covered neighbours' light, not the empty background's, and no
    // division by the coverage is left here (lima 26 -> 23 words).
    vec3 we = texture2DProj(u_wide, v_screen).rgb;
    vec3 wide = we * we;
#else
#if JD_WIDE_ONLY
    float lit = jd_lit_ramp(nl, vis);
#else
    float lit = jd_lit_ramp(dot(n, u_light_dir), vis);
#endif
    vec3 wide = jd_diffused(u_lv0, u_lv1, u_lv2, u_lv3, u_lv4, v_shadow.xyw, u_lw, u_ls, u_ls[1].z, u_light_map.w, lit);
#ifndef JD_NO_SLAB
    // As the vertex stage's (mesh.vert): through thin parts, to faces the
    // light does not reach.
    // The shadow map's depth read again, not merged with the test's read
    // above: held across the levels' loop, that read's value took lima
    // past its six registers (1:4 spills). The bias keeps the compilers
    // from merging the two; the map has no mip levels, so it reads the
    // same texels.
    float sd = jd_depth(texture2D(u_depth, v_shadow.xy, -1.0));
    wide += jd_slab_light(u_lv1, u_slab, v_shadow.xy, v_shadow.w, u_slab_scale, sd, v_pos.y * u_slab_scale, lit,
                          jd_soft_lit(u_depth, v_exit));
#endif
#if JD_WIDE_ONLY
    // As the vertex stage's: a lit face of a thin part returns R(t); and
    // the light between parts. Both come halved (mesh.vert), as the
    // buffer holds the sum.
    wide = wide * v_keep + v_bounce;
#endif
#endif
#if JD_WIDE_ONLY
    gl_FragColor = vec4(sqrt(clamp(wide, 0.0, 1.0)), 1.0);
    return;
#else
    // The local part held at 0 or more: on a multisampled target a pixel
    // of the outline whose centre lies off its triangle takes fl
    // extrapolated there, below 0 where a triangle spans the terminator
    // (fl is 0 at its unlit vertices), and its covered samples came out
    // dark, as the view's factor's did (JD_FT_V). lima takes the max as
    // its multiply's output modifier: no word.
#if JD_WIDE_BUFFER
    vec3 mo = u_amb_x + max(v_fresnel.xyz * vis, 0.0) + u_wide_x * wide;
#else
    vec3 mo = u_amb_x + u_local_x * max(v_fresnel.x * vis, 0.0) + u_wide_x * wide;
#endif
#if JD_ALBEDO
    // The view's Fresnel factor came with the colour (mesh.vert).
    vec3 col = mo * alb + spec * u_spec_x;
#else
    vec3 col = JD_FT_V * mo + spec * u_spec_x;
#endif
#endif
#else
#if JD_ALBEDO
#if JD_SPREAD
    vec3 alb = albedo_factor();
#endif
    vec3 col = u_albedo * alb * (u_shading.x + ndl * vis * u_light_color) + u_shading.y * spec * u_light_color;
#else
    vec3 col = u_albedo * (u_shading.x + ndl * vis * u_light_color) + u_shading.y * spec * u_light_color;
#endif
#endif
#if JD_TRANSLUCENT
    vec3 a0 = translucency();
#if JD_SPREAD
    // w0 A0 + the spread layers; where the low-resolution layers did not
    // reach (a silhouette pixel the proxy missed), A0 stands in for them:
    // w0 A0 + (1 - w0) A0.
    a0 = sp.a > 0.5 ? u_w0 * a0 + 2.0 * sp.rgb * sp.rgb : a0;
#endif
    // At the silhouette the per-vertex A0 of a grazing vertex (its
    // refraction box-projected to wherever the capture is brightest) would
    // light single pixels that flicker as the light moves; the Fresnel
    // transmittance there is near zero anyway, per fragment.
#if JD_ALBEDO
    a0 *= alb;
#endif
    col += a0 * smoothstep(0.0, 0.25, dot(n, v));
#endif
#if !JD_WIDE_ONLY
#if !JD_FULL
    col *= u_shading.w;
#endif
    // Reinhard-style shoulder, then display gamma 2.0 (a sqrt is cheaper than
    // pow on every GPU jade targets): sqrt(c / (1 + 0.15 c)), written as
    // c / sqrt(c (1 + 0.15 c)), one inverse square root a channel where a
    // reciprocal and a square root were two (lima's one scalar unit for
    // them took 3 instruction words more). Below 2^-14 (fp16's least
    // normal) the root's argument is held there: the colours below linear
    // 6e-5 come out up to half a display step darker. Above 1 the RGBA8
    // target clamps, as GLES 2.0 has every fixed-point colour buffer do
    // (an explicit min cost VideoCore IV and Adreno 4 instructions).
    // Alpha: where the pass after the frame runs on every frame (a target
    // without samples: JD_LUMA_ALPHA, render_program.c), the colour's luma
    // for its edge test (antialias.frag), which then reads one channel a
    // neighbour where it took a dot product of three: 2 instructions here
    // against 7 there on the Vivante GC2000, which tests every pixel of the
    // object's box and shades a fifth to a half of them. Elsewhere whatever
    // is at hand, not 1, and masked off where this is drawn (pass_screen.c,
    // jdr_pass_main): lima took two words to write the 1, four the luma.
    vec3 enc = col * inversesqrt(max(col * (0.15 * col + 1.0), 6.1035e-5));
#ifdef JD_LUMA_ALPHA
    gl_FragColor = vec4(enc, dot(enc, JD_LUMA));
#else
    gl_FragColor = enc.xyzx;
#endif
#endif
#endif
}
