/* Device profiles: a board's GLES 2.0 limits, applied by jade to what the
 * local GPU reports, so a desktop runs the code paths the board will. */
#ifndef JD_PROFILE_H
#define JD_PROFILE_H

#include "gl_caps.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct jd_profile {
    const char *name;
    const char *summary;
    int max_texture_size, max_renderbuffer_size, max_viewport, max_cube_map_size;
    int max_vertex_uniform_vectors, max_fragment_uniform_vectors, max_varying_vectors;
    int max_texture_units, max_vertex_texture_units;
    int frag_highp;             /* 0: mediump (fp16) only */
    int ext_element_index_uint; /* 32-bit indices */
    const char *source;         /* where the numbers come from */
    const char *antialias;      /* how the board's edges get anti-aliased */
    /* What the board's GPU is, beyond its limits (set in the caps as
     * jd_gl_caps_recognise sets them for the real GPU): */
    int small_register_file;    /* shaders kept small (Mali-400/450, VideoCore IV) */
    int max_program_instructions; /* per stage, 0: no limit known */
    const char *tier;           /* the boards' tier it draws at (docs/frame-cost.md), or NULL */
    int levels_per_fragment_from; /* gl_caps.h: full's levels per fragment from this vertex count, 0: never */
} jd_profile;

extern const jd_profile jd_profiles[];
extern const int jd_profile_count;
const jd_profile *jd_profile_find(const char *name);

/* Lowers caps to the profile's limits (never raises them); masks the
 * extensions the device lacks. */
void jd_profile_apply(const jd_profile *p, jd_gl_caps *caps);

#ifdef __cplusplus
}
#endif

#endif
