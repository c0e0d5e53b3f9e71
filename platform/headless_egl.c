/* Headless GLES 2.0 through EGL: Mesa's surfaceless platform first, then the
 * EGL device platform (NVIDIA), then the default display with a pbuffer.
 * Frames go to an offscreen framebuffer object of the requested size. */
#include "backend.h"
#include "egl_setup.h"
#include "gl_caps.h" /* jd_extension_listed */

#include <stdio.h>
#include <string.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES2/gl2.h>
#include <GLES2/gl2ext.h>

#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif

struct jd_platform_headless {
    EGLDisplay dpy;
    EGLContext ctx;
    EGLSurface surf;
    GLuint fbo, color, depth;
    int w, h;
    int samples; /* attached with EXT_multisampled_render_to_texture, else 0 */
    char describe[160];
};

typedef struct jd_platform_headless jd_headless;
static jd_headless g_headless; /* one context per process is all jade needs */

/* Tries one display: initialise, pick an ES2 config, create a context and make
 * it current, surfaceless if the display allows, else on a 1x1 pbuffer. */
static int try_display(jd_headless *p, EGLDisplay dpy, const char *how)
{
    if (dpy == EGL_NO_DISPLAY) return 0;
    EGLint major, minor;
    if (!eglInitialize(dpy, &major, &minor)) return 0;
    const char *exts = eglQueryString(dpy, EGL_EXTENSIONS);
    int surfaceless = jd_extension_listed(exts, "EGL_KHR_surfaceless_context");
    const EGLint cfg_attr[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES2_BIT,
                               EGL_SURFACE_TYPE, surfaceless ? 0 : EGL_PBUFFER_BIT,
                               EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_NONE};
    EGLConfig cfg;
    EGLint n = 0;
    if (!eglBindAPI(EGL_OPENGL_ES_API) || !eglChooseConfig(dpy, cfg_attr, &cfg, 1, &n) || n < 1) {
        eglTerminate(dpy);
        return 0;
    }
    EGLContext ctx = jd_egl_es2_context(dpy, cfg);
    if (ctx == EGL_NO_CONTEXT) { eglTerminate(dpy); return 0; }
    EGLSurface surf = EGL_NO_SURFACE;
    if (!surfaceless) {
        const EGLint pb[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
        surf = eglCreatePbufferSurface(dpy, cfg, pb);
        if (surf == EGL_NO_SURFACE) { eglDestroyContext(dpy, ctx); eglTerminate(dpy); return 0; }
    }
    if (!eglMakeCurrent(dpy, surf, surf, ctx)) {
        if (surf != EGL_NO_SURFACE) eglDestroySurface(dpy, surf);
        eglDestroyContext(dpy, ctx);
        eglTerminate(dpy);
        return 0;
    }
    p->dpy = dpy;
    p->ctx = ctx;
    p->surf = surf;
    snprintf(p->describe, sizeof p->describe, "EGL %d.%d %s%s (%s)", major, minor, how,
             surfaceless ? "" : " + pbuffer", eglQueryString(dpy, EGL_VENDOR));
    return 1;
}

static int open_any_display(jd_headless *p)
{
    /* Empty attribute lists, never NULL: some drivers read them unchecked. */
    static const EGLint no_attribs[] = {EGL_NONE};
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (get_platform_display && jd_extension_listed(client, "EGL_MESA_platform_surfaceless") &&
        try_display(p, get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, no_attribs),
                    "surfaceless"))
        return 1;
    PFNEGLQUERYDEVICESEXTPROC query_devices =
        (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
    if (get_platform_display && query_devices && jd_extension_listed(client, "EGL_EXT_platform_device")) {
        EGLDeviceEXT devs[8];
        EGLint n = 0;
        if (query_devices(8, devs, &n))
            for (EGLint i = 0; i < n; i++)
                if (try_display(p, get_platform_display(EGL_PLATFORM_DEVICE_EXT, devs[i], no_attribs),
                                "device"))
                    return 1;
    }
    return try_display(p, eglGetDisplay(EGL_DEFAULT_DISPLAY), "default display");
}

static void headless_close(void *impl);

static jd_result headless_open(const jd_platform_desc *desc, void **out, jd_error *err)
{
    jd_headless *p = &g_headless;
    memset(p, 0, sizeof *p);
    p->w = desc->width > 0 ? desc->width : 512;
    p->h = desc->height > 0 ? desc->height : 512;
    if (!open_any_display(p))
        return jd_fail(err, JD_ERR_PLATFORM,
                       "no EGL display gives a GLES 2.0 context (tried surfaceless, device, default; "
                       "is libegl-mesa0 installed?)");
    GLint max_rb = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_rb);
    if (p->w > max_rb || p->h > max_rb) {
        int w = p->w, h = p->h;
        headless_close(p);
        return jd_fail(err, JD_ERR_UNSUPPORTED, "size %dx%d exceeds this GPU's limit of %d", w, h, max_rb);
    }
    /* An RGBA8 texture as colour target (core ES 2.0 has no RGBA8
     * renderbuffer), power-of-two sized for drivers without NPOT targets;
     * frames use the w x h corner. */
    int tw = 1, th = 1;
    while (tw < p->w) tw <<= 1;
    while (th < p->h) th <<= 1;
    glGenTextures(1, &p->color);
    glBindTexture(GL_TEXTURE_2D, p->color);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, tw, th, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glGenRenderbuffers(1, &p->depth);
    glBindRenderbuffer(GL_RENDERBUFFER, p->depth);
    glGenFramebuffers(1, &p->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, p->fbo);
    GLenum st = 0;
    /* EXT_multisampled_render_to_texture: 4x samples that live in a tiler's
     * tile buffer only and are resolved as tiles are written out, so the
     * target stays an ordinary texture. Untried where jade was developed
     * (llvmpipe lacks it); an incomplete framebuffer falls back to none. */
    const char *gl_exts = (const char *)glGetString(GL_EXTENSIONS);
    PFNGLRENDERBUFFERSTORAGEMULTISAMPLEEXTPROC storage_ms =
        (PFNGLRENDERBUFFERSTORAGEMULTISAMPLEEXTPROC)eglGetProcAddress("glRenderbufferStorageMultisampleEXT");
    PFNGLFRAMEBUFFERTEXTURE2DMULTISAMPLEEXTPROC texture_ms =
        (PFNGLFRAMEBUFFERTEXTURE2DMULTISAMPLEEXTPROC)eglGetProcAddress("glFramebufferTexture2DMultisampleEXT");
    if (!desc->single_sample && jd_extension_listed(gl_exts, "GL_EXT_multisampled_render_to_texture") && storage_ms && texture_ms) {
        storage_ms(GL_RENDERBUFFER, 4, GL_DEPTH_COMPONENT16, tw, th);
        texture_ms(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, p->color, 0, 4);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, p->depth);
        st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        while (glGetError() != GL_NO_ERROR) {}
        p->samples = st == GL_FRAMEBUFFER_COMPLETE ? 4 : 0;
    }
    if (st != GL_FRAMEBUFFER_COMPLETE) {
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT16, tw, th);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, p->color, 0);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, p->depth);
        st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    }
    if (st != GL_FRAMEBUFFER_COMPLETE) {
        headless_close(p);
        return jd_fail(err, JD_ERR_PLATFORM, "offscreen framebuffer %dx%d incomplete (0x%x)", tw, th, st);
    }
    *out = p;
    return JD_OK;
}

static void headless_size(const void *impl, int *w, int *h)
{
    const jd_headless *p = impl;
    *w = p->w;
    *h = p->h;
}

static unsigned headless_framebuffer(const void *impl) { return ((const jd_headless *)impl)->fbo; }
static const char *headless_describe(const void *impl) { return ((const jd_headless *)impl)->describe; }
static int headless_samples(const void *impl) { return ((const jd_headless *)impl)->samples; }

static jd_result headless_present(void *impl, jd_error *err)
{
    (void)impl;
    (void)err;
    glFlush(); /* nothing to show; the frame stays in the FBO for readback */
    return JD_OK;
}

static int headless_poll(void *impl, jd_event *ev)
{
    (void)impl;
    (void)ev;
    return 0;
}

static void headless_stats(const void *impl, jd_present_stats *st)
{
    (void)impl;
    (void)st;
}

static void headless_close(void *impl)
{
    jd_headless *p = impl;
    if (!p || !p->dpy) return;
    if (p->fbo) glDeleteFramebuffers(1, &p->fbo);
    if (p->color) glDeleteTextures(1, &p->color);
    if (p->depth) glDeleteRenderbuffers(1, &p->depth);
    eglMakeCurrent(p->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (p->surf != EGL_NO_SURFACE) eglDestroySurface(p->dpy, p->surf);
    eglDestroyContext(p->dpy, p->ctx);
    eglTerminate(p->dpy);
    memset(p, 0, sizeof *p);
}

const jd_platform_ops jd_headless_ops = {
    "headless", NULL, headless_open, headless_size, headless_size, headless_framebuffer, headless_present,
    headless_poll, headless_stats, headless_describe, headless_close, NULL /* no display to read back */,
    NULL /* nothing to scan out */, NULL, headless_samples,
};
