/* jade's ground truth: the scene of `jade render` rendered on the CPU with
 * the Jensen et al. 2001 dipole BSSRDF, summed hierarchically (ref_diffusion.h).
 *
 * Conventions shared with jade's composite, so only the subsurface part
 * differs: the object normalised to its bounding box (centre at the origin,
 * half-diagonal 1), the same camera, directional light, ambient term,
 * Blinn-Phong specular and tone curve. Where jade has Rd_total (ambient +
 * N.L) + its translucent layers, the reference has
 *
 *   L(xo) = X(xo, wo) * Mo(xo),   Mo(xo) = sum_i Rd(|x_i - xo|) E_i A_i
 *   E_i   = ambient + I max(N.L, 0) Ft(wi)/c * visible(x_i -> light)
 *
 * with Ft the true unpolarised Fresnel transmittance and c its mean under
 * diffuse light, and X how a scattering half-space sends its light out
 * (ref_render.c, leaving_light: 1 over the hemisphere's cosine-weighted
 * mean), so that a flat slab under uniform light shows exactly Rd_total:
 * jade's own albedo. */
#ifndef JD_REF_RENDER_H
#define JD_REF_RENDER_H

#include <stdint.h>
#include "mesh.h"
#include "renderer.h"

typedef struct jd_ref_desc {
    const jd_mesh *mesh;
    jd_scene scene;          /* camera, light, material, scale, exposure: as jade render */
    int width, height;
    uint32_t samples;        /* [0: one per (0.3 mm)^2 of surface, 20,000 to 400,000] */
    float error;             /* [0.01] octree: largest node area / distance^2 summed as one */
    float window_mm;         /* [0: 2.5 mm or 3 sample spacings] near-field window r0 */
    int pixel_samples;       /* [1] N x N rays a pixel on a regular grid, averaged in linear light:
                                the edges of a colour texture's pattern as a filtered texture shows them */
    int threads;             /* [0: every core] */
    int progress;            /* a live progress bar on stderr */
    uint32_t seed;           /* sample placement */
    int half_space;          /* every sample as if on a half-space (the dipole alone, no light carried
                                across thin parts, ref_slab.h): the reference before 2026-11-25 */
    int volume;              /* the diffusion equation solved in the body (ref_volume.h) in place of the
                                dipole's sum: light round bends and through thick parts */
    float volume_mm;         /* [0: ref_volume's choice] its cells' size */
    int bounces;             /* [0] times the light the object gives out falls on it again and enters
                                (inter-reflection through the air between its parts; 8 rays a sample) */
    int single_scatter;      /* the light scattered once traced along each camera ray (ref_single.h), in
                                place of the light carried across thin parts; eta 1 only */
    /* Tests: replaces the light's irradiance (world position, outward normal). */
    void (*irradiance)(void *user, const float p[3], const float n[3], float e[3]);
    void *user;
} jd_ref_desc;

typedef struct jd_ref_stats {
    uint32_t samples;
    uint32_t carried;        /* samples whose light also leaves the far side of a thin part */
    double spacing_mm, window_mm, surface_mm2, mm_per_world;
    double setup_ms, irradiance_ms, tree_ms, bounce_ms, pixels_ms; /* tree_ms: the octrees, or the volume's solve */
    double evals_per_pixel;
    uint32_t volume_cells;   /* desc.volume: cells inside, their size, the solve's iterations and residual */
    float volume_mm;
    int volume_iterations;
    double volume_residual, volume_lost;
    long object_pixels;
    int threads;
} jd_ref_stats;

typedef struct jd_ref jd_ref;

/* BVH, samples, their irradiance and the octree. */
jd_result jd_ref_create(const jd_ref_desc *desc, jd_ref **out, jd_ref_stats *stats, jd_error *err);
void jd_ref_destroy(jd_ref *r);
/* The same samples lit again with the light at another azimuth (the
 * scene's elevation): afterwards jd_ref_render draws, bit for bit, what a
 * jd_ref made with that azimuth draws, without placing the samples and
 * tabulating the half-space again. Not for desc.volume. */
jd_result jd_ref_relight(jd_ref *r, float light_azimuth, jd_ref_stats *stats, jd_error *err);
/* Mo at a world point with outward normal n (no Fresnel, no specular). */
void jd_ref_exitance(const jd_ref *r, const float p[3], const float n[3], float out[3]);
/* The picture: linear colour (w*h*3, top row first, exposure applied, before
 * the tone curve) and a mask (255 where the object is). */
jd_result jd_ref_render(jd_ref *r, float *linear, uint8_t *mask, jd_ref_stats *stats, jd_error *err);

#endif
