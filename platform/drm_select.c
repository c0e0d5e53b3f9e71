#include "drm_select.h"

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The kernel's names (drm_connector.c), by DRM_MODE_CONNECTOR_* value. */
static const char *const type_names[] = {
    "Unknown", "VGA", "DVI-I", "DVI-D", "DVI-A", "Composite", "SVIDEO", "LVDS", "Component", "DIN",
    "DP", "HDMI-A", "HDMI-B", "TV", "eDP", "Virtual", "DSI", "DPI", "Writeback", "SPI", "USB",
};

void jd_drm_connector_name(const jd_drm_connector *c, char *out, size_t cap)
{
    const char *t = c->type < sizeof type_names / sizeof type_names[0] ? type_names[c->type] : "Unknown";
    snprintf(out, cap, "%s-%u", t, c->type_id);
}

int jd_drm_pick_connector(const jd_drm_connector *c, int n, const char *want, char *why, size_t cap)
{
    char name[32], seen[256] = "";
    for (int i = 0; i < n; i++) {
        jd_drm_connector_name(&c[i], name, sizeof name);
        size_t len = strlen(seen);
        snprintf(seen + len, sizeof seen - len, "%s%s %s", i ? ", " : "", name,
                 c[i].connected ? "connected" : "disconnected");
        if (want) {
            if (strcmp(name, want) != 0) continue;
            if (!c[i].connected || c[i].num_modes == 0) {
                snprintf(why, cap, "connector %s has no display attached", want);
                return -1;
            }
            return i;
        }
        if (c[i].connected && c[i].num_modes > 0) return i;
    }
    if (want) snprintf(why, cap, "no connector named %s (have: %s)", want, n ? seen : "none");
    else snprintf(why, cap, "no connected display (connectors: %s)", n ? seen : "none");
    return -1;
}

int jd_drm_parse_mode(const char *s, int *w, int *h, int *hz)
{
    char extra;
    *hz = 0;
    if (sscanf(s, "%dx%d@%d%c", w, h, hz, &extra) == 3 && *hz > 0) return *w > 0 && *h > 0;
    *hz = 0;
    return sscanf(s, "%dx%d%c", w, h, &extra) == 2 && *w > 0 && *h > 0;
}

/* Whether mode a beats b (NULL: nothing yet) as "the largest, then the
 * fastest". */
static int larger(const jd_drm_mode *a, const jd_drm_mode *b)
{
    long area = (long)a->w * a->h, best = b ? (long)b->w * b->h : -1;
    return area > best || (area == best && a->hz > b->hz);
}

int jd_drm_pick_mode(const jd_drm_mode *m, int n, int w, int h, int hz)
{
    int best = -1;
    for (int i = 0; i < n; i++) {
        if (w) {
            if (m[i].w != w || m[i].h != h || (hz && m[i].hz != hz)) continue;
            if (best < 0 || m[i].hz > m[best].hz) best = i;
            continue;
        }
        if (m[i].preferred) return i;
        if (larger(&m[i], best < 0 ? NULL : &m[best])) best = i;
    }
    return best;
}

jd_drm_follow jd_drm_follow_connector(const jd_drm_connector *now, int lost, int cur_w, int cur_h, int cur_hz,
                                      int want_w, int want_h, int want_hz, int max_w, int max_h, int *mode_out,
                                      char *why, size_t cap)
{
    char name[32];
    jd_drm_connector_name(now, name, sizeof name);
    *mode_out = -1;
    why[0] = 0;
    if (!now->connected || now->num_modes == 0) {
        if (!lost) snprintf(why, cap, "%s: the display went away; waiting for it to come back", name);
        return lost ? JD_DRM_KEEP : JD_DRM_LOST;
    }
    int m = want_w ? jd_drm_pick_mode(now->modes, now->num_modes, want_w, want_h, want_hz) : -1;
    const char *note = "";
    if (m < 0) {
        m = jd_drm_pick_mode(now->modes, now->num_modes, 0, 0, 0);
        if (want_w) note = " (the mode asked for is not offered now: the preferred one instead)";
    }
    if (m >= 0 && (now->modes[m].w > max_w || now->modes[m].h > max_h)) {
        /* The renderer took its memory once, for the first mode: the largest
         * mode within that, else nothing. */
        m = -1;
        for (int i = 0; i < now->num_modes; i++) {
            const jd_drm_mode *c = &now->modes[i];
            if (c->w <= max_w && c->h <= max_h && larger(c, m < 0 ? NULL : &now->modes[m])) m = i;
        }
        note = " (the largest mode within the size jade started with)";
        if (m < 0) {
            if (!lost)
                snprintf(why, cap, "%s: no mode the display offers fits within %dx%d, the size jade started with; "
                         "waiting (restart jade for a larger display)", name, max_w, max_h);
            return lost ? JD_DRM_KEEP : JD_DRM_LOST;
        }
    }
    const jd_drm_mode *n = &now->modes[m];
    if (!lost && n->w == cur_w && n->h == cur_h && n->hz == cur_hz) return JD_DRM_KEEP;
    *mode_out = m;
    snprintf(why, cap, "%s: %s: %dx%d@%d%s", name, lost ? "the display is back" : "the display's modes changed", n->w,
             n->h, n->hz, note);
    return JD_DRM_MODESET;
}

int jd_drm_uevent_is_change(const char *msg, size_t len, const char *card)
{
    int drm = 0, change = 0, ours = 0;
    char devname[48];
    snprintf(devname, sizeof devname, "DEVNAME=dri/%s", card);
    /* The header ("change@/devices/...") then KEY=VALUE strings; a message
     * from udev rather than the kernel starts with "libudev" and is skipped
     * by the KEY tests failing on its binary header. */
    for (size_t at = 0; at < len;) {
        const char *s = msg + at;
        size_t n = strnlen(s, len - at);
        if (n == 13 && !memcmp(s, "ACTION=change", 13)) change = 1;
        else if (n == 13 && !memcmp(s, "SUBSYSTEM=drm", 13)) drm = 1;
        else if (n == strlen(devname) && !memcmp(s, devname, n)) ours = 1;
        at += n + 1;
    }
    return drm && change && ours;
}

int jd_drm_modifiers_for(const void *blob, size_t len, uint32_t format, uint64_t *out, int cap)
{
    /* drm_format_modifier_blob: version, flags, count_formats,
     * formats_offset, count_modifiers, modifiers_offset (u32 each); then
     * u32 formats, and 24-byte entries {u64 formats mask, u32 offset, u32
     * pad, u64 modifier}: the mask's bit i says the modifier serves format
     * offset + i. */
    const uint8_t *b = blob;
    uint32_t h[6];
    if (!b || len < sizeof h) return 0;
    memcpy(h, b, sizeof h);
    uint64_t fmt_end = (uint64_t)h[3] + 4ull * h[2], mod_end = (uint64_t)h[5] + 24ull * h[4];
    if (h[0] != 1 || fmt_end > len || mod_end > len) return 0;
    int index = -1;
    for (uint32_t i = 0; i < h[2] && index < 0; i++) {
        uint32_t f;
        memcpy(&f, b + h[3] + 4 * i, 4);
        if (f == format) index = (int)i;
    }
    if (index < 0) return 0;
    int n = 0;
    for (uint32_t i = 0; i < h[4] && n < cap; i++) {
        const uint8_t *e = b + h[5] + 24 * i;
        uint64_t mask, mod;
        uint32_t offset;
        memcpy(&mask, e, 8);
        memcpy(&offset, e + 8, 4);
        memcpy(&mod, e + 16, 8);
        if ((uint32_t)index >= offset && (uint32_t)index - offset < 64 && (mask >> (index - (int)offset) & 1)) out[n++] = mod;
    }
    return n;
}

int jd_drm_holders(const char *proc_root, const char *device, int self_pid, char *out, size_t cap)
{
    struct stat dev;
    out[0] = 0;
    if (stat(device, &dev) != 0 || !S_ISCHR(dev.st_mode)) return 0;
    DIR *procs = opendir(proc_root);
    if (!procs) return 0;
    int found = 0;
    size_t at = 0;
    struct dirent *e;
    while ((e = readdir(procs)) != NULL) {
        char *end;
        long pid = strtol(e->d_name, &end, 10);
        if (*end || pid <= 0 || pid == self_pid) continue;
        char path[512];
        snprintf(path, sizeof path, "%s/%s/fd", proc_root, e->d_name);
        DIR *fds = opendir(path);
        if (!fds) continue; /* another user's process: not ours to see */
        struct dirent *f;
        int holds = 0;
        while (!holds && (f = readdir(fds)) != NULL) {
            struct stat st;
            char fd_path[512 + 256 + 2]; /* path and a d_name */
            snprintf(fd_path, sizeof fd_path, "%s/%s", path, f->d_name);
            holds = f->d_name[0] != '.' && stat(fd_path, &st) == 0 && S_ISCHR(st.st_mode) && st.st_rdev == dev.st_rdev;
        }
        closedir(fds);
        if (!holds) continue;
        char comm[64] = "?";
        snprintf(path, sizeof path, "%s/%s/comm", proc_root, e->d_name);
        FILE *cf = fopen(path, "r");
        if (cf) {
            if (fgets(comm, sizeof comm, cf)) comm[strcspn(comm, "\n")] = 0;
            fclose(cf);
        }
        if (at < cap) at += (size_t)snprintf(out + at, cap - at, "%s%s (pid %ld)", found ? ", " : "", comm, pid);
        found++;
    }
    closedir(procs);
    return found;
}

void jd_drm_master_message(const char *device, int errnum, char *out, size_t cap)
{
    char holders[256];
    int n = jd_drm_holders("/proc", device, (int)getpid(), holders, sizeof holders);
    if (n > 0)
        snprintf(out, cap, "%s: cannot become DRM master (%s): the display is held by %s; stop it or run from a free VT",
                 device, strerror(errnum), holders);
    else
        snprintf(out, cap,
                 "%s: cannot become DRM master (%s): %s", device, strerror(errnum),
                 errnum == EACCES || errnum == EPERM || errnum == EBUSY
                     ? "a display server (X11, Wayland) owns the display; stop it or run from a free VT (systemd unit)"
                     : "the display is held by another process");
}
