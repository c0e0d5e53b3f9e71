/* Irradiance sample points for the reference: uniform by area over a mesh,
 * and spread like blue noise (dart throwing: a random candidate is kept
 * only when no kept point lies within a minimum distance). Evenly spread
 * points make the diffusion sum far less grainy than independent ones at
 * the same count. */
#ifndef JD_REF_SAMPLES_H
#define JD_REF_SAMPLES_H

#include <stdint.h>
#include "jd_result.h"

typedef struct jd_surface_point {
    uint32_t tri;
    float u, v;      /* barycentrics of the second and third vertex */
} jd_surface_point;

double jd_triangle_area(const float a[3], const float b[3], const float c[3]);

/* Up to `target` points (fewer where the surface is full at the spacing
 * sqrt(area / target)); *out is malloc'd. */
jd_result jd_surface_samples(const float *pos, const uint32_t *tri, uint32_t num_tris, uint32_t target, uint32_t seed,
                             jd_surface_point **out, uint32_t *count, jd_error *err);

#endif
