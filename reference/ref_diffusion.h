/* The diffusion term of the Jensen et al. 2001 dipole, summed over
 * irradiance samples the way Jensen & Buhler 2002 do it: an octree whose
 * nodes carry their total power E*A and its centre, used in place of their
 * points where the node looks small from the point being shaded (solid angle
 * area / distance^2 under an error bound).
 *
 *   Mo(xo) = sum_i Rd(|x_i - xo|) E_i A_i
 *
 * (plus, where the object is thin, the light carried across it: ref_slab.h)
 *
 * Near xo the dipole peaks with a width of one mean free path (0.3-4 mm for
 * the measured materials), finer than any affordable sample spacing, so the
 * kernel is split with a smooth window w(r) = (1 - r^2/r0^2)^2 (r < r0):
 * Rd w is integrated exactly over the local tangent plane (a flat
 * neighbourhood of radius r0) times the samples' irradiance averaged with
 * the same weights; Rd (1 - w), which vanishes at r = 0, is summed over the
 * samples. Rd is diffusion's own profile; the exact albedo's excess over
 * it (the first scatterings' light) joins the window's part, where the
 * light entered (jd_ref_diffusion_share). */
#ifndef JD_REF_DIFFUSION_H
#define JD_REF_DIFFUSION_H

#include <stdint.h>
#include "jd_result.h"
#include "material.h"

/* Of the half-space's light (Rd_total, the transport equation's albedo),
 * the share that diffusion's own profile carries: 1 / jd_albedo_ratio. The
 * rest, (1 - share) Rd_total, is the light of the first few scatterings,
 * which leaves where it entered: scaled over the whole profile it also lit
 * the far light (docs/quality.md, "The excess where the light enters"). */
static inline double jd_ref_diffusion_share(const jd_dipole *dp, int c)
{
    return dp->ratio[c] > 0 ? 1.0 / dp->ratio[c] : 1.0;
}

typedef struct jd_ref_point {
    float p[3];   /* mm */
    float ea[3];  /* irradiance times area, per channel */
    float area;   /* mm^2 */
    float thick;  /* carried light (ref_slab.h): the part's thickness, mm; 0 for a sample */
} jd_ref_point;

typedef struct jd_octree_node {
    float lo[3], hi[3];
    float c[3];          /* power-weighted centre */
    float ea[3];
    float area;
    float thick;         /* power-weighted mean of the points' (a tree of carried light) */
    uint32_t first;      /* leaf: first point; inner: first child */
    uint32_t count;      /* leaf: points; inner: children */
    uint32_t leaf;
} jd_octree_node;

typedef struct jd_diffusion {
    jd_ref_point *pts;       /* reordered in place by the build */
    uint32_t num_pts;
    jd_octree_node *nodes;
    uint32_t num_nodes, cap_nodes;
    float r0;                /* window radius, mm */
    float error;             /* largest node solid angle summed as one */
    float zr2[3], zv2[3], zr[3], zv[3], str[3], k[3]; /* Rd(r) constants per channel */
    float zb2[3];            /* twice the extrapolated boundary's distance, z_v - z_r */
    int carried;             /* the points are carried light (ref_slab.h): summed whole with their own profile */
    double local[3];         /* integral of Rd w over the plane within r0 */
    /* Near the samples, Rd (1 - w) averaged over a disk of one sample's
     * area: what a sample stands for. The sum stays an unbiased estimate of
     * the integral and loses most of its graininess. Indexed by distance. */
    float *table;            /* 3 per entry */
    int table_n;
    float table_rmax, table_inv_dr;
} jd_diffusion;

/* pts stays owned by the caller and is reordered (all of the same area).
 * error: e.g. 0.01. carried: every point is light carried across a thin
 * part (thick > 0), none a sample of the surface. */
jd_result jd_diffusion_build(jd_diffusion *d, jd_ref_point *pts, uint32_t n, const jd_dipole *dp, float r0_mm,
                             float error, int carried, jd_error *err);
void jd_diffusion_free(jd_diffusion *d);
/* Mo at x (mm) where the irradiance is e_local; returns the kernel
 * evaluations it took. */
uint32_t jd_diffusion_exitance(const jd_diffusion *d, const float x[3], const float e_local[3], float out[3]);
/* The summed part alone, and the window's weighted irradiance sums
 * (numerator and denominator; either may be NULL). */
uint32_t jd_diffusion_sum(const jd_diffusion *d, const float x[3], double out[3], double wnum[3], double wden[3]);

#endif
