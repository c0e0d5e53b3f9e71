/* Single scattering in the reference: the light that scatters once inside
 * the medium on its way from the light to the camera, traced along the
 * camera's ray through an index-matched boundary (Jensen et al. 2001's
 * S^(1), here exact for the shape: every part the ray passes through, the
 * medium between each point and the light found by rays, not a plane's).
 *
 * Diffusion puts this light where it entered, spread by the dipole's
 * profile, or carries it across a thin part along the normal; in a thin or
 * absorbing part lit from behind (a bunny's ears, ketchup) most of what
 * comes through is this (docs/quality.md, "Single scattering"). */
#ifndef JD_REF_SINGLE_H
#define JD_REF_SINGLE_H

#include <stdint.h>
#include "ref_bvh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct jd_single {
    const jd_bvh *bvh;
    const float *nrm;       /* outward vertex normals, 3 a vertex: which way a face looks */
    float mm_per_world;
    double sigma_t[3];      /* mm^-1, per channel */
    double sigma_s[3];      /* reduced, scattering isotropically, as Cycles' medium takes it */
} jd_single;

/* Pi times the radiance that single scattering sends back along -dir out
 * of the medium that the camera ray dir enters at p (world units, the
 * face's outward geometric normal ng), for a directional light of normal
 * irradiance e from direction light (unit, towards the light): 1 is a
 * white Lambertian surface's under that light at normal incidence. The ray
 * goes on straight through the air between parts (an index-matched
 * boundary), each part's light dimmed by the medium before it. seed turns
 * the stratified samples along the ray. Returns the parts the ray passed
 * through, or -1 (out all 0) where it found no way out of the medium (an
 * open mesh's hole behind the point): no figure for that ray. */
int jd_single_scatter(const jd_single *s, const float p[3], const float ng[3], const float dir[3],
                       const float light[3], float e, uint32_t seed, float out[3]);

/* The same for a half-space lit as the point is, in closed form: light at
 * cosine mu0 to the normal, seen at cosine mu, single-scattering albedo
 * alpha: e alpha / 4 mu0 / (mu0 + mu) (Chandrasekhar's law of diffuse
 * reflection to first order, the part of it the half-space's exit laws
 * already hold). */
static inline float jd_single_halfspace(float e, float alpha, float mu0, float mu)
{
    return mu0 > 0 && mu > 0 ? e * alpha * 0.25f * mu0 / (mu0 + mu) : 0.0f;
}

#ifdef __cplusplus
}
#endif

#endif
