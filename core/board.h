/* The boards jade is for, as the frame-cost model sees them: a clock, how
 * many instruction words the fragment and vertex processors issue per
 * clock, the fixed-function rates, and the compiler that counts their
 * programs (a driver column of tests/device-shaders.expected). Every
 * constant's public source is in `sources` and docs/performance.md. */
#ifndef JD_BOARD_H
#define JD_BOARD_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum jd_board_units {
    /* Utgard: one vertex processor beside the pixel processors; the frame
     * costs the larger of the two. */
    JD_UNITS_SEPARATE = 0,
    /* VideoCore IV, Midgard: vertex and fragment work on the same shader
     * cores; the frame costs their sum. */
    JD_UNITS_SHARED
} jd_board_units;

typedef struct jd_board {
    const char *name;       /* mali400-mp2 */
    const char *summary;    /* what it is and where it is found */
    const char *profile;    /* the device profile jade draws with (core/profile.c) */
    const char *compiler;   /* the compiler table's driver column */
    double clock_mhz;
    jd_board_units units;
    /* Program costs per clock across the GPU, in the compiler table's
     * cost unit (lima: instruction words; vc4: QPU cycles of a 16-wide
     * batch; panfrost: bundles): fragments x cost per clock. */
    double fragment_rate, vertex_rate;
    /* Fragments or vertices one cost unit covers (a QPU instruction
     * shades 16 lanes in 4 clocks: 4). */
    double fragment_lanes, vertex_lanes;
    double fill_rate;       /* pixels written per clock at most (the published fill rate) */
    double triangle_clocks; /* clocks per triangle set up (the published triangle rate); 0: not modelled */
    int vertex_cache;       /* 0: every vertex of a draw's index range shaded once; N: a FIFO of N */
    double dram_gbs;        /* peak memory bandwidth, GB/s */
    const char *sources;
    /* 1: the board's Mesa driver offers the display a 4x multisampled EGL
     * config, which takes the edges (lima, vc4, panfrost); 0: it offers
     * none, and the pass after the frame smooths them every frame
     * (etnaviv only with ETNA_MESA_DEBUG=msaa, freedreno's a3xx never:
     * Mesa 22.3.6's etnaviv_screen.c, fd3_screen.c). bench --device draws
     * as that display does. */
    int multisampled;
    /* 1: the driver also draws a texture with those samples (its tile
     * buffer's, EXT_multisampled_render_to_texture: lima, panfrost), so a
     * picture the tier draws smaller and the GPU enlarges keeps them; 0
     * (vc4): that picture has one sample, and the pass after the frame
     * smooths it at its own size before it is enlarged. */
    int texture_samples;
} jd_board;

extern const jd_board jd_boards[];
extern const int jd_board_count;
const jd_board *jd_board_find(const char *name);

#ifdef __cplusplus
}
#endif

#endif
