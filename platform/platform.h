/* The one small interface every platform implements: a GLES 2.0 context,
 * somewhere to draw, and the user's input. Knows nothing of translucency. */
#ifndef JD_PLATFORM_H
#define JD_PLATFORM_H

#include <stdint.h>
#include "jd_result.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct jd_platform jd_platform;

/* How the drm platform sets the mode and shows frames. */
typedef enum jd_kms_api {
    JD_KMS_AUTO = 0, /* atomic where the driver offers it (and takes the first modeset), else legacy */
    JD_KMS_ATOMIC,   /* atomic only: opening fails where the driver has none */
    JD_KMS_LEGACY    /* SetCrtc and PageFlip: no plane scaling, no explicit fences */
} jd_kms_api;

/* Zero fields take the defaults in brackets. */
typedef struct jd_platform_desc {
    const char *kind;         /* "headless" [default], "x11" or "drm" */
    int width, height;        /* [512 x 512]; drm: taken from the display mode */
    int fullscreen;           /* x11: the whole screen (EWMH), no pointer shown */
    int single_sample;        /* no multisampling (else 4x where the EGL config or, headless,
                                 EXT_multisampled_render_to_texture has it) */
    /* drm only */
    const char *drm_device;   /* [the first KMS-capable /dev/dri/card*] */
    const char *connector;    /* e.g. "HDMI-A-1" [the first connected] */
    const char *display_mode; /* "WxH" or "WxH@Hz" [preferred, else largest] */
    jd_kms_api kms;           /* [JD_KMS_AUTO] */
    int atomic;               /* nonzero: the same as kms = JD_KMS_ATOMIC (its older name) */
} jd_platform_desc;

typedef enum jd_event_type {
    JD_EVENT_NONE = 0,
    JD_EVENT_QUIT,   /* window closed, or SIGINT/SIGTERM */
    JD_EVENT_RESIZE, /* w, h */
    JD_EVENT_KEY,    /* key: an ASCII character, or 27 for Escape */
    JD_EVENT_DRAG,   /* dx, dy in pixels, primary button held */
    JD_EVENT_SCROLL, /* dy: +1 away from the user, -1 towards */
    JD_EVENT_RELOAD  /* SIGHUP: re-read the configuration */
} jd_event_type;

typedef struct jd_event {
    jd_event_type type;
    int w, h, key;
    float dx, dy;
} jd_event;

typedef struct jd_present_stats {
    unsigned frames, missed_vblanks; /* missed: flips that took more than one refresh */
    unsigned flips;                  /* page flips the display confirmed (drm: frames - modesets) */
    unsigned modesets;               /* drm: 1, and one more each time a display came back or changed mode */
    unsigned in_fences, out_fences;  /* drm, atomic: commits that carried the GPU's fence; flip fences waited on */
    double refresh_hz;
    int atomic;                      /* drm: the mode is set and frames shown by atomic commits */
} jd_present_stats;

/* Says, in milliseconds and without creating a GL context, whether open
 * could succeed: no such platform, no display, no KMS device. */
jd_result jd_platform_probe(const jd_platform_desc *desc, jd_error *err);
jd_result jd_platform_open(const jd_platform_desc *desc, jd_platform **out, jd_error *err);
void jd_platform_size(const jd_platform *p, int *w, int *h);
/* The largest size the drawable can take (screen size for windows). */
void jd_platform_max_size(const jd_platform *p, int *w, int *h);
/* The GL framebuffer object frames go to (0 for a window surface). */
unsigned jd_platform_framebuffer(const jd_platform *p);
/* Samples per pixel of that framebuffer (0 or 1: one). The headless target
 * says what it attached: Mesa 22.3's GL_SAMPLES reads 0 for a framebuffer
 * whose colour EXT_multisampled_render_to_texture attached with samples
 * (it takes the colour texture's own count), though it draws with them;
 * the others ask GL_SAMPLES, which an EGL config's samples answer. */
int jd_platform_samples(const jd_platform *p);
jd_result jd_platform_present(jd_platform *p, jd_error *err);
/* Top-down RGBA8 rows of the frame just drawn (call before present). */
jd_result jd_platform_read_rgba(jd_platform *p, uint8_t *dst, jd_error *err);
/* Frames drawn at w x h and enlarged by the display engine on their way
 * out (drm, atomic: the primary plane's scaler, where the driver takes it,
 * asked with a test commit), not by a GL pass: the drawable becomes w x h,
 * the display keeps its mode. 1 if taken, 0 if not (nothing changed).
 * The display's own size takes the scaling off again. */
int jd_platform_scale_out(jd_platform *p, int w, int h);
/* The size the display shows: jd_platform_size, or what the display
 * engine enlarges it to (jd_platform_scale_out). */
void jd_platform_display_size(const jd_platform *p, int *w, int *h);
/* What the display controller scans out now, read back by the display
 * hardware itself (drm: a writeback connector on the CRTC; the others
 * have none and say so): top-down RGBA8 rows of jd_platform_display_size. For
 * checking a kiosk's screen from afar, not for every frame: on most
 * drivers it takes a modeset (the connector joins the CRTC) and a wait. */
jd_result jd_platform_capture(jd_platform *p, uint8_t *dst, jd_error *err);
/* 1 and an event while there are some; never blocks. */
int jd_platform_poll(jd_platform *p, jd_event *ev);
void jd_platform_present_stats(const jd_platform *p, jd_present_stats *st);
/* Milliseconds on the monotonic clock: frame pacing and statistics. */
double jd_platform_time_ms(void);
void *jd_platform_gl_proc(const char *name);
/* One line: which path was taken, e.g. "EGL 1.5 surfaceless (Mesa Project)". */
const char *jd_platform_describe(const jd_platform *p);
void jd_platform_close(jd_platform *p);

/* SIGINT and SIGTERM set a flag that jd_platform_poll reports as
 * JD_EVENT_QUIT, so a kiosk always gets to restore the display; each
 * SIGHUP is reported once as JD_EVENT_RELOAD. */
void jd_quit_on_signals(void);
int jd_quit_requested(void);
int jd_reload_count(void); /* SIGHUPs received */

#ifdef __cplusplus
}
#endif

#endif
