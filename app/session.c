#include "session.h"

#include "gl_debug.h"
#include "image_out.h"
#include "profile.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#ifndef JD_ASSET_INSTALL_DIR
#define JD_ASSET_INSTALL_DIR "/usr/local/share/jade"
#endif


int jd_default_asset(char *out, size_t cap)
{
    char exe[4096];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = 0;
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = 0;
            snprintf(out, cap, "%s/../assets/default.drc", exe);
            if (access(out, R_OK) == 0) return 1;
            /* Installed: PREFIX/bin/jade finds PREFIX/share/jade, wherever
             * the prefix was moved to. */
            snprintf(out, cap, "%s/../share/jade/default.drc", exe);
            if (access(out, R_OK) == 0) return 1;
            snprintf(out, cap, "%s/assets/default.drc", exe);
            if (access(out, R_OK) == 0) return 1;
        }
    }
    snprintf(out, cap, "%s/default.drc", JD_ASSET_INSTALL_DIR);
    return access(out, R_OK) == 0;
}

/* A load's failure in one line; a decode stopped at its deadline says
 * how to give it more (a board's slower cores take longer over a large
 * mesh than the default allows for). */
static void say_load_failure(const char *cmd, jd_result r, const jd_error *err)
{
    fprintf(stderr, "jade %s: %s%s\n", cmd, err->msg,
            r == JD_ERR_TIMEOUT ? " (--decode-timeout-ms N gives it N ms)" : "");
}

/* The mesh path, the memory budget and the decoded mesh: all a command
 * needs before any display. */
static int load_mesh(jd_session *s, jd_options *o, const char *cmd)
{
    jd_error err = {0};
    /* The one allocation of the run: everything the core keeps lives here.
     * Without --budget-mb it follows the job: 8 MiB for the core, the
     * output pictures at this size, and, should the mesh not fit, twice as
     * much until it does (up to 2 GiB), settled before any frame. */
    size_t budget = (size_t)o->budget_mb << 20;
    if (!o->has_budget) budget += (size_t)o->width * (size_t)o->height * 4 * (o->sheet ? JD_MODE_COUNT + 2 : 2);
    for (;;) {
        s->memory = malloc(budget);
        if (!s->memory) {
            fprintf(stderr, "jade %s: cannot reserve a memory budget of %zu MiB\n", cmd, budget >> 20);
            return 0;
        }
        jd_arena_init(&s->arena, s->memory, budget);
        /* Before any GL: the loader forks, and a GL driver may have threads. */
        jd_load_desc ld = o->load;
        ld.path = s->mesh_path;
        ld.allow_32bit_indices = 1; /* the renderer checks the device later */
        jd_result r = jd_mesh_load_draco(&ld, &s->arena, &s->mesh, &s->load, &err);
        if (r == JD_OK) {
            jd_options_file_material(o, &s->load, s->mesh_path, cmd);
            return 1;
        }
        free(s->memory);
        s->memory = NULL;
        if (r != JD_ERR_BUDGET || o->has_budget || budget >= ((size_t)1 << 31) / 2) {
            say_load_failure(cmd, r, &err);
            return 0;
        }
        budget *= 2;
    }
}

static int mesh_path(jd_session *s, jd_options *o, const char *cmd)
{
    if (o->mesh) {
        snprintf(s->mesh_path, sizeof s->mesh_path, "%s", o->mesh);
    } else if (!jd_default_asset(s->mesh_path, sizeof s->mesh_path)) {
        fprintf(stderr, "jade %s: the default asset default.drc is not beside the program or in %s; pass --mesh\n", cmd,
                JD_ASSET_INSTALL_DIR);
        return 0;
    }
    /* The run's inputs are never written over; its outputs are checked
     * before any work (a reference takes a minute). */
    jd_output_protect(s->mesh_path);
    jd_output_protect(o->sheet_ref);
    const char *outs[] = {o->out, o->sheet, o->pfm, o->mask_out, o->screenshot};
    for (size_t i = 0; i < sizeof outs / sizeof outs[0]; i++) {
        jd_error err = {0};
        if (outs[i] && ((outs[i] != o->pfm && jd_picture_kind_of(outs[i], &err) == JD_PICTURE_NONE) ||
                        jd_output_check(outs[i], &err))) {
            fprintf(stderr, "jade %s: %s\n", cmd, err.msg);
            return 0;
        }
    }
    return 1;
}

int jd_session_open_mesh(jd_session *s, jd_options *o, const char *cmd)
{
    memset(s, 0, sizeof *s);
    s->t_start_ms = jd_clock_ms();
    return mesh_path(s, o, cmd) && load_mesh(s, o, cmd);
}

/* The driver's warnings and errors on stderr, one line each. */
static void log_driver(void *user, const char *kind, const char *msg)
{
    if (strcmp(kind, "info") && strcmp(kind, "performance"))
        fprintf(stderr, "jade %s: GL driver %s: %s\n", (const char *)user, kind, msg);
}

static int make_renderer(jd_session *s, jd_options *o, const char *cmd);

/* Probes (open = 0) or opens (1) the platform; with --wait-display, tries
 * again every second, saying so once, until it works or a signal asks to
 * stop (s->stopped). */
static int wait_for(jd_session *s, jd_options *o, const char *cmd, const jd_platform_desc *pd, int open)
{
    int said = 0;
    for (;;) {
        jd_error err = {0};
        jd_result r = open ? jd_platform_open(pd, &s->platform, &err) : jd_platform_probe(pd, &err);
        if (r == JD_OK) {
            if (said) fprintf(stderr, "jade %s: the display is there now\n", cmd);
            return 1;
        }
        if (!o->wait_display) {
            fprintf(stderr, "jade %s: %s\n", cmd, err.msg);
            return 0;
        }
        if (!said) fprintf(stderr, "jade %s: waiting for a display (%s)\n", cmd, err.msg);
        said = 1;
        for (int i = 0; i < 10; i++) {
            if (jd_quit_requested()) {
                s->stopped = 1;
                fprintf(stderr, "jade %s: stopped while waiting for a display\n", cmd);
                return 0;
            }
            struct timespec ts = {0, 100 * 1000 * 1000};
            nanosleep(&ts, NULL);
        }
    }
}

int jd_session_open(jd_session *s, jd_options *o, const char *cmd)
{
    memset(s, 0, sizeof *s);
    s->t_start_ms = jd_clock_ms();
    jd_error err = {0};
    if (!mesh_path(s, o, cmd)) return 0;
    jd_platform_desc pd = {.kind = o->platform ? o->platform : "headless", .width = o->width, .height = o->height,
                           .drm_device = o->drm_device, .connector = o->connector, .display_mode = o->display_mode,
                           /* post asks for the pass alone: a multisampled
                            * target under it would anti-alias twice (and on
                            * an immediate-mode GPU pay the samples' memory
                            * traffic for nothing). */
                           .single_sample = o->rdesc.antialias != JD_AA_AUTO, .fullscreen = o->fullscreen,
                           .kms = o->atomic ? JD_KMS_ATOMIC : (jd_kms_api)o->kms};
    /* No display, no point decoding: say so at once (or, with
     * --wait-display, wait for one: systemd may start the kiosk before the
     * panel is on or the display server has let go of it). */
    if (!wait_for(s, o, cmd, &pd, 0)) return 0;
    if (!load_mesh(s, o, cmd)) return 0;
    if (!wait_for(s, o, cmd, &pd, 1)) return 0;
    jd_gl_debug_enable(jd_platform_gl_proc, log_driver, (void *)cmd);
    /* The drawable decides the size (a display mode, a window). */
    jd_platform_size(s->platform, &o->width, &o->height);
    if (jd_gl_caps_query(&s->caps, &err)) {
        fprintf(stderr, "jade %s: %s\n", cmd, err.msg);
        return 0;
    }
    if (o->profile) jd_profile_apply(jd_profile_find(o->profile), &s->caps);
    return make_renderer(s, o, cmd);
}

/* Another mesh for a running session (a kiosk told to re-read its
 * configuration): the renderer and the old mesh leave the arena, the new
 * mesh and a new renderer take it. Nothing is presented meanwhile, so the
 * display keeps the last frame. Should the new mesh not load or not fit,
 * the old one comes back. */
int jd_session_reload_mesh(jd_session *s, jd_options *o, const char *cmd)
{
    char old[sizeof s->mesh_path];
    memcpy(old, s->mesh_path, sizeof old);
    if (o->mesh) snprintf(s->mesh_path, sizeof s->mesh_path, "%s", o->mesh);
    else if (!jd_default_asset(s->mesh_path, sizeof s->mesh_path)) memcpy(s->mesh_path, old, sizeof old);
    jd_renderer_destroy(s->renderer);
    s->renderer = NULL;
    for (int attempt = 0; attempt < 2; attempt++) {
        jd_error err = {0};
        jd_arena_init(&s->arena, s->memory, s->arena.size);
        jd_load_desc ld = o->load;
        ld.path = s->mesh_path;
        ld.allow_32bit_indices = 1;
        jd_result r = jd_mesh_load_draco(&ld, &s->arena, &s->mesh, &s->load, &err);
        if (r == JD_OK) {
            jd_options_file_material(o, &s->load, s->mesh_path, cmd);
            if (make_renderer(s, o, cmd)) return attempt == 0;
        } else {
            say_load_failure(cmd, r, &err);
        }
        if (attempt == 0) fprintf(stderr, "jade %s: going on with %s\n", cmd, old);
        memcpy(s->mesh_path, old, sizeof old);
    }
    return -1;
}

static int make_renderer(jd_session *s, jd_options *o, const char *cmd)
{
    jd_error err = {0};
    jd_renderer_desc rd = o->rdesc;
    rd.mesh = &s->mesh;
    rd.caps = &s->caps;
    rd.target_fbo = jd_platform_framebuffer(s->platform);
    /* The drawable as it is now: a display that changed mode, or a picture
     * the display engine enlarges, since the session opened. */
    jd_platform_size(s->platform, &rd.width, &rd.height);
    jd_platform_max_size(s->platform, &rd.max_width, &rd.max_height);
    rd.rotation = o->rotation;
    rd.get_proc = jd_platform_gl_proc;
    /* bench --device says the board's display's samples, which the
     * headless target stands in for; otherwise the target's own. */
    if (!rd.target_samples) rd.target_samples = jd_platform_samples(s->platform);
    if (jd_renderer_create(&rd, &s->arena, &s->renderer, &err)) {
        fprintf(stderr, "jade %s: %s: %s\n", cmd, s->mesh_path, err.msg);
        return 0;
    }
    /* What this device cannot run, said once, before the first frame. */
    jd_renderer_info info;
    jd_renderer_get_info(s->renderer, &info);
    if (info.fallback) fprintf(stderr, "jade %s: on this GPU: %s\n", cmd, info.fallback);
    if (info.tier && strcmp(cmd, "info")) /* info --compile builds the enlarging pass; it draws nothing */
        fprintf(stderr, "jade %s: %s; --render-scale 1 for the full resolution\n", cmd, info.tier);
    return 1;
}

void jd_session_close(jd_session *s)
{
    if (s->renderer) jd_renderer_destroy(s->renderer);
    if (s->platform) jd_platform_close(s->platform);
    free(s->memory);
    memset(s, 0, sizeof *s);
}

const char *jd_session_triangles(const jd_session *s, char *buf, size_t cap)
{
    uint32_t n = s->mesh.num_indices / 3, read = s->load.declared_faces;
    if (read && read < n) snprintf(buf, cap, "%u triangles, split to %u where coarse", read, n);
    else if (read && read > n) snprintf(buf, cap, "%u triangles, simplified to %u", read, n);
    else snprintf(buf, cap, "%u triangles", n);
    return buf;
}

const char *jd_antialias_describe(const jd_renderer *r)
{
    static char line[400];
    jd_renderer_info info;
    jd_renderer_get_info(r, &info);
    int samples = info.target_samples;
    if (info.post_antialias && samples > 1 && info.tier)
        /* The target's samples see only the enlarging pass's quad: the
         * picture drawn smaller is smoothed at its own size first. */
        snprintf(line, sizeof line, "anti-aliasing: a pass after the frame on the picture drawn at %dx%d%s, then "
                 "enlarged (the target's %dx multisampling sees only the enlarging%s%s)", info.render_width,
                 info.render_height, info.antialias_edges_only ? ", on the edges its test marks" : "", samples,
                 info.samples_note ? "; " : ": no EXT_multisampled_render_to_texture to draw it with samples",
                 info.samples_note ? info.samples_note : "");
    else if (info.post_antialias)
        snprintf(line, sizeof line, "anti-aliasing: a pass after the frame (the target has no multisampling)%s",
                 info.antialias_edges_only ? ", on the edges its test marks" : "");
    else if (samples > 1 && info.tier && info.picture_samples > 1)
        snprintf(line, sizeof line, "anti-aliasing: %dx multisampling in the picture drawn at %dx%d "
                 "(EXT_multisampled_render_to_texture), then enlarged", info.picture_samples, info.render_width,
                 info.render_height);
    else if (samples > 1 && info.tier)
        /* Drawn smaller into a texture of one sample, with the pass after
         * the frame turned off: the target's samples see only the
         * enlarging pass's quad. */
        snprintf(line, sizeof line, "anti-aliasing: none on the picture drawn at %dx%d (the target's %dx multisampling "
                 "sees only the enlarging%s%s)", info.render_width, info.render_height, samples,
                 info.samples_note ? "; " : ": no EXT_multisampled_render_to_texture to draw it with samples",
                 info.samples_note ? info.samples_note : "");
    else if (samples > 1)
        snprintf(line, sizeof line, "anti-aliasing: %dx multisampling in the target", samples);
    else
        snprintf(line, sizeof line, "anti-aliasing: off");
    return line;
}
