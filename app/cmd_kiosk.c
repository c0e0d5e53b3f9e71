/* jade kiosk: fullscreen without a desktop, the light orbiting, until a
 * signal or --frames N; then frame-time statistics. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "health.h"

#define KIOSK_SAMPLES 4096 /* the last frames kept for the statistics */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* One line per --log-every: the frames since the last line, their median
 * and p95, and the process's health. */
static void health_line(jd_session *s, const double *times, double *sorted, long frames, long recent, double t_ms)
{
    int n = recent < KIOSK_SAMPLES ? (int)recent : KIOSK_SAMPLES;
    if (n <= 0) return;
    for (int i = 0; i < n; i++) sorted[i] = times[(frames - 1 - i) % KIOSK_SAMPLES];
    qsort(sorted, (size_t)n, sizeof(double), cmp_double);
    jd_present_stats ps;
    jd_platform_present_stats(s->platform, &ps);
    jd_health h;
    jd_health_sample(&h);
    printf("kiosk: at %.1f s, %ld frames, last %ld: median %.2f ms, p95 %.2f ms, missed vblanks %u", t_ms / 1000.0,
           frames, recent, sorted[n / 2], sorted[(n * 95) / 100], ps.missed_vblanks);
    jd_health_print(stdout, &h);
    printf("\n");
}

int jd_cmd_kiosk(int argc, char **argv)
{
    jd_options o;
    jd_options_defaults(&o);
    o.platform = "drm";
    int rc = jd_options_command(&o, JD_OPT_KIOSK, "kiosk",
                                "Shows the scene fullscreen (DRM/KMS by default), the light orbiting, until SIGINT or\n"
                                "SIGTERM or --frames N; then prints frame-time statistics. Needs DRM master: run\n"
                                "it from a text console or a systemd service, not inside a desktop session.",
                                argc, argv);
    if (rc >= 0) return rc;
    jd_quit_on_signals();
    jd_session s;
    if (!jd_session_open(&s, &o, "kiosk")) {
        int stopped = s.stopped;
        jd_session_close(&s);
        return stopped ? 0 : 1;
    }
    jd_error err = {0};
    double *times = jd_arena_alloc(&s.arena, sizeof(double) * KIOSK_SAMPLES, 16, "kiosk frame times", &err);
    double *sorted = jd_arena_alloc(&s.arena, sizeof(double) * KIOSK_SAMPLES, 16, "kiosk frame times", &err);
    if (!times || !sorted) { fprintf(stderr, "jade kiosk: %s\n", err.msg); jd_session_close(&s); return 1; }
    fprintf(stderr, "%s\n%s\n", jd_platform_describe(s.platform), jd_antialias_describe(s.renderer));
    jd_scene sc = o.scene;
    double t_start = jd_now_ms(), t_prev = t_start, t_log = t_start;
    long frames = 0, frames_logged = 0;
    rc = 0;
    while (!o.frames || frames < o.frames) {
        jd_event ev;
        int quit = 0;
        while (jd_platform_poll(s.platform, &ev))
            if (ev.type == JD_EVENT_QUIT) quit = 1;
        if (quit) break;
        /* By the clock, so the motion stays smooth when frames are dropped;
         * wrapped, so float precision holds over months. A still light
         * keeps the scene unchanged and the renderer reuses its work. */
        if (o.light_speed != 0.0f)
            sc.light_azimuth = o.scene.light_azimuth +
                               (float)fmod((jd_now_ms() - t_start) / 1000.0 * (double)o.light_speed, 360.0);
        if (jd_renderer_frame(s.renderer, &sc, NULL, &err) || jd_platform_present(s.platform, &err)) {
            fprintf(stderr, "jade kiosk: %s\n", err.msg);
            rc = 1;
            break;
        }
        double now = jd_now_ms();
        times[frames % KIOSK_SAMPLES] = now - t_prev;
        t_prev = now;
        frames++;
        if (o.log_every > 0 && now - t_log >= o.log_every * 1000.0) {
            health_line(&s, times, sorted, frames, frames - frames_logged, now - t_start);
            frames_logged = frames;
            t_log = now;
        }
    }
    if (frames > 0) {
        int n = frames < KIOSK_SAMPLES ? (int)frames : KIOSK_SAMPLES;
        memcpy(sorted, times, sizeof(double) * (size_t)n);
        qsort(sorted, (size_t)n, sizeof(double), cmp_double);
        jd_present_stats ps;
        jd_platform_present_stats(s.platform, &ps);
        printf("kiosk: %ld frames in %.1f s, frame time median %.2f ms, p95 %.2f ms, missed vblanks %u",
               frames, (t_prev - t_start) / 1000.0, sorted[n / 2], sorted[(n * 95) / 100], ps.missed_vblanks);
        if (ps.refresh_hz > 0) printf(" (display %.0f Hz)", ps.refresh_hz);
        printf("\n");
    }
    jd_session_close(&s);
    return rc;
}
