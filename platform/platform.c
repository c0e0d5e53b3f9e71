/* Dispatch to the platform chosen at open, and what all of them share. */
#include "backend.h"
#include "clock.h"

#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include <EGL/egl.h>
#include <GLES2/gl2.h>

struct jd_platform {
    const jd_platform_ops *ops;
    void *impl;
    int quit_reported; /* a signal's QUIT is one event, not one on every poll */
    int reload_seen;   /* SIGHUPs already reported */
};

static struct jd_platform g_platform; /* one display per process */

static const jd_platform_ops *const backends[] = {
    &jd_headless_ops,
#ifdef JD_HAVE_X11
    &jd_x11_ops,
#endif
#ifdef JD_HAVE_DRM
    &jd_drm_ops,
#endif
};

static const jd_platform_ops *find_backend(const char *kind, jd_error *err)
{
    for (size_t i = 0; i < sizeof backends / sizeof backends[0]; i++)
        if (strcmp(backends[i]->kind, kind) == 0) return backends[i];
    char have[64] = "";
    for (size_t i = 0; i < sizeof backends / sizeof backends[0]; i++)
        snprintf(have + strlen(have), sizeof have - strlen(have), "%s%s", i ? ", " : "", backends[i]->kind);
    jd_fail(err, JD_ERR_ARG, "platform '%s' is not built into this program (have: %s)", kind, have);
    return NULL;
}

jd_result jd_platform_probe(const jd_platform_desc *desc, jd_error *err)
{
    const jd_platform_ops *ops = find_backend(desc->kind ? desc->kind : "headless", err);
    if (!ops) return JD_ERR_ARG;
    return ops->probe ? ops->probe(desc, err) : JD_OK;
}

jd_result jd_platform_open(const jd_platform_desc *desc, jd_platform **out, jd_error *err)
{
    if (g_platform.ops) return jd_fail(err, JD_ERR_PLATFORM, "a platform is already open");
    const jd_platform_ops *ops = find_backend(desc->kind ? desc->kind : "headless", err);
    if (!ops) return JD_ERR_ARG;
    jd_result r = ops->open(desc, &g_platform.impl, err);
    if (r) return r;
    g_platform.ops = ops;
    g_platform.reload_seen = jd_reload_count();
    *out = &g_platform;
    return JD_OK;
}

void jd_platform_size(const jd_platform *p, int *w, int *h) { p->ops->size(p->impl, w, h); }
void jd_platform_max_size(const jd_platform *p, int *w, int *h) { p->ops->max_size(p->impl, w, h); }
int jd_platform_scale_out(jd_platform *p, int w, int h) { return p->ops->scale_out ? p->ops->scale_out(p->impl, w, h) : 0; }
void jd_platform_display_size(const jd_platform *p, int *w, int *h)
{
    if (p->ops->display_size) p->ops->display_size(p->impl, w, h);
    else p->ops->size(p->impl, w, h);
}
unsigned jd_platform_framebuffer(const jd_platform *p) { return p->ops->framebuffer(p->impl); }
int jd_platform_samples(const jd_platform *p)
{
    if (p->ops->samples) return p->ops->samples(p->impl);
    GLint samples = 0, was = 0;
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &was);
    glBindFramebuffer(GL_FRAMEBUFFER, jd_platform_framebuffer(p));
    glGetIntegerv(GL_SAMPLES, &samples);
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)was);
    return samples;
}
jd_result jd_platform_present(jd_platform *p, jd_error *err) { return p->ops->present(p->impl, err); }
int jd_platform_poll(jd_platform *p, jd_event *ev)
{
    /* Reported once: callers drain events with while (poll), and a QUIT
     * returned on every call kept a signalled kiosk spinning for ever. */
    if (jd_quit_requested() && !p->quit_reported) {
        p->quit_reported = 1;
        ev->type = JD_EVENT_QUIT;
        return 1;
    }
    if (jd_reload_count() != p->reload_seen) {
        p->reload_seen = jd_reload_count();
        memset(ev, 0, sizeof *ev);
        ev->type = JD_EVENT_RELOAD;
        return 1;
    }
    return p->ops->poll(p->impl, ev);
}
void jd_platform_present_stats(const jd_platform *p, jd_present_stats *st)
{
    memset(st, 0, sizeof *st);
    p->ops->stats(p->impl, st);
}
const char *jd_platform_describe(const jd_platform *p) { return p->ops->describe(p->impl); }
void *jd_platform_gl_proc(const char *name) { return (void *)eglGetProcAddress(name); }

/* The core's monotonic clock: every figure jade prints comes from one. */
double jd_platform_time_ms(void) { return jd_clock_ms(); }

jd_result jd_platform_read_rgba(jd_platform *p, uint8_t *dst, jd_error *err)
{
    int w, h;
    jd_platform_size(p, &w, &h);
    return jd_read_rgba_flipped(jd_platform_framebuffer(p), w, h, dst, err);
}

jd_result jd_platform_capture(jd_platform *p, uint8_t *dst, jd_error *err)
{
    if (!p->ops->capture)
        return jd_fail(err, JD_ERR_UNSUPPORTED, "the %s platform cannot read back what a display scans out "
                       "(only drm can, through a writeback connector)", p->ops->kind);
    return p->ops->capture(p->impl, dst, err);
}

void jd_platform_close(jd_platform *p)
{
    if (!p || !p->ops) return;
    p->ops->close(p->impl);
    memset(p, 0, sizeof *p);
}

jd_result jd_read_rgba_flipped(unsigned fbo, int w, int h, uint8_t *dst, jd_error *err)
{
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, dst);
    if (glGetError() != GL_NO_ERROR) return jd_fail(err, JD_ERR_GL, "glReadPixels failed");
    /* GL rows run bottom-up; images run top-down. Swap in place, no scratch. */
    size_t row = (size_t)w * 4;
    for (int y = 0; y < h / 2; y++) {
        uint8_t *a = dst + row * (size_t)y, *b = dst + row * (size_t)(h - 1 - y);
        for (size_t i = 0; i < row; i++) { uint8_t t = a[i]; a[i] = b[i]; b[i] = t; }
    }
    return JD_OK;
}

static volatile sig_atomic_t quit_flag, reload_count;
static void on_signal(int sig)
{
    if (sig == SIGHUP) reload_count++;
    else quit_flag = 1;
}

void jd_quit_on_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    /* Not reset after the first: a second SIGTERM or SIGINT while the kiosk
     * gives the display back only sets the flag again, and never kills it
     * half-way through the restore. Interrupted calls resume. */
    sa.sa_handler = on_signal;
    sa.sa_flags = SA_RESTART;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
}

int jd_quit_requested(void) { return quit_flag; }
int jd_reload_count(void) { return reload_count; }
