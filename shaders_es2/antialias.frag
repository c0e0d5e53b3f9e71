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

float luma(vec3 c) { return dot(c, vec3(0.299, 0.587, 0.114)); }

void main()
{
    vec3 m = texture2D(u_src, v_uv).rgb;
    float nw = luma(texture2D(u_src, v_diag0.xy).rgb);
    float ne = luma(texture2D(u_src, v_diag0.zw).rgb);
    float sw = luma(texture2D(u_src, v_diag1.xy).rgb);
    float se = luma(texture2D(u_src, v_diag1.zw).rgb);
    float lm = luma(m);
    float lo = min(lm, min(min(nw, ne), min(sw, se)));
    float hi = max(lm, max(max(nw, ne), max(sw, se)));
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
    vec3 t0 = texture2D(u_src, v_uv - dir * (1.0 / 6.0)).rgb, t1 = texture2D(u_src, v_uv + dir * (1.0 / 6.0)).rgb;
    vec3 t2 = texture2D(u_src, v_uv - dir * 0.5).rgb, t3 = texture2D(u_src, v_uv + dir * 0.5).rgb;
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
    float lb = luma(0.25 * (t0 + t1) + 0.125 * (t2 + t3));
    vec3 a = 0.5 * (t0 * t0 + t1 * t1);
    vec3 b = lb < lo || lb > hi ? a : 0.5 * a + 0.25 * (t2 * t2 + t3 * t3);
    gl_FragColor = vec4(sqrt(b), 1.0);
#endif
}
