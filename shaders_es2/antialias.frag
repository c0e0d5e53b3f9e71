#version 100
// Anti-aliasing after the fact, where the target has no multisampling: the
// luma of the four diagonal neighbours says whether this pixel sits on an
// edge and which way it runs; the colour is then averaged along the edge
// (two or four taps, in linear light), and the wider average is kept only
// if its luma stays within the neighbourhood's range (else it crossed
// another edge).
// JD_AA_MARK: the same test alone, drawn first over the whole box: a flat
// pixel is copied and writes the depth buffer, an edge pixel is discarded,
// and the full pass then runs under the depth test on the edges only (a
// few percent of the box: pass_screen.c, smooth_box). The test is this
// file's in both, so that a pixel the mark copies is one the full pass
// would have left as it was.
uniform sampler2D u_src;    // the frame, display-encoded, bilinear
uniform vec2 u_texel;       // 1 / the source texture's size
varying vec2 v_uv;
varying vec4 v_diag0;       // the diagonal neighbours' coordinates (quad.vert, JD_DIAGONALS)
varying vec4 v_diag1;

float luma(vec3 c) { return dot(c, JD_LUMA); }

void main()
{
    vec4 mc = texture2D(u_src, v_uv);
    vec3 m = mc.rgb;
#ifdef JD_LUMA_ALPHA
    // The frame's alpha holds each pixel's luma (shade.frag; the clear's,
    // pass_screen.c): one channel a neighbour, the four side by side. On
    // the Vivante GC2000 the test alone 24 -> 17 instructions, on the
    // Adreno 306 72 -> 60.
    vec4 l4 = vec4(texture2D(u_src, v_diag0.xy).a, texture2D(u_src, v_diag0.zw).a,
                   texture2D(u_src, v_diag1.xy).a, texture2D(u_src, v_diag1.zw).a);
    float nw = l4.x, ne = l4.y, sw = l4.z, se = l4.w, lm = mc.a;
    vec2 lo2 = min(l4.xy, l4.zw), hi2 = max(l4.xy, l4.zw);
    float lo = min(lm, min(lo2.x, lo2.y));
    float hi = max(lm, max(hi2.x, hi2.y));
#else
    float nw = luma(texture2D(u_src, v_diag0.xy).rgb);
    float ne = luma(texture2D(u_src, v_diag0.zw).rgb);
    float sw = luma(texture2D(u_src, v_diag1.xy).rgb);
    float se = luma(texture2D(u_src, v_diag1.zw).rgb);
    float lm = luma(m);
    float lo = min(lm, min(min(nw, ne), min(sw, se)));
    float hi = max(lm, max(max(nw, ne), max(sw, se)));
#endif
    // Flat regions (most of the picture) stay exactly as they are.
#ifdef JD_AA_MARK
    if (!(hi - lo < 0.05)) discard;
    gl_FragColor = vec4(m, 1.0);
#else
    if (hi - lo < 0.05) {
        gl_FragColor = vec4(m, 1.0);
        return;
    }
    vec2 dir = vec2(-((nw + ne) - (sw + se)), (nw + sw) - (ne + se));
    float reduce = max((nw + ne + sw + se) * 0.03125, 1.0 / 128.0);
    float scale = 1.0 / (min(abs(dir.x), abs(dir.y)) + reduce);
    dir = clamp(dir * scale, vec2(-4.0), vec2(4.0)) * u_texel;
    vec4 c0 = texture2D(u_src, v_uv - dir * (1.0 / 6.0)), c1 = texture2D(u_src, v_uv + dir * (1.0 / 6.0));
    vec4 c2 = texture2D(u_src, v_uv - dir * 0.5), c3 = texture2D(u_src, v_uv + dir * 0.5);
    vec3 t0 = c0.rgb, t1 = c1.rgb, t2 = c2.rgb, t3 = c3.rgb;
    // Which average to keep is decided on the display-encoded colours, as
    // FXAA decides; the average itself is taken in linear light. The frame
    // is encoded about as a square root (shade.frag's sqrt(c / (1 + 0.15
    // c))), and a mean of encoded values is darker than the light's own
    // mean, which a pixel's box in linear light (Cycles', the reference's
    // --pixel-samples) takes: averaged encoded, a silhouette's inner pixels
    // came out 0.028 too dark in linear light against the same frame drawn
    // at 4 x 4 the size and box-filtered, 0.019 averaged in linear light
    // (the outer ones 0.0105 and 0.0086; the whole object's RMSE 0.0203 and
    // 0.0180; docs/quality.md, "Anti-aliasing in linear light"). A
    // multisampled RGBA8 target resolves its encoded samples, as this pass
    // did: the boards that multisample darken their silhouettes so. In fp16
    // the square of an encoded value under 2/255 falls below the least
    // normal: where a GPU flushes it, such a pixel comes out at most 2/255
    // darker.
#ifdef JD_LUMA_ALPHA
    float lb = 0.25 * (c0.a + c1.a) + 0.125 * (c2.a + c3.a); // filtered as the colour: its luma
#else
    float lb = luma(0.25 * (t0 + t1) + 0.125 * (t2 + t3));
#endif
    vec3 a = 0.5 * (t0 * t0 + t1 * t1);
    vec3 b = lb < lo || lb > hi ? a : 0.5 * a + 0.25 * (t2 * t2 + t3 * t3);
    gl_FragColor = vec4(sqrt(b), 1.0);
#endif
}
