/* GL tests on the headless platform (llvmpipe in CI). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mesh_load.h"
#include "platform.h"
#include "renderer.h"
#include "gl_program.h"
#include "sh.h"

/* Linked with -Wl,--wrap=malloc,...: every heap call made from the core's
 * objects (statically linked here) lands in these counters; the GL driver's
 * own calls, from its shared library, do not. */
static unsigned long core_allocs;
void *__real_malloc(size_t);
void *__real_calloc(size_t, size_t);
void *__real_realloc(void *, size_t);
void __real_free(void *);
void *__wrap_malloc(size_t n) { core_allocs++; return __real_malloc(n); }
void *__wrap_calloc(size_t a, size_t b) { core_allocs++; return __real_calloc(a, b); }
void *__wrap_realloc(void *p, size_t n) { core_allocs++; return __real_realloc(p, n); }
void __wrap_free(void *p) { if (p) core_allocs++; __real_free(p); }

static unsigned char mem[48 << 20];

static jd_renderer *make(jd_arena *a, jd_mesh *m, const jd_gl_caps *caps, jd_platform *p, jd_precision prec, int size)
{
    jd_renderer_desc d = {0};
    d.mesh = m;
    d.caps = caps;
    d.target_fbo = jd_platform_framebuffer(p);
    d.width = d.height = size;
    d.precision = prec;
    jd_renderer *r = NULL;
    jd_error err = {0};
    jd_result res = jd_renderer_create(&d, a, &r, &err);
    CHECK(res == JD_OK, "renderer: %s", err.msg);
    return res ? NULL : r;
}

static void test_sh_reduction(jd_renderer *r, const char *label, double tol)
{
    static uint8_t atlas[256 * 3 * 256 * 2 * 4];
    uint8_t sh27[27 * 4];
    jd_scene s;
    jd_scene_defaults(&s, jd_material_find("marble"));
    s.mode = JD_MODE_SINGLE;
    double worst_rel = 0;
    for (int k = 0; k < 4; k++) {
        s.light_azimuth = 40.0f + 90.0f * k;
        s.light_elevation = 30.0f - 20.0f * k;
        jd_error err = {0};
        int n = 0;
        CHECK(jd_renderer_frame(r, &s, NULL, &err) == JD_OK, "frame: %s", err.msg);
        CHECK(jd_renderer_read_capture(r, atlas, sh27, &n, &err) == JD_OK, "readback: %s", err.msg);
        double ref[9][3];
        jd_sh_project_atlas(atlas, n, ref);
        jd_sh9 gpu;
        jd_renderer_info info;
        jd_renderer_get_info(r, &info);
        jd_sh_decode(sh27, info.highp, &gpu);
        double dc = fmax(fabs(ref[0][0]), fmax(fabs(ref[0][1]), fabs(ref[0][2])));
        CHECK(dc > 0.05, "the capture sees the lit object (DC %.4f)", dc);
        for (int i = 0; i < 9; i++)
            for (int c = 0; c < 3; c++) {
                double rel = fabs(gpu.c[i][c] - ref[i][c]) / dc;
                if (rel > worst_rel) worst_rel = rel;
            }
    }
    printf("SH reduction (%s packing): largest coefficient error %.4f%% of DC over 4 light directions (limit %.1f%%)\n",
           label, 100 * worst_rel, 100 * tol);
    CHECK(worst_rel <= tol, "%s SH error %.4f%% of DC", label, 100 * worst_rel);
}

int main(int argc, char **argv)
{
    const char *mesh_path = argc > 1 ? argv[1] : "assets/default.drc";
    /* test_gl MESH --mediump-fp16: only the mediump SH packing, and only
     * where mediump really runs at 16 bits (a canary says); else skipped. */
    int fp16_only = argc > 2 && !strcmp(argv[2], "--mediump-fp16");
    if (argc > 2 && !fp16_only) jd_program_dump_to(argv[2]); /* for tests/glsl_validate.sh */
    jd_arena a;
    jd_arena_init(&a, mem, sizeof mem);
    jd_error err = {0};
    jd_mesh mesh;
    jd_load_desc ld = {.path = mesh_path, .allow_32bit_indices = 1};
    if (jd_mesh_load_draco(&ld, &a, &mesh, NULL, &err)) {
        printf("cannot load %s: %s\n", mesh_path, err.msg);
        return 1;
    }
    jd_platform *p = NULL;
    jd_platform_desc pd = {.kind = "headless", .width = 64, .height = 64};
    if (jd_platform_open(&pd, &p, &err)) {
        printf("no GL: %s\n", err.msg);
        return 1;
    }
    jd_gl_caps caps;
    jd_gl_caps_query(&caps, &err);
    printf("GL: %s | %s | %s\n", caps.renderer, caps.version, jd_platform_describe(p));
    {
        /* No display engine to enlarge a headless picture: the size stays. */
        int w = 0, h = 0;
        CHECK(!jd_platform_scale_out(p, 32, 32), "headless: no display engine's scaler");
        jd_platform_display_size(p, &w, &h);
        CHECK(w == 64 && h == 64, "headless: the display's size is the drawable's (%dx%d)", w, h);
        jd_platform_size(p, &w, &h);
        CHECK(w == 64 && h == 64, "headless: the drawable unchanged (%dx%d)", w, h);
    }

    size_t mark = jd_arena_mark(&a);
    if (fp16_only) {
        int fp16 = jd_gl_mediump_is_fp16();
        if (fp16 != 1) {
            printf("skipped: mediump runs at %s on this driver (canary shader), so an fp16 claim cannot be tested "
                   "here; llvmpipe lowers mediump to 16 bits only on CPUs with F16C\n",
                   fp16 == 0 ? "32 bits" : "an unknown precision");
            jd_platform_close(p);
            return 77;
        }
        printf("mediump runs at 16 bits here (canary shader): the mediump packing is tested at fp16\n");
        jd_renderer *r = make(&a, &mesh, &caps, p, JD_PRECISION_MEDIUMP, 64);
        if (r) {
            test_sh_reduction(r, "mediump, run at fp16,", 0.03);
            jd_renderer_destroy(r);
        }
        jd_platform_close(p);
        return jd_check_summary("gl mediump fp16");
    }
    {
        /* A create that fails leaves the arena as it found it, and the
         * defaults a zeroed descriptor gets are the documented ones. */
        jd_renderer_desc d;
        memset(&d, 0, sizeof d);
        jd_renderer_desc_defaults(&d);
        CHECK(d.width == 512 && d.height == 512 && d.cube_size == 64 && d.light_map_size == 256 &&
                  d.proxy_cells == 40 && d.capture_cells == 24 && d.spread_divisor == 8 && d.diffusion_size == 64,
              "documented defaults");
        d.mesh = &mesh;
        d.caps = &caps;
        d.target_fbo = jd_platform_framebuffer(p);
        size_t bottom = jd_arena_mark(&a), top = jd_arena_top_mark(&a);
        jd_renderer *bad = NULL;
        d.cube_size = 12; /* not a multiple of 8: refused after the renderer's memory was taken */
        CHECK(jd_renderer_create(&d, &a, &bad, &err) == JD_ERR_ARG, "cube size 12 refused: %s", err.msg);
        d.cube_size = 64;
        d.light_map_size = 4096; /* refused later still */
        CHECK(jd_renderer_create(&d, &a, &bad, &err) == JD_ERR_ARG, "light map 4096 refused: %s", err.msg);
        CHECK(jd_arena_mark(&a) == bottom && jd_arena_top_mark(&a) == top, "a failed create gives the arena back");
        /* Refused last of all, at the size's own targets (jd_renderer_resize). */
        jd_gl_caps tiny = caps;
        tiny.max_texture_size = 256;
        d.caps = &tiny;
        d.light_map_size = 256;
        d.antialias = JD_AA_POST; /* the frame goes through its own target, 512x512 */
        CHECK(jd_renderer_create(&d, &a, &bad, &err) == JD_ERR_UNSUPPORTED && strstr(err.msg, "exceeds the max texture size"),
              "a frame target past the GPU's texture size refused: %s", err.msg);
        CHECK(jd_arena_mark(&a) == bottom && jd_arena_top_mark(&a) == top, "that failed create gives the arena back too");
    }
    jd_renderer *r = make(&a, &mesh, &caps, p, JD_PRECISION_AUTO, 64);
    if (r) {
        /* 100 frames per mode, light orbiting: the core must not allocate. */
        jd_scene s;
        jd_scene_defaults(&s, NULL);
        core_allocs = 0;
        for (int m = 0; m < JD_MODE_COUNT; m++)
            for (int i = 0; i < 100; i++) {
                s.mode = (jd_mode)m;
                s.light_azimuth = 3.6f * i;
                if (jd_renderer_frame(r, &s, NULL, &err)) { CHECK(0, "frame: %s", err.msg); break; }
            }
        printf("core heap calls during %d frames (100 per mode): %lu\n", 100 * JD_MODE_COUNT, core_allocs);
        CHECK(core_allocs == 0, "the frame loop allocates nothing (%lu calls)", core_allocs);
        jd_renderer_info info;
        jd_renderer_get_info(r, &info);
        printf("render targets: %zu bytes at 64x64\n", info.target_bytes);
        if (caps.frag_highp_precision >= 23) test_sh_reduction(r, info.highp ? "highp" : "mediump", 0.01);
        jd_renderer_destroy(r);
    }
    jd_arena_reset(&a, mark);
    /* A still scene reuses the light-space passes (and, with the camera
     * still, the spread): the picture must be the one a full frame gives,
     * with no read-back and fewer target switches. */
    jd_arena_reset(&a, mark);
    r = make(&a, &mesh, &caps, p, JD_PRECISION_AUTO, 64);
    if (r) {
        static uint8_t fresh[64 * 64 * 4], reused[64 * 64 * 4];
        for (int m = 0; m < JD_MODE_COUNT; m++) {
            jd_scene s;
            jd_scene_defaults(&s, NULL);
            s.mode = (jd_mode)m;
            jd_frame_stats st1, st2;
            s.light_azimuth = 40;
            jd_renderer_frame(r, &s, NULL, &err);
            s.light_azimuth = 100; /* a frame that must recompute */
            int ok = jd_renderer_frame(r, &s, &st1, &err) == JD_OK && jd_platform_read_rgba(p, fresh, &err) == JD_OK &&
                     jd_renderer_frame(r, &s, &st2, &err) == JD_OK && jd_platform_read_rgba(p, reused, &err) == JD_OK;
            CHECK(ok && !memcmp(fresh, reused, sizeof fresh) && st1.reused == 0 && st2.reused == 2,
                  "%s: a still frame reuses its passes (reused %d -> %d) and gives the same picture", jd_mode_name(s.mode),
                  st1.reused, st2.reused);
            CHECK((st2.readbacks == 0 && st2.target_switches < st1.target_switches) || m == JD_MODE_NONE,
                  "%s: still: %d read-backs, %d target switches (moving: %d, %d)", jd_mode_name(s.mode), st2.readbacks,
                  st2.target_switches, st1.readbacks, st1.target_switches);
            printf("%s: moving light %d read-backs, %d target switches; still %d, %d\n", jd_mode_name(s.mode),
                   st1.readbacks, st1.target_switches, st2.readbacks, st2.target_switches);
        }
        jd_renderer_destroy(r);
    }
    /* The targets that follow the picture's size are sized for it at each
     * resize: a tier's 1080p drawn at 960x540 takes a 1024x1024 frame
     * target, and the same renderer made 960x540 (the display engine
     * enlarging) keeps one texel of it. Grown again, the picture is the one
     * a renderer made at that size draws. */
    jd_arena_reset(&a, mark);
    {
        jd_gl_caps board = caps;
        snprintf(board.tier, sizeof board.tier, "test board");
        board.max_vertex_texture_units = 0; /* full's levels' sum per fragment, in its own target */
        jd_renderer_desc d = {0};
        d.mesh = &mesh;
        d.caps = &board;
        d.target_fbo = jd_platform_framebuffer(p);
        d.width = 1920, d.height = 1080;
        d.antialias = JD_AA_OFF;
        jd_renderer *t = NULL;
        CHECK(jd_renderer_create(&d, &a, &t, &err) == JD_OK, "tier renderer: %s", err.msg);
        if (t) {
            jd_renderer_info i1, i2, i3;
            jd_renderer_get_info(t, &i1);
            CHECK(jd_renderer_resize(t, 960, 540, &err) == JD_OK, "resize to 960x540: %s", err.msg);
            jd_renderer_get_info(t, &i2);
            CHECK(jd_renderer_resize(t, 1920, 1080, &err) == JD_OK, "resize to 1920x1080: %s", err.msg);
            jd_renderer_get_info(t, &i3);
            /* The frame target 1024x1024 with depth -> one texel; full's
             * levels' sum (480x270 -> 512x512) the same at both sizes. */
            size_t frame_target = (size_t)1024 * 1024 * 6 - 6;
            printf("render targets, a tier's 1920x1080 drawn at 960x540: %zu bytes; at 960x540 unscaled: %zu; "
                   "1920x1080 again: %zu\n", i1.target_bytes, i2.target_bytes, i3.target_bytes);
            CHECK(i1.target_bytes - i2.target_bytes == frame_target && i3.target_bytes == i1.target_bytes,
                  "the frame target follows the size (%zu -> %zu -> %zu bytes)", i1.target_bytes, i2.target_bytes,
                  i3.target_bytes);
            jd_renderer_destroy(t);
        }
        jd_arena_reset(&a, mark);
        static uint8_t grown[64 * 64 * 4], made[64 * 64 * 4];
        jd_scene s;
        jd_scene_defaults(&s, NULL);
        d.width = d.height = 32;
        d.max_width = d.max_height = 64;
        d.render_scale = 0.5f; /* drawn at half, enlarged: through the frame target */
        d.antialias = JD_AA_AUTO;
        t = NULL;
        CHECK(jd_renderer_create(&d, &a, &t, &err) == JD_OK && jd_renderer_frame(t, &s, NULL, &err) == JD_OK &&
                  jd_renderer_resize(t, 64, 64, &err) == JD_OK && jd_renderer_frame(t, &s, NULL, &err) == JD_OK &&
                  jd_platform_read_rgba(p, grown, &err) == JD_OK,
              "32x32 grown to 64x64: %s", err.msg);
        jd_renderer_destroy(t);
        jd_arena_reset(&a, mark);
        d.width = d.height = 64;
        t = NULL;
        CHECK(jd_renderer_create(&d, &a, &t, &err) == JD_OK && jd_renderer_frame(t, &s, NULL, &err) == JD_OK &&
                  jd_platform_read_rgba(p, made, &err) == JD_OK,
              "made at 64x64: %s", err.msg);
        jd_renderer_destroy(t);
        CHECK(!memcmp(grown, made, sizeof made), "a renderer grown to 64x64 draws what one made at 64x64 does");
    }
    /* Small register files (VideoCore IV, Mali-400) project 2x2 blocks and
     * reduce once more: the same coefficients. */
    jd_arena_reset(&a, mark);
    jd_gl_caps small = caps;
    small.small_register_file = 1;
    r = make(&a, &mesh, &small, p, JD_PRECISION_AUTO, 64);
    if (r) {
        test_sh_reduction(r, "2x2-block", 0.01);
        jd_renderer_destroy(r);
    }
    jd_arena_reset(&a, mark);
    /* The mediump packing's arithmetic at whatever precision this driver
     * runs mediump; ctest gl_mediump_fp16 checks it where that is 16 bits. */
    r = make(&a, &mesh, &caps, p, JD_PRECISION_MEDIUMP, 64);
    if (r) {
        test_sh_reduction(r, "mediump", 0.03);
        jd_renderer_destroy(r);
    }
    jd_platform_close(p);
    return jd_check_summary("gl");
}
