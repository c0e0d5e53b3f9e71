#include "board.h"

#include <string.h>

/* Per clock: Utgard's pixel processors each issue one instruction word per
 * clock for one fragment (so fragments x words / processors) and write one
 * pixel; its one vertex processor one word per clock. A VideoCore IV QPU
 * issues one instruction per clock for 4 of a batch's 16 lanes, twelve
 * QPUs for vertices and fragments alike. A Midgard core issues a bundle per
 * clock on each of its two arithmetic pipelines. */
const jd_board jd_boards[] = {
    {"mali400-mp2", "Mali-400 MP2 at 500 MHz (Allwinner H3, A20 class)", "mali400", "lima", 500.0, JD_UNITS_SEPARATE,
     2.0, 1.0, 1.0, 1.0, 2.0, 500.0 / 55.0, 0, 5.4,
     "ARM Mali-400 MP: one pixel per clock per pixel processor, 55 Mtri/s and 500 Mpix/s for MP1 at 500 MHz; "
     "Mesa lima_draw.c: an indexed draw shades max_index - min_index + 1 vertices; Allwinner H3 datasheet: "
     "32-bit DDR3 at 672 MHz (5.4 GB/s)", 1, 1},
    {"mali450-mp3", "Mali-450 MP3 at 750 MHz (Amlogic S905 class)", "mali400", "lima", 750.0, JD_UNITS_SEPARATE,
     3.0, 2.0, 1.0, 1.0, 3.0, 500.0 / 55.0 / 2.0, 0, 8.5,
     "ARM Mali-450 MP overview: Mali-400's pixel processors, vertex throughput doubled (so half Mali-400's clocks "
     "per triangle); Amlogic S905 datasheet: 32-bit DDR3/DDR4 up to 2133 MT/s (8.5 GB/s)", 1, 1},
    {"vc4", "VideoCore IV at 400 MHz (Raspberry Pi 3B+)", "vc4", "vc4", 400.0, JD_UNITS_SHARED,
     12.0, 12.0, 4.0, 4.0, 4.0, 0.0, 16, 3.6,
     "Broadcom VideoCore IV 3D Architecture Reference Guide (2013): 12 QPUs, 16-way SIMD multiplexed 4x over four "
     "cycles, vertex batches shaded on the same QPUs; BCM2835: 1 Gpixel/s at 250 MHz (4 per clock); Mesa vc4: "
     "the scheduler's estimated cycles count texture waits of single-threaded shaders; Raspberry Pi 3B+: LPDDR2 "
     "at 450 MHz, 32 bits (3.6 GB/s). Vertex reuse: a 16-entry FIFO (assumed; the guide gives no size)", 1, 0},
    {"t860-mp4", "Mali-T860 MP4 at 800 MHz (Rockchip RK3399)", "generic", "panfrost-t860", 800.0, JD_UNITS_SHARED,
     8.0, 8.0, 1.0, 1.0, 4.0, 0.0, 0, 14.9,
     "ARM Mali-T860: two arithmetic pipelines per core, one pixel per clock per core; Mesa panfrost: bundles per "
     "shader; Midgard shades an indexed draw's vertex range; RK3399 datasheet: dual-channel 32-bit DDR3-1866 "
     "(14.9 GB/s)", 1, 1},
    {"imx6q-gc2000", "Vivante GC2000 at 594 MHz (NXP i.MX6 Quad/Dual)", "vivante", "etnaviv-gc2000", 594.0,
     JD_UNITS_SHARED, 4.0, 4.0, 1.0, 1.0, 2.0, 594.0 / 200.0, 16, 8.5,
     "Vivante's feature database (Mesa etnaviv drm-shim, etna_viv's GPU table) for i.MX6Q's GC2000 rev 5108: 4 "
     "unified shader cores (a vec4 instruction per clock each), 2 pixel pipes, a 16-entry vertex cache; Freescale's "
     "i.MX6 announcement: 200 Mtri/s; NXP i.MX6DQ: GPU3D shader clock 594 MHz, 64-bit DDR3-1066 (8.5 GB/s). "
     "Vivante draws in immediate mode: no tile-buffer resolve, bytes as counted", 0, 0},
    {"sd410-a306", "Adreno 306 at 400 MHz (Qualcomm Snapdragon 410 / APQ8016)", "adreno3xx", "freedreno-a306", 400.0,
     JD_UNITS_SHARED, 24.0, 24.0, 1.0, 1.0, 2.0, 0.0, 16, 4.3,
     "Qualcomm Adreno 306: 24 ALUs (scalar lanes, unified), 2 render back-ends (0.8 Gpix/s at 400 MHz); Linux "
     "msm8916.dtsi: the GPU's top operating point 400 MHz; Mesa ir3: scalar instructions, one issue per clock, "
     "nops and repeats counted; APQ8016: 32-bit LPDDR3 at 533 MHz (4.3 GB/s). Vertex reuse: a 16-entry FIFO "
     "(assumed); triangle set-up and the binning pass's vertex shader not modelled", 0, 0},
    {"imx8mq-gc7000l", "Vivante GC7000Lite at 800 MHz (NXP i.MX8M Quad)", "gc7000l", "etnaviv-gc7000l", 800.0,
     JD_UNITS_SHARED, 4.0, 4.0, 1.0, 1.0, 2.0, 800.0 / 267.0, 16, 12.8,
     "NXP i.MX8M reference manual (GPU chapter): GC7000Lite, 4 shaders, up to 800 MHz, 267 Mtri/s, 1.6 Gpixel/s, "
     "25.6 GFLOPS fp32 (4 cores x a vec4 multiply-add per clock: one instruction per clock each, as GC2000's); "
     "i.MX8M Quad datasheet: 32-bit LPDDR4-3200 (12.8 GB/s); a 16-entry vertex cache (assumed, as GC2000's). "
     "Vivante draws in immediate mode: no tile-buffer resolve, bytes as counted", 0, 0},
};
const int jd_board_count = (int)(sizeof jd_boards / sizeof jd_boards[0]);

const jd_board *jd_board_find(const char *name)
{
    for (int i = 0; name && i < jd_board_count; i++)
        if (!strcmp(jd_boards[i].name, name)) return &jd_boards[i];
    return NULL;
}
