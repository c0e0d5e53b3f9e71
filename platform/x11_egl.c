/* A desktop window through EGL on X11: jade's emulator for developers. */
#include "backend.h"
#include "egl_setup.h"
#include "gl_caps.h" /* jd_extension_listed */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <X11/Xlib.h>
#include <X11/Xatom.h>
#include <X11/Xutil.h>
#include <X11/keysym.h>
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES2/gl2.h>

#ifndef EGL_PLATFORM_X11_KHR
#define EGL_PLATFORM_X11_KHR 0x31D5
#endif

typedef struct x11_platform {
    Display *dpy;
    Window win;
    Colormap cmap;
    Atom wm_delete;
    EGLDisplay edpy;
    EGLContext ctx;
    EGLSurface surf;
    int w, h, screen_w, screen_h;
    int dragging, last_x, last_y, fullscreen;
    char describe[192];
} x11_platform;

static x11_platform g_x11;

static void x11_close(void *impl);

static EGLDisplay egl_display_for(Display *dpy)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    PFNEGLGETPLATFORMDISPLAYEXTPROC get =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    static const EGLint no_attribs[] = {EGL_NONE};
    if (get && jd_extension_listed(client, "EGL_EXT_platform_x11")) return get(EGL_PLATFORM_X11_KHR, dpy, no_attribs);
    return eglGetDisplay((EGLNativeDisplayType)dpy);
}

static jd_result x11_probe(const jd_platform_desc *desc, jd_error *err)
{
    (void)desc;
    const char *name = getenv("DISPLAY");
    if (!name || !*name)
        return jd_fail(err, JD_ERR_PLATFORM, "no X display: DISPLAY is not set (run under X or Xvfb, or use headless)");
    Display *d = XOpenDisplay(NULL);
    if (!d) return jd_fail(err, JD_ERR_PLATFORM, "cannot open the X display '%s'", name);
    XCloseDisplay(d);
    return JD_OK;
}

static jd_result x11_open(const jd_platform_desc *desc, void **out, jd_error *err)
{
    x11_platform *p = &g_x11;
    memset(p, 0, sizeof *p);
    const char *name = getenv("DISPLAY");
    if (!name || !*name)
        return jd_fail(err, JD_ERR_PLATFORM, "no X display: DISPLAY is not set (run under X or Xvfb, or use headless)");
    p->dpy = XOpenDisplay(NULL);
    if (!p->dpy) return jd_fail(err, JD_ERR_PLATFORM, "cannot open the X display '%s'", name);
    int scr = DefaultScreen(p->dpy);
    p->screen_w = DisplayWidth(p->dpy, scr);
    p->screen_h = DisplayHeight(p->dpy, scr);
    p->w = desc->width > 0 ? desc->width : 512;
    p->h = desc->height > 0 ? desc->height : 512;
    p->fullscreen = desc->fullscreen;
    if (p->fullscreen) { /* the whole screen, whatever size was asked */
        p->w = p->screen_w;
        p->h = p->screen_h;
    }
    if (p->w > p->screen_w) p->screen_w = p->w;
    if (p->h > p->screen_h) p->screen_h = p->h;

    EGLint major, minor;
    p->edpy = egl_display_for(p->dpy);
    if (p->edpy == EGL_NO_DISPLAY || !eglInitialize(p->edpy, &major, &minor)) {
        x11_close(p);
        return jd_fail(err, JD_ERR_PLATFORM, "EGL cannot use the X display '%s'", name);
    }
    /* 4x multisampling where a config has it (the renderer then needs no
     * anti-aliasing pass of its own), else none. */
    EGLConfig cfg = jd_egl_window_config(p->edpy, desc->single_sample, 0);
    if (!cfg) {
        x11_close(p);
        return jd_fail(err, JD_ERR_PLATFORM, "no EGL config with RGB8, 16-bit depth and GLES 2.0 on '%s'", name);
    }
    EGLint vid = 0;
    eglGetConfigAttrib(p->edpy, cfg, EGL_NATIVE_VISUAL_ID, &vid);
    XVisualInfo tmpl = {0}, *vi;
    tmpl.visualid = (VisualID)vid;
    int nvi = 0;
    vi = XGetVisualInfo(p->dpy, VisualIDMask, &tmpl, &nvi);
    Visual *visual = vi ? vi->visual : DefaultVisual(p->dpy, scr);
    int depth = vi ? vi->depth : DefaultDepth(p->dpy, scr);
    Window root = RootWindow(p->dpy, scr);
    p->cmap = XCreateColormap(p->dpy, root, visual, AllocNone);
    XSetWindowAttributes wa = {0};
    wa.colormap = p->cmap;
    wa.event_mask = StructureNotifyMask | KeyPressMask | ButtonPressMask | ButtonReleaseMask | PointerMotionMask;
    p->win = XCreateWindow(p->dpy, root, 0, 0, (unsigned)p->w, (unsigned)p->h, 0, depth, InputOutput, visual,
                           CWColormap | CWEventMask, &wa);
    if (vi) XFree(vi);
    XStoreName(p->dpy, p->win, "jade");
    p->wm_delete = XInternAtom(p->dpy, "WM_DELETE_WINDOW", False);
    XSetWMProtocols(p->dpy, p->win, &p->wm_delete, 1);
    if (p->fullscreen) {
        /* EWMH: a window manager shows it full screen, above panels; with
         * none (a bare X server, the usual kiosk), it already covers the
         * screen from 0,0. Set before mapping, as the spec asks. */
        Atom state = XInternAtom(p->dpy, "_NET_WM_STATE", False);
        Atom full = XInternAtom(p->dpy, "_NET_WM_STATE_FULLSCREEN", False);
        XChangeProperty(p->dpy, p->win, state, XA_ATOM, 32, PropModeReplace, (unsigned char *)&full, 1);
        /* No pointer over the picture: an empty 1x1 cursor. */
        static char empty[1] = {0};
        Pixmap blank = XCreateBitmapFromData(p->dpy, p->win, empty, 1, 1);
        XColor black = {0};
        Cursor none = XCreatePixmapCursor(p->dpy, blank, blank, &black, &black, 0, 0);
        XDefineCursor(p->dpy, p->win, none);
        XFreeCursor(p->dpy, none);
        XFreePixmap(p->dpy, blank);
    }
    XMapWindow(p->dpy, p->win);

    /* An empty list, never NULL: some drivers read it unchecked. */
    static const EGLint no_attribs[] = {EGL_NONE};
    p->surf = eglCreateWindowSurface(p->edpy, cfg, (EGLNativeWindowType)p->win, no_attribs);
    p->ctx = jd_egl_es2_context(p->edpy, cfg);
    if (p->surf == EGL_NO_SURFACE || p->ctx == EGL_NO_CONTEXT || !eglMakeCurrent(p->edpy, p->surf, p->surf, p->ctx)) {
        x11_close(p);
        return jd_fail(err, JD_ERR_PLATFORM, "cannot make a GLES 2.0 context current on an X window (0x%x)",
                       eglGetError());
    }
    eglSwapInterval(p->edpy, 1);
    snprintf(p->describe, sizeof p->describe, "EGL %d.%d on X11 display %s (%s), window %dx%d%s", major, minor, name,
             eglQueryString(p->edpy, EGL_VENDOR), p->w, p->h, p->fullscreen ? ", full screen" : "");
    *out = p;
    return JD_OK;
}

static void x11_size(const void *impl, int *w, int *h)
{
    const x11_platform *p = impl;
    *w = p->w;
    *h = p->h;
}

static void x11_max_size(const void *impl, int *w, int *h)
{
    const x11_platform *p = impl;
    *w = p->screen_w;
    *h = p->screen_h;
}

static unsigned x11_framebuffer(const void *impl)
{
    (void)impl;
    return 0;
}

static jd_result x11_present(void *impl, jd_error *err)
{
    x11_platform *p = impl;
    if (!eglSwapBuffers(p->edpy, p->surf)) return jd_fail(err, JD_ERR_PLATFORM, "eglSwapBuffers failed (0x%x)", eglGetError());
    return JD_OK;
}

static int x11_poll(void *impl, jd_event *ev)
{
    x11_platform *p = impl;
    memset(ev, 0, sizeof *ev);
    while (XPending(p->dpy)) {
        XEvent e;
        XNextEvent(p->dpy, &e);
        switch (e.type) {
        case ConfigureNotify:
            if (e.xconfigure.width != p->w || e.xconfigure.height != p->h) {
                /* The renderer's targets were sized for the screen: clamp. */
                p->w = e.xconfigure.width < p->screen_w ? e.xconfigure.width : p->screen_w;
                p->h = e.xconfigure.height < p->screen_h ? e.xconfigure.height : p->screen_h;
                ev->type = JD_EVENT_RESIZE;
                ev->w = p->w;
                ev->h = p->h;
                return 1;
            }
            break;
        case ClientMessage:
            if ((Atom)e.xclient.data.l[0] == p->wm_delete) {
                ev->type = JD_EVENT_QUIT;
                return 1;
            }
            break;
        case KeyPress: {
            char buf[8] = "";
            KeySym sym = 0;
            int n = XLookupString(&e.xkey, buf, sizeof buf, &sym, NULL);
            if (sym == XK_Escape) {
                ev->type = JD_EVENT_KEY;
                ev->key = 27;
                return 1;
            }
            if (n == 1) {
                ev->type = JD_EVENT_KEY;
                ev->key = (unsigned char)buf[0];
                return 1;
            }
            break;
        }
        case ButtonPress:
            if (e.xbutton.button == Button1) {
                p->dragging = 1;
                p->last_x = e.xbutton.x;
                p->last_y = e.xbutton.y;
            } else if (e.xbutton.button == Button4 || e.xbutton.button == Button5) {
                ev->type = JD_EVENT_SCROLL;
                ev->dy = e.xbutton.button == Button4 ? 1.0f : -1.0f;
                return 1;
            }
            break;
        case ButtonRelease:
            if (e.xbutton.button == Button1) p->dragging = 0;
            break;
        case MotionNotify:
            if (p->dragging) {
                ev->type = JD_EVENT_DRAG;
                ev->dx = (float)(e.xmotion.x - p->last_x);
                ev->dy = (float)(e.xmotion.y - p->last_y);
                p->last_x = e.xmotion.x;
                p->last_y = e.xmotion.y;
                return 1;
            }
            break;
        default:
            break;
        }
    }
    return 0;
}

static void x11_stats(const void *impl, jd_present_stats *st)
{
    (void)impl;
    (void)st;
}

static const char *x11_describe(const void *impl) { return ((const x11_platform *)impl)->describe; }

static void x11_close(void *impl)
{
    x11_platform *p = impl;
    if (p->edpy) {
        eglMakeCurrent(p->edpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (p->surf) eglDestroySurface(p->edpy, p->surf);
        if (p->ctx) eglDestroyContext(p->edpy, p->ctx);
        eglTerminate(p->edpy);
    }
    if (p->dpy) {
        if (p->win) XDestroyWindow(p->dpy, p->win);
        if (p->cmap) XFreeColormap(p->dpy, p->cmap);
        XCloseDisplay(p->dpy);
    }
    memset(p, 0, sizeof *p);
}

const jd_platform_ops jd_x11_ops = {
    "x11", x11_probe, x11_open, x11_size, x11_max_size, x11_framebuffer, x11_present, x11_poll, x11_stats, x11_describe, x11_close,
    NULL /* the X server composes; no writeback */, NULL /* nor a plane of jade's own to scale */, NULL,
    NULL /* samples: the EGL config's, GL_SAMPLES */,
};
