/* What each platform file provides to platform.c. */
#ifndef JD_PLATFORM_BACKEND_H
#define JD_PLATFORM_BACKEND_H

#include "platform.h"

typedef struct jd_platform_ops {
    const char *kind;
    /* Cheap check that the display can be had, before any GL (optional). */
    jd_result (*probe)(const jd_platform_desc *desc, jd_error *err);
    jd_result (*open)(const jd_platform_desc *desc, void **impl, jd_error *err);
    void (*size)(const void *impl, int *w, int *h);
    void (*max_size)(const void *impl, int *w, int *h);
    unsigned (*framebuffer)(const void *impl);
    jd_result (*present)(void *impl, jd_error *err);
    int (*poll)(void *impl, jd_event *ev);
    void (*stats)(const void *impl, jd_present_stats *st);
    const char *(*describe)(const void *impl);
    void (*close)(void *impl);
    /* What the display scans out, as top-down RGBA rows of display_size (optional). */
    jd_result (*capture)(void *impl, uint8_t *dst, jd_error *err);
    /* The display engine enlarging a w x h drawable (optional: 0). */
    int (*scale_out)(void *impl, int w, int h);
    /* The size the display shows (optional: size). */
    void (*display_size)(const void *impl, int *w, int *h);
    /* Samples per pixel of framebuffer (optional: GL_SAMPLES of it). */
    int (*samples)(const void *impl);
} jd_platform_ops;

extern const jd_platform_ops jd_headless_ops;
#ifdef JD_HAVE_X11
extern const jd_platform_ops jd_x11_ops;
#endif
#ifdef JD_HAVE_DRM
extern const jd_platform_ops jd_drm_ops;
#endif

/* Shared by the EGL backends: the frame's pixels, flipped to top-down rows. */
jd_result jd_read_rgba_flipped(unsigned fbo, int w, int h, uint8_t *dst, jd_error *err);

#endif
