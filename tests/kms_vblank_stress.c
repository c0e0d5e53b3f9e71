/* Brings about vkms's vblank-timer deadlock, if the module has it:
 * kms_vblank_stress DEVICE SECONDS, in tools/kms-test.sh's guest when
 * JADE_KMS_VBLANK_STRESS=SECONDS is set (not in ctest's run).
 *
 * A process on CPU 0 keeps vblank on with waits for the next vblank, so
 * the vblank timer runs there; one on CPU 1 turns the CRTC off and on at
 * random times, as a kiosk's modesets do, which turns vblank off while the
 * timer may be firing on CPU 0. Linux 6.1's vkms, unpatched, froze a
 * two-CPU guest so within 30 s; the results say how many of each were
 * made, and a frozen guest is what tools/kms-test.sh reports. */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

static int fail(const char *what, const char *dev)
{
    fprintf(stderr, "kms_vblank_stress: %s: %s: %s\n", dev, what, strerror(errno));
    return 1;
}

int main(int argc, char **argv)
{
    if (argc != 3 || atoi(argv[2]) <= 0) {
        fprintf(stderr, "usage: kms_vblank_stress DEVICE SECONDS\n");
        return 2;
    }
    const char *dev = argv[1];
    int secs = atoi(argv[2]);
    int fd = open(dev, O_RDWR | O_CLOEXEC);
    if (fd < 0) return fail("cannot open", dev);
    drmModeRes *res = drmModeGetResources(fd);
    if (!res || res->count_crtcs < 1) return fail("no CRTC", dev);
    drmModeConnector *conn = NULL;
    for (int i = 0; i < res->count_connectors && !conn; i++) {
        conn = drmModeGetConnector(fd, res->connectors[i]);
        if (conn && (conn->connection != DRM_MODE_CONNECTED || conn->count_modes < 1)) {
            drmModeFreeConnector(conn);
            conn = NULL;
        }
    }
    if (!conn) return fail("no connected display", dev);
    drmModeModeInfo mode = conn->modes[0];
    struct drm_mode_create_dumb dumb = { .width = mode.hdisplay, .height = mode.vdisplay, .bpp = 32 };
    if (drmIoctl(fd, DRM_IOCTL_MODE_CREATE_DUMB, &dumb)) return fail("cannot make a dumb buffer", dev);
    uint32_t fb, crtc = res->crtcs[0], connector = conn->connector_id;
    if (drmModeAddFB(fd, mode.hdisplay, mode.vdisplay, 24, 32, dumb.pitch, dumb.handle, &fb))
        return fail("cannot add the framebuffer", dev);
    if (drmModeSetCrtc(fd, crtc, fb, 0, 0, &connector, 1, &mode)) return fail("cannot set the mode", dev);
    printf("kms_vblank_stress: %s on, %d s\n", mode.name, secs);
    fflush(stdout);
    for (int cpu = 0; cpu < 2; cpu++) {
        pid_t pid = fork();
        if (pid < 0) return fail("cannot fork", dev);
        if (pid > 0) continue;
        cpu_set_t set;
        CPU_ZERO(&set);
        CPU_SET(cpu, &set);
        if (sched_setaffinity(0, sizeof set, &set)) {
            fail("cannot keep to one CPU", dev);
            _exit(1);
        }
        srand((unsigned)getpid());
        time_t end = time(NULL) + secs;
        long made = 0, refused = 0;
        while (time(NULL) < end) {
            if (cpu == 0) {
                drmVBlank vb = { .request = { .type = DRM_VBLANK_RELATIVE, .sequence = 1 } };
                /* Refused while the CRTC is off: wait a little and again. */
                if (drmWaitVBlank(fd, &vb)) {
                    refused++;
                    usleep(1000);
                }
            } else {
                usleep((useconds_t)(rand() % 20000));
                if (drmModeSetCrtc(fd, crtc, 0, 0, 0, NULL, 0, NULL)) refused++;
                if (drmModeSetCrtc(fd, crtc, fb, 0, 0, &connector, 1, &mode)) refused++;
                usleep((useconds_t)(rand() % 20000));
            }
            made++;
        }
        printf("kms_vblank_stress: CPU %d: %ld %s, %ld refused\n", cpu, made,
               cpu ? "off-and-on modesets" : "vblank waits", refused);
        fflush(stdout); /* _exit does not flush it */
        _exit(0);
    }
    int status, bad = 0;
    while (wait(&status) > 0) bad |= !WIFEXITED(status) || WEXITSTATUS(status);
    return bad;
}
