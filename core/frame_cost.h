/* The frame-cost model: what a frame costs on a board (core/board.h), from
 * what the renderer counted in one frame (jd_renderer_count: fragments and
 * vertices per pass, targets, bytes) and what the board's compiler says
 * each program costs (the committed compiler table,
 * tests/device-shaders.expected, built into jade). An estimate, and a lower
 * bound in the ways docs/performance.md lists. */
#ifndef JD_FRAME_COST_H
#define JD_FRAME_COST_H

#include "board.h"
#include "jd_result.h"

#ifdef __cplusplus
extern "C" {
#endif

#define JD_COUNT_PASSES 64

/* One render pass (one target bound, one program drawing). */
typedef struct jd_pass_count {
    char pass[24];        /* what it is: "light-depth", "diffusion-2v", "main" (the picture's resolution) */
    char program[96];     /* its program, as the compiler table names it */
    int width, height;    /* the target region */
    double fragments;     /* shaded: with overdraw, after the depth test (a counting draw) */
    double vertices;      /* shaded, after the vertex reuse jd_renderer_count was asked to model */
    double triangles;     /* submitted */
    double trips;         /* the program's dynamic loops' trip count in this pass; 1: no loop */
    double bytes_written; /* colour written out of tile memory */
    double bytes_read;    /* textures sampled: the regions read, each texel once */
} jd_pass_count;

typedef struct jd_frame_count {
    int num_passes;
    int target_switches;  /* render-target binds: each a tile write-out on a tiler */
    int overflow;         /* more passes than JD_COUNT_PASSES: the rest were not counted */
    jd_pass_count pass[JD_COUNT_PASSES];
} jd_frame_count;

typedef struct jd_pass_estimate {
    double vs_instructions, fs_instructions; /* as the compiler table lists them */
    double vs_cost, fs_cost;                 /* charged per vertex and fragment, loops at this pass's trips */
    double vertex_ms, fragment_ms, fill_ms, triangle_ms, memory_ms;
    double ms;                               /* the pass on its own: its slowest unit */
} jd_pass_estimate;

typedef struct jd_estimate {
    const jd_board *board;
    int num_passes;
    jd_pass_estimate pass[JD_COUNT_PASSES];
    double vertex_ms;     /* the vertex work of the frame (with triangle set-up) */
    double fragment_ms;   /* the pixel work (each pass's slowest of shading, fill and memory) */
    double frame_ms;      /* separate units: the larger of the two; shared: the sum */
} jd_estimate;

/* The compiler table built into this jade (tests/device-shaders.expected). */
const char *jd_frame_cost_table(void);
/* The most instructions any one stage of any program has on `compiler` (a
 * driver column, e.g. "etnaviv-gc2000") in `table` (NULL: the built-in
 * one), to set beside a GPU's program limit; 0 where it has no rows. */
int jd_frame_cost_largest_program(const char *table, const char *compiler);

/* Estimates `count` on `board` with the compiler table `table` (NULL: the
 * built-in one). Fails naming the program and compiler where the table has
 * no row for a program the frame used. */
jd_result jd_frame_cost_estimate(const jd_board *board, const jd_frame_count *count, const char *table,
                                 jd_estimate *out, jd_error *err);

#ifdef __cplusplus
}
#endif

#endif
