/* Anti-aliasing: without multisampling, the pass after the frame must soften
 * the silhouette's staircase (fewer hard steps between neighbours) and leave
 * every pixel away from an edge as it was. Where the target has a depth
 * buffer the pass's test marks the flat pixels first and the pass shades
 * the rest only: the picture must be the one pass's into a target without
 * depth, byte for byte, and the count (jd_renderer_count) a few percent of
 * the box. The default asset, in the tree. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "display_curve.h"
#include "frame_cost.h"
#include "gl.h"
#include "gl_fixture.h"
#include "mesh_load.h"
#include "platform.h"
#include "renderer.h"

enum { W = 256, H = 256 };
static unsigned char mem[32 << 20];
static uint8_t pic[3][W * H * 4], small[3][W * H * 4], lit[2][W * H * 4], big[16 * W * H * 4];
static jd_frame_count count;

/* A framebuffer of w x h, with a depth buffer or without (where the pass
 * after the frame runs whole). */
static GLuint target(int w, int h, int with_depth)
{
    GLuint tex, depth, fbo;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    if (with_depth) {
        glGenRenderbuffers(1, &depth);
        glBindRenderbuffer(GL_RENDERBUFFER, depth);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT16, w, h);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    }
    return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE ? fbo : 0;
}

/* A frame of `s` into `fbo`, its w x h corner read back (rows bottom-up,
 * as every target here holds them): 0 with err set where it failed. */
static int frame_into(jd_renderer *r, const jd_scene *s, GLuint fbo, int w, int h, uint8_t *out, jd_error *err)
{
    if (jd_renderer_frame(r, s, NULL, err) != JD_OK) return 0;
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, out);
    return 1;
}

/* A renderer of `d` in the arena from `mark`, and what it chose. */
static jd_renderer *make(const jd_renderer_desc *d, jd_arena *a, size_t mark, jd_renderer_info *info, jd_error *err)
{
    jd_renderer *r = NULL;
    jd_arena_reset(a, mark);
    if (jd_renderer_create(d, a, &r, err) != JD_OK) return NULL;
    jd_renderer_get_info(r, info);
    return r;
}

/* The fragments counted for the program labelled exactly `label`. */
static double counted(const char *label)
{
    double n = 0;
    for (int i = 0; i < count.num_passes; i++)
        if (!strcmp(count.pass[i].program, label)) n += count.pass[i].fragments;
    return n;
}

/* The pass against the box filter: the default asset lit from the front
 * (bright rims against the dark background, where the encoded average
 * showed most), drawn at W x H without the pass and with it, and at 4 x 4
 * the size without it, each pixel then the box of its 16 in linear light
 * (as Cycles' pixel and the reference's --pixel-samples take it). Over the
 * pixels the pass changed, its RMSE against the box is under 0.9 of no
 * pass's (measured 0.0334 against 0.0386: 0.87), and it is not much darker
 * on the whole (measured -0.0083 in the mean). Averaged on the encoded
 * values, as before 2026-12-01, it was 0.0356 against 0.0379 (0.94), and
 * failed here; its mean, -0.0096, passes the second check, which is there
 * against a gross change of level. */
static void box_compare(jd_platform *P, const jd_mesh *mesh, const jd_gl_caps *caps, jd_arena *a, size_t mark)
{
    jd_error err = {0};
    jd_scene s;
    jd_scene_defaults(&s, NULL);
    s.light_azimuth = -30, s.light_elevation = 40;
    GLuint bfbo = target(4 * W, 4 * H, 1);
    CHECK(bfbo != 0, "a framebuffer of %dx%d", 4 * W, 4 * H);
    if (!bfbo) return;
    for (int k = 0; k < 3; k++) {
        GLuint fbo = k == 2 ? bfbo : jd_platform_framebuffer(P);
        int w = k == 2 ? 4 * W : W, h = k == 2 ? 4 * H : H;
        jd_renderer_desc d = {.mesh = mesh, .caps = caps, .target_fbo = fbo, .width = w, .height = h,
                              .antialias = k == 1 ? JD_AA_POST : JD_AA_OFF};
        jd_renderer_info info;
        jd_renderer *r = make(&d, a, mark, &info, &err);
        CHECK(r != NULL, "%s", err.msg);
        if (!r) return;
        CHECK(frame_into(r, &s, fbo, w, h, k == 2 ? big : lit[k], &err), "%s", err.msg);
        jd_renderer_destroy(r);
    }
    double sum[2] = {0, 0}, sq[2] = {0, 0};
    int n = 0;
    for (int i = 0; i < W * H; i++) {
        int changed = 0;
        for (int ch = 0; ch < 3; ch++) changed |= abs(lit[0][4 * i + ch] - lit[1][4 * i + ch]) > 1;
        if (!changed) continue;
        n++;
        int x = i % W, y = i / W;
        for (int ch = 0; ch < 3; ch++) {
            double box = 0;
            for (int dy = 0; dy < 4; dy++)
                for (int dx = 0; dx < 4; dx++)
                    box += jd_display_to_linear(big[4 * ((4 * y + dy) * 4 * W + 4 * x + dx) + ch]);
            box /= 16.0;
            for (int k = 0; k < 2; k++) {
                double dv = jd_display_to_linear(lit[k][4 * i + ch]) - box;
                sum[k] += dv, sq[k] += dv * dv;
            }
        }
    }
    double n3 = 3.0 * (n > 0 ? n : 1);
    printf("lit from the front, the %d pixels the pass changed against the box of 4 x 4 the size: RMSE %.4f without "
           "the pass, %.4f with it; mean difference %.4f and %.4f\n",
           n, sqrt(sq[0] / n3), sqrt(sq[1] / n3), sum[0] / n3, sum[1] / n3);
    CHECK(n > 100 && sqrt(sq[1]) < 0.9 * sqrt(sq[0]), "the pass brings the edges closer to the box (its average in "
                                                      "linear light)");
    CHECK(fabs(sum[1] / n3) < 0.0125, "the pass keeps the edges' level");
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "assets/default.drc";
    jd_error err = {0};
    jd_platform *P;
    /* Single-sampled, so both pictures come from the same kind of target:
     * where the headless target has EXT_multisampled_render_to_texture
     * (NVIDIA), "off" would otherwise be the multisampled picture. */
    jd_platform_desc pd = {.kind = "headless", .width = W, .height = H, .single_sample = 1};
    if (jd_platform_open(&pd, &P, &err)) { printf("%s\n", err.msg); return 1; }
    jd_gl_caps caps;
    jd_arena a;
    jd_mesh mesh;
    if (jd_test_fixture(path, mem, sizeof mem, &caps, &a, &mesh)) return 1;
    size_t mark = jd_arena_mark(&a);
    const jd_antialias modes[3] = {JD_AA_OFF, JD_AA_POST, JD_AA_POST};
    GLuint plain = target(W, H, 0);
    CHECK(plain != 0, "a framebuffer without depth");
    jd_scene s;
    jd_scene_defaults(&s, NULL);
    for (int k = 0; k < 3; k++) {
        GLuint fbo = k == 2 ? plain : jd_platform_framebuffer(P);
        jd_renderer_desc d = {.mesh = &mesh, .caps = &caps, .target_fbo = fbo, .width = W, .height = H,
                              .antialias = modes[k]};
        jd_renderer_info info;
        jd_renderer *r = make(&d, &a, mark, &info, &err);
        CHECK(r != NULL, "%s", err.msg);
        if (!r) return 1;
        CHECK(info.post_antialias == (k > 0), "the pass runs only when asked for");
        CHECK(info.antialias_edges_only == (k == 1), "%s", k == 1 ? "the headless target's depth marks the flat pixels"
                                                                  : "no depth buffer, no mark");
        CHECK(frame_into(r, &s, fbo, W, H, pic[k], &err), "%s", err.msg);
        if (k == 1) {
            CHECK(jd_renderer_count(r, &s, 0, &count, &err) == JD_OK, "%s", err.msg);
            double marked = counted("quad.vert+antialias.frag[mark]"), edges = counted("quad.vert+antialias.frag");
            printf("the pass after the frame: its test over %.0f pixels, the whole pass over %.0f of them\n", marked,
                   edges);
            CHECK(marked > 0 && edges > 10 && edges < 0.35 * marked, "the whole pass shades the edges only");
        }
        jd_renderer_destroy(r);
    }
    int differ = 0;
    for (size_t i = 0; i < sizeof pic[1]; i++) differ += pic[1][i] != pic[2][i];
    printf("the pass on the edges its test marks against the whole pass: %d bytes differ\n", differ);
    CHECK(differ == 0, "the edges-only pass draws the whole pass's picture");
    /* Drawn smaller, the frame's depth serves the mark, with or without one
     * in the target; and after a resize that takes other powers of two (the
     * frame's depth attached again), the picture is a fresh renderer's. */
    GLuint fbo = jd_platform_framebuffer(P);
    for (int k = 0; k < 3; k++) {
        jd_renderer_desc d = {.mesh = &mesh, .caps = &caps, .target_fbo = k == 1 ? plain : fbo,
                              .width = k == 2 ? W / 2 : W, .height = H, .max_width = W, .max_height = H,
                              .antialias = JD_AA_POST, .render_scale = 0.5f};
        jd_renderer_info info;
        jd_renderer *r = make(&d, &a, mark, &info, &err);
        CHECK(r != NULL, "%s", err.msg);
        if (!r) return 1;
        CHECK(info.antialias_edges_only, "drawn at %dx%d, the frame's depth marks the flat pixels", info.render_width,
              info.render_height);
        if (k != 1) CHECK(frame_into(r, &s, fbo, d.width, H, small[k == 2 ? 1 : 0], &err), "%s", err.msg);
        if (k == 0) { /* W x H (128 x 128 drawn) -> W/2 x H (64 x 128) -> W x H again */
            CHECK(jd_renderer_resize(r, W / 2, H, &err) == JD_OK && frame_into(r, &s, fbo, W / 2, H, small[2], &err), "%s",
                  err.msg);
            CHECK(jd_renderer_resize(r, W, H, &err) == JD_OK && frame_into(r, &s, fbo, W, H, small[1], &err), "%s", err.msg);
            CHECK(!memcmp(small[0], small[1], (size_t)W * H * 4), "back at %dx%d after a resize: the same picture", W, H);
        }
        jd_renderer_destroy(r);
    }
    CHECK(!memcmp(small[1], small[2], (size_t)W / 2 * H * 4),
          "resized to %dx%d: the picture of a renderer made at that size", W / 2, H);
    /* The frame's alpha holds its luma for the pass's test (JD_LUMA_ALPHA):
     * what reaches the target is opaque all the same (an X11 window with
     * an alpha channel, a display plane that blends, a PNG). */
    int see_through = 0;
    for (int i = 0; i < W * H; i++)
        for (int k = 0; k < 3; k++) /* small[1] and [2]: W/2 x H, the last drawn */
            see_through += (pic[k][4 * i + 3] != 255) + (i < (k ? W / 2 * H : W * H) && small[k][4 * i + 3] != 255);
    CHECK(see_through == 0, "the pictures are opaque (%d pixels' alpha under 255)", see_through);
    /* Hard steps: neighbours (right, below) whose luma differs by 64 or more. */
    int steps[2] = {0, 0}, flat = 0, flat_changed = 0;
    for (int y = 1; y < H - 1; y++)
        for (int x = 1; x < W - 1; x++) {
            int i = y * W + x;
            for (int k = 0; k < 2; k++) {
                int c = jd_test_luma(pic[k] + 4 * i);
                steps[k] += abs(c - jd_test_luma(pic[k] + 4 * (i + 1))) >= 64;
                steps[k] += abs(c - jd_test_luma(pic[k] + 4 * (i + W))) >= 64;
            }
            /* Away from edges: the 3x3 neighbourhood within 8 levels. */
            int lo = 255, hi = 0;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int c = jd_test_luma(pic[0] + 4 * (i + dy * W + dx));
                    lo = c < lo ? c : lo;
                    hi = c > hi ? c : hi;
                }
            if (hi - lo <= 8) {
                flat++;
                int changed = 0;
                for (int ch = 0; ch < 3; ch++) changed |= abs(pic[0][4 * i + ch] - pic[1][4 * i + ch]) > 1;
                if (changed && flat_changed < 4)
                    printf("flat pixel (%d, %d) changed: %d %d %d -> %d %d %d\n", x, y, pic[0][4 * i], pic[0][4 * i + 1],
                           pic[0][4 * i + 2], pic[1][4 * i], pic[1][4 * i + 1], pic[1][4 * i + 2]);
                flat_changed += changed;
            }
        }
    printf("hard steps: %d without, %d with the pass; flat pixels %d, changed by more than 1: %d\n", steps[0], steps[1],
           flat, flat_changed);
    box_compare(P, &mesh, &caps, &a, mark);
    CHECK(steps[0] > 50, "the picture has a silhouette");
    CHECK(steps[1] < 0.6 * steps[0], "the pass removes most hard steps");
    CHECK(flat > W * H / 2 && flat_changed == 0, "pixels away from edges stay as they were");
    jd_platform_close(P);
    return jd_check_summary("antialias");
}
