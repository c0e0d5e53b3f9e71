/* The exact albedo of a half-space of isotropically scattering medium under
 * diffuse light, its boundary index-matched: what the dipole's total diffuse
 * reflectance approximates, from the transport equation itself. */
#ifndef JD_HALFSPACE_ALBEDO_H
#define JD_HALFSPACE_ALBEDO_H

#ifdef __cplusplus
extern "C" {
#endif

/* alpha: the single-scattering albedo (0..1). Chandrasekhar's result,
 * R = 1 - 2 sqrt(1 - alpha) * integral of H(mu) mu over [0, 1], H found by
 * iterating 1 / H(mu) = sqrt(1 - alpha) + alpha / 2 * integral of
 * mu' H(mu') / (mu + mu') dmu' (a form that converges near alpha = 1) on
 * 400 points. A few to 60 ms. */
double jd_halfspace_albedo(double alpha);

#ifdef __cplusplus
}
#endif

#endif
