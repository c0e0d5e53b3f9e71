/* Choosing a connector and a display mode: plain logic over recorded data,
 * kept apart from the ioctls so it can be tested without a display. */
#ifndef JD_DRM_SELECT_H
#define JD_DRM_SELECT_H

#include <stddef.h>

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

/* The processes under proc_root (normally /proc) other than self_pid that
 * have `device` open, as "Xorg (pid 812), jade (pid 901)"; their number.
 * Only what this user may see. */
int jd_drm_holders(const char *proc_root, const char *device, int self_pid, char *out, size_t cap);
/* The error for a failed drmSetMaster: who holds the display (by name where
 * /proc says) and what to do. */
void jd_drm_master_message(const char *device, int errnum, char *out, size_t cap);

#endif
