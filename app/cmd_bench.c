#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "alloc_count.h"
#include "board.h"
#include "commands.h"
#include "frame_stats.h"
#include "health.h"
#include "json_out.h"

/* The frame-cost model's estimate of one frame of `sc` on the board, as
 * a JSON member: counted here (read-backs, outside the timed frames), the
 * instructions from the built-in compiler table. */
static int print_estimate(jd_session *s, const jd_board *b, const jd_scene *sc, jd_error *err)
{
    static jd_frame_count count; /* one at a time; large for a stack */
    static jd_estimate est;
    if (jd_renderer_count(s->renderer, sc, b->vertex_cache, &count, err) ||
        jd_frame_cost_estimate(b, &count, NULL, &est, err))
        return 0;
    double written = 0, read = 0;
    for (int i = 0; i < count.num_passes; i++) {
        written += count.pass[i].bytes_written;
        read += count.pass[i].bytes_read;
    }
    double khz = b->clock_mhz * 1e3; /* clocks per ms */
    printf(", \"estimate\": {\"board\": \"%s\", \"frame_ms\": %.3f, \"frame_cycles\": %.0f, \"fps\": %.1f, "
           "\"vertex_ms\": %.3f, \"fragment_ms\": %.3f, \"target_switches\": %d, \"bytes_written\": %.0f, "
           "\"bytes_read\": %.0f, \"passes\": [",
           b->name, est.frame_ms, est.frame_ms * khz, 1000.0 / est.frame_ms, est.vertex_ms, est.fragment_ms,
           count.target_switches, written, read);
    for (int i = 0; i < count.num_passes; i++) {
        const jd_pass_count *p = &count.pass[i];
        const jd_pass_estimate *e = &est.pass[i];
        printf("%s{\"pass\": \"%s\", \"program\": \"%s\", \"size\": \"%dx%d\", \"fragments\": %.0f, "
               "\"vertices\": %.0f, \"triangles\": %.0f, \"fs_instructions\": %.0f, \"vs_instructions\": %.0f, "
               "\"loop_trips\": %.0f, \"fs_cost\": %.1f, \"vs_cost\": %.1f, \"bytes_written\": %.0f, \"bytes_read\": %.0f, "
               "\"cycles\": %.0f, \"ms\": %.4f}",
               i ? ", " : "", p->pass, p->program, p->width, p->height, p->fragments, p->vertices, p->triangles,
               e->fs_instructions, e->vs_instructions, p->trips, e->fs_cost, e->vs_cost, p->bytes_written,
               p->bytes_read, e->ms * khz, e->ms);
    }
    printf("]}");
    /* A mesh whose vertices bind the board's frame past 60 Hz (a scan on a
     * Mali-400's one vertex processor): the option that helps, and about
     * how far, the vertex side taken as proportional to the triangles. */
    static int said;
    double fit = 0.9 * 1000.0 / 60.0, want = est.fragment_ms > fit ? est.fragment_ms : 0.85 * 1000.0 / 60.0;
    uint32_t tris = s->mesh.num_indices / 3;
    if (!said && est.vertex_ms > fit && est.vertex_ms > est.fragment_ms && tris > 2000) {
        said = 1;
        uint32_t n = (uint32_t)((double)tris * want / est.vertex_ms) / 1000 * 1000;
        fprintf(stderr, "jade bench: on %s the %u triangles' vertices bind the frame (%.1f ms, the pixels %.1f): "
                "--simplify %u would bring them to about %.1f ms\n", b->name, tris, est.vertex_ms, est.fragment_ms,
                n ? n : 1000, want);
    }
    return 1;
}

/* Runs `frames` frames of one mode with the light orbiting once per 120
 * frames, so thickness, capture and SH are recomputed every frame. */
static int bench_mode(jd_session *s, jd_options *o, jd_mode mode, double *times, int first)
{
    jd_scene sc = o->scene;
    sc.mode = mode;
    jd_error err = {0};
    double pass[JD_PASS_COUNT] = {0}, gpu[JD_PASS_COUNT] = {0};
    int gpu_frames = 0;
    jd_frame_stats st;
    /* Warm-up frames build driver-side state (shader variants, caches). */
    for (int i = 0; i < 5; i++) {
        sc.light_azimuth = o->scene.light_azimuth + 3.0f * i;
        if (jd_renderer_frame(s->renderer, &sc, NULL, &err)) goto fail;
    }
    jd_renderer_finish(s->renderer);
    jd_alloc_count_start();
    static double t_log;
    if (!t_log) t_log = jd_clock_ms();
    jd_frame_stats fs;
    double switches = 0, readbacks = 0, fragments = 0, bytes = 0;
    for (int i = 0; i < o->frames; i++) {
        sc.light_azimuth = o->scene.light_azimuth + 360.0f * (float)i / 120.0f;
        if (o->cycle_materials) { /* the diffusion refit and every uniform path, in the loop */
            const jd_material *m = &jd_materials[(i / 10) % jd_material_count];
            memcpy(sc.sigma_s, m->sigma_s, sizeof sc.sigma_s);
            memcpy(sc.sigma_a, m->sigma_a, sizeof sc.sigma_a);
            sc.eta = m->eta;
        }
        double t0 = jd_clock_ms();
        if (jd_renderer_frame(s->renderer, &sc, &fs, &err)) { jd_alloc_count_stop(); goto fail; }
        jd_renderer_finish(s->renderer);
        double t1 = jd_clock_ms();
        times[i] = t1 - t0;
        switches += fs.target_switches;
        readbacks += fs.readbacks;
        fragments += fs.fragments;
        bytes += fs.target_bytes_written;
        if (o->log_every > 0 && t1 - t_log >= o->log_every * 1000.0) {
            jd_health h;
            jd_health_sample(&h);
            fprintf(stderr, "bench: at %.1f s, %s frame %d of %d", (t1 - s->t_start_ms) / 1000.0, jd_mode_name(mode),
                    i + 1, o->frames);
            jd_health_print(stderr, &h);
            fprintf(stderr, "\n");
            t_log = t1;
        }
    }
    unsigned long allocs = jd_alloc_count_stop();
    /* Per-pass times come from a separate run with glFinish after each pass,
     * which serialises the GPU and so is kept out of the frame times. */
    int timed = o->frames < 60 ? o->frames : 60;
    jd_renderer_set_timing(s->renderer, 1);
    for (int i = 0; i < timed; i++) {
        sc.light_azimuth = o->scene.light_azimuth + 360.0f * (float)i / 120.0f;
        if (jd_renderer_frame(s->renderer, &sc, &st, &err)) { jd_renderer_set_timing(s->renderer, 0); goto fail; }
        for (int p = 0; p < JD_PASS_COUNT; p++) pass[p] += st.pass_ms[p] / timed;
        if (st.gpu_valid) {
            gpu_frames++;
            for (int p = 0; p < JD_PASS_COUNT; p++) gpu[p] += st.gpu_ms[p];
        }
    }
    jd_renderer_set_timing(s->renderer, 0);
    double sorted_sum = 0;
    for (int i = 0; i < o->frames; i++) sorted_sum += times[i];
    jd_sort_times(times, o->frames);
    double med = jd_percentile(times, o->frames, 0.5), p95 = jd_percentile(times, o->frames, 0.95);
    /* The same mode with the light and the camera still (a kiosk between
     * animations): the light-space passes and the spread are reused. */
    int still = o->frames < 60 ? o->frames : 60;
    double still_switches = 0, still_readbacks = 0;
    sc.light_azimuth = o->scene.light_azimuth;
    for (int i = 0; i < still; i++) {
        double t0 = jd_clock_ms();
        if (jd_renderer_frame(s->renderer, &sc, &fs, &err)) goto fail;
        jd_renderer_finish(s->renderer);
        times[i] = jd_clock_ms() - t0;
        if (i) { still_switches += fs.target_switches; still_readbacks += fs.readbacks; }
    }
    jd_sort_times(times, still);
    double still_med = jd_percentile(times, still, 0.5);
    printf("%s    \"%s\": {\"frame_ms_median\": %.3f, \"frame_ms_p95\": %.3f, \"frame_ms_mean\": %.3f, \"fps\": %.1f, "
           "\"heap_allocations_in_loop\": %lu, \"readbacks_per_frame\": %.2f, \"target_switches_per_frame\": %.2f, "
           "\"fragments_per_frame\": %.0f, \"target_bytes_written_per_frame\": %.0f, \"still_frame_ms_median\": %.3f, "
           "\"still_readbacks_per_frame\": %.2f, \"still_target_switches_per_frame\": %.2f, \"pass_ms_mean\": {",
           first ? "" : ",\n", jd_mode_name(mode), med, p95, sorted_sum / o->frames, 1000.0 / med, allocs,
           readbacks / o->frames, switches / o->frames, fragments / o->frames, bytes / o->frames, still_med,
           still > 1 ? still_readbacks / (still - 1) : 0.0, still > 1 ? still_switches / (still - 1) : 0.0);
    for (int p = 0; p < JD_PASS_COUNT; p++)
        printf("%s\"%s\": %.3f", p ? ", " : "", jd_pass_name(p), pass[p]);
    printf("}");
    if (gpu_frames) {
        printf(", \"gpu_pass_ms_mean\": {");
        for (int p = 0; p < JD_PASS_COUNT; p++)
            printf("%s\"%s\": %.3f", p ? ", " : "", jd_pass_name(p), gpu[p] / gpu_frames);
        printf("}");
    }
    if (o->device && !print_estimate(s, jd_board_find(o->device), &sc, &err)) goto fail;
    printf("}");
    return 1;
fail:
    fprintf(stderr, "jade bench: %s\n", err.msg);
    return 0;
}

int jd_cmd_bench(int argc, char **argv)
{
    jd_options o;
    jd_options_defaults(&o);
    o.mode_list = "all";
    int rc = jd_options_command(&o, JD_OPT_BENCH, "bench",
                                "Renders N frames per mode with the light orbiting and prints one JSON object.\n"
                                "Frame times: glFinish at the end of each frame. Pass times: a separate run of\n"
                                "up to 60 frames with glFinish after each pass.",
                                argc, argv);
    if (rc >= 0) return rc;
    if (!o.frames) o.frames = 200;
    /* A board draws its edges as its display does under Mesa: from a 4x
     * multisampled EGL config (shaded once per pixel on a tile buffer) with
     * no pass after the frame, or, where the driver offers no such config
     * (etnaviv, freedreno's a3xx), with the pass after the frame. Where the
     * tier draws the picture smaller and the driver cannot draw a texture
     * with samples (vc4), the renderer is told the display's 4 samples, as
     * the board's display gives them, and smooths that picture with the
     * pass at its own size. */
    if (o.device && o.rdesc.antialias == JD_AA_AUTO) {
        const jd_board *b = jd_board_find(o.device);
        if (b && b->multisampled && !b->texture_samples)
            o.rdesc.target_samples = 4;
        else
            o.rdesc.antialias = b && !b->multisampled ? JD_AA_POST : JD_AA_OFF;
    }

    jd_session s;
    if (!jd_session_open(&s, &o, "bench")) { jd_session_close(&s); return 1; }
    jd_error err = {0};
    double *times = jd_arena_alloc(&s.arena, sizeof(double) * (size_t)o.frames, 16, "bench timings", &err);
    if (!times) { fprintf(stderr, "jade bench: %s\n", err.msg); jd_session_close(&s); return 1; }
    /* Time to first frame: from process start to a finished frame. */
    jd_scene first = o.scene;
    first.mode = o.scene.mode; /* with "all": the default, full */
    if (jd_renderer_frame(s.renderer, &first, NULL, &err)) { fprintf(stderr, "jade bench: %s\n", err.msg); jd_session_close(&s); return 1; }
    jd_renderer_finish(s.renderer);
    double ttff = jd_clock_ms() - s.t_start_ms;
    jd_renderer_info info;
    jd_renderer_get_info(s.renderer, &info);

    printf("{\n  \"mesh\": ");
    jd_json_string(stdout, s.mesh_path);
    /* file_triangles: the file's own, where loading split (coarse) or
     * simplified (--simplify) them. */
    printf(", \"triangles\": %u, \"file_triangles\": %u, \"vertices\": %u, \"proxy_triangles\": %u,\n",
           s.mesh.num_indices / 3, s.load.declared_faces ? s.load.declared_faces : s.mesh.num_indices / 3,
           s.mesh.num_vertices, info.proxy->num_indices / 3);
    printf("  \"size\": \"%dx%d\", \"frames\": %d, \"material\": ", o.width, o.height, o.frames);
    jd_json_string(stdout, o.material);
    printf(", \"cube_size\": %d, \"precision\": \"%s\", \"full_levels\": \"%s\",\n  \"gl_renderer\": ",
           o.rdesc.cube_size ? o.rdesc.cube_size : 64, info.highp ? "highp" : "mediump",
           info.vertex_levels ? "per vertex" : "per fragment");
    jd_json_string(stdout, s.caps.renderer);
    printf(", \"platform\": ");
    jd_json_string(stdout, jd_platform_describe(s.platform));
    printf(", \"gpu_timer_query\": %s,\n", info.gpu_timer ? "true" : "false");
    if (o.device) {
        const jd_board *b = jd_board_find(o.device);
        printf("  \"device\": \"%s\", \"device_summary\": ", b->name);
        jd_json_string(stdout, b->summary);
        printf(", \"profile\": \"%s\", \"compiler\": \"%s\",\n", b->profile, b->compiler);
    }
    printf("  \"time_to_first_frame_ms\": %.1f, \"draco_decode_ms\": %.2f, \"file_bytes\": %zu,\n", ttff,
           s.load.decode_ms, s.load.file_bytes);
    printf("  \"arena_budget_bytes\": %zu, \"arena_peak_bytes\": %zu, \"render_target_bytes\": %zu,\n", s.arena.size,
           s.arena.peak, info.target_bytes);
    printf("  \"colour_texture_bytes\": %zu, \"colour_texture_size\": [%d, %d],\n", info.texture_bytes,
           info.texture_width, info.texture_height);
    if (o.cycle_materials) {
        /* A soak: every mode's programs and targets made once before the
         * first health line, so later growth is growth, not set-up. */
        for (int m = 0; m < JD_MODE_COUNT; m++) {
            jd_scene w = o.scene;
            w.mode = (jd_mode)m;
            if (jd_renderer_frame(s.renderer, &w, NULL, &err)) {
                fprintf(stderr, "jade bench: %s\n", err.msg);
                jd_session_close(&s);
                return 1;
            }
        }
        jd_renderer_finish(s.renderer);
    }
    printf("  \"modes\": {\n");
    int ok = 1, n = 0;
    for (int m = 0; m < JD_MODE_COUNT && ok; m++) {
        if (strcmp(o.mode_list, "all") && m != (int)o.scene.mode) continue;
        ok = bench_mode(&s, &o, (jd_mode)m, times, n++ == 0);
    }
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    printf("\n  },\n  \"peak_rss_bytes\": %ld\n}\n", ru.ru_maxrss * 1024L);
    jd_session_close(&s);
    return ok ? 0 : 1;
}
