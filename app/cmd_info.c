#include <stdio.h>
#include <string.h>

#include "board.h"
#include "commands.h"
#include "options.h"
#include "gl.h"
#include "gl_caps.h"
#include "gl_program.h"
#include "platform.h"
#include "frame_cost.h"
#include "profile.h"

/* info --compile: every program the renderer builds for this device (or
 * profile), one row each, the driver's messages in between on stderr. */
typedef struct compile_log {
    int count, failed;
    char label[160];
} compile_log;

static void on_program(void *user, const char *vs, const char *fs, const char *defines, int result, const char *msg)
{
    compile_log *l = user;
    if (result < 0) {
        jd_program_label(vs, fs, defines, l->label, sizeof l->label);
        fprintf(stderr, "jade: compiling program %d: %s\n", l->count, l->label);
        return;
    }
    printf("program %2d  %-58s %s%s\n", l->count, l->label, result ? "FAILED: " : "compiled and linked",
           result ? msg : "");
    if (result) l->failed++;
    l->count++;
}

/* One more renderer on the session's mesh, or on `m`, with full's levels
 * summed where `levels` says: its programs are built and observed. The
 * first renderer's target and its samples (session.c), so that the pass
 * after the frame, and the luma the picture's programs write for it or not,
 * are the board's here too. */
static int compile_variant(jd_session *s, const jd_options *o, const jd_mesh *m, jd_levels levels, const char *what)
{
    jd_error err = {0};
    jd_renderer_desc rd = o->rdesc;
    rd.mesh = m;
    rd.caps = &s->caps;
    rd.levels = levels;
    rd.width = o->width;
    rd.height = o->height;
    rd.max_width = o->width;
    rd.max_height = o->height;
    rd.target_fbo = jd_platform_framebuffer(s->platform);
    if (!rd.target_samples) rd.target_samples = jd_platform_samples(s->platform);
    rd.get_proc = jd_platform_gl_proc;
    jd_renderer *r = NULL;
    if (jd_renderer_create(&rd, &s->arena, &r, &err)) {
        fprintf(stderr, "jade info: %s: %s\n", what, err.msg);
        return 0;
    }
    jd_renderer_destroy(r);
    return 1;
}

/* The picture's programs for a model with its own colours (JD_ALBEDO,
 * JD_ALBEDO_MAP, JD_ALBEDO_PARTIAL): more renderers on the same mesh given
 * a colour per vertex and a 4 x 4 texture, full's levels where `levels`
 * says. Its other programs are the first renderer's over again; the
 * compiler table keeps the first of each name. */
static int compile_colour_variants(jd_session *s, const jd_options *o, jd_levels levels)
{
    jd_error err = {0};
    jd_mesh m = s->mesh;
    size_t nv = m.num_vertices;
    m.colors = jd_arena_alloc(&s->arena, 4 * nv, 16, "colour variants: colours", &err);
    if (!m.uvs) m.uvs = jd_arena_alloc(&s->arena, sizeof(float) * 2 * nv, 16, "colour variants: uvs", &err);
    m.texels = jd_arena_alloc(&s->arena, 4 * 4 * 4, 16, "colour variants: texture", &err);
    if (!m.colors || !m.uvs || !m.texels) {
        fprintf(stderr, "jade info: %s\n", err.msg);
        return 0;
    }
    for (size_t i = 0; i < nv; i++) memcpy(m.colors + 4 * i, (const uint8_t[4]){200, 200, 200, 255}, 4);
    if (!s->mesh.uvs) memset(m.uvs, 0, sizeof(float) * 2 * nv);
    memset(m.texels, 200, 4 * 4 * 4);
    m.texture_w = m.texture_h = 4;
    jd_mesh_albedo_prepare(&m);
    /* Twice: every vertex textured, then one not (a model whose materials
     * are partly untextured). */
    for (int partial = 0; partial < 2; partial++) {
        m.colors[3] = partial ? 0 : 255;
        if (!compile_variant(s, o, &m, levels, "the colour variants")) return 0;
    }
    return 1;
}

static int compile_all(jd_options *o)
{
    compile_log l = {0};
    jd_program_observe(on_program, &l);
    if (o->unroll_loops > 0) {
        char def[40];
        snprintf(def, sizeof def, "#define JD_UNROLL %d\n", o->unroll_loops);
        jd_program_extra_defines(def);
    }
    o->platform = "headless";
    o->width = o->height = 64;
    /* Nothing drawn: the drm-shim drivers never signal a fence, and a
     * failed program is reported here, not fallen back from. */
    o->rdesc.program_probe = JD_PROBE_OFF;
    /* A picture drawn smaller: its enlarging pass is built too. */
    o->rdesc.render_scale = 0.5f;
    /* Its display's samples as the profile's boards give them (bench
     * --device, core/board.h), so that the programs are the board's: where
     * a board multisamples its display but draws no texture with those
     * samples (VideoCore IV), the pass after the frame smooths only the
     * picture drawn smaller, and the picture's programs write no luma for
     * it (renderer.c, luma_alpha), which they do where the display has no
     * samples (Vivante, Adreno 3xx: the shims' targets have none either).
     * The pass itself is built either way (a picture drawn smaller). */
    for (int i = 0; o->profile && i < jd_board_count; i++)
        if (!strcmp(jd_boards[i].profile, o->profile) && jd_boards[i].multisampled && !jd_boards[i].texture_samples)
            o->rdesc.target_samples = 4;
    jd_session s;
    /* The session passes the driver's messages on (the compiler's among
     * them) as they come, between this program's two lines. */
    int ok = jd_session_open(&s, o, "info");
    if (ok && !s.mesh.colors) ok = compile_colour_variants(&s, o, o->rdesc.levels);
    /* Where the vertex stage can sum full's levels, the path this mesh did
     * not take too: the renderer takes the other on meshes of another size
     * (gl_caps.h, levels_per_fragment_from) or with a colour texture, and
     * --levels asks for either, so that the table prices both. */
    if (ok && s.caps.max_vertex_texture_units >= JD_DIFFUSION_VERTEX_UNITS && o->rdesc.levels == JD_LEVELS_AUTO &&
        !o->rdesc.fragment_thickness) {
        jd_renderer_info info;
        jd_renderer_get_info(s.renderer, &info);
        jd_levels other = info.vertex_levels ? JD_LEVELS_FRAGMENT : JD_LEVELS_VERTEX;
        ok = compile_variant(&s, o, &s.mesh, other, "full's levels the other way") &&
             (s.mesh.colors || compile_colour_variants(&s, o, other));
    }
    jd_program_observe(NULL, NULL);
    jd_program_extra_defines(NULL);
    if (ok) printf("jade info --compile: %d programs built for %s (%s), none failed\n", l.count, s.caps.renderer,
                   o->profile ? o->profile : "no profile");
    /* The picture's targets were made too: whether the driver took samples
     * in the one the picture is drawn into before it is enlarged. */
    if (ok) printf("%s\n", jd_antialias_describe(s.renderer));
    jd_session_close(&s);
    return ok && !l.failed ? 0 : 1;
}

/* A program limit beside what jade's largest programs need there, from
 * the compiler table built into jade (tests/device-shaders.expected). */
static void print_program_limit(const jd_gl_caps *c)
{
    char drv[32];
    snprintf(drv, sizeof drv, "etnaviv-gc%d", c->vivante ? c->vivante : 2000);
    int most = jd_frame_cost_largest_program(NULL, drv);
    printf("program limit      %d instructions per stage (no instruction cache); ", c->max_program_instructions);
    if (most) printf("jade's largest on %s: %d\n", drv, most);
    else printf("%s is not in jade's compiler table\n", drv);
}

int jd_cmd_info(int argc, char **argv)
{
    jd_options o;
    jd_options_defaults(&o);
    char summary[1024];
    int at = snprintf(summary, sizeof summary,
                      "Prints the GL device's limits and the extensions jade can use;\n"
                      "with --profile, the limits jade enforces when emulating that device:");
    for (int k = 0; k < jd_profile_count && at < (int)sizeof summary; k++)
        at += snprintf(summary + at, sizeof summary - (size_t)at, "\n  %-9s %s", jd_profiles[k].name,
                       jd_profiles[k].summary);
    int rc = jd_options_command(&o, JD_OPT_INFO, "info", summary, argc, argv);
    if (rc >= 0) return rc;
    if (o.compile_only) return compile_all(&o);
    if (o.list_boards) {
        /* The frame-cost model's boards (core/board.c): what bench --device
         * takes, and where each constant comes from. */
        printf("%-12s %-8s %-14s %6s  %s\n", "board", "profile", "compiler", "MHz", "what");
        for (int b = 0; b < jd_board_count; b++) {
            const jd_board *d = &jd_boards[b];
            printf("%-12s %-8s %-14s %6.0f  %s\n", d->name, d->profile, d->compiler, d->clock_mhz, d->summary);
            printf("%-12s fill %.0f Mpix/s, fragment cost units %.0f per clock x %.0f lanes, vertex %.0f x %.0f, %s;"
                   " %.1f GB/s\n", "", d->fill_rate * d->clock_mhz, d->fragment_rate, d->fragment_lanes, d->vertex_rate,
                   d->vertex_lanes, d->units == JD_UNITS_SHARED ? "vertices and fragments share the cores"
                                                                : "the vertex processor beside the pixel processors",
                   d->dram_gbs);
            printf("%-12s sources: %s\n", "", d->sources);
        }
        return 0;
    }
    if (o.list_materials) {
        printf("%-10s %-22s %-25s %-4s %s\n", "material", "sigma_s' (mm^-1, RGB)", "sigma_a (mm^-1, RGB)", "eta",
               "source");
        for (int m = 0; m < jd_material_count; m++) {
            const jd_material *t = &jd_materials[m];
            char s1[40], s2[40];
            snprintf(s1, sizeof s1, "%g %g %g", t->sigma_s[0], t->sigma_s[1], t->sigma_s[2]);
            snprintf(s2, sizeof s2, "%g %g %g", t->sigma_a[0], t->sigma_a[1], t->sigma_a[2]);
            printf("%-10s %-22s %-25s %-4g %s\n", t->name, s1, s2, t->eta, t->source);
        }
        return 0;
    }
    const jd_profile *prof = o.profile ? jd_profile_find(o.profile) : NULL;
    jd_error err = {0};
    jd_platform *p = NULL;
    jd_platform_desc pd = {.kind = "headless", .width = 64, .height = 64};
    if (jd_platform_open(&pd, &p, &err)) {
        fprintf(stderr, "jade info: %s\n", err.msg);
        return 1;
    }
    jd_gl_caps c;
    if (jd_gl_caps_query(&c, &err)) {
        fprintf(stderr, "jade info: %s\n", err.msg);
        jd_platform_close(p);
        return 1;
    }
    if (prof) {
        jd_profile_apply(prof, &c);
        printf("profile            %s: %s\n                   (%s)\n", prof->name, prof->summary, prof->source);
        printf("                   the limits below are the device's, lowered to the profile's\n");
    }
    printf("platform           %s\n", jd_platform_describe(p));
    printf("GL_VENDOR          %s\nGL_RENDERER        %s\nGL_VERSION         %s\nGLSL               %s\n", c.vendor,
           c.renderer, c.version, c.glsl);
    printf("max texture size   %d\nmax renderbuffer   %d\nmax cube map       %d\nmax viewport       %dx%d\n",
           c.max_texture_size, c.max_renderbuffer_size, c.max_cube_map_size, c.max_viewport_w, c.max_viewport_h);
    printf("vertex attribs     %d\nvertex uniforms    %d vec4\nfragment uniforms  %d vec4\nvaryings           %d vec4\n",
           c.max_vertex_attribs, c.max_vertex_uniform_vectors, c.max_fragment_uniform_vectors, c.max_varying_vectors);
    printf("texture units      %d (vertex: %d)\n", c.max_texture_units, c.max_vertex_texture_units);
    {
        /* What the renderer does to a model's colour texture here
         * (jdr_upload_albedo): halved to the device's largest and to what
         * a mediump texture coordinate addresses. */
        int side = c.max_texture_size < JD_TEXTURE_MEDIUMP_SIDE ? c.max_texture_size : JD_TEXTURE_MEDIUMP_SIDE;
        printf("colour textures    up to %dx%d, %zu bytes with mipmaps (texture coordinates are mediump: 11 bits)\n",
               side, side, (size_t)side * side * 16 / 3);
    }
    printf("fragment highp     %s (precision %d bits, range 2^%d)\n", c.frag_highp_precision >= 23 ? "yes" : "no",
           c.frag_highp_precision, c.frag_highp_range);
    printf("fragment mediump   precision %d bits, range 2^%d\n", c.frag_mediump_precision, c.frag_mediump_range);
    unsigned char px[4];
    int fp16 = jd_gl_mediump_canary(px);
    if (fp16 < 0)
        printf("mediump arithmetic unknown (the canary shader read back red %d, alpha %d: a driver that draws "
               "nothing)\n", px[0], px[3]);
    else
        printf("mediump arithmetic %s (a canary shader says so, red %d%s)\n", fp16 == 1 ? "16 bits" : "32 bits", px[0],
               fp16 == 1 ? "" : ": fp16 is not exercised here; llvmpipe lowers mediump only on CPUs with F16C");
    if (c.utgard) printf("                   Mali-400/450 (Utgard) recognised by %s: fp16 fragments, mediump packing\n",
                         c.profile[0] ? "profile" : "name");
    if (c.vivante) printf("                   Vivante GC%d recognised by name\n", c.vivante);
    if (c.adreno) printf("                   Adreno %d recognised by name (Mesa's FD307 is the Adreno 306)\n", c.adreno);
    if (c.max_program_instructions) print_program_limit(&c);
    printf("SH packing         %s\n", c.frag_highp_precision >= 23 ? "highp (3 bytes)" : "mediump (2 x 2 bytes)");
    printf("thickness read     %s\n", c.max_vertex_texture_units >= 2 ? "per vertex" : "per fragment (no vertex texture units)");
    {
        /* The renderer's choice (gl_caps.h) for the smallest mesh, without
         * and with a colour texture, and the vertex count it changes at. */
        int plain = jd_gl_caps_levels_per_vertex(&c, 0, 0), coloured = jd_gl_caps_levels_per_vertex(&c, 0, 1);
        if (!plain)
            printf("full's diffusion   per fragment, at half resolution (%s)\n",
                   c.max_vertex_texture_units < JD_DIFFUSION_VERTEX_UNITS ? "under 6 vertex texture units"
                                                                          : "too few texture units");
        else if (c.levels_per_fragment_from > 0)
            printf("full's diffusion   per vertex on meshes under %d vertices, per fragment at half resolution on "
                   "larger ones (cheaper there on this GPU)\n", c.levels_per_fragment_from);
        else
            printf("full's diffusion   per vertex\n");
        if (plain && !coloured)
            printf("                   per fragment with a colour texture (%d texture units: per vertex, none left for "
                   "the light through thin parts)\n", c.max_texture_units);
    }
    /* The target jade draws into here: EXT_multisampled_render_to_texture
     * makes the headless one multisampled where the driver has it. */
    int samples = jd_platform_samples(p);
    if (prof)
        printf("anti-aliasing      %s\n", prof->antialias);
    else if (samples > 1)
        printf("anti-aliasing      %dx multisampling in this headless target (EXT_multisampled_render_to_texture)\n",
               samples);
    else
        printf("anti-aliasing      the pass after the frame (this headless target has no multisampling; windows and "
               "KMS take a 4x config where there is one)\n");
    printf("extensions (%d), those jade can use:\n", c.num_extensions);
    printf("  OES_element_index_uint      %s (meshes over 65,536 vertices)\n", c.ext_element_index_uint ? "yes" : "no");
    printf("  EXT_disjoint_timer_query    %s (GPU pass timings in bench)\n", c.ext_disjoint_timer_query ? "yes" : "no");
    printf("  OES_texture_npot            %s (not needed: jade clamps NPOT)\n", c.ext_texture_npot ? "yes" : "no");
    printf("  OES_depth_texture           %s (not needed: depth packed in RGBA8)\n", c.ext_depth_texture ? "yes" : "no");
    printf("  OES_texture_float           %s (not needed: SH packed in RGBA8)\n", c.ext_texture_float ? "yes" : "no");
    if (c.ext_multisampled_render_to_texture)
        printf("  EXT_multisampled_render_to_texture yes, %d samples (a picture drawn smaller is multisampled before it "
               "is enlarged)\n", c.max_samples);
    else
        printf("  EXT_multisampled_render_to_texture no (where the target is multisampled, a picture drawn smaller "
               "is smoothed by the pass after the frame at its own size, then enlarged)\n");
    jd_platform_close(p);
    return 0;
}
