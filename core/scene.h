/* The scene's physics on the CPU (core/scene.c): what the renderer derives
 * from a jd_scene before any GL, apart from the GL passes. The public part
 * (jd_scene_defaults, jd_scene_view_of, the mode names) is declared in
 * renderer.h. */
#ifndef JD_SCENE_H
#define JD_SCENE_H

#include "material.h"
#include "renderer.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What the material makes of light: the dipole, Rd_total (the albedo of the
 * direct part), the A0 scale K (1 - Fdr)/pi alpha'/2, the paper's per
 * channel blend of A0, A1, A2 and the mean reduced scattering (mm^-1). */
typedef struct jd_scene_optics {
    jd_dipole dipole;
    float albedo[3], a0_scale[3];
    float w0[3], w1[3], w2[3];
    double mean_sigma_s;
} jd_scene_optics;

void jd_scene_optics_of(const jd_scene *s, const jd_scene_view *sv, jd_scene_optics *o);

#ifdef __cplusplus
}
#endif

#endif
