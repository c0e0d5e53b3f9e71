/* x11_drag NAME DX DY: drags across the X window named NAME with the left
 * button, as a finger on a touch screen under X would (ButtonPress, ten
 * motions, ButtonRelease), through XSendEvent: no XTest extension needed.
 * Says first which _NET_WM_STATE atoms the window carries (a full-screen
 * kiosk has _NET_WM_STATE_FULLSCREEN). Exit 0 when the window was found and
 * the events sent. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <X11/Xatom.h>
#include <X11/Xlib.h>

static Window find(Display *d, Window w, const char *name)
{
    char *n = NULL;
    if (XFetchName(d, w, &n) && n) {
        int hit = !strcmp(n, name);
        XFree(n);
        if (hit) return w;
    }
    Window root, parent, *kids = NULL;
    unsigned nk = 0;
    if (!XQueryTree(d, w, &root, &parent, &kids, &nk)) return 0;
    Window found = 0;
    for (unsigned i = 0; i < nk && !found; i++) found = find(d, kids[i], name);
    if (kids) XFree(kids);
    return found;
}

static void send(Display *d, Window w, int type, int x, int y, long mask)
{
    XEvent e;
    memset(&e, 0, sizeof e);
    e.type = type;
    if (type == MotionNotify) {
        e.xmotion.window = w;
        e.xmotion.x = x;
        e.xmotion.y = y;
        e.xmotion.state = Button1Mask;
    } else {
        e.xbutton.window = w;
        e.xbutton.x = x;
        e.xbutton.y = y;
        e.xbutton.button = Button1;
    }
    XSendEvent(d, w, True, mask, &e);
}

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: x11_drag NAME DX DY\n");
        return 2;
    }
    Display *d = XOpenDisplay(NULL);
    if (!d) { fprintf(stderr, "x11_drag: no display\n"); return 1; }
    Window w = find(d, DefaultRootWindow(d), argv[1]);
    if (!w) { fprintf(stderr, "x11_drag: no window named %s\n", argv[1]); return 1; }
    Atom type, *atoms = NULL;
    int format;
    unsigned long n = 0, after;
    printf("x11_drag: _NET_WM_STATE:");
    if (XGetWindowProperty(d, w, XInternAtom(d, "_NET_WM_STATE", False), 0, 16, False, XA_ATOM, &type, &format, &n,
                           &after, (unsigned char **)&atoms) == Success && atoms) {
        for (unsigned long i = 0; i < n; i++) {
            char *name = XGetAtomName(d, atoms[i]);
            printf(" %s", name ? name : "?");
            if (name) XFree(name);
        }
        XFree(atoms);
    }
    printf("\n");
    int dx = atoi(argv[2]), dy = atoi(argv[3]), x = 50, y = 50;
    send(d, w, ButtonPress, x, y, ButtonPressMask);
    for (int i = 1; i <= 10; i++) send(d, w, MotionNotify, x + dx * i / 10, y + dy * i / 10, PointerMotionMask);
    send(d, w, ButtonRelease, x + dx, y + dy, ButtonReleaseMask);
    XSync(d, False);
    XCloseDisplay(d);
    printf("x11_drag: sent a drag of %d,%d px to window 0x%lx\n", dx, dy, (unsigned long)w);
    return 0;
}
