/* The diffusion equation solved in the object's volume (Stam 1995's
 * "multiple scattering as a diffusion process" on a grid; Wang et al. 2008
 * solve it on a polygrid for the same reason): where the dipole
 * (ref_diffusion.h) sums a half-space's profile over straight distances,
 * light here spreads through the body as it is, round bends and through
 * thick parts.
 *
 *   -div(D grad phi) + sigma_a phi = Q      inside, D = 1 / (3 sigma_t')
 *   phi + 2 A D dphi/dn = 0                 on the surface (the dipole's
 *                                           extrapolated boundary)
 *
 * Q: each irradiance sample's entering power times the reduced albedo, at
 * one reduced mean free path under its surface (the dipole's real source).
 * Cubic cells of h mm, the inside found by ray parity along the three axes
 * (two of three must agree), finite volumes, conjugate gradients with a
 * diagonal preconditioner, all three channels at once. Cut cells: each
 * boundary face takes the surface where a ray along its axis meets it,
 * with the flux D phi / (t + 2AD) through it (t the centre's distance
 * along the surface's normal) weighted by |cos| of that normal to the axis,
 * so the grid's steps add up to the true area. The picture reads the flux
 * at those faces' own surface points within 3 cells, with a smooth window:
 * exactly the light the solve lets out: diffusion's, unscaled (the exact
 * albedo's excess over it is added where the light entered, ref_render.c,
 * as the dipole's sum adds it in its window).
 *
 * Checked (tests/test_reference.c, a closed 100 x 100 mm marble box lit
 * on top): 4 mm thick, the lit and the far face give Donner & Jensen's
 * multipole R(d) and T(d) at the centre within 0.2% at 0.25 mm cells (1.3%
 * at the test's 0.4 mm); 40 mm thick, the lit face the half-space's total
 * within 0.3% at 0.5 mm (2% at the test's 0.8 mm). Good where the diffusion length (1 / sigma_tr) spans
 * several cells (marble, milk); where it is under one (ketchup's green and
 * blue) the grid cannot resolve the profile and the dipole is the better
 * model. Near the light's entry it is coarser than the dipole's window
 * (one cell, 0.25 mm or more, against the exact integral), and a slanted
 * face keeps faint blotches a few cells wide (docs/quality.md). */
#ifndef JD_REF_VOLUME_H
#define JD_REF_VOLUME_H

#include <stdint.h>
#include "jd_result.h"
#include "material.h"
#include "ref_bvh.h"
#include "ref_diffusion.h"

typedef struct jd_volume {
    int nx, ny, nz;
    float h;                 /* cell size, mm */
    float lo[3];             /* the first cell's corner, mm */
    int32_t *index;          /* per cell: its unknown, or -1 outside */
    uint32_t num_inside;
    float *phi;              /* 3 per unknown: fluence per channel */
    int32_t *nb;             /* 6 per unknown: its neighbours' unknowns, -1 where outside */
    float *bw;               /* 3 per unknown: its boundary faces' conductance (per unit D, times h) */
    uint32_t *first_face;    /* per unknown (and one past): its boundary faces in faces[] */
    struct jd_volume_face {
        float y[3];          /* where the face's axis meets the surface, mm */
        float w;             /* |cos| of the surface's normal to the axis: its share of the true surface */
        float t;             /* the cell centre's distance from the surface along its normal, mm */
        uint8_t axis;        /* the face's outward direction: -x, +x, -y, +y, -z, +z */
    } *faces;
    uint32_t num_faces;
    float D[3], zb[3];       /* diffusion constant, 2AD */
    int iterations;          /* the solve's, the largest of the three channels' */
    double residual;         /* relative, at the end */
    double lost;             /* the share of the sources' power that found no cell (parts thinner than one) */
} jd_volume;
typedef struct jd_volume_face jd_volume_face;

typedef struct jd_volume_desc {
    const jd_bvh *bvh;       /* world units */
    float mm_per_world;
    const jd_dipole *dp;
    float cell_mm;           /* [0: the finest that keeps the box to max_cells, at least 0.25 mm] */
    uint32_t max_cells;      /* [0: 6,000,000] in the box around the mesh; about 110 bytes each inside */
} jd_volume_desc;

/* Cells and the inside, once per mesh. */
jd_result jd_volume_init(jd_volume *v, const jd_volume_desc *d, jd_error *err);
/* Solves for the sources: pts (mm, power in ea) with their outward normals
 * (n, 6 floats apart: jd_ref's pt_n layout). */
jd_result jd_volume_solve(jd_volume *v, const jd_volume_desc *d, const jd_ref_point *pts, const float *normals,
                          uint32_t n, jd_error *err);
/* Mo at the surface point x (mm) with outward normal n. */
void jd_volume_exitance(const jd_volume *v, const float x[3], const float n[3], float out[3]);
void jd_volume_free(jd_volume *v);

#endif
