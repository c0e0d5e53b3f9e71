/* Choosing a connector and a display mode: plain logic over recorded data,
 * kept apart from the ioctls so it can be tested without a display. */
#ifndef JD_DRM_SELECT_H
#define JD_DRM_SELECT_H

#include <stddef.h>
#include <stdint.h>

typedef struct jd_drm_mode {
    int w, h, hz;
    int preferred;
} jd_drm_mode;

typedef struct jd_drm_connector {
    unsigned type;     /* DRM_MODE_CONNECTOR_* */
    unsigned type_id;  /* 1, 2, ... per type */
    int connected;
    int num_modes;
    const jd_drm_mode *modes;
} jd_drm_connector;

/* "HDMI-A-1", as the kernel names connectors. */
void jd_drm_connector_name(const jd_drm_connector *c, char *out, size_t cap);
/* The connector called `want`, or the first connected one when want is
 * NULL; -1 and a reason otherwise. */
int jd_drm_pick_connector(const jd_drm_connector *c, int n, const char *want, char *why, size_t cap);
/* "WxH" or "WxH@Hz"; 1 on success. */
int jd_drm_parse_mode(const char *s, int *w, int *h, int *hz);
/* The mode matching w x h (and hz when non-zero); with w == 0 the preferred
 * mode, else the largest (then the fastest). -1 when none matches. */
int jd_drm_pick_mode(const jd_drm_mode *m, int n, int w, int h, int hz);

/* Following the display after a hotplug event. */
typedef enum jd_drm_follow {
    JD_DRM_KEEP,   /* nothing to do: the display shows what it showed */
    JD_DRM_LOST,   /* the display went away (or offers nothing that fits): wait */
    JD_DRM_MODESET /* set the mode *mode_out again: back, or its modes changed */
} jd_drm_follow;

/* What the kiosk does once the connector it drives has been probed again
 * (`now`): lost says whether it was gone already; cur_* the mode in use;
 * want_* what was asked for (w 0: the preferred mode); max_* the largest
 * picture the renderer's budget allows. A mode that was asked for and is
 * no longer offered gives way to the preferred one; one that does not fit
 * the budget to the largest that does. why: one line for the log. */
jd_drm_follow jd_drm_follow_connector(const jd_drm_connector *now, int lost, int cur_w, int cur_h, int cur_hz,
                                      int want_w, int want_h, int want_hz, int max_w, int max_h, int *mode_out,
                                      char *why, size_t cap);

/* 1 when a kernel uevent (a header line and NUL-separated KEY=VALUE
 * strings, as read from a NETLINK_KOBJECT_UEVENT socket) is a change of
 * the DRM device `card` ("card0"): a hotplug, or any other change after
 * which the connectors are worth probing again. */
int jd_drm_uevent_is_change(const char *msg, size_t len, const char *card);

/* The modifiers a plane's IN_FORMATS blob (struct drm_format_modifier_blob,
 * as the kernel lays it out) lists for `format`, into out (at most cap);
 * their number, 0 where the blob is malformed or lacks the format. The
 * blob's offsets and counts are checked against its length. */
int jd_drm_modifiers_for(const void *blob, size_t len, uint32_t format, uint64_t *out, int cap);

/* The processes under proc_root (normally /proc) other than self_pid that
 * have `device` open, as "Xorg (pid 812), jade (pid 901)"; their number.
 * Only what this user may see. */
int jd_drm_holders(const char *proc_root, const char *device, int self_pid, char *out, size_t cap);
/* The error for a failed drmSetMaster: who holds the display (by name where
 * /proc says) and what to do. */
void jd_drm_master_message(const char *device, int errnum, char *out, size_t cap);

#endif
