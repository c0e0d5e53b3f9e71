#version 100
// The visible surface: Lambert + Blinn-Phong, plus in translucent modes the
// transmitted layer A0 = K Ft (1-Fdr)/pi M(t) E(d), and in dual mode the two
// spread layers, blended per channel before tone mapping.
precision mediump float;
uniform vec3 u_light_dir;
uniform vec3 u_eye;
uniform vec3 u_albedo;
uniform vec3 u_light_color;
uniform vec4 u_shading;      // ambient, specular, shininess, exposure
varying vec3 v_pos;
varying vec3 v_normal;
#if JD_TRANSLUCENT
#if !JD_VERTEX_THICKNESS
uniform sampler2D u_depth;
uniform sampler2D u_tail;    // sqrt of the dipole tail M(t)/M-scale, t across [0, range]
varying vec3 v_light;
#endif
varying vec3 v_trans;
#endif
#if JD_SPREAD
uniform sampler2D u_spread;  // sqrt((w1 A1 + w2 A2) / 2), alpha = covered
uniform vec2 u_inv_viewport;
uniform vec3 u_w0;
#endif

#if JD_TRANSLUCENT
// A0: the per-vertex part times the dipole tail of the thickness, which comes
// from a lookup table (two exp and two sqrt per channel, per fragment, cost
// more than the rest of the shader on small GPUs).
vec3 translucency()
{
#if JD_VERTEX_THICKNESS
    return v_trans;
#else
    float shadow = jd_unpack(texture2D(u_depth, v_light.xy));
    float t = clamp(v_light.z - shadow, 0.0, 1.0);
    vec3 m = texture2D(u_tail, vec2(t, 0.5)).rgb;
    return 2.0 * m * m * v_trans;
#endif
}
#endif

void main()
{
    vec3 n = normalize(v_normal);
    vec3 v = normalize(u_eye - v_pos);
    if (dot(n, v) < 0.0) n = -n;
#if JD_A0_ONLY
    // The spread funnel's input: A0 premultiplied by coverage (alpha 1), at
    // half range so values up to 2 survive RGBA8.
    gl_FragColor = vec4(0.5 * translucency(), 1.0);
#else
    float ndl = max(dot(n, u_light_dir), 0.0);
    vec3 h = normalize(u_light_dir + v);
    float spec = ndl > 0.0 ? pow(max(dot(n, h), 0.0), u_shading.z) : 0.0;
    vec3 col = u_albedo * (u_shading.x + ndl * u_light_color) + u_shading.y * spec * u_light_color;
#if JD_TRANSLUCENT
    vec3 a0 = translucency();
#if JD_SPREAD
    vec4 sp = texture2D(u_spread, gl_FragCoord.xy * u_inv_viewport);
    // Where the low-resolution layers did not reach (a silhouette pixel the
    // proxy missed), A0 stands in for them.
    vec3 spread = sp.a > 0.5 ? 2.0 * sp.rgb * sp.rgb : (1.0 - u_w0) * a0;
    col += u_w0 * a0 + spread;
#else
    col += a0;
#endif
#endif
    col *= u_shading.w;
    // Reinhard-style shoulder, then display gamma 2.0 (a sqrt is cheaper than
    // pow on every GPU jade targets).
    col = col / (1.0 + 0.15 * col);
    gl_FragColor = vec4(sqrt(clamp(col, 0.0, 1.0)), 1.0);
#endif
}
