/* Fullscreen on a kiosk without a desktop: DRM/KMS for the display, GBM for
 * the buffers, EGL for the context. One modeset, then page flips paced by
 * vblank events; the original CRTC is put back on close. */
#include "backend.h"
#include "drm_select.h"
#include "egl_setup.h"
#include "gl_caps.h" /* jd_extension_listed */
#include "input.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <linux/netlink.h>

#include <xf86drm.h>
#include <xf86drmMode.h>
#include <gbm.h>
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES2/gl2.h>

#ifndef EGL_PLATFORM_GBM_KHR
#define EGL_PLATFORM_GBM_KHR 0x31D7
#endif

#define MAX_CONNECTORS 16
#define MAX_MODES 64
#define MAX_MODIFIERS 32
#ifndef DRM_FORMAT_MOD_INVALID
#define DRM_FORMAT_MOD_INVALID 0x00ffffffffffffffULL
#endif

typedef struct drm_platform {
    int fd;
    jd_input *input; /* touch screen and mouse, or NULL */
    char device[64], connector_name[32];
    uint32_t connector_id, crtc_id;
    drmModeModeInfo mode;
    drmModeCrtc *saved_crtc;
    struct gbm_device *gbm;
    struct gbm_surface *gbm_surface;
    uint32_t format;
    /* The drawable where the plane's scaler enlarges it to the mode
     * (jd_platform_scale_out, atomic only); 0 x 0: the mode's size. */
    int out_w, out_h;
    EGLDisplay edpy;
    EGLContext ctx;
    EGLSurface surf;
    struct gbm_bo *shown;
    int modeset_done, flip_pending;
    /* Atomic modesetting: the primary plane and the property ids it needs.
     * atomic_auto: chosen, not asked for (JD_KMS_AUTO): a first modeset the
     * driver refuses falls back to legacy. kms_why: why legacy, if so. */
    int atomic, atomic_auto;
    char kms_why[96];
    uint32_t plane_id, mode_blob;
    uint32_t p_conn_crtc, p_crtc_mode, p_crtc_active, p_fb, p_plane_crtc, p_src_x, p_src_y, p_src_w, p_src_h,
        p_crtc_x, p_crtc_y, p_crtc_w, p_crtc_h;
    /* Explicit fences (atomic): the GPU's "rendering done" handed to the
     * plane (IN_FENCE_FD, from EGL_ANDROID_native_fence_sync), so scan-out
     * waits for it even where the display and the GPU are separate devices
     * that share no implicit sync (kmsro boards); the kernel's "flip done"
     * back from the CRTC (OUT_FENCE_PTR), waited on before the next frame. */
    uint32_t p_in_fence, p_out_fence;
    PFNEGLCREATESYNCKHRPROC create_sync;
    PFNEGLDESTROYSYNCKHRPROC destroy_sync;
    PFNEGLDUPNATIVEFENCEFDANDROIDPROC dup_fence;
    unsigned in_fences, out_fences;
    unsigned frames, missed, last_seq, flips, modesets;
    /* Hotplug: the kernel's uevents, the card's name in them, whether the
     * display is gone, what was asked for and the most the budget allows. */
    int uevent_fd;
    char card[32];
    int lost, want_w, want_h, want_hz, max_w, max_h;
    EGLConfig cfg;
    char failed[256]; /* a hotplug that could not be followed, said at the next present */
    /* Buffer layouts: the modifiers the primary plane takes for the format
     * (tiled or compressed scan-out on newer boards), and whether the
     * driver takes framebuffers with modifiers. */
    uint64_t modifiers[MAX_MODIFIERS];
    int num_modifiers, surface_modifiers, fb_modifiers;
    char render_node[64]; /* the GPU's render node, where it is another device (kmsro boards) */
    char describe[640];
} drm_platform;

static drm_platform g_drm;

static void drm_close(void *impl);

static int kms_capable(int fd)
{
    drmModeRes *res = drmModeGetResources(fd);
    int ok = res && res->count_connectors > 0 && res->count_crtcs > 0;
    drmModeFreeResources(res);
    return ok;
}

static jd_result open_device(drm_platform *p, const char *want, jd_error *err)
{
    if (want) {
        p->fd = open(want, O_RDWR | O_CLOEXEC);
        if (p->fd < 0)
            return jd_fail(err, JD_ERR_PLATFORM, "%s: cannot open: %s%s", want, strerror(errno),
                           errno == EACCES ? " (add the user to the 'video' group)" : "");
        if (!kms_capable(p->fd))
            return jd_fail(err, JD_ERR_PLATFORM, "%s: not a KMS display device (no connectors or CRTCs)", want);
        snprintf(p->device, sizeof p->device, "%s", want);
        return JD_OK;
    }
    /* The kernel's own list of DRM devices: the first whose primary node
     * drives a display. On boards whose display engine and GPU are two
     * devices (kmsro: sun4i or rockchip display, lima or panfrost GPU) the
     * GPU's render node is noted; Mesa's GBM on the display node reaches it. */
    drmDevicePtr devs[16];
    int n = drmGetDevices2(0, devs, 16);
    for (int i = 0; i < n && p->fd < 0; i++) {
        if (!(devs[i]->available_nodes & (1 << DRM_NODE_PRIMARY))) continue;
        const char *path = devs[i]->nodes[DRM_NODE_PRIMARY];
        int fd = open(path, O_RDWR | O_CLOEXEC);
        if (fd < 0) continue;
        if (!kms_capable(fd)) { close(fd); continue; }
        p->fd = fd;
        snprintf(p->device, sizeof p->device, "%s", path);
        for (int k = 0; k < n && !p->render_node[0]; k++) {
            int own = k == i;
            if ((devs[k]->available_nodes & (1 << DRM_NODE_RENDER)) && (own || !(devs[i]->available_nodes & (1 << DRM_NODE_RENDER))))
                snprintf(p->render_node, sizeof p->render_node, "%s", devs[k]->nodes[DRM_NODE_RENDER]);
        }
    }
    if (n > 0) drmFreeDevices(devs, n);
    if (p->fd >= 0) return JD_OK;
    for (int i = 0; i < 16 && n < 0; i++) { /* no enumeration (an old kernel): the card nodes in turn */
        char path[32];
        snprintf(path, sizeof path, "/dev/dri/card%d", i);
        int fd = open(path, O_RDWR | O_CLOEXEC);
        if (fd < 0) continue;
        if (kms_capable(fd)) {
            p->fd = fd;
            snprintf(p->device, sizeof p->device, "%s", path);
            return JD_OK;
        }
        close(fd);
    }
    return jd_fail(err, JD_ERR_PLATFORM,
                   "no DRM/KMS display device (no KMS-capable /dev/dri/card*); a kiosk needs a display driver");
}

/* Finds a CRTC for the connector: the one its encoder drives, else the
 * first any of its encoders can use. */
static uint32_t find_crtc(int fd, drmModeRes *res, drmModeConnector *conn)
{
    if (conn->encoder_id) {
        drmModeEncoder *enc = drmModeGetEncoder(fd, conn->encoder_id);
        uint32_t crtc = enc ? enc->crtc_id : 0;
        drmModeFreeEncoder(enc);
        if (crtc) return crtc;
    }
    for (int e = 0; e < conn->count_encoders; e++) {
        drmModeEncoder *enc = drmModeGetEncoder(fd, conn->encoders[e]);
        if (!enc) continue;
        for (int c = 0; c < res->count_crtcs; c++)
            if (enc->possible_crtcs & (1u << c)) {
                drmModeFreeEncoder(enc);
                return res->crtcs[c];
            }
        drmModeFreeEncoder(enc);
    }
    return 0;
}

static jd_result choose_output(drm_platform *p, const jd_platform_desc *desc, jd_error *err)
{
    drmModeRes *res = drmModeGetResources(p->fd);
    if (!res) return jd_fail(err, JD_ERR_PLATFORM, "%s: cannot read KMS resources", p->device);
    static jd_drm_connector info[MAX_CONNECTORS];
    static jd_drm_mode modes[MAX_CONNECTORS][MAX_MODES];
    drmModeConnector *conns[MAX_CONNECTORS] = {0};
    int n = res->count_connectors < MAX_CONNECTORS ? res->count_connectors : MAX_CONNECTORS;
    for (int i = 0; i < n; i++) {
        conns[i] = drmModeGetConnector(p->fd, res->connectors[i]);
        memset(&info[i], 0, sizeof info[i]);
        if (!conns[i]) continue;
        info[i].type = conns[i]->connector_type;
        info[i].type_id = conns[i]->connector_type_id;
        info[i].connected = conns[i]->connection == DRM_MODE_CONNECTED;
        int m = conns[i]->count_modes < MAX_MODES ? conns[i]->count_modes : MAX_MODES;
        for (int k = 0; k < m; k++) {
            modes[i][k].w = conns[i]->modes[k].hdisplay;
            modes[i][k].h = conns[i]->modes[k].vdisplay;
            modes[i][k].hz = (int)conns[i]->modes[k].vrefresh;
            modes[i][k].preferred = (conns[i]->modes[k].type & DRM_MODE_TYPE_PREFERRED) != 0;
        }
        info[i].num_modes = m;
        info[i].modes = modes[i];
    }
    char why[300];
    jd_result r = JD_OK;
    int c = jd_drm_pick_connector(info, n, desc->connector, why, sizeof why);
    if (c < 0) {
        r = jd_fail(err, JD_ERR_PLATFORM, "%s: %s", p->device, why);
        goto done;
    }
    jd_drm_connector_name(&info[c], p->connector_name, sizeof p->connector_name);
    int w = 0, h = 0, hz = 0;
    if (desc->display_mode && !jd_drm_parse_mode(desc->display_mode, &w, &h, &hz)) {
        r = jd_fail(err, JD_ERR_ARG, "display mode '%s' is not WxH or WxH@Hz", desc->display_mode);
        goto done;
    }
    p->want_w = w, p->want_h = h, p->want_hz = hz;
    int m = jd_drm_pick_mode(info[c].modes, info[c].num_modes, w, h, hz);
    if (m < 0) {
        r = jd_fail(err, JD_ERR_PLATFORM, "%s: %s does not offer the mode %s", p->device, p->connector_name,
                    desc->display_mode);
        goto done;
    }
    p->mode = conns[c]->modes[m];
    p->connector_id = conns[c]->connector_id;
    p->crtc_id = find_crtc(p->fd, res, conns[c]);
    if (!p->crtc_id) r = jd_fail(err, JD_ERR_PLATFORM, "%s: no CRTC can drive %s", p->device, p->connector_name);
done:
    for (int i = 0; i < n; i++) drmModeFreeConnector(conns[i]);
    drmModeFreeResources(res);
    return r;
}

static uint32_t prop_id(int fd, uint32_t obj, uint32_t type, const char *name)
{
    drmModeObjectProperties *props = drmModeObjectGetProperties(fd, obj, type);
    uint32_t id = 0;
    for (uint32_t i = 0; props && i < props->count_props && !id; i++) {
        drmModePropertyRes *pr = drmModeGetProperty(fd, props->props[i]);
        if (pr && strcmp(pr->name, name) == 0) id = pr->prop_id;
        drmModeFreeProperty(pr);
    }
    drmModeFreeObjectProperties(props);
    return id;
}

static uint64_t prop_value(int fd, uint32_t obj, uint32_t type, const char *name)
{
    drmModeObjectProperties *props = drmModeObjectGetProperties(fd, obj, type);
    uint64_t v = 0;
    for (uint32_t i = 0; props && i < props->count_props; i++) {
        drmModePropertyRes *pr = drmModeGetProperty(fd, props->props[i]);
        if (pr && strcmp(pr->name, name) == 0) v = props->prop_values[i];
        drmModeFreeProperty(pr);
    }
    drmModeFreeObjectProperties(props);
    return v;
}

/* The CRTC's index in the resources (planes and encoders name CRTCs by
 * it), -1 if it is not there. */
static int crtc_index(drm_platform *p)
{
    drmModeRes *res = drmModeGetResources(p->fd);
    int index = -1;
    for (int i = 0; res && i < res->count_crtcs; i++)
        if (res->crtcs[i] == p->crtc_id) index = i;
    drmModeFreeResources(res);
    return index;
}

/* The primary plane that can feed the CRTC, 0 if none (needs the
 * universal planes capability). */
static uint32_t primary_plane(drm_platform *p)
{
    int index = crtc_index(p);
    uint32_t id = 0;
    drmModePlaneRes *planes = drmModeGetPlaneResources(p->fd);
    for (uint32_t i = 0; planes && index >= 0 && i < planes->count_planes && !id; i++) {
        drmModePlane *pl = drmModeGetPlane(p->fd, planes->planes[i]);
        if (pl && (pl->possible_crtcs & (1u << index)) &&
            prop_value(p->fd, pl->plane_id, DRM_MODE_OBJECT_PLANE, "type") == DRM_PLANE_TYPE_PRIMARY)
            id = pl->plane_id;
        drmModeFreePlane(pl);
    }
    drmModeFreePlaneResources(planes);
    return id;
}

/* Atomic needs the CRTC's primary plane and the ids of the properties a
 * commit sets. */
static jd_result setup_atomic(drm_platform *p, jd_error *err)
{
    if (drmSetClientCap(p->fd, DRM_CLIENT_CAP_UNIVERSAL_PLANES, 1) != 0 ||
        drmSetClientCap(p->fd, DRM_CLIENT_CAP_ATOMIC, 1) != 0)
        return jd_fail(err, JD_ERR_UNSUPPORTED, "%s: the driver does not offer atomic modesetting", p->device);
    p->plane_id = primary_plane(p);
    if (!p->plane_id) return jd_fail(err, JD_ERR_PLATFORM, "%s: no primary plane for the CRTC of %s", p->device, p->connector_name);
    const uint32_t C = DRM_MODE_OBJECT_CONNECTOR, R = DRM_MODE_OBJECT_CRTC, P = DRM_MODE_OBJECT_PLANE;
    p->p_conn_crtc = prop_id(p->fd, p->connector_id, C, "CRTC_ID");
    p->p_crtc_mode = prop_id(p->fd, p->crtc_id, R, "MODE_ID");
    p->p_crtc_active = prop_id(p->fd, p->crtc_id, R, "ACTIVE");
    p->p_fb = prop_id(p->fd, p->plane_id, P, "FB_ID");
    p->p_plane_crtc = prop_id(p->fd, p->plane_id, P, "CRTC_ID");
    p->p_src_x = prop_id(p->fd, p->plane_id, P, "SRC_X");
    p->p_src_y = prop_id(p->fd, p->plane_id, P, "SRC_Y");
    p->p_src_w = prop_id(p->fd, p->plane_id, P, "SRC_W");
    p->p_src_h = prop_id(p->fd, p->plane_id, P, "SRC_H");
    p->p_crtc_x = prop_id(p->fd, p->plane_id, P, "CRTC_X");
    p->p_crtc_y = prop_id(p->fd, p->plane_id, P, "CRTC_Y");
    p->p_crtc_w = prop_id(p->fd, p->plane_id, P, "CRTC_W");
    p->p_crtc_h = prop_id(p->fd, p->plane_id, P, "CRTC_H");
    if (!p->p_conn_crtc || !p->p_crtc_mode || !p->p_crtc_active || !p->p_fb || !p->p_plane_crtc)
        return jd_fail(err, JD_ERR_UNSUPPORTED, "%s: the atomic properties jade needs are missing", p->device);
    p->p_in_fence = prop_id(p->fd, p->plane_id, P, "IN_FENCE_FD");   /* both since Linux 4.10; 0 where absent */
    p->p_out_fence = prop_id(p->fd, p->crtc_id, R, "OUT_FENCE_PTR");
    if (drmModeCreatePropertyBlob(p->fd, &p->mode, sizeof p->mode, &p->mode_blob) != 0)
        return jd_fail(err, JD_ERR_PLATFORM, "%s: cannot create the mode blob: %s", p->device, strerror(errno));
    return JD_OK;
}

/* What the GPU draws: the mode's size, or smaller where the plane's
 * scaler enlarges it. */
static void surface_size(const drm_platform *p, int *w, int *h)
{
    *w = p->out_w ? p->out_w : p->mode.hdisplay;
    *h = p->out_h ? p->out_h : p->mode.vdisplay;
}

/* The first commit sets the mode (ALLOW_MODESET); later ones only move
 * the plane to the new framebuffer and ask for the flip event. modeset 2:
 * the first commit only tried (TEST_ONLY). The plane shows the whole
 * framebuffer over the whole mode: enlarged where it is smaller. in_fence:
 * the GPU's fence for fb, or -1; out_fence: where the kernel puts the
 * flip's fence, or NULL. */
static int atomic_commit(drm_platform *p, uint32_t fb, int modeset, int in_fence, int *out_fence)
{
    int sw, sh;
    surface_size(p, &sw, &sh);
    drmModeAtomicReq *req = drmModeAtomicAlloc();
    if (!req) return -1;
    if (modeset) {
        drmModeAtomicAddProperty(req, p->connector_id, p->p_conn_crtc, p->crtc_id);
        drmModeAtomicAddProperty(req, p->crtc_id, p->p_crtc_mode, p->mode_blob);
        drmModeAtomicAddProperty(req, p->crtc_id, p->p_crtc_active, 1);
        drmModeAtomicAddProperty(req, p->plane_id, p->p_plane_crtc, p->crtc_id);
        drmModeAtomicAddProperty(req, p->plane_id, p->p_src_x, 0);
        drmModeAtomicAddProperty(req, p->plane_id, p->p_src_y, 0);
        drmModeAtomicAddProperty(req, p->plane_id, p->p_src_w, (uint64_t)sw << 16);
        drmModeAtomicAddProperty(req, p->plane_id, p->p_src_h, (uint64_t)sh << 16);
        drmModeAtomicAddProperty(req, p->plane_id, p->p_crtc_x, 0);
        drmModeAtomicAddProperty(req, p->plane_id, p->p_crtc_y, 0);
        drmModeAtomicAddProperty(req, p->plane_id, p->p_crtc_w, p->mode.hdisplay);
        drmModeAtomicAddProperty(req, p->plane_id, p->p_crtc_h, p->mode.vdisplay);
    }
    drmModeAtomicAddProperty(req, p->plane_id, p->p_fb, fb);
    if (in_fence >= 0) drmModeAtomicAddProperty(req, p->plane_id, p->p_in_fence, (uint64_t)in_fence);
    if (out_fence) drmModeAtomicAddProperty(req, p->crtc_id, p->p_out_fence, (uint64_t)(uintptr_t)out_fence);
    uint32_t flags = modeset == 2 ? DRM_MODE_ATOMIC_ALLOW_MODESET | DRM_MODE_ATOMIC_TEST_ONLY
                     : modeset   ? DRM_MODE_ATOMIC_ALLOW_MODESET
                                 : DRM_MODE_ATOMIC_NONBLOCK | DRM_MODE_PAGE_FLIP_EVENT;
    int rc = drmModeAtomicCommit(p->fd, req, flags, p);
    drmModeAtomicFree(req);
    return rc;
}

/* The modifiers the CRTC's primary plane takes for the format, from its
 * IN_FORMATS property (none where the driver does not say). */
static void plane_modifiers(drm_platform *p, uint32_t format)
{
    p->num_modifiers = 0;
    drmSetClientCap(p->fd, DRM_CLIENT_CAP_UNIVERSAL_PLANES, 1);
    uint32_t plane = primary_plane(p);
    uint64_t blob_id = plane ? prop_value(p->fd, plane, DRM_MODE_OBJECT_PLANE, "IN_FORMATS") : 0;
    drmModePropertyBlobRes *blob = blob_id ? drmModeGetPropertyBlob(p->fd, (uint32_t)blob_id) : NULL;
    if (blob) p->num_modifiers = jd_drm_modifiers_for(blob->data, blob->length, format, p->modifiers, MAX_MODIFIERS);
    drmModeFreePropertyBlob(blob);
}

/* The scan-out surface at surface_size: with the plane's modifiers
 * where it names some (the driver then picks the best layout it can scan
 * out), else with none (linear, or the driver's implicit choice). */
static struct gbm_surface *make_gbm_surface(drm_platform *p, uint32_t format)
{
    struct gbm_surface *s = NULL;
    int w, h;
    surface_size(p, &w, &h);
    plane_modifiers(p, format);
    p->surface_modifiers = 0;
    if (p->num_modifiers > 0) {
        s = gbm_surface_create_with_modifiers(p->gbm, (uint32_t)w, (uint32_t)h, format, p->modifiers,
                                              (unsigned)p->num_modifiers);
        p->surface_modifiers = s != NULL;
    }
    if (!s) s = gbm_surface_create(p->gbm, (uint32_t)w, (uint32_t)h, format, GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
    return s;
}

/* The kernel's uevents, to follow the display when it is unplugged, comes
 * back or changes its modes: read straight from the kernel, since kiosks
 * often run without a udev daemon. Without the socket the kiosk still
 * runs, it only does not follow. */
static void open_uevents(drm_platform *p)
{
    char *real = realpath(p->device, NULL); /* /dev/dri/by-path/... names card0 too */
    const char *dev = real ? real : p->device, *slash = strrchr(dev, '/');
    snprintf(p->card, sizeof p->card, "%.31s", slash ? slash + 1 : dev);
    free(real);
    p->uevent_fd = socket(AF_NETLINK, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, NETLINK_KOBJECT_UEVENT);
    if (p->uevent_fd < 0) return;
    struct sockaddr_nl a;
    memset(&a, 0, sizeof a);
    a.nl_family = AF_NETLINK;
    a.nl_groups = 1; /* the kernel's own messages, not udev's */
    if (bind(p->uevent_fd, (struct sockaddr *)&a, sizeof a) != 0) {
        close(p->uevent_fd);
        p->uevent_fd = -1;
    }
}

/* 1 when the kernel said something about this card since the last call
 * (or messages were lost: probing once more costs little). */
static int card_changed(drm_platform *p)
{
    int hit = 0;
    char buf[8192];
    while (p->uevent_fd >= 0) {
        struct sockaddr_nl from;
        socklen_t len = sizeof from;
        ssize_t n = recvfrom(p->uevent_fd, buf, sizeof buf, MSG_DONTWAIT, (struct sockaddr *)&from, &len);
        if (n < 0) {
            if (errno == ENOBUFS) { hit = 1; continue; }
            break;
        }
        if (from.nl_pid == 0 && jd_drm_uevent_is_change(buf, (size_t)n, p->card)) hit = 1;
    }
    return hit;
}

/* A new GBM surface and EGL window surface at surface_size, the context
 * kept. The old buffers go first: the one on screen with them (the modeset
 * that follows puts a new one there). */
static int remake_surface(drm_platform *p)
{
    static const EGLint no_attribs[] = {EGL_NONE};
    eglMakeCurrent(p->edpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (p->shown) gbm_surface_release_buffer(p->gbm_surface, p->shown);
    p->shown = NULL;
    if (p->surf) eglDestroySurface(p->edpy, p->surf);
    p->surf = EGL_NO_SURFACE;
    gbm_surface_destroy(p->gbm_surface);
    p->gbm_surface = make_gbm_surface(p, p->format);
    if (p->gbm_surface)
        p->surf = eglCreateWindowSurface(p->edpy, p->cfg, (EGLNativeWindowType)p->gbm_surface, no_attribs);
    if (!p->gbm_surface || p->surf == EGL_NO_SURFACE || !eglMakeCurrent(p->edpy, p->surf, p->surf, p->ctx)) {
        int w, h;
        surface_size(p, &w, &h);
        snprintf(p->failed, sizeof p->failed, "%s: no %dx%d surface for the mode %dx%d (0x%x)", p->device, w, h,
                 p->mode.hdisplay, p->mode.vdisplay, eglGetError());
        return 0;
    }
    return 1;
}

/* After a uevent: the connector probed again and followed (see
 * jd_drm_follow_connector). 1 and a RESIZE event when the picture's size
 * changed. */
static int follow_display(drm_platform *p, jd_event *ev)
{
    drmModeConnector *c = drmModeGetConnector(p->fd, p->connector_id); /* as DRM master: probes it */
    if (!c) return 0;
    static jd_drm_mode modes[MAX_MODES];
    int n = c->count_modes < MAX_MODES ? c->count_modes : MAX_MODES;
    for (int k = 0; k < n; k++) {
        modes[k].w = c->modes[k].hdisplay;
        modes[k].h = c->modes[k].vdisplay;
        modes[k].hz = (int)c->modes[k].vrefresh;
        modes[k].preferred = (c->modes[k].type & DRM_MODE_TYPE_PREFERRED) != 0;
    }
    jd_drm_connector now = {c->connector_type, c->connector_type_id, c->connection == DRM_MODE_CONNECTED, n, modes};
    char why[300];
    int m, resized = 0;
    jd_drm_follow f = jd_drm_follow_connector(&now, p->lost, p->mode.hdisplay, p->mode.vdisplay, (int)p->mode.vrefresh,
                                              p->want_w, p->want_h, p->want_hz, p->max_w, p->max_h, &m, why, sizeof why);
    if (why[0]) fprintf(stderr, "jade: %s: %s\n", p->device, why);
    if (f == JD_DRM_LOST) p->lost = 1;
    if (f == JD_DRM_MODESET) {
        resized = c->modes[m].hdisplay != p->mode.hdisplay || c->modes[m].vdisplay != p->mode.vdisplay;
        /* Another size: the drawable takes the mode's, unscaled; the
         * program may ask for the scaler again (JD_EVENT_RESIZE). */
        if (resized) p->out_w = p->out_h = 0;
        p->mode = c->modes[m];
        p->lost = 0;
        p->modeset_done = 0; /* the next present sets the mode */
        if (p->mode_blob) {
            drmModeDestroyPropertyBlob(p->fd, p->mode_blob);
            p->mode_blob = 0;
            if (drmModeCreatePropertyBlob(p->fd, &p->mode, sizeof p->mode, &p->mode_blob) != 0)
                snprintf(p->failed, sizeof p->failed, "%s: cannot create the new mode's blob: %s", p->device,
                         strerror(errno));
        }
        if (resized && !remake_surface(p)) resized = 0;
    }
    drmModeFreeConnector(c);
    if (!resized) return 0;
    memset(ev, 0, sizeof *ev);
    ev->type = JD_EVENT_RESIZE;
    ev->w = p->mode.hdisplay;
    ev->h = p->mode.vdisplay;
    return 1;
}

static jd_result drm_probe(const jd_platform_desc *desc, jd_error *err)
{
    drm_platform probe;
    memset(&probe, 0, sizeof probe);
    probe.fd = -1;
    jd_result r = open_device(&probe, desc->drm_device, err);
    if (probe.fd >= 0) close(probe.fd);
    return r;
}

/* Records the error first (its text may name the device), then releases
 * everything opened so far. */
static jd_result fail_open(drm_platform *p, jd_result r)
{
    drm_close(p);
    return r;
}

static jd_result drm_open(const jd_platform_desc *desc, void **out, jd_error *err)
{
    drm_platform *p = &g_drm;
    memset(p, 0, sizeof *p);
    p->fd = p->uevent_fd = -1;
    jd_result r = open_device(p, desc->drm_device, err);
    if (r) return fail_open(p, r);
    /* A display server holding DRM master makes every modeset fail: say so
     * now rather than at the first frame. */
    if (!drmIsMaster(p->fd) && drmSetMaster(p->fd) != 0) {
        char why[700];
        jd_drm_master_message(p->device, errno, why, sizeof why);
        return fail_open(p, jd_fail(err, JD_ERR_PLATFORM, "%s", why));
    }
    if ((r = choose_output(p, desc, err))) return fail_open(p, r);
    p->saved_crtc = drmModeGetCrtc(p->fd, p->crtc_id);
    jd_kms_api kms = desc->atomic ? JD_KMS_ATOMIC : desc->kms;
    if (kms != JD_KMS_LEGACY) {
        jd_error why = {0};
        r = setup_atomic(p, kms == JD_KMS_ATOMIC ? err : &why);
        if (r && kms == JD_KMS_ATOMIC) {
            size_t n = strlen(err->msg);
            snprintf(err->msg + n, sizeof err->msg - n, " (--kms auto falls back to legacy)");
            return fail_open(p, r);
        }
        if (r) {
            /* Auto: legacy it is, and the kiosk says why. */
            const char *at = strstr(why.msg, ": ");
            snprintf(p->kms_why, sizeof p->kms_why, "%.90s", at ? at + 2 : why.msg);
            drmSetClientCap(p->fd, DRM_CLIENT_CAP_ATOMIC, 0);
            if (p->mode_blob) drmModeDestroyPropertyBlob(p->fd, p->mode_blob);
            p->mode_blob = 0;
        }
        p->atomic = !r;
        p->atomic_auto = !r && kms == JD_KMS_AUTO;
    } else
        snprintf(p->kms_why, sizeof p->kms_why, "asked for");
    p->max_w = p->mode.hdisplay, p->max_h = p->mode.vdisplay;
    open_uevents(p);

    p->gbm = gbm_create_device(p->fd);
    if (!p->gbm) return fail_open(p, jd_fail(err, JD_ERR_PLATFORM, "%s: GBM cannot use this device", p->device));
    uint64_t cap = 0;
    p->fb_modifiers = drmGetCap(p->fd, DRM_CAP_ADDFB2_MODIFIERS, &cap) == 0 && cap;
    const uint32_t formats[] = {GBM_FORMAT_XRGB8888, GBM_FORMAT_ARGB8888};
    for (int i = 0; i < 2 && !p->gbm_surface; i++) {
        p->format = formats[i];
        p->gbm_surface = make_gbm_surface(p, p->format);
    }
    if (!p->gbm_surface)
        return fail_open(p, jd_fail(err, JD_ERR_PLATFORM, "%s: no scan-out surface in XRGB8888 or ARGB8888 at %dx%d",
                                    p->device, p->mode.hdisplay, p->mode.vdisplay));
    PFNEGLGETPLATFORMDISPLAYEXTPROC get =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    /* Empty attribute lists, never NULL: some drivers read them unchecked. */
    static const EGLint no_attribs[] = {EGL_NONE};
    p->edpy = get ? get(EGL_PLATFORM_GBM_KHR, p->gbm, no_attribs) : eglGetDisplay((EGLNativeDisplayType)p->gbm);
    EGLint major, minor;
    if (p->edpy == EGL_NO_DISPLAY || !eglInitialize(p->edpy, &major, &minor)) /* the API: jd_egl_window_config */
        return fail_open(p, jd_fail(err, JD_ERR_PLATFORM, "%s: EGL cannot use the GBM device", p->device));
    /* The config must carry the GBM surface's format as its visual. */
    EGLConfig cfg = p->cfg = jd_egl_window_config(p->edpy, desc->single_sample, (EGLint)p->format);
    if (!cfg)
        return fail_open(p, jd_fail(err, JD_ERR_PLATFORM, "%s: no EGL config matches the GBM format %s", p->device,
                                    p->format == GBM_FORMAT_XRGB8888 ? "XRGB8888" : "ARGB8888"));
    p->ctx = jd_egl_es2_context(p->edpy, cfg);
    p->surf = eglCreateWindowSurface(p->edpy, cfg, (EGLNativeWindowType)p->gbm_surface, no_attribs);
    if (p->ctx == EGL_NO_CONTEXT || p->surf == EGL_NO_SURFACE || !eglMakeCurrent(p->edpy, p->surf, p->surf, p->ctx))
        return fail_open(p, jd_fail(err, JD_ERR_PLATFORM, "%s: cannot make a GLES 2.0 context current on GBM (0x%x)",
                                    p->device, eglGetError()));
    const char *egl_ext = eglQueryString(p->edpy, EGL_EXTENSIONS);
    if (p->atomic && p->p_in_fence && jd_extension_listed(egl_ext, "EGL_ANDROID_native_fence_sync") &&
        jd_extension_listed(egl_ext, "EGL_KHR_fence_sync")) {
        p->create_sync = (PFNEGLCREATESYNCKHRPROC)eglGetProcAddress("eglCreateSyncKHR");
        p->destroy_sync = (PFNEGLDESTROYSYNCKHRPROC)eglGetProcAddress("eglDestroySyncKHR");
        p->dup_fence = (PFNEGLDUPNATIVEFENCEFDANDROIDPROC)eglGetProcAddress("eglDupNativeFenceFDANDROID");
        if (!p->create_sync || !p->destroy_sync) p->dup_fence = NULL;
    }
    snprintf(p->describe, sizeof p->describe, "DRM/KMS %.63s %.31s %dx%d@%d, GBM %s, EGL %d.%d (%.60s)", p->device,
             p->connector_name, p->mode.hdisplay, p->mode.vdisplay, p->mode.vrefresh,
             p->format == GBM_FORMAT_XRGB8888 ? "XRGB8888" : "ARGB8888", major, minor,
             eglQueryString(p->edpy, EGL_VENDOR));
    size_t at = strlen(p->describe);
    snprintf(p->describe + at, sizeof p->describe - at, "; buffers %s%s%s",
             p->surface_modifiers   ? "with the plane's modifiers"
             : p->num_modifiers > 0 ? "without modifiers (GBM took none of the plane's)"
                                    : "without modifiers (the plane lists none)",
             p->render_node[0] ? ", GPU " : "", p->render_node);
    at = strlen(p->describe);
    if (p->atomic)
        snprintf(p->describe + at, sizeof p->describe - at, "; atomic modesetting; fences: %s, %s",
                 p->dup_fence ? "the GPU's to the plane" : p->p_in_fence ? "none to the plane (EGL has no native fences)"
                                                                           : "none to the plane (no IN_FENCE_FD)",
                 p->p_out_fence ? "the flip's waited on" : "flip events only (no OUT_FENCE_PTR)");
    else
        snprintf(p->describe + at, sizeof p->describe - at, "; legacy modesetting (%s)", p->kms_why);
    at = strlen(p->describe);
    snprintf(p->describe + at, sizeof p->describe - at, "; hotplug %s",
             p->uevent_fd >= 0 ? "followed (kernel uevents)" : "not followed (no uevent socket)");
    char why[96] = "";
    p->input = jd_input_open(p->mode.hdisplay, p->mode.vdisplay, why, sizeof why);
    at = strlen(p->describe);
    if (p->input)
        snprintf(p->describe + at, sizeof p->describe - at, "; input: %d touch or pointer device(s) on seat0 (libinput)",
                 jd_input_devices(p->input));
    else
        snprintf(p->describe + at, sizeof p->describe - at, "; no touch or mouse input (%s)", why);
    *out = p;
    return JD_OK;
}

static void destroy_fb(struct gbm_bo *bo, void *data)
{
    int fd = gbm_device_get_fd(gbm_bo_get_device(bo));
    uint32_t fb = (uint32_t)(uintptr_t)data;
    if (fb) drmModeRmFB(fd, fb);
}

/* The scan-out framebuffer of a GBM buffer, made once and kept with it. */
static uint32_t fb_for(drm_platform *p, struct gbm_bo *bo)
{
    uint32_t fb = (uint32_t)(uintptr_t)gbm_bo_get_user_data(bo);
    if (fb) return fb;
    /* Every plane of the buffer, with its layout (modifier) where the driver
     * takes it; a driver that refuses gets the plain call, which serves
     * linear and implicitly laid-out buffers. */
    uint32_t handles[4] = {0}, pitches[4] = {0}, offsets[4] = {0};
    uint64_t mods[4] = {0}, mod = gbm_bo_get_modifier(bo);
    int planes = gbm_bo_get_plane_count(bo);
    for (int i = 0; i < planes && i < 4; i++) {
        handles[i] = gbm_bo_get_handle_for_plane(bo, i).u32;
        pitches[i] = gbm_bo_get_stride_for_plane(bo, i);
        offsets[i] = gbm_bo_get_offset(bo, i);
        mods[i] = mod;
    }
    uint32_t w = gbm_bo_get_width(bo), h = gbm_bo_get_height(bo);
    int rc = -1;
    if (p->fb_modifiers && mod != DRM_FORMAT_MOD_INVALID)
        rc = drmModeAddFB2WithModifiers(p->fd, w, h, p->format, handles, pitches, offsets, mods, &fb, DRM_MODE_FB_MODIFIERS);
    if (rc != 0) rc = drmModeAddFB2(p->fd, w, h, p->format, handles, pitches, offsets, &fb, 0);
    if (rc != 0) return 0;
    gbm_bo_set_user_data(bo, (void *)(uintptr_t)fb, destroy_fb);
    return fb;
}

static void on_flip(int fd, unsigned seq, unsigned sec, unsigned usec, void *data)
{
    (void)fd;
    (void)sec;
    (void)usec;
    drm_platform *p = data;
    if (p->last_seq && seq > p->last_seq + 1) p->missed += seq - p->last_seq - 1;
    p->last_seq = seq;
    p->flip_pending = 0;
    p->flips++;
}

static jd_result wait_flip(drm_platform *p, jd_error *err)
{
    drmEventContext ev = {0};
    ev.version = 2;
    ev.page_flip_handler = on_flip;
    while (p->flip_pending) {
        struct pollfd pfd = {p->fd, POLLIN, 0};
        int k = poll(&pfd, 1, 1000);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) return jd_fail(err, JD_ERR_PLATFORM, "%s: a page flip did not complete within 1 s", p->device);
        drmHandleEvent(p->fd, &ev);
    }
    return JD_OK;
}

/* Waits for a fence fd (a second at most) and closes it. */
static int wait_fence(int fd)
{
    struct pollfd pfd = {fd, POLLIN, 0};
    int k;
    do k = poll(&pfd, 1, 1000);
    while (k < 0 && errno == EINTR);
    close(fd);
    return k > 0;
}

static jd_result drm_present(void *impl, jd_error *err)
{
    drm_platform *p = impl;
    if (p->failed[0]) return jd_fail(err, JD_ERR_PLATFORM, "%s", p->failed);
    /* The GPU's fence goes into the command stream before the swap flushes
     * it; its fd exists once flushed. */
    EGLSyncKHR sync = EGL_NO_SYNC_KHR;
    if (p->dup_fence && p->modeset_done && !p->lost) {
        static const EGLint attribs[] = {EGL_SYNC_NATIVE_FENCE_FD_ANDROID, EGL_NO_NATIVE_FENCE_FD_ANDROID, EGL_NONE};
        sync = p->create_sync(p->edpy, EGL_SYNC_NATIVE_FENCE_ANDROID, attribs);
    }
    if (!eglSwapBuffers(p->edpy, p->surf)) {
        if (sync != EGL_NO_SYNC_KHR) p->destroy_sync(p->edpy, sync);
        return jd_fail(err, JD_ERR_PLATFORM, "eglSwapBuffers failed (0x%x)", eglGetError());
    }
    int in_fence = -1;
    if (sync != EGL_NO_SYNC_KHR) {
        in_fence = p->dup_fence(p->edpy, sync);
        p->destroy_sync(p->edpy, sync);
    }
    struct gbm_bo *bo = gbm_surface_lock_front_buffer(p->gbm_surface);
    if (p->lost) {
        /* Nothing to show it on: the frame is dropped, and the loop waits
         * for the kernel's next word (or a signal), a second at most. */
        if (bo) gbm_surface_release_buffer(p->gbm_surface, bo);
        if (in_fence >= 0) close(in_fence);
        struct pollfd pfd = {p->uevent_fd, POLLIN, 0};
        poll(&pfd, 1, 1000);
        return JD_OK;
    }
    uint32_t fb = bo ? fb_for(p, bo) : 0;
    if (!fb) {
        if (in_fence >= 0) close(in_fence);
        return jd_fail(err, JD_ERR_PLATFORM, "%s: cannot make a scan-out framebuffer", p->device);
    }
    if (!p->modeset_done) {
        /* The one modeset; every later frame is a page flip. */
        int rc = p->atomic ? atomic_commit(p, fb, 1, -1, NULL)
                           : drmModeSetCrtc(p->fd, p->crtc_id, fb, 0, 0, &p->connector_id, 1, &p->mode);
        if (rc != 0 && p->atomic_auto && !p->out_w && !p->modesets && errno != EACCES) {
            /* Atomic chosen, not asked for, and its first modeset refused:
             * the legacy path, for good, said once. Not where the plane
             * scales the picture (legacy cannot show it enlarged). */
            int e = errno;
            rc = drmModeSetCrtc(p->fd, p->crtc_id, fb, 0, 0, &p->connector_id, 1, &p->mode);
            if (rc == 0) {
                snprintf(p->kms_why, sizeof p->kms_why, "the atomic modeset was refused: %.60s", strerror(e));
                fprintf(stderr, "jade: %s: %s; legacy modesetting from here on\n", p->device, p->kms_why);
                p->atomic = p->atomic_auto = 0;
                p->dup_fence = NULL;
                drmSetClientCap(p->fd, DRM_CLIENT_CAP_ATOMIC, 0);
            }
        }
        if (rc != 0)
            return jd_fail(err, JD_ERR_PLATFORM, "%s: modeset on %s failed: %s%s", p->device, p->connector_name,
                           strerror(errno), errno == EACCES ? " (another process is DRM master)" : "");
        p->modeset_done = 1;
        if (++p->modesets > 1) /* after a hotplug: the journal says the picture is back */
            fprintf(stderr, "jade: %s: %s: %dx%d@%d set again, frames shown\n", p->device, p->connector_name,
                    p->mode.hdisplay, p->mode.vdisplay, p->mode.vrefresh);
    } else {
        int out_fence = -1;
        int rc = p->atomic ? atomic_commit(p, fb, 0, in_fence, p->p_out_fence ? &out_fence : NULL)
                           : drmModePageFlip(p->fd, p->crtc_id, fb, DRM_MODE_PAGE_FLIP_EVENT, p);
        if (in_fence >= 0) {
            int e = errno;
            close(in_fence); /* the kernel holds its own reference */
            errno = e;
            p->in_fences += rc == 0;
            if (rc != 0 && e == EINVAL) {
                /* The plane refused the GPU's fence (a driver whose
                 * IN_FENCE_FD path takes no fence EGL makes): the flip
                 * without it, and every one from here on, said once. The
                 * buffer's implicit fence still holds scan-out until the
                 * GPU is done, as it does on the legacy path. */
                rc = atomic_commit(p, fb, 0, -1, p->p_out_fence ? &out_fence : NULL);
                if (rc == 0) {
                    fprintf(stderr, "jade: %s: the plane refused the GPU's fence (%s): flips without it from here on\n",
                            p->device, strerror(e));
                    p->dup_fence = NULL;
                }
            }
        }
        if (rc != 0)
            return jd_fail(err, JD_ERR_PLATFORM, "%s: page flip failed: %s", p->device, strerror(errno));
        p->flip_pending = 1;
        /* The flip's own fence: signalled when the new frame is on the
         * screen and the old buffer free to draw into. */
        if (out_fence >= 0) p->out_fences += wait_fence(out_fence);
        jd_result r = wait_flip(p, err);
        if (r) return r;
    }
    if (p->shown) gbm_surface_release_buffer(p->gbm_surface, p->shown);
    p->shown = bo;
    p->frames++;
    return JD_OK;
}

static void drm_size(const void *impl, int *w, int *h) { surface_size(impl, w, h); }

static void drm_display_size(const void *impl, int *w, int *h)
{
    const drm_platform *p = impl;
    *w = p->mode.hdisplay;
    *h = p->mode.vdisplay;
}

/* The plane's scaler, asked with a test commit of a buffer of w x h over
 * the mode (a driver without a scaler, or with limits this passes, says
 * no: the drawable stays as it was); taken, the surface is made again at
 * w x h and the next frame sets the mode with it. */
static int drm_scale_out(void *impl, int w, int h)
{
    drm_platform *p = impl;
    int mw = p->mode.hdisplay, mh = p->mode.vdisplay, ow = p->out_w, oh = p->out_h;
    if (w == mw && h == mh) {
        if (!ow) return 1;
        p->out_w = p->out_h = 0;
    } else {
        if (!p->atomic || p->lost || w < 1 || h < 1 || w > mw || h > mh) return 0;
        struct gbm_bo *bo = gbm_bo_create(p->gbm, (uint32_t)w, (uint32_t)h, p->format, GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
        uint32_t fb = bo ? fb_for(p, bo) : 0;
        p->out_w = w, p->out_h = h;
        int ok = fb && atomic_commit(p, fb, 2, -1, NULL) == 0;
        if (bo) gbm_bo_destroy(bo); /* its framebuffer with it */
        if (!ok) {
            p->out_w = ow, p->out_h = oh;
            return 0;
        }
    }
    p->modeset_done = 0;
    if (remake_surface(p)) {
        p->failed[0] = 0;
        return 1;
    }
    /* The old size back, where a surface can still be had. */
    p->out_w = ow, p->out_h = oh;
    if (remake_surface(p)) p->failed[0] = 0;
    return 0;
}

/* The first mode's size: the renderer's budget is taken for it once, and a
 * display plugged in later gets a mode within it. */
static void drm_max_size(const void *impl, int *w, int *h)
{
    const drm_platform *p = impl;
    *w = p->max_w;
    *h = p->max_h;
}

static unsigned drm_framebuffer(const void *impl)
{
    (void)impl;
    return 0;
}

static int drm_poll(void *impl, jd_event *ev)
{
    /* Signals arrive through jd_quit_requested; the display's comings and
     * goings, touch and mouse here. */
    drm_platform *p = impl;
    if (card_changed(p) && follow_display(p, ev)) return 1;
    return jd_input_poll(p->input, ev);
}

static void drm_stats(const void *impl, jd_present_stats *st)
{
    const drm_platform *p = impl;
    st->frames = p->frames;
    st->missed_vblanks = p->missed;
    st->flips = p->flips;
    st->modesets = p->modesets;
    st->in_fences = p->in_fences;
    st->atomic = p->atomic;
    st->out_fences = p->out_fences;
    st->refresh_hz = p->mode.vrefresh;
}

static const char *drm_describe(const void *impl) { return ((const drm_platform *)impl)->describe; }

/* The writeback connector that can join the kiosk's CRTC, 0 if none. */
static uint32_t find_writeback(drm_platform *p)
{
    int index = crtc_index(p);
    drmModeRes *res = drmModeGetResources(p->fd);
    uint32_t found = 0;
    for (int i = 0; res && index >= 0 && i < res->count_connectors && !found; i++) {
        drmModeConnector *c = drmModeGetConnector(p->fd, res->connectors[i]);
        for (int e = 0; c && c->connector_type == DRM_MODE_CONNECTOR_WRITEBACK && e < c->count_encoders; e++) {
            drmModeEncoder *enc = drmModeGetEncoder(p->fd, c->encoders[e]);
            if (enc && (enc->possible_crtcs & (1u << index))) found = c->connector_id;
            drmModeFreeEncoder(enc);
        }
        drmModeFreeConnector(c);
    }
    drmModeFreeResources(res);
    return found;
}

/* Whether the writeback connector writes XRGB8888 (its property lists
 * the formats it can). */
static int writeback_takes_xrgb(drm_platform *p, uint32_t wb)
{
    uint64_t blob_id = prop_value(p->fd, wb, DRM_MODE_OBJECT_CONNECTOR, "WRITEBACK_PIXEL_FORMATS");
    drmModePropertyBlobRes *blob = blob_id ? drmModeGetPropertyBlob(p->fd, (uint32_t)blob_id) : NULL;
    int ok = 0;
    for (uint32_t i = 0; blob && i < blob->length / 4; i++) ok |= ((const uint32_t *)blob->data)[i] == GBM_FORMAT_XRGB8888;
    drmModeFreePropertyBlob(blob);
    return ok;
}

/* One writeback job: the connector joins the CRTC with a dumb buffer to
 * write into and a fence to say when it is written, then leaves again.
 * Joining a CRTC is a modeset in the kernel's eyes, hence ALLOW_MODESET. */
static jd_result drm_capture(void *impl, uint8_t *dst, jd_error *err)
{
    drm_platform *p = impl;
    if (!p->modeset_done || p->lost) return jd_fail(err, JD_ERR_PLATFORM, "%s: nothing is on the display to capture", p->device);
    if (drmSetClientCap(p->fd, DRM_CLIENT_CAP_ATOMIC, 1) != 0 ||
        drmSetClientCap(p->fd, DRM_CLIENT_CAP_WRITEBACK_CONNECTORS, 1) != 0)
        return jd_fail(err, JD_ERR_UNSUPPORTED, "%s: the driver offers no writeback connectors (it needs atomic modesetting)",
                       p->device);
    uint32_t wb = find_writeback(p);
    if (!wb) return jd_fail(err, JD_ERR_UNSUPPORTED, "%s: no writeback connector can read back the CRTC of %s", p->device, p->connector_name);
    if (!writeback_takes_xrgb(p, wb))
        return jd_fail(err, JD_ERR_UNSUPPORTED, "%s: the writeback connector does not write XRGB8888", p->device);
    const uint32_t C = DRM_MODE_OBJECT_CONNECTOR;
    uint32_t p_crtc = prop_id(p->fd, wb, C, "CRTC_ID"), p_fb = prop_id(p->fd, wb, C, "WRITEBACK_FB_ID"),
             p_fence = prop_id(p->fd, wb, C, "WRITEBACK_OUT_FENCE_PTR");
    if (!p_crtc || !p_fb || !p_fence) return jd_fail(err, JD_ERR_UNSUPPORTED, "%s: the writeback connector lacks its properties", p->device);
    int w = p->mode.hdisplay, h = p->mode.vdisplay;
    uint32_t handle = 0, pitch = 0, fb = 0;
    uint64_t size = 0, offset = 0;
    void *map = MAP_FAILED;
    int fence = -1;
    jd_result r = JD_OK;
    if (drmModeCreateDumbBuffer(p->fd, (uint32_t)w, (uint32_t)h, 32, 0, &handle, &pitch, &size) != 0) {
        r = jd_fail(err, JD_ERR_PLATFORM, "%s: no %dx%d buffer for the capture: %s", p->device, w, h, strerror(errno));
        goto done;
    }
    uint32_t handles[4] = {handle}, pitches[4] = {pitch}, offsets[4] = {0};
    if (drmModeAddFB2(p->fd, (uint32_t)w, (uint32_t)h, GBM_FORMAT_XRGB8888, handles, pitches, offsets, &fb, 0) != 0) {
        r = jd_fail(err, JD_ERR_PLATFORM, "%s: no framebuffer for the capture: %s", p->device, strerror(errno));
        goto done;
    }
    drmModeAtomicReq *req = drmModeAtomicAlloc();
    if (!req) { r = jd_fail(err, JD_ERR_PLATFORM, "no memory for an atomic request"); goto done; }
    drmModeAtomicAddProperty(req, wb, p_crtc, p->crtc_id);
    drmModeAtomicAddProperty(req, wb, p_fb, fb);
    drmModeAtomicAddProperty(req, wb, p_fence, (uint64_t)(uintptr_t)&fence);
    int rc = drmModeAtomicCommit(p->fd, req, DRM_MODE_ATOMIC_ALLOW_MODESET, NULL);
    drmModeAtomicFree(req);
    if (rc != 0) {
        r = jd_fail(err, JD_ERR_PLATFORM, "%s: the driver refused the writeback job: %s", p->device, strerror(errno));
        goto done;
    }
    struct pollfd pfd = {fence, POLLIN, 0};
    int k;
    do k = poll(&pfd, 1, 2000);
    while (k < 0 && errno == EINTR);
    if (k <= 0) {
        r = jd_fail(err, JD_ERR_PLATFORM, "%s: the writeback did not complete within 2 s", p->device);
        goto detach;
    }
    if (drmModeMapDumbBuffer(p->fd, handle, &offset) != 0 ||
        (map = mmap(NULL, (size_t)size, PROT_READ, MAP_SHARED, p->fd, (off_t)offset)) == MAP_FAILED) {
        r = jd_fail(err, JD_ERR_PLATFORM, "%s: cannot map the captured buffer: %s", p->device, strerror(errno));
        goto detach;
    }
    /* XRGB8888 is a little-endian word: bytes B, G, R, X. */
    for (int y = 0; y < h; y++) {
        const uint8_t *src = (const uint8_t *)map + (size_t)y * pitch;
        uint8_t *out = dst + (size_t)y * (size_t)w * 4;
        for (int x = 0; x < w; x++) {
            out[4 * x] = src[4 * x + 2];
            out[4 * x + 1] = src[4 * x + 1];
            out[4 * x + 2] = src[4 * x];
            out[4 * x + 3] = 255;
        }
    }
detach:
    /* The connector leaves the CRTC, which goes on as it was. */
    req = drmModeAtomicAlloc();
    if (req) {
        drmModeAtomicAddProperty(req, wb, p_crtc, 0);
        if (drmModeAtomicCommit(p->fd, req, DRM_MODE_ATOMIC_ALLOW_MODESET, NULL) != 0 && !r)
            r = jd_fail(err, JD_ERR_PLATFORM, "%s: the writeback connector would not leave the CRTC: %s", p->device,
                        strerror(errno));
        drmModeAtomicFree(req);
    }
done:
    if (map != MAP_FAILED) munmap(map, (size_t)size);
    if (fence >= 0) close(fence);
    if (fb) drmModeRmFB(p->fd, fb);
    if (handle) drmModeDestroyDumbBuffer(p->fd, handle);
    return r;
}

/* Shutdown, SIGTERM's included: the display goes back first, while jade's
 * last frame is still on it (no black gap, one modeset); then everything
 * is torn down in the reverse order of its creation, each buffer released
 * while the surface that owns it still exists. */
static void drm_close(void *impl)
{
    drm_platform *p = impl;
    jd_input_close(p->input);
    p->input = NULL;
    if (p->flip_pending) { /* restoring under a pending flip fails with EBUSY */
        jd_error e;
        wait_flip(p, &e);
        p->flip_pending = 0;
    }
    if (p->saved_crtc && p->modeset_done) {
        drmModeCrtc *c = p->saved_crtc;
        /* A display that was off (no mode) is switched off again. */
        int rc = c->mode_valid
                     ? drmModeSetCrtc(p->fd, c->crtc_id, c->buffer_id, c->x, c->y, &p->connector_id, 1, &c->mode)
                     : drmModeSetCrtc(p->fd, c->crtc_id, 0, 0, 0, NULL, 0, NULL);
        if (rc != 0)
            fprintf(stderr, "jade: %s: could not give %s back as it was: %s\n", p->device, p->connector_name,
                    strerror(errno));
    }
    if (p->saved_crtc) drmModeFreeCrtc(p->saved_crtc);
    if (p->shown && p->gbm_surface) gbm_surface_release_buffer(p->gbm_surface, p->shown);
    if (p->edpy) {
        eglMakeCurrent(p->edpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (p->surf) eglDestroySurface(p->edpy, p->surf);
        if (p->ctx) eglDestroyContext(p->edpy, p->ctx);
        eglTerminate(p->edpy);
    }
    if (p->gbm_surface) gbm_surface_destroy(p->gbm_surface); /* its buffers' framebuffers go with them */
    if (p->uevent_fd >= 0) close(p->uevent_fd);
    if (p->mode_blob) drmModeDestroyPropertyBlob(p->fd, p->mode_blob);
    if (p->gbm) gbm_device_destroy(p->gbm);
    if (p->fd >= 0) {
        drmDropMaster(p->fd);
        close(p->fd);
    }
    memset(p, 0, sizeof *p);
    p->fd = p->uevent_fd = -1;
}

const jd_platform_ops jd_drm_ops = {
    "drm", drm_probe, drm_open, drm_size, drm_max_size, drm_framebuffer, drm_present, drm_poll, drm_stats, drm_describe, drm_close,
    drm_capture, drm_scale_out, drm_display_size, NULL /* samples: the EGL config's, GL_SAMPLES */,
};
