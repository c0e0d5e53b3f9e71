/* A picture drawn smaller into a multisampled target: where the GPU has
 * EXT_multisampled_render_to_texture the renderer draws it with the target's
 * samples (at most the extension's) before it is enlarged; where the GPU
 * has no such extension, or the driver refuses the samples (it says why),
 * it is drawn with one and the pass after the frame smooths it at its own
 * size, on the edges its test marks in the frame's depth, before it is
 * enlarged: fewer hard steps at the outline than with anti-aliasing off.
 *
 * llvmpipe has no such extension, so its two entry points are stood in for
 * here: one that takes the samples (attaching as with one sample: llvmpipe
 * then draws what it would), one that leaves the framebuffer incomplete as
 * a refusing driver does. What this holds is jade's side: when it asks, with
 * what count and size, the fallback, the bytes counted and the picture. A
 * driver that has the extension (an NVIDIA GPU's) is tried with its own:
 * fewer hard steps at the outline. Lima's framebuffer made complete with the
 * samples is the device compilers' check's (tools/device-shaders.sh); what
 * lima draws with them, a board's.
 *
 * The target is an ES 3 multisampled framebuffer (llvmpipe's contexts are ES
 * 3.2); a context without ES 3 skips (77). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "gl_fixture.h"
#include "gl.h"
#include "mesh_load.h"
#include "platform.h"
#include "renderer.h"

enum { W = 256, H = 256 };
static unsigned char mem[32 << 20];
static uint8_t pic[W * H * 4], ref[W * H * 4];

typedef void (*storage_ms_fn)(GLenum, GLsizei, GLenum, GLsizei, GLsizei);
typedef void (*blit_fn)(GLint, GLint, GLint, GLint, GLint, GLint, GLint, GLint, GLbitfield, GLenum);
static storage_ms_fn es3_storage_ms;
static blit_fn es3_blit;

/* What the stand-ins were asked: calls, the last count and size. */
static int refuse, tex_calls, tex_samples, rb_calls, rb_samples, rb_w, rb_h;

static void GL_APIENTRY fake_texture_ms(GLenum target, GLenum attachment, GLenum textarget, GLuint texture,
                                        GLint level, GLsizei samples)
{
    tex_calls++;
    tex_samples = samples;
    /* Refused: the framebuffer left incomplete, as by a driver that cannot
     * draw the format with samples (here: the texture's level 1, which it
     * does not have: GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT). */
    glFramebufferTexture2D(target, attachment, textarget, texture, refuse ? 1 : level);
}

static void GL_APIENTRY fake_storage_ms(GLenum target, GLsizei samples, GLenum format, GLsizei w, GLsizei h)
{
    rb_calls++;
    rb_samples = samples;
    rb_w = w;
    rb_h = h;
    glRenderbufferStorage(target, format, w, h);
}

static void *get_proc(const char *name)
{
    if (!strcmp(name, "glFramebufferTexture2DMultisampleEXT")) return (void *)fake_texture_ms;
    if (!strcmp(name, "glRenderbufferStorageMultisampleEXT")) return (void *)fake_storage_ms;
    return jd_platform_gl_proc(name);
}

/* A 4x multisampled W x H target: colour and depth renderbuffers. */
static GLuint make_ms_target(void)
{
    GLuint fbo, rb[2];
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(2, rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb[0]);
    es3_storage_ms(GL_RENDERBUFFER, 4, GL_RGBA8_OES, W, H);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
    glBindRenderbuffer(GL_RENDERBUFFER, rb[1]);
    es3_storage_ms(GL_RENDERBUFFER, 4, GL_DEPTH_COMPONENT16, W, H);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
    return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE ? fbo : 0;
}

/* The multisampled target resolved into `resolve` (one sample) and read. */
static void read_resolved(GLuint ms, GLuint resolve, uint8_t *dst)
{
    /* The blit is scissored too: the renderer leaves the test on, with the
     * object's box, and the background outside it would not be copied. */
    glDisable(GL_SCISSOR_TEST);
    glBindFramebuffer(0x8CA8 /* GL_READ_FRAMEBUFFER */, ms);
    glBindFramebuffer(0x8CA9 /* GL_DRAW_FRAMEBUFFER */, resolve);
    es3_blit(0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, resolve);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, dst);
}

static int differing(const uint8_t *a, const uint8_t *b)
{
    int n = 0;
    for (int i = 0; i < W * H * 4; i++) n += a[i] != b[i];
    return n;
}

/* Hard steps at the outline: neighbours (right, below), one of them the
 * background (the corner pixel's colour), whose luma differs by 32 or more
 * (test_antialias's measure of a staircase at half its threshold: the
 * enlarging's bilinear filter spreads each step over two pixels). */
static int is_bg(const uint8_t *p, const uint8_t *bg) { return !memcmp(p, bg, 3); }
static int hard_steps(const uint8_t *p)
{
    int n = 0;
    for (int y = 0; y < H - 1; y++)
        for (int x = 0; x < W - 1; x++) {
            int i = y * W + x, c = jd_test_luma(p + 4 * i);
            for (int k = 0; k < 2; k++) {
                int o = k ? i + W : i + 1;
                n += is_bg(p + 4 * i, p) != is_bg(p + 4 * o, p) && abs(c - jd_test_luma(p + 4 * o)) >= 32;
            }
        }
    return n;
}

/* Pixels 25 luma levels darker than all eight neighbours. */
static int specks(const uint8_t *p)
{
    int n = 0;
    for (int y = 1; y < H - 1; y++)
        for (int x = 1; x < W - 1; x++) {
            int c = jd_test_luma(p + 4 * (y * W + x)), darker = 1;
            for (int dy = -1; dy <= 1 && darker; dy++)
                for (int dx = -1; dx <= 1; dx++)
                    if ((dx || dy) && jd_test_luma(p + 4 * ((y + dy) * W + x + dx)) < c + 25) darker = 0;
            n += darker;
        }
    return n;
}

/* The default scene drawn by a renderer of `d` (the arena back at `mark`),
 * resolved into `resolve` and read into dst; its info. 0 on a failure. */
static int drawn(jd_arena *a, size_t mark, const jd_renderer_desc *d, const char *what, GLuint resolve, uint8_t *dst,
                 jd_renderer_info *info)
{
    jd_error err = {0};
    jd_arena_reset(a, mark);
    jd_renderer *r = NULL;
    jd_scene s;
    jd_scene_defaults(&s, NULL);
    CHECK(jd_renderer_create(d, a, &r, &err) == JD_OK, "%s: %s", what, err.msg);
    if (!r) return 0;
    jd_renderer_get_info(r, info);
    int ok = jd_renderer_frame(r, &s, NULL, &err) == JD_OK;
    CHECK(ok, "%s: %s", what, err.msg);
    if (ok) read_resolved(d->target_fbo, resolve, dst);
    jd_renderer_destroy(r);
    return ok;
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "assets/default.drc";
    jd_error err = {0};
    jd_platform *P;
    jd_platform_desc pd = {.kind = "headless", .width = W, .height = H, .single_sample = 1};
    if (jd_platform_open(&pd, &P, &err)) { printf("%s\n", err.msg); return 1; }
    const char *version = (const char *)glGetString(GL_VERSION);
    es3_storage_ms = (storage_ms_fn)jd_platform_gl_proc("glRenderbufferStorageMultisample");
    es3_blit = (blit_fn)jd_platform_gl_proc("glBlitFramebuffer");
    GLuint ms = 0;
    if (version && strncmp(version, "OpenGL ES 2", 11) && es3_storage_ms && es3_blit) ms = make_ms_target();
    if (!ms) {
        printf("skip: no ES 3 multisampled framebuffer here (%s)\n", version ? version : "no version");
        jd_platform_close(P);
        return 77;
    }
    GLint target_samples = 0;
    glGetIntegerv(GL_SAMPLES, &target_samples);
    CHECK(target_samples == 4, "the target has 4 samples (%d)", target_samples);
    jd_gl_caps caps;
    jd_arena a;
    jd_mesh mesh;
    if (jd_test_fixture(path, mem, sizeof mem, &caps, &a, &mesh)) return 1;
    size_t mark = jd_arena_mark(&a);
    GLuint resolve = jd_platform_framebuffer(P);

    /* Four renderers: anti-aliasing off (one sample, no pass: the reference
     * picture), the extension taken (the stand-in draws what one sample
     * would: the same picture), absent and refused (the pass at the
     * picture's size: the same picture as each other). At half the size. */
    struct { const char *what; int has_ext, refuse; jd_antialias aa; } cases[] = {
        {"off", 1, 0, JD_AA_OFF}, {"taken", 1, 0, JD_AA_AUTO}, {"absent", 0, 0, JD_AA_AUTO},
        {"refused", 1, 1, JD_AA_AUTO}};
    size_t bytes[4] = {0};
    static uint8_t smoothed[W * H * 4];
    for (int k = 0; k < 4; k++) {
        jd_arena_reset(&a, mark);
        jd_gl_caps c = caps;
        c.ext_multisampled_render_to_texture = cases[k].has_ext;
        c.max_samples = cases[k].has_ext ? 4 : 0;
        refuse = cases[k].refuse;
        tex_calls = rb_calls = tex_samples = rb_samples = rb_w = rb_h = 0;
        jd_renderer_desc d = {.mesh = &mesh, .caps = &c, .target_fbo = ms, .width = W, .height = H,
                              .max_width = 2 * W, .max_height = 2 * H, .render_scale = 0.5f,
                              .antialias = cases[k].aa, .get_proc = get_proc};
        jd_renderer *r = NULL;
        jd_scene s;
        jd_scene_defaults(&s, NULL);
        CHECK(jd_renderer_create(&d, &a, &r, &err) == JD_OK, "%s: %s", cases[k].what, err.msg);
        if (!r) return 1;
        jd_renderer_info info;
        jd_renderer_get_info(r, &info);
        bytes[k] = info.target_bytes;
        printf("%-8s picture %dx%d, %d samples; the extension's calls: texture %d (%d samples), depth %d "
               "(%d samples, %dx%d); %s\n", cases[k].what, info.render_width, info.render_height,
               info.picture_samples, tex_calls, tex_samples, rb_calls, rb_samples, rb_w, rb_h,
               info.samples_note ? info.samples_note : "no note");
        CHECK(info.render_width == W / 2 && info.render_height == H / 2, "%s: drawn at half the size", cases[k].what);
        if (k < 2) {
            CHECK(!info.post_antialias, "%s: no pass after the frame", cases[k].what);
        } else {
            CHECK(info.post_antialias && info.antialias_edges_only,
                  "%s: the pass after the frame on the picture's edges (pass %d, edges only %d)", cases[k].what,
                  info.post_antialias, info.antialias_edges_only);
        }
        if (k == 1) {
            CHECK(info.picture_samples == 4 && !info.samples_note, "taken: the picture drawn with 4 samples");
            CHECK(tex_calls >= 1 && tex_samples == 4 && rb_calls >= 1 && rb_samples == 4, "taken: asked for 4");
            CHECK(rb_w == W / 2 && rb_h == H / 2, "taken: at the picture's size, a power of two (%dx%d)", rb_w, rb_h);
        } else {
            CHECK(info.picture_samples <= 1, "%s: one sample (%d)", cases[k].what, info.picture_samples);
        }
        if (k == 0 || k == 2) CHECK(tex_calls == 0 && rb_calls == 0, "%s: never asked", cases[k].what);
        if (k == 3)
            CHECK(info.samples_note && strstr(info.samples_note, "refused"), "refused: it says so (%s)",
                  info.samples_note ? info.samples_note : "nothing");
        CHECK(jd_renderer_frame(r, &s, NULL, &err) == JD_OK, "%s: %s", cases[k].what, err.msg);
        read_resolved(ms, resolve, k == 0 ? ref : k == 2 ? smoothed : pic);
        if (k == 1) {
            int n = differing(ref, pic);
            printf("%-8s %d bytes differ from the picture with anti-aliasing off\n", cases[k].what, n);
            CHECK(n == 0, "%s: the same picture (%d bytes differ)", cases[k].what, n);
        } else if (k == 2) {
            int one = hard_steps(ref), passed = hard_steps(smoothed);
            printf("%-8s hard steps at the outline %d, with anti-aliasing off %d\n", cases[k].what, passed, one);
            CHECK(one > 20 && passed < one / 2, "%s: the pass takes the outline's steps (%d against %d)",
                  cases[k].what, passed, one);
        } else if (k == 3) {
            int n = differing(smoothed, pic);
            printf("%-8s %d bytes differ from the picture without the extension\n", cases[k].what, n);
            CHECK(n == 0, "%s: the same picture as without the extension (%d bytes differ)", cases[k].what, n);
        }
        if (k == 1) {
            /* Larger: the picture's texture grows to the next power of two
             * and is attached with its samples again. */
            rb_calls = 0;
            CHECK(jd_renderer_resize(r, 2 * W - 100, 2 * H - 100, &err) == JD_OK, "%s", err.msg);
            CHECK(rb_calls == 1 && rb_samples == 4 && rb_w == 256 && rb_h == 256,
                  "resized: attached again with 4 samples at 256x256 (%d calls, %d, %dx%d)", rb_calls, rb_samples,
                  rb_w, rb_h);
        }
        jd_renderer_destroy(r);
    }
    /* The depth's samples are counted: 2 bytes each over the 128 x 128
     * texels; the smoothed picture's target where the pass runs, 4 bytes
     * each, and one texel where it does not (taken). */
    CHECK(bytes[1] == bytes[0] + (size_t)128 * 128 * 2 * 3 + 4,
          "taken: 3 more depth samples counted (%zu against %zu)", bytes[1], bytes[0]);
    CHECK(bytes[2] == bytes[0] + (size_t)128 * 128 * 4, "absent: the smoothed picture's target counted (%zu against %zu)",
          bytes[2], bytes[0]);
    CHECK(bytes[3] == bytes[2], "refused: counted as one sample (%zu against %zu)", bytes[3], bytes[2]);

    /* Drawn at the target's own size with its 4 samples: a pixel on the
     * outline whose centre lies off the triangle takes the varyings
     * extrapolated there (GLES 2.0 has no centroid), and full's view
     * Fresnel factor, steep at grazing, went below 0 there: dark specks
     * along the outline (25 levels under all 8 neighbours), 17 on the
     * default scene at 512x512 before the factor was held at 0.15; with
     * the local part's n.l Ft(l), 0 at unlit vertices, held at 0 or more
     * too (2026-12-05) none at 256x256. */
    {
        jd_renderer_desc d = {.mesh = &mesh, .caps = &caps, .target_fbo = ms, .width = W, .height = H,
                              .render_scale = 1.0f, .get_proc = jd_platform_gl_proc};
        jd_renderer_info info;
        if (!drawn(&a, mark, &d, "specks", resolve, pic, &info)) return 1;
        int n = specks(pic);
        printf("full with the target's 4 samples: %d dark specks\n", n);
        CHECK(n <= 1, "full with the target's samples: at most 1 dark speck at the outline (%d)", n);
    }

    /* The driver's own extension, where it has one (an NVIDIA GPU; not
     * llvmpipe): the picture drawn smaller has its edges multisampled, so
     * fewer hard steps than drawn with one sample. */
    if (!caps.ext_multisampled_render_to_texture || caps.max_samples < 2) {
        printf("driver   no EXT_multisampled_render_to_texture here: its own samples not tried (hard steps with one "
               "sample: %d)\n", hard_steps(ref));
    } else {
        jd_renderer_desc d = {.mesh = &mesh, .caps = &caps, .target_fbo = ms, .width = W, .height = H,
                              .render_scale = 0.5f, .get_proc = jd_platform_gl_proc};
        jd_renderer_info info;
        if (!drawn(&a, mark, &d, "driver", resolve, pic, &info)) return 1;
        CHECK(info.picture_samples > 1, "driver: the picture drawn with samples (%d; %s)", info.picture_samples,
              info.samples_note ? info.samples_note : "no note");
        int one = hard_steps(ref), many = hard_steps(pic);
        printf("driver   %d samples: hard steps %d, with one sample %d\n", info.picture_samples, many, one);
        CHECK(one > 20 && many < one, "driver: fewer hard steps at the outline (%d against %d)", many, one);
    }
    jd_platform_close(P);
    return jd_check_summary("tier_samples");
}
