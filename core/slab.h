/* A slab's totals: what a part d mm thick does to the dipole's light.
 *
 * Jensen et al.'s dipole is the answer for a half-space: light that enters
 * and wanders deep still comes back out of the lit side, or is absorbed on
 * the way. Where the object is d mm thick, that light leaves through the far
 * side instead (a back-lit ear, the knot's lobes, milk in a thin glass).
 * Donner & Jensen 2005 ("Light diffusion in multi-layered translucent
 * materials", SIGGRAPH) put the dipole between both faces of a slab and
 * mirror it in each, without end:
 *
 *   z_r,i = 2i (d + 2 z_b) + z_r,   z_v,i = 2i (d + 2 z_b) - z_r - 2 z_b,   i = -n..n
 *
 * (positive sources at z_r,i, negative at z_v,i, depth below the lit face;
 * z_b the extrapolated boundary's distance, the same for both faces: jade's
 * object has one eta). A source at height h over a plane sends through it,
 * summed over the plane, sign(h) e^(-sigma_tr |h|) / 2 of the dipole flux's
 * constant (the integral of h (1 + s D) e^(-s D) / (4 pi D^3)), so the
 * slab's reflectance and transmittance totals are sums of exponentials, and
 * for d -> infinity the reflectance is the dipole's own Rd total.
 *
 * The CPU reference (reference/ref_slab.h) and the full mode's light through
 * thin parts (pass_light.c) both take them from here. */
#ifndef JD_SLAB_H
#define JD_SLAB_H

#include "material.h"

/* Channel c of a slab d mm thick: the light it returns through the lit face
 * (*r) and sends out of the far face (*t), each over the half-space's
 * total (the dipole's Rd total: *r -> 1, *t -> 0 as d grows). */
void jd_slab_totals(const jd_dipole *dp, int c, double d_mm, double *r, double *t);

/* The multipole needs its real source, one transport mean free path z_r
 * deep, inside the slab with room to spare: a part thinner than 2 z_r is
 * taken as 2 z_r thick (there most light goes straight through,
 * which no diffusion profile describes; this keeps R(d) <= 1 and both
 * totals monotonic in d). */
static inline double jd_slab_thickness(double d_mm, double zr) { return d_mm > 2.0 * zr ? d_mm : 2.0 * zr; }

#endif
