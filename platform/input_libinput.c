#include "input.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#ifdef JD_HAVE_LIBINPUT
#include <libinput.h>
#include <libudev.h>

struct jd_input {
    struct udev *udev;
    struct libinput *li;
    int w, h, devices;
    int button;        /* left button held */
    int touching;      /* a finger down (the first one drives) */
    int32_t slot;
    double tx, ty;     /* its last position, screen pixels */
};

static struct jd_input g_input; /* one seat per process, as one display */

/* libinput opens the event devices through these (a logind session would
 * hand them out; a kiosk service in the input group opens them itself). */
static int open_restricted(const char *path, int flags, void *user)
{
    (void)user;
    int fd = open(path, flags | O_CLOEXEC);
    return fd < 0 ? -errno : fd;
}

static void close_restricted(int fd, void *user)
{
    (void)user;
    close(fd);
}

static const struct libinput_interface iface = {open_restricted, close_restricted};

/* Devices announced at start (and plugged in later) are counted if they can
 * turn the object. */
static void count_device(jd_input *in, struct libinput_event *e, int sign)
{
    struct libinput_device *d = libinput_event_get_device(e);
    if (libinput_device_has_capability(d, LIBINPUT_DEVICE_CAP_TOUCH) ||
        libinput_device_has_capability(d, LIBINPUT_DEVICE_CAP_POINTER))
        in->devices += sign;
}

jd_input *jd_input_open(int screen_w, int screen_h, char *why, size_t cap)
{
    jd_input *in = &g_input;
    memset(in, 0, sizeof *in);
    in->w = screen_w;
    in->h = screen_h;
    in->udev = udev_new();
    if (!in->udev) {
        snprintf(why, cap, "udev is not available");
        return NULL;
    }
    in->li = libinput_udev_create_context(&iface, NULL, in->udev);
    if (!in->li || libinput_udev_assign_seat(in->li, "seat0") != 0) {
        snprintf(why, cap, "libinput cannot take seat0");
        jd_input_close(in);
        return NULL;
    }
    /* The devices present now arrive as DEVICE_ADDED events. */
    libinput_dispatch(in->li);
    struct libinput_event *e;
    while (libinput_next_event_type(in->li) == LIBINPUT_EVENT_DEVICE_ADDED && (e = libinput_get_event(in->li))) {
        count_device(in, e, 1);
        libinput_event_destroy(e);
    }
    return in;
}

int jd_input_devices(const jd_input *in) { return in ? in->devices : 0; }

int jd_input_poll(jd_input *in, jd_event *ev)
{
    if (!in) return 0;
    libinput_dispatch(in->li);
    struct libinput_event *e;
    while ((e = libinput_get_event(in->li))) {
        int got = 0;
        memset(ev, 0, sizeof *ev);
        switch (libinput_event_get_type(e)) {
        case LIBINPUT_EVENT_DEVICE_ADDED: count_device(in, e, 1); break;
        case LIBINPUT_EVENT_DEVICE_REMOVED: count_device(in, e, -1); break;
        case LIBINPUT_EVENT_POINTER_BUTTON: {
            struct libinput_event_pointer *p = libinput_event_get_pointer_event(e);
            if (libinput_event_pointer_get_button(p) == 0x110 /* BTN_LEFT */)
                in->button = libinput_event_pointer_get_button_state(p) == LIBINPUT_BUTTON_STATE_PRESSED;
            break;
        }
        case LIBINPUT_EVENT_POINTER_MOTION:
            if (in->button) {
                struct libinput_event_pointer *p = libinput_event_get_pointer_event(e);
                ev->type = JD_EVENT_DRAG;
                ev->dx = (float)libinput_event_pointer_get_dx(p);
                ev->dy = (float)libinput_event_pointer_get_dy(p);
                got = 1;
            }
            break;
        case LIBINPUT_EVENT_TOUCH_DOWN: {
            struct libinput_event_touch *t = libinput_event_get_touch_event(e);
            if (!in->touching) {
                in->touching = 1;
                in->slot = libinput_event_touch_get_seat_slot(t);
                in->tx = libinput_event_touch_get_x_transformed(t, (uint32_t)in->w);
                in->ty = libinput_event_touch_get_y_transformed(t, (uint32_t)in->h);
            }
            break;
        }
        case LIBINPUT_EVENT_TOUCH_MOTION: {
            struct libinput_event_touch *t = libinput_event_get_touch_event(e);
            if (in->touching && libinput_event_touch_get_seat_slot(t) == in->slot) {
                double x = libinput_event_touch_get_x_transformed(t, (uint32_t)in->w);
                double y = libinput_event_touch_get_y_transformed(t, (uint32_t)in->h);
                ev->type = JD_EVENT_DRAG;
                ev->dx = (float)(x - in->tx);
                ev->dy = (float)(y - in->ty);
                in->tx = x;
                in->ty = y;
                got = 1;
            }
            break;
        }
        case LIBINPUT_EVENT_TOUCH_UP:
        case LIBINPUT_EVENT_TOUCH_CANCEL: {
            struct libinput_event_touch *t = libinput_event_get_touch_event(e);
            if (libinput_event_touch_get_seat_slot(t) == in->slot) in->touching = 0;
            break;
        }
        default:
            break;
        }
        libinput_event_destroy(e);
        if (got) return 1;
    }
    return 0;
}

void jd_input_close(jd_input *in)
{
    if (!in) return;
    if (in->li) libinput_unref(in->li);
    if (in->udev) udev_unref(in->udev);
    memset(in, 0, sizeof *in);
}

#else

jd_input *jd_input_open(int screen_w, int screen_h, char *why, size_t cap)
{
    (void)screen_w;
    (void)screen_h;
    snprintf(why, cap, "built without libinput");
    return NULL;
}
int jd_input_devices(const jd_input *in) { (void)in; return 0; }
int jd_input_poll(jd_input *in, jd_event *ev)
{
    (void)in;
    (void)ev;
    return 0;
}
void jd_input_close(jd_input *in) { (void)in; }

#endif
