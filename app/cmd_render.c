#include <limits.h>
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "display_curve.h"
#include "image_out.h"
#include "session.h"

/* The still drawn at n times its size each way, each n x n block averaged
 * in linear light into one pixel (its alpha as it is), in place: the box
 * over the pixel that the reference's rays and Cycles' box filter take.
 * Row by row from the top, so no source row is overwritten before it is
 * read (the output's row y ends where the source's row n y begins). */
static void shrink_box(uint8_t *px, int w, int h, int n)
{
    const float inv = 1.0f / (float)(n * n);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            float sum[4] = {0, 0, 0, 0};
            for (int j = 0; j < n; j++) {
                const uint8_t *row = px + ((size_t)(y * n + j) * (size_t)(w * n) + (size_t)x * n) * 4;
                for (int i = 0; i < n; i++)
                    for (int c = 0; c < 4; c++) sum[c] += c < 3 ? jd_display_to_linear(row[4 * i + c]) : row[4 * i + c];
            }
            uint8_t *o = px + ((size_t)y * w + x) * 4;
            for (int c = 0; c < 3; c++) o[c] = jd_display_encode(sum[c] * inv);
            o[3] = (uint8_t)(sum[3] * inv + 0.5f);
        }
}

int jd_cmd_render(int argc, char **argv)
{
    jd_options o;
    jd_options_defaults(&o);
    o.out = "jade.png";
    int rc = jd_options_command(&o, JD_OPT_RENDER, "render",
                                "Renders a Draco mesh in translucent material, headless, to a PNG.", argc, argv);
    if (rc >= 0) return rc;
    if (!o.frames) o.frames = 1;
    if (o.sheet) o.out = NULL; /* the sheet is the only picture written: --out is not checked */
    /* --pixel-samples N: a still whose edges are averaged over each pixel,
     * as the reference and a path tracer average them (a silhouette drawn
     * with one sample and the pass after the frame is not a pixel's
     * coverage: the knot at 128x128 against Cycles, a quarter of its
     * pixels on an outline, docs/quality.md). Drawn at N times the size
     * without the pass after the frame and at the full resolution of that
     * size (no tier's enlarging), then shrunk (shrink_box). */
    const int ps = o.pixel_samples > 1 ? o.pixel_samples : 1;
    if (ps > 1) {
        if (o.sheet) {
            fprintf(stderr, "jade render: --pixel-samples: not with --sheet (a still of one mode)\n");
            return 2;
        }
        if (o.width * ps > 4096 || o.height * ps > 4096) {
            fprintf(stderr, "jade render: --pixel-samples %d at %dx%d draws %dx%d, over 4096 a side\n", ps, o.width,
                    o.height, o.width * ps, o.height * ps);
            return 2;
        }
        o.width *= ps, o.height *= ps;
        if (o.rdesc.antialias == JD_AA_AUTO) o.rdesc.antialias = JD_AA_OFF;
        if (o.rdesc.render_scale == 0.0f) o.rdesc.render_scale = 1.0f;
    }

    jd_session s;
    if (!jd_session_open(&s, &o, "render")) { jd_session_close(&s); return 1; }
    jd_error err = {0};
    rc = 0;
    uint8_t *px = jd_arena_alloc(&s.arena, (size_t)o.width * o.height * 4, 16, "the output image", &err);
    if (!px) {
        fprintf(stderr, "jade render: %s\n", err.msg);
        jd_session_close(&s);
        return 1;
    }
    if (o.sheet) {
        rc = jd_render_sheet(&s, &o, px);
        jd_session_close(&s);
        return rc;
    }
    /* With --light-step the light turns from frame to frame; with a %d in
     * --out every frame is written under its number, else the last only.
     * The names are checked before the first frame, as the session checked
     * --out's. */
    char name[PATH_MAX];
    int sequence = jd_frame_names_check(o.out, o.frames, &err);
    if (sequence < 0) {
        fprintf(stderr, "jade render: %s\n", err.msg);
        jd_session_close(&s);
        return 1;
    }
    const float azimuth = o.scene.light_azimuth;
    /* Frame -1 warms the driver up (shaders compile on first use, llvmpipe
     * JITs them): the time reported is a steady frame's. */
    double first_ms = 0, frame_ms = 0, read_ms = 0;
    for (int i = -1; i < o.frames; i++) {
        o.scene.light_azimuth = jd_options_light_at(azimuth, o.light_step, i < 0 ? 0 : i);
        double t0 = jd_clock_ms();
        if (jd_renderer_frame(s.renderer, &o.scene, NULL, &err)) {
            fprintf(stderr, "jade render: %s\n", err.msg);
            jd_session_close(&s);
            return 1;
        }
        jd_renderer_finish(s.renderer);
        frame_ms = jd_clock_ms() - t0;
        if (i == -1) first_ms = jd_clock_ms() - s.t_start_ms;
        if (i < 0 || (!sequence && i < o.frames - 1)) continue;
        double t1 = jd_clock_ms();
        if (jd_platform_read_rgba(s.platform, px, &err)) {
            fprintf(stderr, "jade render: %s\n", err.msg);
            jd_session_close(&s);
            return 1;
        }
        if (ps > 1) shrink_box(px, o.width / ps, o.height / ps, ps);
        read_ms = jd_clock_ms() - t1;
        jd_frame_name(o.out, i, name, sizeof name, &err);
        if (jd_png_write(name, o.width / ps, o.height / ps, px, &err)) {
            fprintf(stderr, "jade render: %s\n", err.msg);
            jd_session_close(&s);
            return 1;
        }
    }
    jd_renderer_info info;
    jd_renderer_get_info(s.renderer, &info);
    char tri[80], last[PATH_MAX];
    jd_frame_name(o.out, o.frames - 1, last, sizeof last, &err);
    jd_frame_name(o.out, 0, name, sizeof name, &err);
    if (sequence && o.frames > 1)
        printf("wrote %s to %s (%d frames, the light turning %g degrees a frame; ", name, last, o.frames,
               (double)o.light_step);
    else
        printf("wrote %s (", last);
    printf("%dx%d", o.width / ps, o.height / ps);
    if (ps > 1) printf(" from %dx%d, %d x %d samples a pixel", o.width, o.height, ps, ps);
    printf(", %s, %s, mesh %s: %s)\n", jd_mode_name(o.scene.mode), o.material, s.mesh_path,
           jd_session_triangles(&s, tri, sizeof tri));
    printf("frame %.1f ms (after a warm-up frame), readback %.1f ms, first frame %.0f ms after start, "
           "decode %.1f ms, arena peak %zu bytes, render targets %zu bytes",
           frame_ms, read_ms, first_ms, s.load.decode_ms, s.arena.peak, info.target_bytes);
    if (info.texture_bytes)
        printf(", colour texture %dx%d %zu bytes", info.texture_width, info.texture_height, info.texture_bytes);
    printf("\n");
    jd_session_close(&s);
    return rc;
}
