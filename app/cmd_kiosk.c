/* jade kiosk: fullscreen without a desktop, the light orbiting, until a
 * signal or --frames N; then frame-time statistics. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "frame_stats.h"
#include "health.h"
#include "image_out.h"

#define KIOSK_SAMPLES 4096 /* the last frames kept for the statistics */

/* One line per --log-every: the frames since the last line, their median
 * and p95, and the process's health. */
static void health_line(jd_session *s, const double *times, double *sorted, long frames, long recent, double t_ms)
{
    int n = recent < KIOSK_SAMPLES ? (int)recent : KIOSK_SAMPLES;
    if (n <= 0) return;
    for (int i = 0; i < n; i++) sorted[i] = times[(frames - 1 - i) % KIOSK_SAMPLES];
    jd_sort_times(sorted, n);
    jd_present_stats ps;
    jd_platform_present_stats(s->platform, &ps);
    jd_health h;
    jd_health_sample(&h);
    printf("kiosk: at %.1f s, %ld frames, last %ld: median %.2f ms, p95 %.2f ms, missed vblanks %u", t_ms / 1000.0,
           frames, recent, jd_percentile(sorted, n, 0.5), jd_percentile(sorted, n, 0.95), ps.missed_vblanks);
    jd_health_print(stdout, &h);
    printf("\n");
}

static const char kiosk_summary[] =
    "Shows the scene fullscreen (DRM/KMS by default), the light orbiting, until SIGINT or\n"
    "SIGTERM or --frames N; then prints frame-time statistics. SIGHUP re-reads --config.\n"
    "Touch or a mouse drag turns the object; --idle seconds later it turns back. Needs DRM\n"
    "master: run it from a text console or a systemd service, not inside a desktop session.";

/* The options in force: the defaults, then the configuration file, then the
 * command line (which wins). 1, or 0 after saying why. */
static int kiosk_options(jd_options *o, const char *config, int argc, char **argv, char *store, size_t cap)
{
    jd_options_defaults(o);
    o->platform = "drm";
    if (config && !jd_options_parse_file(o, JD_OPT_KIOSK, "kiosk", config, store, cap)) return 0;
    if (jd_options_parse(o, JD_OPT_KIOSK, "kiosk", argc, argv, 2) != 1) return 0;
    return jd_options_finish(o, "kiosk");
}

static int same_str(const char *a, const char *b) { return a == b || (a && b && !strcmp(a, b)); }

/* SIGHUP: the configuration again. What can change while running changes
 * (the scene, the material, the light, the mesh); what needs another
 * display or another renderer set-up is said and waits for a restart. The
 * display keeps the last frame until the new one is ready. */
static void reload(jd_session *s, jd_options *o, jd_scene *sc, int argc, char **argv, char (*store)[65536], int *cur)
{
    jd_options n;
    if (!kiosk_options(&n, o->config, argc, argv, store[!*cur], sizeof store[0])) {
        fprintf(stderr, "jade kiosk: SIGHUP: the configuration was not changed\n");
        return;
    }
    const char *later = NULL;
    if (!same_str(n.platform, o->platform)) later = "platform";
    else if (!same_str(n.drm_device, o->drm_device)) later = "drm-device";
    else if (!same_str(n.connector, o->connector)) later = "connector";
    else if (!same_str(n.display_mode, o->display_mode)) later = "display-mode";
    else if (n.atomic != o->atomic) later = "atomic";
    else if (n.kms != o->kms) later = "kms";
    else if (n.rotation != o->rotation) later = "rotate";
    else if (!same_str(n.profile, o->profile)) later = "profile";
    else if (memcmp(&n.rdesc, &o->rdesc, sizeof n.rdesc)) later = "a renderer option";
    if (later) fprintf(stderr, "jade kiosk: SIGHUP: %s changed; that takes effect at the next start\n", later);
    /* The display stays as opened and the renderer as set up. (The new
     * strings are kept: the old ones live in the text about to be reused.) */
    n.atomic = o->atomic, n.kms = o->kms, n.rotation = o->rotation, n.rdesc = o->rdesc, n.fullscreen = o->fullscreen;
    n.width = o->width, n.height = o->height;
    int mesh_changed = !same_str(n.mesh, o->mesh) || memcmp(&n.load, &o->load, sizeof n.load);
    *cur = !*cur;
    *o = n;
    if (mesh_changed) {
        int r = jd_session_reload_mesh(s, o, "kiosk");
        if (r < 0) return; /* said; the loop stops at the renderer's absence */
    } else {
        /* The same mesh, not read again: what its file says of its
         * material still holds where the new configuration names none. */
        jd_options_file_material(o, &s->load, s->mesh_path, "kiosk");
    }
    *sc = o->scene;
    fprintf(stderr, "jade kiosk: SIGHUP: configuration re-read from %s: mesh %s, material %s, light speed %g deg/s\n",
            o->config ? o->config : "the command line", s->mesh_path, o->material, o->light_speed);
}

/* --screenshot: what the display shows at the end, as the display hardware
 * reads it (not jade's own frame): proof from afar of what a kiosk shows.
 * 1 after saying why it failed. */
static int capture(jd_session *s, const char *path)
{
    int w, h;
    jd_platform_display_size(s->platform, &w, &h);
    uint8_t *px = malloc((size_t)w * (size_t)h * 4);
    jd_error err = {0};
    jd_result r = px ? jd_platform_capture(s->platform, px, &err) : jd_fail(&err, JD_ERR_BUDGET, "no memory for the capture");
    if (!r) r = jd_png_write(path, w, h, px, &err);
    if (r) fprintf(stderr, "jade kiosk: --screenshot %s: %s\n", path, err.msg);
    else printf("kiosk: what the display scans out (%dx%d) written to %s\n", w, h, path);
    free(px);
    return r != JD_OK;
}

/* Where the device's tier draws the picture smaller than the display, the
 * display engine enlarges it on its way out if it can (the plane's
 * scaler, drm with atomic modesetting): the GL pass that enlarges it goes, and so does
 * writing the full-size picture to memory every frame (Mali-400 MP2 at
 * 1080p: 1.6 ms of its 8.9, docs/frame-cost.md). The renderer then draws
 * at the smaller size, which its tier leaves as it is. 1 after saying why
 * it failed. */
static int enlarge_on_display(jd_session *s, const jd_options *o)
{
    jd_renderer_info info;
    jd_renderer_get_info(s->renderer, &info);
    int dw, dh, w = info.render_width, h = info.render_height;
    jd_platform_display_size(s->platform, &dw, &dh);
    if (!info.tier || (w >= dw && h >= dh)) return 0;
    /* An explicit --render-scale keeps the GPU's enlarging: the renderer
     * would scale the smaller drawable once more. */
    const char *kept = o->gpu_enlarge                 ? "--gpu-enlarge"
                       : o->rdesc.render_scale != 0.0f ? "--render-scale: the display engine is asked only for the tier's size"
                                                       : NULL;
    if (kept || !jd_platform_scale_out(s->platform, w, h)) {
        jd_present_stats ps;
        jd_platform_present_stats(s->platform, &ps);
        printf("kiosk: the GPU enlarges %dx%d to %dx%d (%s)\n", w, h, dw, dh,
               kept                       ? kept
               : strcmp(o->platform, "drm") ? "only drm asks a display engine's scaler"
               : ps.atomic                ? "the display engine's scaler refused it"
                                          : "legacy modesetting cannot ask the display engine's scaler");
        return 0;
    }
    jd_error err = {0};
    if (jd_renderer_resize(s->renderer, w, h, &err)) {
        fprintf(stderr, "jade kiosk: %s\n", err.msg);
        return 1;
    }
    printf("kiosk: the display engine enlarges %dx%d to %dx%d (the plane's scaler); no GL pass does\n", w, h, dw, dh);
    return 0;
}

static double kiosk_times[KIOSK_SAMPLES], kiosk_sorted[KIOSK_SAMPLES];
static char kiosk_store[2][65536]; /* the configuration's text, this one and the next */

int jd_cmd_kiosk(int argc, char **argv)
{
    jd_options o;
    jd_options_defaults(&o);
    o.platform = "drm";
    int rc = jd_options_command(&o, JD_OPT_KIOSK, "kiosk", kiosk_summary, argc, argv);
    if (rc >= 0) return rc;
    int cur = 0;
    if (o.config && !kiosk_options(&o, o.config, argc, argv, kiosk_store[cur], sizeof kiosk_store[0])) return 2;
    o.fullscreen = 1;
    if (o.screenshot && strcmp(o.platform, "drm") != 0) {
        fprintf(stderr, "jade kiosk: --screenshot reads back what a display scans out, which only --platform drm can\n");
        return 2;
    }
    jd_quit_on_signals();
    jd_session s;
    if (!jd_session_open(&s, &o, "kiosk")) {
        int stopped = s.stopped;
        jd_session_close(&s);
        return stopped ? 0 : 1;
    }
    jd_error err = {0};
    double *times = kiosk_times, *sorted = kiosk_sorted;
    fprintf(stderr, "%s\n", jd_platform_describe(s.platform));
    if (enlarge_on_display(&s, &o)) {
        jd_session_close(&s);
        return 1;
    }
    fprintf(stderr, "%s\n", jd_antialias_describe(s.renderer)); /* as drawn now: the scaler changes it */
    jd_scene sc = o.scene;
    double t_start = jd_clock_ms(), t_prev = t_start, t_log = t_start, t_input = -1e300, t_ease = t_start;
    /* The user's turn of the camera, eased back to the scene's own once
     * --idle seconds pass without input. */
    float turn_az = 0, turn_el = 0;
    int touched = 0;
    long frames = 0, frames_logged = 0;
    rc = 0;
    while (!o.frames || frames < o.frames) {
        jd_event ev;
        int quit = 0, reread = 0;
        while (jd_platform_poll(s.platform, &ev)) {
            if (ev.type == JD_EVENT_QUIT) quit = 1;
            else if (ev.type == JD_EVENT_RELOAD) reread = 1;
            else if (ev.type == JD_EVENT_RESIZE && jd_renderer_resize(s.renderer, ev.w, ev.h, &err)) {
                /* A display plugged in with another mode (drm): within the
                 * size the budget was taken for, which the platform keeps. */
                fprintf(stderr, "jade kiosk: %s\n", err.msg);
                rc = 1;
                quit = 1;
            } else if (ev.type == JD_EVENT_RESIZE) {
                /* The tier follows the size: said again with it. */
                jd_renderer_info info;
                jd_renderer_get_info(s.renderer, &info);
                printf("kiosk: the display is now %dx%d%s%s\n", ev.w, ev.h, info.tier ? "; " : "",
                       info.tier ? info.tier : "");
                if (enlarge_on_display(&s, &o)) {
                    rc = 1;
                    quit = 1;
                }
            }
            else if (ev.type == JD_EVENT_DRAG) {
                int w, h; /* the drag is in the display's pixels, whatever size the picture is drawn at */
                jd_platform_display_size(s.platform, &w, &h);
                /* A drag across the whole screen turns the object half round;
                 * on a panel mounted turned (--rotate, counter-clockwise),
                 * the drag is turned back into the picture's directions. */
                float per_px = 180.0f / (float)(w > h ? w : h), dx = ev.dx, dy = ev.dy;
                if (o.rotation == 90) dx = -ev.dy, dy = ev.dx;
                else if (o.rotation == 180) dx = -ev.dx, dy = -ev.dy;
                else if (o.rotation == 270) dx = ev.dy, dy = -ev.dx;
                turn_az -= dx * per_px;
                turn_el += dy * per_px;
                if (!touched)
                    printf("kiosk: touched at %.1f s: the object follows, and turns back after %g s without input\n",
                           (jd_clock_ms() - t_start) / 1000.0, o.idle_s);
                touched = 1;
                t_input = jd_clock_ms();
            }
        }
        if (quit) break;
        if (reread) {
            reload(&s, &o, &sc, argc, argv, kiosk_store, &cur);
            if (!s.renderer) { rc = 1; break; }
        }
        double now = jd_clock_ms(), dt = now - t_ease;
        t_ease = now;
        if (now - t_input > o.idle_s * 1000.0) {
            /* Back to the idle animation, by half every 0.4 s of clock. */
            float k = (float)exp(-dt / 577.0);
            turn_az = fabsf(turn_az) < 0.1f ? 0 : turn_az * k; /* then exactly still */
            turn_el = fabsf(turn_el) < 0.1f ? 0 : turn_el * k;
            if (touched && turn_az == 0 && turn_el == 0) {
                printf("kiosk: back in place at %.1f s, after %g s without input\n", (now - t_start) / 1000.0, o.idle_s);
                touched = 0;
            }
        }
        sc.cam_azimuth = o.scene.cam_azimuth + turn_az;
        float el = o.scene.cam_elevation + turn_el;
        sc.cam_elevation = el > 85 ? 85 : el < -85 ? -85 : el;
        turn_el = sc.cam_elevation - o.scene.cam_elevation;
        /* By the clock, so the motion stays smooth when frames are dropped;
         * wrapped, so float precision holds over months. A still light
         * keeps the scene unchanged and the renderer reuses its work. */
        if (o.light_speed != 0.0f)
            sc.light_azimuth = o.scene.light_azimuth +
                               (float)fmod((now - t_start) / 1000.0 * (double)o.light_speed, 360.0);
        if (jd_renderer_frame(s.renderer, &sc, NULL, &err) || jd_platform_present(s.platform, &err)) {
            fprintf(stderr, "jade kiosk: %s\n", err.msg);
            rc = 1;
            break;
        }
        now = jd_clock_ms();
        times[frames % KIOSK_SAMPLES] = now - t_prev;
        t_prev = now;
        frames++;
        if (o.log_every > 0 && now - t_log >= o.log_every * 1000.0) {
            health_line(&s, times, sorted, frames, frames - frames_logged, now - t_start);
            frames_logged = frames;
            t_log = now;
        }
    }
    if (o.screenshot && rc == 0 && capture(&s, o.screenshot)) rc = 1;
    if (frames > 0) {
        int n = frames < KIOSK_SAMPLES ? (int)frames : KIOSK_SAMPLES;
        memcpy(sorted, times, sizeof(double) * (size_t)n);
        jd_sort_times(sorted, n);
        jd_present_stats ps;
        jd_platform_present_stats(s.platform, &ps);
        printf("kiosk: %ld frames in %.1f s, frame time median %.2f ms, p95 %.2f ms, missed vblanks %u",
               frames, (t_prev - t_start) / 1000.0, jd_percentile(sorted, n, 0.5), jd_percentile(sorted, n, 0.95),
               ps.missed_vblanks);
        if (ps.refresh_hz > 0)
            printf(" (display %.0f Hz), page flips %u, modesets %u", ps.refresh_hz, ps.flips, ps.modesets);
        if (ps.in_fences || ps.out_fences) printf(", fences in %u out %u", ps.in_fences, ps.out_fences);
        printf("\n");
    }
    jd_session_close(&s);
    return rc;
}
