/* DRM connector and mode selection on recorded data (no display needed). */
#include <errno.h>
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
