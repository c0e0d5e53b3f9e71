#include <limits.h>
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "image_out.h"
#include "session.h"

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
        read_ms = jd_clock_ms() - t1;
        jd_frame_name(o.out, i, name, sizeof name, &err);
        if (jd_png_write(name, o.width, o.height, px, &err)) {
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
    printf("%dx%d, %s, %s, mesh %s: %s)\n", o.width, o.height, jd_mode_name(o.scene.mode), o.material,
           s.mesh_path, jd_session_triangles(&s, tri, sizeof tri));
    printf("frame %.1f ms (after a warm-up frame), readback %.1f ms, first frame %.0f ms after start, "
           "decode %.1f ms, arena peak %zu bytes, render targets %zu bytes",
           frame_ms, read_ms, first_ms, s.load.decode_ms, s.arena.peak, info.target_bytes);
    if (info.texture_bytes)
        printf(", colour texture %dx%d %zu bytes", info.texture_width, info.texture_height, info.texture_bytes);
    printf("\n");
    jd_session_close(&s);
    return rc;
}
