/* jade: real-time translucency for GLES 2.0 displays. */
#include <malloc.h>
#include <stdio.h>
#include <string.h>

#include "commands.h"

#ifndef JD_VERSION
#define JD_VERSION "0.1.0"
#endif

static void usage(FILE *f)
{
    fprintf(f,
            "usage: jade <command> [options]\n\n"
            "commands:\n"
            "  render   render a mesh in translucent material to a PNG\n"
            "  bench    time every mode (none, single, dual, full) with an orbiting light, print JSON\n"
            "  view     an X11 window with the scene, under a device profile if asked\n"
            "  kiosk    fullscreen on DRM/KMS (no desktop), frame statistics at the end\n"
            "  info     print the GL device's limits and usable extensions\n"
            "  reference render the same scene on the CPU with the full dipole BSSRDF (slow, exact)\n"
            "  metric   compare a picture with a reference in linear light (RMSE, PSNR, SSIM)\n"
            "  convert  turn a glTF, OBJ, PLY or STL mesh into a Draco file\n\n"
            "'jade <command> --help' lists a command's options.\n");
}

int main(int argc, char **argv)
{
    /* The GL driver (llvmpipe above all) frees and reallocates its frame
     * buffers every frame; with glibc's default trimming each frame gives
     * the pages back and faults them in again. A kiosk keeps them. */
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
    mallopt(M_MMAP_THRESHOLD, 64 << 20);
    /* Lines reach a pipe or the journal as they are printed, not when a
     * 4 KiB buffer fills or the process ends. */
    setvbuf(stdout, NULL, _IOLBF, 0);
    if (argc < 2) {
        fprintf(stderr, "jade: no command given (see jade --help)\n");
        return 2;
    }
    const char *c = argv[1];
    if (!strcmp(c, "--help") || !strcmp(c, "-h") || !strcmp(c, "help")) { usage(stdout); return 0; }
    if (!strcmp(c, "--version")) { printf("jade %s\n", JD_VERSION); return 0; }
    if (!strcmp(c, "render")) return jd_cmd_render(argc, argv);
    if (!strcmp(c, "info")) return jd_cmd_info(argc, argv);
    if (!strcmp(c, "bench")) return jd_cmd_bench(argc, argv);
    if (!strcmp(c, "view")) return jd_cmd_view(argc, argv);
    if (!strcmp(c, "kiosk")) return jd_cmd_kiosk(argc, argv);
    if (!strcmp(c, "metric")) return jd_cmd_metric(argc, argv);
    if (!strcmp(c, "reference")) return jd_cmd_reference(argc, argv);
    if (!strcmp(c, "convert")) return jd_cmd_convert(argc, argv);
    fprintf(stderr, "jade: unknown command '%s' (see jade --help)\n", c);
    return 2;
}
