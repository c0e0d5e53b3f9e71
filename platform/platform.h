/* The one small interface every platform implements: a GLES 2.0 context and
 * somewhere to draw. Knows nothing of translucency. */
#ifndef JD_PLATFORM_H
#define JD_PLATFORM_H

#include <stdint.h>
#include "jd_result.h"

typedef struct jd_platform jd_platform;

typedef struct jd_platform_desc {
    const char *kind; /* "headless" [default] */
    int width, height; /* [512 x 512] */
} jd_platform_desc;

jd_result jd_platform_open(const jd_platform_desc *desc, jd_platform **out, jd_error *err);
void jd_platform_size(const jd_platform *p, int *w, int *h);
/* The GL framebuffer object frames go to (0 for a window surface). */
unsigned jd_platform_framebuffer(const jd_platform *p);
jd_result jd_platform_present(jd_platform *p, jd_error *err);
/* Top-down RGBA8 rows of the last frame, w*h*4 bytes into dst. */
jd_result jd_platform_read_rgba(jd_platform *p, uint8_t *dst, jd_error *err);
void *jd_platform_proc(const jd_platform *p, const char *name);
/* The same for the platform that is open, as a plain function for the core. */
void *jd_platform_gl_proc(const char *name);
/* One line: which EGL path was taken, e.g. "EGL 1.5 surfaceless (Mesa Project)". */
const char *jd_platform_describe(const jd_platform *p);
void jd_platform_close(jd_platform *p);

#endif
