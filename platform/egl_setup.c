#include "egl_setup.h"

#include <stddef.h>

EGLConfig jd_egl_window_config(EGLDisplay dpy, int single_sample, EGLint visual)
{
    const EGLint attr[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES2_BIT, EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RED_SIZE, 8,
                           EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_DEPTH_SIZE, 16, EGL_NONE};
    EGLConfig cfgs[64], best = NULL;
    EGLint n = 0, best_samples = -1, max_samples = single_sample ? 1 : 4;
    if (!eglBindAPI(EGL_OPENGL_ES_API) || !eglChooseConfig(dpy, attr, cfgs, 64, &n)) return NULL;
    for (EGLint i = 0; i < n; i++) {
        EGLint id = 0, samples = 0;
        if (visual && (!eglGetConfigAttrib(dpy, cfgs[i], EGL_NATIVE_VISUAL_ID, &id) || id != visual)) continue;
        eglGetConfigAttrib(dpy, cfgs[i], EGL_SAMPLES, &samples);
        if (samples > max_samples) continue;
        if (samples > best_samples) { best = cfgs[i]; best_samples = samples; }
    }
    return best;
}

EGLContext jd_egl_es2_context(EGLDisplay dpy, EGLConfig cfg)
{
    const EGLint attr[] = {EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE};
    return eglCreateContext(dpy, cfg, EGL_NO_CONTEXT, attr);
}
