/* What the EGL platforms share: the config a window draws with and the
 * GLES 2.0 context, set up one way for X11, DRM/KMS and headless. */
#ifndef JD_EGL_SETUP_H
#define JD_EGL_SETUP_H

#include <EGL/egl.h>

/* The config of a window surface: GLES 2.0, 8-bit RGB, 16-bit depth; the
 * most samples up to 4 (multisampling is nearly free on tile-based GPUs,
 * and the renderer then needs no anti-aliasing pass), or single-sampled
 * ones only; with visual non-zero, only configs whose native visual it is
 * (GBM's buffer format). NULL when none matches. */
EGLConfig jd_egl_window_config(EGLDisplay dpy, int single_sample, EGLint visual);
/* A GLES 2.0 context on cfg (EGL_NO_CONTEXT on failure; eglGetError says why). */
EGLContext jd_egl_es2_context(EGLDisplay dpy, EGLConfig cfg);

#endif
