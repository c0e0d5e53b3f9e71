/* DRM connector and mode selection on recorded data (no display needed). */
#include <errno.h>
#include <stdint.h>
#include <string.h>
#include <unistd.h>
#include <sys/stat.h>
#include <stdlib.h>

#include "check.h"
#include "drm_select.h"

/* Recorded from boards: a Raspberry Pi 4 on a 1080p monitor (HDMI-A-1
 * connected, HDMI-A-2 empty), a laptop (eDP-1 panel, DP-1 empty). */
static const jd_drm_mode pi_modes[] = {
    {3840, 2160, 30, 0}, {1920, 1080, 60, 1}, {1920, 1080, 50, 0}, {1280, 720, 60, 0}, {720, 576, 50, 0},
};
static const jd_drm_mode no_pref[] = {{1024, 768, 60, 0}, {1280, 1024, 75, 0}, {1280, 1024, 60, 0}, {800, 600, 60, 0}};
enum { HDMIA = 11, EDP = 14, DP = 10, DSI = 16 };

int main(void)
{
    char why[300], name[32];
    jd_drm_connector pi[] = {{HDMIA, 1, 1, 5, pi_modes}, {HDMIA, 2, 0, 0, NULL}};
    jd_drm_connector_name(&pi[0], name, sizeof name);
    CHECK(!strcmp(name, "HDMI-A-1"), "kernel name (%s)", name);
    jd_drm_connector dsi = {DSI, 1, 1, 1, pi_modes};
    jd_drm_connector_name(&dsi, name, sizeof name);
    CHECK(!strcmp(name, "DSI-1"), "DSI name (%s)", name);
    CHECK(jd_drm_pick_connector(pi, 2, NULL, why, sizeof why) == 0, "first connected");
    CHECK(jd_drm_pick_connector(pi, 2, "HDMI-A-1", why, sizeof why) == 0, "by name");
    CHECK(jd_drm_pick_connector(pi, 2, "HDMI-A-2", why, sizeof why) < 0 && strstr(why, "no display attached"),
          "named but empty: %s", why);
    CHECK(jd_drm_pick_connector(pi, 2, "DP-1", why, sizeof why) < 0 && strstr(why, "no connector named DP-1") &&
              strstr(why, "HDMI-A-1 connected"),
          "unknown name lists what exists: %s", why);
    jd_drm_connector laptop[] = {{DP, 1, 0, 0, NULL}, {EDP, 1, 1, 5, pi_modes}};
    CHECK(jd_drm_pick_connector(laptop, 2, NULL, why, sizeof why) == 1, "skips the disconnected DP-1");
    jd_drm_connector none[] = {{HDMIA, 1, 0, 0, NULL}, {HDMIA, 2, 0, 0, NULL}};
    CHECK(jd_drm_pick_connector(none, 2, NULL, why, sizeof why) < 0 && strstr(why, "no connected display") &&
              strstr(why, "HDMI-A-2 disconnected"),
          "nothing connected: %s", why);
    CHECK(jd_drm_pick_connector(none, 0, NULL, why, sizeof why) < 0 && strstr(why, "none"), "no connectors: %s", why);

    int w, h, hz;
    CHECK(jd_drm_parse_mode("1920x1080", &w, &h, &hz) && w == 1920 && h == 1080 && hz == 0, "WxH");
    CHECK(jd_drm_parse_mode("1920x1080@50", &w, &h, &hz) && hz == 50, "WxH@Hz");
    CHECK(!jd_drm_parse_mode("1920x", &w, &h, &hz) && !jd_drm_parse_mode("big", &w, &h, &hz) &&
              !jd_drm_parse_mode("1920x1080@", &w, &h, &hz) && !jd_drm_parse_mode("-5x3", &w, &h, &hz),
          "bad modes refused");
    CHECK(jd_drm_pick_mode(pi_modes, 5, 0, 0, 0) == 1, "preferred mode");
    CHECK(jd_drm_pick_mode(no_pref, 4, 0, 0, 0) == 1, "no preferred: largest, then fastest");
    CHECK(jd_drm_pick_mode(pi_modes, 5, 1920, 1080, 50) == 2, "exact refresh");
    CHECK(jd_drm_pick_mode(pi_modes, 5, 1920, 1080, 0) == 1, "size only: fastest of that size");
    CHECK(jd_drm_pick_mode(pi_modes, 5, 1600, 900, 0) < 0, "absent size");
    CHECK(jd_drm_pick_mode(pi_modes, 5, 1280, 720, 30) < 0, "absent refresh");

    /* Hotplug, on recorded connector data: the Pi's monitor unplugged, back,
     * swapped for a 4K one, for a smaller one; a mode asked for that the
     * new monitor lacks. */
    int m;
    jd_drm_connector gone = {HDMIA, 1, 0, 0, NULL}, back = {HDMIA, 1, 1, 5, pi_modes};
    CHECK(jd_drm_follow_connector(&gone, 0, 1920, 1080, 60, 0, 0, 0, 1920, 1080, &m, why, sizeof why) == JD_DRM_LOST &&
              strstr(why, "HDMI-A-1: the display went away"),
          "unplugged: lost (%s)", why);
    CHECK(jd_drm_follow_connector(&gone, 1, 1920, 1080, 60, 0, 0, 0, 1920, 1080, &m, why, sizeof why) == JD_DRM_KEEP,
          "still unplugged: nothing more to do or say");
    CHECK(jd_drm_follow_connector(&back, 1, 1920, 1080, 60, 0, 0, 0, 1920, 1080, &m, why, sizeof why) ==
                  JD_DRM_MODESET && m == 1 && strstr(why, "is back: 1920x1080@60"),
          "plugged back: the mode set again (%s)", why);
    CHECK(jd_drm_follow_connector(&back, 0, 1920, 1080, 60, 0, 0, 0, 1920, 1080, &m, why, sizeof why) == JD_DRM_KEEP,
          "a hotplug event that changed nothing: keep");
    static const jd_drm_mode uhd[] = {{3840, 2160, 60, 1}, {2560, 1440, 60, 0}, {1920, 1080, 60, 0}, {1280, 720, 60, 0}};
    jd_drm_connector big = {HDMIA, 1, 1, 4, uhd};
    CHECK(jd_drm_follow_connector(&big, 0, 1920, 1080, 60, 0, 0, 0, 1920, 1080, &m, why, sizeof why) == JD_DRM_KEEP,
          "a 4K monitor for the 1080p one: its 1080p mode, which is in use: keep (%s)", why);
    CHECK(jd_drm_follow_connector(&big, 0, 1920, 1080, 50, 0, 0, 0, 1920, 1080, &m, why, sizeof why) == JD_DRM_MODESET &&
              m == 2 && strstr(why, "within the size"),
          "4K, 1080p50 in use: the largest mode within the budget (%s)", why);
    static const jd_drm_mode xga[] = {{1024, 768, 60, 1}, {800, 600, 60, 0}};
    jd_drm_connector small = {HDMIA, 1, 1, 2, xga};
    CHECK(jd_drm_follow_connector(&small, 0, 1920, 1080, 60, 1920, 1080, 0, 1920, 1080, &m, why, sizeof why) ==
                  JD_DRM_MODESET && m == 0 && strstr(why, "1024x768@60") && strstr(why, "not offered now"),
          "a smaller monitor lacking the mode asked for: its preferred (%s)", why);
    static const jd_drm_mode huge[] = {{7680, 4320, 60, 1}};
    jd_drm_connector eightk = {HDMIA, 1, 1, 1, huge};
    CHECK(jd_drm_follow_connector(&eightk, 0, 1920, 1080, 60, 0, 0, 0, 1920, 1080, &m, why, sizeof why) == JD_DRM_LOST &&
              strstr(why, "fits within 1920x1080"),
          "nothing within the budget: wait and say so (%s)", why);
    /* Uevents as the kernel sends them (a real hotplug, and the synthetic
     * one `echo change > /sys/class/drm/card0/uevent` makes). */
    static const char hotplug[] = "change@/devices/pci0000:00/0000:00:02.0/drm/card0\0ACTION=change\0"
                                  "DEVPATH=/devices/pci0000:00/0000:00:02.0/drm/card0\0SUBSYSTEM=drm\0HOTPLUG=1\0"
                                  "DEVNAME=dri/card0\0DEVTYPE=drm_minor\0SEQNUM=2911\0MAJOR=226\0MINOR=0";
    CHECK(jd_drm_uevent_is_change(hotplug, sizeof hotplug, "card0"), "a hotplug of card0");
    CHECK(!jd_drm_uevent_is_change(hotplug, sizeof hotplug, "card1"), "another card's");
    static const char usb[] = "add@/devices/usb1/1-1\0ACTION=add\0DEVPATH=/devices/usb1/1-1\0SUBSYSTEM=usb\0SEQNUM=5";
    CHECK(!jd_drm_uevent_is_change(usb, sizeof usb, "card0"), "a USB device");
    static const char cut[] = "change@/devices/x/drm/card0\0ACTION=change\0SUBSYSTEM=drm\0DEVNAME=dri/car";
    CHECK(!jd_drm_uevent_is_change(cut, sizeof cut - 1, "card0"), "a message cut short");

    /* A plane's IN_FORMATS, laid out as the kernel does: XRGB8888 in LINEAR
     * and a vendor's compressed layout, ARGB8888 in LINEAR only. */
    {
        uint8_t blob[24 + 8 + 48];
        uint32_t hdr[6] = {1, 0, 2, 24, 2, 32}, fmts[2] = {0x34325258, 0x34325241};
        uint64_t m0[3] = {3, 0, 0}, m1[3] = {1, 0, 0x0800000000000001ull};
        memcpy(blob, hdr, 24);
        memcpy(blob + 24, fmts, 8);
        memcpy(blob + 32, m0, 24);
        memcpy(blob + 56, m1, 24);
        uint64_t mods[8];
        int k = jd_drm_modifiers_for(blob, sizeof blob, 0x34325258, mods, 8);
        CHECK(k == 2 && mods[0] == 0 && mods[1] == 0x0800000000000001ull, "XRGB8888: linear and the vendor's (%d)", k);
        k = jd_drm_modifiers_for(blob, sizeof blob, 0x34325241, mods, 8);
        CHECK(k == 1 && mods[0] == 0, "ARGB8888: linear only (%d)", k);
        CHECK(jd_drm_modifiers_for(blob, sizeof blob, 0x36314752, mods, 8) == 0, "a format the plane lacks: none");
        CHECK(jd_drm_modifiers_for(blob, sizeof blob - 1, 0x34325258, mods, 8) == 0, "a blob cut short: none");
        hdr[5] = 0xfffffff0u;
        memcpy(blob, hdr, 24);
        CHECK(jd_drm_modifiers_for(blob, sizeof blob, 0x34325258, mods, 8) == 0, "an offset past the end: none");
    }

    jd_drm_master_message("/dev/dri/card0", EACCES, why, sizeof why);
    CHECK(strstr(why, "/dev/dri/card0") && strstr(why, "cannot become DRM master") && strstr(why, "display server"),
          "no master: %s", why);
    /* Who holds the device, from a recorded /proc: process 812 (Xorg) has
     * it open (here /dev/null stands for the card), 900 has something else. */
    char root[] = "/tmp/jade-proc-XXXXXX";
    if (mkdtemp(root)) {
        char path[256];
        snprintf(path, sizeof path, "%s/812", root); mkdir(path, 0755);
        snprintf(path, sizeof path, "%s/812/fd", root); mkdir(path, 0755);
        snprintf(path, sizeof path, "%s/812/fd/7", root); symlink("/dev/null", path);
        snprintf(path, sizeof path, "%s/812/comm", root);
        FILE *f = fopen(path, "w"); if (f) { fputs("Xorg\n", f); fclose(f); }
        snprintf(path, sizeof path, "%s/900", root); mkdir(path, 0755);
        snprintf(path, sizeof path, "%s/900/fd", root); mkdir(path, 0755);
        snprintf(path, sizeof path, "%s/900/fd/3", root); symlink("/dev/zero", path);
        char who[128];
        int n = jd_drm_holders(root, "/dev/null", 1, who, sizeof who);
        CHECK(n == 1 && !strcmp(who, "Xorg (pid 812)"), "the holder named: %d, '%s'", n, who);
        CHECK(jd_drm_holders(root, "/dev/null", 812, who, sizeof who) == 0, "itself not counted");
        char cmd[300];
        snprintf(cmd, sizeof cmd, "rm -rf %s", root);
        if (system(cmd) != 0) printf("could not remove %s\n", root);
    }
    return jd_check_summary("drm selection");
}
