/* The dipole's radial profile Rd(r) as a sum of normalised 2-D Gaussians
 * (d'Eon, Luebke & Enderton 2007), for the full mode's diffusion of the
 * directly lit irradiance. The variances are given (the renderer's blur
 * levels); the weights are fitted per material and channel. */
#ifndef JD_DIFFUSION_FIT_H
#define JD_DIFFUSION_FIT_H

#include "material.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { JD_DIFFUSION_MAX_GAUSSIANS = 8 };

typedef struct jd_diffusion_fit {
    int count;
    float sigma_mm[JD_DIFFUSION_MAX_GAUSSIANS];   /* standard deviations, increasing */
    float weight[JD_DIFFUSION_MAX_GAUSSIANS][3];  /* per RGB channel, >= 0 */
    float rd_total[3];   /* the weights of each channel add up to this */
    float fit_error[3];  /* relative L2 error of r Rd(r) before the sum is rescaled */
    float reach_mm[3];   /* the radius the fit covered: 8 / sigma_tr, at most 3 widest sigmas */
} jd_diffusion_fit;

/* Fits Rd(r) ~= sum_k w_k G(sigma_k, r), G(s, r) = exp(-r^2 / 2s^2) / (2 pi s^2),
 * weights >= 0, least squares on r Rd(r) (every ring by its area), then scales
 * each channel so its weights add up to Rd_total: diffusion moves light, it
 * neither makes nor loses it. count <= JD_DIFFUSION_MAX_GAUSSIANS. No heap. */
void jd_diffusion_fit_profile(const jd_dipole *d, const float *sigma_mm, int count, jd_diffusion_fit *out);

#ifdef __cplusplus
}
#endif

#endif
