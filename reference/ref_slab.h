/* Thin parts in the reference: where the dipole's light leaves a part d mm
 * thick (core/slab.h gives the slab's totals, Donner & Jensen 2005's
 * multipole).
 *
 * The reference keeps the dipole's profile where the light entered and
 * hands the rest to the point where the ray along the inward normal leaves
 * the object: a source there at the height of the dipole's real source
 * over the far face (d - z_r, at least z_r), whose profile is as wide as
 * the slab is thick (ref_diffusion.c). Their weights (jd_slab_weights) make
 * a slab's faces give out R(d) and T(d) with each profile's reach across
 * the part counted. */
#ifndef JD_REF_SLAB_H
#define JD_REF_SLAB_H

#include "slab.h"

/* The height of the light carried across d mm over the far face: the
 * real source's, at least z_r. */
static inline double jd_slab_carried_height(double d_mm, double zr) { return jd_slab_thickness(d_mm, zr) - zr; }

/* Channel c, a part d mm thick between the point where light entered and
 * where the ray along its inward normal leaves: the factor on the light the
 * sample gives out with the dipole's profile (*sample) and on the light
 * carried to the far face (*carried, for the profile of a source at the
 * carried height over that face, with its image 2 z_b above), such that a
 * slab's lit face gives out R(d) and its far face T(d) of the half-space's
 * total, each profile's reach across the part at the straight distance d
 * counted. */
void jd_slab_weights(const jd_dipole *dp, int c, double d_mm, double *sample, double *carried);

#endif
