/* Is the reference right? Checks of `jade reference` against the dipole's
 * own closed forms, and of its convergence:
 *   1. a flat slab under uniform light: exitance = total diffuse reflectance
 *      Rd (Jensen et al. 2001) within 1%, for marble, skin1 and ketchup; in
 *      two colours, that times sqrt(A / mean A) where it entered, within 2%;
 *   2. a narrow beam on a large flat patch: the exitance around it follows
 *      the profile Rd(r) (the beam convolved with Rd, integrated finely);
 *   3. doubling the samples, and tightening the octree's error bound, change
 *      the picture by less than the stated tolerances;
 *   4. every pixel finite and non-negative;
 *   5. a thin slab (two faces d mm apart) lit on one face: the lit face
 *      gives out R(d) and the far face T(d) of Donner & Jensen's multipole
 *      (its profiles integrated here, term by term), within 4% (a point's
 *      exitance carries the sample placement's noise: the same two faces
 *      40 mm apart, where nothing crosses, come out 0.02-1.3% under the
 *      half-space's total at the centre over four placements);
 *   6. the half-space's exact albedo, for diffuse light and for a beam,
 *      index-matched and behind a Fresnel boundary, against a Monte Carlo
 *      walk of the same medium written here; the renderer's table of it
 *      (jd_albedo_ratio) against the solution between its points;
 *   7. light between parts (jd_ref_desc.bounces): two plates facing each
 *      other, one lit: what the dark one takes from the lit one's exitance
 *      against the same exitance integrated over the lit plate here (view
 *      factor and both boundaries), within 4%.
 * Usage: test_reference [--quick] ASSET.drc (the project's default asset).
 * --quick, for the sanitizer build (tests/CMakeLists.txt): every part of
 * the reference still runs under the sanitizers, here or in tests/cli.sh,
 * but 6's Monte Carlo walks are left out (the test's own arithmetic, where
 * the sanitizers have nothing to find: a minute in a release build), the
 * volume's second box (the same solve, larger) and 7 (a minute a material
 * in a release build, nearly all of it the bounce round's 240,000 rays: the
 * same code runs in cli.sh's `jade reference --bounces 1` on a few
 * thousand samples). Under the sanitizers the whole test took 830 s on a
 * slow day, past a third of CI's time; 422 s with 7 for one material. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "halfspace_albedo.h"
#include "material.h"
#include "mesh_load.h"
#include "ref_render.h"

#define HALF_MM 50.0f /* the patch: 100 mm square; marble's tail beyond 50 mm is 1e-4 of Rd */
#define CELLS 100

static float slab_pos[(CELLS + 1) * (CELLS + 1) * 3], slab_nrm[(CELLS + 1) * (CELLS + 1) * 3];
static uint32_t slab_idx[CELLS * CELLS * 6];

static void make_slab(jd_mesh *m)
{
    int k = 0;
    for (int j = 0; j <= CELLS; j++)
        for (int i = 0; i <= CELLS; i++, k++) {
            slab_pos[3 * k] = -HALF_MM + 2 * HALF_MM * i / CELLS;
            slab_pos[3 * k + 1] = -HALF_MM + 2 * HALF_MM * j / CELLS;
            slab_pos[3 * k + 2] = 0;
            slab_nrm[3 * k] = 0; slab_nrm[3 * k + 1] = 0; slab_nrm[3 * k + 2] = 1;
        }
    k = 0;
    for (int j = 0; j < CELLS; j++)
        for (int i = 0; i < CELLS; i++) {
            uint32_t a = j * (CELLS + 1) + i, b = a + 1, c = a + CELLS + 1, d = c + 1;
            uint32_t q[6] = {a, b, d, a, d, c};
            memcpy(slab_idx + k, q, sizeof q);
            k += 6;
        }
    memset(m, 0, sizeof *m);
    m->num_vertices = (CELLS + 1) * (CELLS + 1);
    m->num_indices = CELLS * CELLS * 6;
    m->positions = slab_pos;
    m->normals = slab_nrm;
    m->indices = slab_idx;
    m->index_size = 4;
    jd_mesh_compute_bounds(m);
}

/* The patch's world units: jade normalises to half-diagonal 1. */
static const float MM_PER_WORLD = 70.710678f; /* HALF_MM * sqrt(2) */

static void uniform_light(void *user, const float p[3], const float n[3], float e[3])
{
    (void)user; (void)p; (void)n;
    e[0] = e[1] = e[2] = 1.0f;
}

/* A Gaussian beam (a laser's profile) of width beam_mm: smooth, so what is
 * measured is the diffusion sum, not how many samples a sharp edge caught. */
static float beam_mm;
static void beam_light(void *user, const float p[3], const float n[3], float e[3])
{
    (void)user; (void)n;
    float x = p[0] * MM_PER_WORLD, y = p[1] * MM_PER_WORLD;
    e[0] = e[1] = e[2] = expf(-(x * x + y * y) / (2 * beam_mm * beam_mm));
}

static jd_ref *slab_ref(const jd_mesh *m, const char *material, void (*light)(void *, const float *, const float *, float *))
{
    const jd_material *mat = jd_material_find(material);
    jd_ref_desc d = {.mesh = m, .width = 1, .height = 1, .irradiance = light};
    jd_scene_defaults(&d.scene, mat);
    d.scene.mm_per_unit = 1.0f;
    jd_ref *r = NULL;
    jd_error err = {0};
    jd_ref_stats st;
    if (jd_ref_create(&d, &r, &st, &err)) {
        printf("jd_ref_create: %s\n", err.msg);
        return NULL;
    }
    printf("  %s: %u samples, %.3f mm apart, window %.2f mm\n", material, st.samples, st.spacing_mm, st.window_mm);
    return r;
}

/* The slab in two colours, its left half (x < 0) A1 and its right half A2
 * per vertex: far from the line between them (25 mm, several of skin1's
 * mean free paths), the light that entered there is scaled by sqrt(A/mean)
 * at its entry (jd_ref_exitance applies no exit colour: it has no surface
 * point), so the exitance is Rd_total sqrt(A1/mean), and sqrt(A2/mean) on
 * the right. */
static void test_slab_colours(const jd_mesh *plain)
{
    static uint8_t col[(CELLS + 1) * (CELLS + 1) * 4];
    const uint8_t c1[3] = {230, 180, 110}, c2[3] = {110, 160, 200}; /* sqrt of the reflectance, 8 bits */
    jd_mesh m = *plain;
    for (uint32_t i = 0; i < m.num_vertices; i++) {
        const uint8_t *c = slab_pos[3 * i] < 0 ? c1 : c2;
        memcpy(col + 4 * i, c, 3);
        col[4 * i + 3] = 0;
    }
    m.colors = col;
    jd_mesh_albedo_prepare(&m);
    jd_ref *r = slab_ref(&m, "skin1", uniform_light);
    CHECK(r != NULL, "reference for the two-colour slab");
    if (!r) return;
    const jd_material *mat = jd_material_find("skin1");
    jd_dipole dp;
    jd_dipole_init(&dp, mat->sigma_s, mat->sigma_a, mat->eta, 1.0f);
    double worst = 0;
    for (int side = 0; side < 2; side++) {
        const uint8_t *c = side ? c2 : c1;
        float p[3] = {(side ? 25.0f : -25.0f) / MM_PER_WORLD, 3.1f / MM_PER_WORLD, 0}, n[3] = {0, 0, 1}, mo[3];
        jd_ref_exitance(r, p, n, mo);
        for (int k = 0; k < 3; k++) {
            double a = (c[k] / 255.0) * (c[k] / 255.0), want = dp.rd_total[k] * sqrt(a / m.albedo_mean[k]);
            double e = fabs(mo[k] - want) / want;
            if (e > worst) worst = e;
            printf("  two-colour skin1 slab, %s half, channel %d: exitance %.5f, Rd total sqrt(A / mean) %.5f\n",
                   side ? "right" : "left", k, mo[k], want);
        }
    }
    printf("  two-colour slab: largest relative error %.3f%%\n", worst * 100);
    /* 2%, as the beam's: a pattern's edge is summed from samples, not
     * integrated (a uniform slab's 1% holds where the light is smooth). */
    CHECK(worst < 0.02, "two-colour slab: the entry's colour scales the exitance by sqrt(A / mean), within 2%% (%.3f%%)",
          worst * 100);
    jd_ref_destroy(r);
}

static void test_slab(const jd_mesh *m, const char *material)
{
    jd_ref *r = slab_ref(m, material, uniform_light);
    CHECK(r != NULL, "reference for %s", material);
    if (!r) return;
    const jd_material *mat = jd_material_find(material);
    jd_dipole dp;
    jd_dipole_init(&dp, mat->sigma_s, mat->sigma_a, mat->eta, 1.0f);
    /* Points away from the centre too: the answer must not depend on where
     * the samples happen to fall. */
    const float at[][2] = {{0, 0}, {3.3f, -1.7f}, {-12.5f, 7.1f}, {20.2f, 15.9f}, {-0.37f, 0.81f}};
    double worst = 0;
    for (size_t i = 0; i < sizeof at / sizeof at[0]; i++) {
        float p[3] = {at[i][0] / MM_PER_WORLD, at[i][1] / MM_PER_WORLD, 0}, n[3] = {0, 0, 1}, mo[3];
        jd_ref_exitance(r, p, n, mo);
        for (int c = 0; c < 3; c++) {
            double want = dp.rd_total[c];
            /* Ketchup's blue reflects 0.0003: judge such channels absolutely. */
            double e = want > 0.01 ? fabs(mo[c] - want) / want : fabs(mo[c] - want) / 0.01;
            if (e > worst) worst = e;
            printf("  %s at (%5.1f, %5.1f) mm, channel %d: exitance %.5f, Rd total %.5f\n", material, at[i][0], at[i][1], c,
                   mo[c], want);
        }
    }
    printf("  %s slab: largest relative error %.3f%%\n", material, worst * 100);
    CHECK(worst < 0.01, "slab of %s: exitance within 1%% of Rd total (largest error %.3f%%)", material, worst * 100);
    jd_ref_destroy(r);
}

/* Two faces of the patch d mm apart (the top's normals up, the bottom's
 * down), lit from above only. */
#define THIN_D 4.0f
static float thin_pos[2 * (CELLS + 1) * (CELLS + 1) * 3], thin_nrm[2 * (CELLS + 1) * (CELLS + 1) * 3];
static uint32_t thin_idx[2 * CELLS * CELLS * 6];

static void make_thin_slab(jd_mesh *m)
{
    jd_mesh one;
    make_slab(&one);
    const uint32_t nv = one.num_vertices, ni = one.num_indices;
    for (uint32_t i = 0; i < nv; i++)
        for (int k = 0; k < 3; k++) {
            thin_pos[3 * i + k] = slab_pos[3 * i + k];
            thin_pos[3 * (nv + i) + k] = k == 2 ? -THIN_D : slab_pos[3 * i + k];
            thin_nrm[3 * i + k] = slab_nrm[3 * i + k];
            thin_nrm[3 * (nv + i) + k] = -slab_nrm[3 * i + k];
        }
    for (uint32_t i = 0; i < ni; i += 3) { /* the bottom wound the other way */
        thin_idx[i] = slab_idx[i]; thin_idx[i + 1] = slab_idx[i + 1]; thin_idx[i + 2] = slab_idx[i + 2];
        thin_idx[ni + i] = nv + slab_idx[i];
        thin_idx[ni + i + 1] = nv + slab_idx[i + 2];
        thin_idx[ni + i + 2] = nv + slab_idx[i + 1];
    }
    *m = one;
    m->num_vertices = 2 * nv;
    m->num_indices = 2 * ni;
    m->positions = thin_pos;
    m->normals = thin_nrm;
    m->indices = thin_idx;
    jd_mesh_compute_bounds(m);
}

static void top_light(void *user, const float p[3], const float n[3], float e[3])
{
    (void)user; (void)p;
    e[0] = e[1] = e[2] = n[2] > 0 ? 1.0f : 0.0f;
}

/* Donner & Jensen's multipole on a slab d thick (sources 2i(d + 2 z_b) + z_r
 * and 2i(d + 2 z_b) - z_r - 2 z_b deep), its profile at distance x on the
 * lit face (far = 0) or the far one, integrated over the plane out to
 * 60 mm in steps of 0.005 mm: what ref_slab.c sums in closed form. */
static double multipole_total(const jd_dipole *dp, int c, double d, int far)
{
    double zr = dp->zr[c], zb = 0.5 * (dp->zv[c] - zr), s = dp->sigma_tr[c], sum = 0, h = 0.005;
    for (double x = 0.5 * h; x < 60.0; x += h) {
        double f = 0;
        for (int i = -30; i <= 30; i++) {
            double z[2] = {2 * i * (d + 2 * zb) + zr, 2 * i * (d + 2 * zb) - zr - 2 * zb};
            for (int k = 0; k < 2; k++) {
                double hh = far ? d - z[k] : z[k], D = sqrt(x * x + hh * hh);
                f += (k ? -1 : 1) * hh * (1 + s * D) * exp(-s * D) / (4 * M_PI * D * D * D);
            }
        }
        sum += f * 2 * M_PI * x * h;
    }
    return dp->alpha[c] * dp->ratio[c] * sum;
}

/* The exitance at three points near the centre of a slab-like box d mm
 * thick lit on its top face (z up, centre at 0), on the lit face and, for
 * a thin one, the far one, against the multipole (thin) or the half-space's
 * total (thick, the lit face only); prints the centre's, returns the
 * largest relative error. */
static double slab_faces(const jd_ref *r, const jd_dipole *dp, const char *label, float d_mm, int thick)
{
    /* jade's world: the box's centre at 0, its half-diagonal 1. */
    double half = sqrt(2.0 * HALF_MM * HALF_MM + 0.25 * d_mm * d_mm), worst = 0;
    for (int far = 0; far < 2 - thick; far++) {
        const float at[][2] = {{0, 0}, {7.3f, -4.1f}, {-11.5f, 9.2f}};
        for (size_t i = 0; i < sizeof at / sizeof at[0]; i++) {
            float p[3] = {(float)(at[i][0] / half), (float)(at[i][1] / half), (float)((far ? -0.5 : 0.5) * d_mm / half)},
                  n[3] = {0, 0, far ? -1.0f : 1.0f}, mo[3];
            jd_ref_exitance(r, p, n, mo);
            for (int c = 0; c < 3; c++) {
                double want = thick ? dp->rd_total[c] : multipole_total(dp, c, d_mm, far), e = fabs(mo[c] / want - 1);
                if (e > worst) worst = e;
                if (!i && thick)
                    printf("  %s, %.0f mm thick, lit face, channel %d: exitance %.5f, half-space %.5f\n", label, d_mm,
                           c, mo[c], want);
                else if (!i)
                    printf("  %s, %.0f mm thick, %s face, channel %d: exitance %.5f, multipole %.5f (half-space "
                           "%.5f)\n",
                           label, d_mm, far ? "far" : "lit", c, mo[c], want, dp->rd_total[c]);
            }
        }
    }
    return worst;
}

static void test_thin_slab(const char *material)
{
    jd_mesh m;
    make_thin_slab(&m);
    const jd_material *mat = jd_material_find(material);
    /* A tight octree bound: the weights are what is measured here. */
    jd_ref_desc d = {.mesh = &m, .width = 1, .height = 1, .irradiance = top_light, .error = 0.0025f};
    jd_scene_defaults(&d.scene, mat);
    d.scene.mm_per_unit = 1.0f;
    jd_ref *r = NULL;
    jd_error err = {0};
    jd_ref_stats st;
    CHECK(!jd_ref_create(&d, &r, &st, &err), "reference for the thin %s slab: %s", material, err.msg);
    if (!r) return;
    jd_dipole dp;
    jd_dipole_init(&dp, mat->sigma_s, mat->sigma_a, mat->eta, 1.0f);
    double worst = slab_faces(r, &dp, material, THIN_D, 0);
    printf("  thin %s slab: %u of %u samples carry light across; largest relative error %.2f%%\n", material, st.carried,
           st.samples, worst * 100);
    CHECK(worst < 0.04, "thin %s slab: both faces within 4%% of the multipole (largest %.2f%%)", material, worst * 100);
    jd_ref_destroy(r);
}

/* The volume's solve (jd_ref_desc.volume, ref_volume.h) on a closed box
 * 100 x 100 x d mm lit on its top face: at the centre, the light given out
 * by the lit face and by the far one against the multipole (the same as
 * the thin slab's; the side walls 50 mm away take under 0.5% of marble's),
 * and for a thick box (40 mm) the lit face against the half-space's total. */
#define BOX_N 24
static float box_pos[6 * (BOX_N + 1) * (BOX_N + 1) * 3], box_nrm[6 * (BOX_N + 1) * (BOX_N + 1) * 3];
static uint32_t box_idx[6 * BOX_N * BOX_N * 6];

static void make_box(jd_mesh *m, float half_z)
{
    const float h[3] = {HALF_MM, HALF_MM, half_z};
    uint32_t v = 0, k = 0;
    for (int f = 0; f < 6; f++) {
        int ax = f / 2, a1 = (ax + 1) % 3, a2 = (ax + 2) % 3;
        float s = f % 2 ? 1.0f : -1.0f;
        uint32_t base = v;
        for (int j = 0; j <= BOX_N; j++)
            for (int i = 0; i <= BOX_N; i++, v++) {
                float *p = box_pos + 3 * v, *n = box_nrm + 3 * v;
                p[ax] = s * h[ax];
                p[a1] = -h[a1] + 2 * h[a1] * i / BOX_N;
                p[a2] = -h[a2] + 2 * h[a2] * j / BOX_N;
                n[0] = n[1] = n[2] = 0;
                n[ax] = s; /* flat: each face's own vertices */
            }
        for (int j = 0; j < BOX_N; j++)
            for (int i = 0; i < BOX_N; i++) {
                uint32_t a = base + j * (BOX_N + 1) + i, b = a + 1, c = a + BOX_N + 1, d = c + 1;
                uint32_t q[6] = {a, b, d, a, d, c}, r[6] = {a, d, b, a, c, d}; /* outward: a1 x a2 is +ax */
                memcpy(box_idx + k, s > 0 ? q : r, sizeof q);
                k += 6;
            }
    }
    memset(m, 0, sizeof *m);
    m->num_vertices = v;
    m->num_indices = k;
    m->positions = box_pos;
    m->normals = box_nrm;
    m->indices = box_idx;
    m->index_size = 4;
    jd_mesh_compute_bounds(m);
}

static void test_volume_box(const char *material, float d_mm, float cell_mm, double bound)
{
    jd_mesh m;
    make_box(&m, 0.5f * d_mm);
    const jd_material *mat = jd_material_find(material);
    jd_ref_desc d = {.mesh = &m, .width = 1, .height = 1, .irradiance = top_light, .volume = 1, .volume_mm = cell_mm};
    jd_scene_defaults(&d.scene, mat);
    d.scene.mm_per_unit = 1.0f;
    jd_ref *r = NULL;
    jd_error err = {0};
    jd_ref_stats st;
    CHECK(!jd_ref_create(&d, &r, &st, &err), "volume reference for the %s box: %s", material, err.msg);
    if (!r) return;
    jd_dipole dp;
    jd_dipole_init(&dp, mat->sigma_s, mat->sigma_a, mat->eta, 1.0f);
    char label[64];
    snprintf(label, sizeof label, "volume, %s", material);
    double worst = slab_faces(r, &dp, label, d_mm, d_mm > 20);
    printf("  volume, %s, %.0f mm box: %u cells of %.2f mm, %d iterations, %.2f%% of the light found no cell; largest "
           "relative error %.2f%%\n",
           material, d_mm, st.volume_cells, st.volume_mm, st.volume_iterations, 100 * st.volume_lost, worst * 100);
    CHECK(worst < bound, "volume, %s, %.0f mm box: within %.0f%% (largest %.2f%%)", material, d_mm, bound * 100,
          worst * 100);
    jd_ref_destroy(r);
}

/* Two plates facing each other across a gap of PLATE_GAP mm: A at z = 0
 * facing up, B above it facing down (open sheets, 100 mm square). */
#define PLATE_GAP 10.0f
#define PCELLS 60
static float plate_pos[2 * (PCELLS + 1) * (PCELLS + 1) * 3], plate_nrm[2 * (PCELLS + 1) * (PCELLS + 1) * 3];
static uint32_t plate_idx[2 * PCELLS * PCELLS * 6];

static void make_plates(jd_mesh *m)
{
    int k = 0, t = 0;
    for (int f = 0; f < 2; f++) {
        int base = k;
        for (int j = 0; j <= PCELLS; j++)
            for (int i = 0; i <= PCELLS; i++, k++) {
                plate_pos[3 * k] = -HALF_MM + 2 * HALF_MM * i / PCELLS;
                plate_pos[3 * k + 1] = -HALF_MM + 2 * HALF_MM * j / PCELLS;
                plate_pos[3 * k + 2] = f ? PLATE_GAP : 0.0f;
                plate_nrm[3 * k] = 0; plate_nrm[3 * k + 1] = 0; plate_nrm[3 * k + 2] = f ? -1.0f : 1.0f;
            }
        for (int j = 0; j < PCELLS; j++)
            for (int i = 0; i < PCELLS; i++) {
                uint32_t a = base + j * (PCELLS + 1) + i, b = a + 1, c = a + PCELLS + 1, d = c + 1;
                uint32_t q[2][6] = {{a, b, d, a, d, c}, {a, d, b, a, c, d}}; /* B wound the other way */
                memcpy(plate_idx + t, q[f], sizeof q[f]);
                t += 6;
            }
    }
    memset(m, 0, sizeof *m);
    m->num_vertices = (uint32_t)k;
    m->num_indices = (uint32_t)t;
    m->positions = plate_pos;
    m->normals = plate_nrm;
    m->indices = plate_idx;
    m->index_size = 4;
    jd_mesh_compute_bounds(m);
}

/* Light on B's face alone. */
static void plate_light(void *user, const float p[3], const float n[3], float e[3])
{
    (void)user; (void)p;
    e[0] = e[1] = e[2] = n[2] < 0 ? 1.0f : 0.0f;
}

static void test_bounce(const char *material)
{
    jd_mesh m;
    make_plates(&m);
    const jd_material *mat = jd_material_find(material);
    jd_ref *r[2] = {NULL, NULL};
    for (int b = 0; b < 2; b++) {
        /* half-space: nothing carried across (the plates are open sheets anyway) */
        jd_ref_desc d = {.mesh = &m, .width = 1, .height = 1, .irradiance = plate_light, .half_space = 1, .bounces = b,
                         .samples = 30000};
        jd_scene_defaults(&d.scene, mat);
        d.scene.mm_per_unit = 1.0f;
        d.scene.eta = 1.0f;
        jd_error err = {0};
        jd_ref_stats st;
        CHECK(!jd_ref_create(&d, &r[b], &st, &err), "reference for two %s plates (%d bounces): %s", material, b, err.msg);
        if (!r[b]) { jd_ref_destroy(r[0]); return; }
    }
    /* jade's world: the box's centre at 0, its half-diagonal 1. */
    double half = sqrt(2.0 * HALF_MM * HALF_MM + 0.25 * PLATE_GAP * PLATE_GAP);
    jd_dipole dp;
    jd_dipole_init(&dp, mat->sigma_s, mat->sigma_a, 1.0f, 1.0f);
    /* What A's centre takes from B: B's exitance (without bounces) over
     * its face, each element seen at distance s at cosine c = gap / s on
     * both plates: M c^2 / (pi s^2) dA. B's light is its own diffuse light
     * given back, which leaves by the half-space's albedo at c over its
     * diffuse albedo (reciprocity); index-matched, all of it enters A. */
    enum { NB = 65 };
    double bs[3][NB];
    for (int ch = 0; ch < 3; ch++) {
        double dif = 0;
        jd_halfspace_albedo_beam(dp.alpha[ch], 1.0, NB, bs[ch], &dif);
        for (int i = 0; i < NB; i++) bs[ch][i] /= dif;
    }
    double want[3] = {0, 0, 0};
    const int q = 200;
    const double h = 2.0 * HALF_MM / q;
    for (int j = 0; j < q; j++)
        for (int i = 0; i < q; i++) {
            double x = -HALF_MM + (i + 0.5) * h, y = -HALF_MM + (j + 0.5) * h, s2 = x * x + y * y + PLATE_GAP * PLATE_GAP;
            double c = PLATE_GAP / sqrt(s2), k = c * c / (M_PI * s2) * h * h, xi = c * (NB - 1);
            int i0 = xi >= NB - 1 ? NB - 2 : (int)xi;
            float p[3] = {(float)(x / half), (float)(y / half), (float)(0.5 * PLATE_GAP / half)}, n[3] = {0, 0, -1}, mo[3];
            jd_ref_exitance(r[0], p, n, mo);
            for (int ch = 0; ch < 3; ch++)
                want[ch] += k * mo[ch] * (bs[ch][i0] + (xi - i0) * (bs[ch][i0 + 1] - bs[ch][i0]));
        }
    double worst = 0;
    float p[3] = {0, 0, (float)(-0.5 * PLATE_GAP / half)}, n[3] = {0, 0, 1}, m0[3], m1[3];
    jd_ref_exitance(r[0], p, n, m0);
    jd_ref_exitance(r[1], p, n, m1);
    for (int c = 0; c < 3; c++) {
        /* The light A took in leaves it again as from uniform light: Rd. */
        double got = (m1[c] - m0[c]) / dp.rd_total[c], e = fabs(got / want[c] - 1);
        if (e > worst) worst = e;
        printf("  %s, channel %d: A's centre takes %.5f of B's light (exitance %.5f -> %.5f), integrated %.5f\n",
               material, c, got, m0[c], m1[c], want[c]);
    }
    CHECK(worst < 0.04, "two %s plates: the light between them within 4%% of the integral (largest %.2f%%)", material,
          worst * 100);
    jd_ref_destroy(r[0]);
    jd_ref_destroy(r[1]);
}

/* The beam (Gaussian, width b) convolved with Rd, at distance x from its
 * centre: polar integration out to 6 b, fine enough to be exact here. */
static double beam_profile(const jd_dipole *dp, int c, double x, double b)
{
    const int nr = 600, na = 360;
    double sum = 0, rmax = 6 * b;
    for (int i = 0; i < nr; i++) {
        double rr = (i + 0.5) * rmax / nr, g = exp(-rr * rr / (2 * b * b));
        for (int j = 0; j < na; j++) {
            double a = (j + 0.5) * 2 * M_PI / na;
            double dx = x - rr * cos(a), dy = rr * sin(a);
            sum += jd_dipole_rd(dp, c, sqrt(dx * dx + dy * dy)) * g * rr;
        }
    }
    return sum * (rmax / nr) * (2 * M_PI / na);
}

static void test_profile(const jd_mesh *m, const char *material)
{
    beam_mm = 1.0f;
    jd_ref *r = slab_ref(m, material, beam_light);
    CHECK(r != NULL, "reference for %s", material);
    if (!r) return;
    const jd_material *mat = jd_material_find(material);
    jd_dipole dp;
    jd_dipole_init(&dp, mat->sigma_s, mat->sigma_a, mat->eta, 1.0f);
    double worst = 0, worst_r = 0;
    int compared = 0;
    printf("  %s profile, r mm: reference / (beam * Rd / ratio), red green blue\n", material);
    /* From 5 mm: the window (2.5 mm) takes the exact albedo's excess with
     * the irradiance it averages, which a beam 1 mm wide still has 1.5 mm
     * from its centre (ketchup 3% over at 4 mm, where its excess is 30-51%
     * of its light). */
    for (double x = 5.0; x <= 45.0; x *= 1.25) {
        /* Four directions around the beam, averaged: the sampling's
         * graininess is not what is being tested. */
        double mo_avg[3] = {0, 0, 0};
        for (int k = 0; k < 4; k++) {
            double a = k * M_PI / 2 + 0.3;
            float p[3] = {(float)(x * cos(a)) / MM_PER_WORLD, (float)(x * sin(a)) / MM_PER_WORLD, 0}, n[3] = {0, 0, 1},
                  mo[3];
            jd_ref_exitance(r, p, n, mo);
            for (int c = 0; c < 3; c++) mo_avg[c] += mo[c] / 4;
        }
        printf("    %5.1f", x);
        for (int c = 0; c < 3; c++) {
            /* Past the window the profile is diffusion's, unscaled: the
             * exact albedo's excess (jd_albedo_ratio) leaves near the entry
             * (ref_diffusion.c). */
            double want = beam_profile(&dp, c, x, beam_mm) / dp.ratio[c];
            /* Where the profile has fallen below a millionth of the beam's
             * power, float round-off is all there is to compare. */
            if (want < 1e-7 * 2 * M_PI * beam_mm * beam_mm) { printf("      -"); continue; }
            double e = fabs(mo_avg[c] / want - 1);
            printf("  %.4f", mo_avg[c] / want);
            compared++;
            if (e > worst) { worst = e; worst_r = x; }
        }
        printf("\n");
    }
    printf("  %s profile: %d comparisons, largest relative error %.2f%% (at %.1f mm)\n", material, compared,
           worst * 100, worst_r);
    CHECK(compared >= 6 && worst < 0.02, "profile of %s follows Rd(r) / ratio within 2%% (largest %.2f%% at %.1f mm)",
          material, worst * 100, worst_r);
    jd_ref_destroy(r);
}

typedef struct picture { float *px; uint8_t *mask; } picture;

static int render(const jd_mesh *m, const char *material, float light_az, uint32_t samples, float error, uint32_t seed,
                  picture *out, jd_ref_stats *st)
{
    enum { S = 64 };
    jd_ref_desc d = {.mesh = m, .width = S, .height = S, .samples = samples, .error = error, .seed = seed};
    jd_scene_defaults(&d.scene, jd_material_find(material));
    d.scene.light_azimuth = light_az;
    out->px = malloc(sizeof(float) * 3 * S * S);
    out->mask = malloc(S * S);
    jd_ref *r = NULL;
    jd_error err = {0};
    if (jd_ref_create(&d, &r, st, &err) || jd_ref_render(r, out->px, out->mask, st, &err)) {
        printf("reference: %s\n", err.msg);
        jd_ref_destroy(r);
        return 0;
    }
    jd_ref_destroy(r);
    return 1;
}

/* RMSE over the object relative to its mean. */
static double rel_rmse(const picture *a, const picture *b, int n)
{
    double se = 0, sum = 0;
    long cnt = 0;
    for (int i = 0; i < n; i++) {
        if (!a->mask[i]) continue;
        for (int c = 0; c < 3; c++) {
            double d = a->px[3 * i + c] - b->px[3 * i + c];
            se += d * d;
            sum += b->px[3 * i + c];
        }
        cnt += 3;
    }
    return cnt ? sqrt(se / cnt) / (sum / cnt) : 1e9;
}

static void test_convergence(const jd_mesh *m)
{
    const int n = 64 * 64;
    const char *mats[] = {"marble", "skin1"};
    for (int k = 0; k < 2; k++) {
        picture base, dbl, tight, reseed;
        jd_ref_stats st;
        if (!render(m, mats[k], 170, 0, 0, 0, &base, &st)) { CHECK(0, "render"); return; }
        uint32_t ns = st.samples;
        int ok = render(m, mats[k], 170, 2 * ns, 0, 0, &dbl, &st) && render(m, mats[k], 170, 0, 0.0025f, 0, &tight, &st) &&
                 render(m, mats[k], 170, 0, 0, 7, &reseed, &st);
        CHECK(ok, "renders");
        if (!ok) return;
        long bad = 0, obj = 0;
        for (int i = 0; i < n; i++) {
            obj += base.mask[i] != 0;
            for (int c = 0; c < 3; c++)
                if (!isfinite(base.px[3 * i + c]) || base.px[3 * i + c] < 0) bad++;
        }
        double e_samples = rel_rmse(&base, &dbl, n), e_error = rel_rmse(&base, &tight, n),
               e_seed = rel_rmse(&base, &reseed, n);
        printf("  %s, 64x64, %ld object pixels: %u -> %u samples changes the picture by %.3f%% (RMSE / mean); "
               "error bound 0.01 -> 0.0025: %.3f%%; another sample placement: %.3f%%\n",
               mats[k], obj, ns, 2 * ns, e_samples * 100, e_error * 100, e_seed * 100);
        CHECK(bad == 0 && obj > 500, "every pixel finite and non-negative (%ld bad), the object seen (%ld px)", bad, obj);
        CHECK(e_samples < 0.02, "doubling the samples changes %s by under 2%% (%.3f%%)", mats[k], e_samples * 100);
        CHECK(e_error < 0.005, "a 4x tighter octree bound changes %s by under 0.5%% (%.3f%%)", mats[k], e_error * 100);
        CHECK(e_seed < 0.02, "another sample placement changes %s by under 2%% (%.3f%%)", mats[k], e_seed * 100);
        free(base.px); free(base.mask); free(dbl.px); free(dbl.mask);
        free(tight.px); free(tight.mask); free(reseed.px); free(reseed.mask);
    }
}

/* A plane-parallel walk: diffuse light onto a half-space of index eta
 * (unit mean free path, isotropic scattering, albedo alpha) behind a smooth
 * boundary; the part of what entered that comes back out. The boundary
 * reflects by the unpolarised Fresnel equations on both sides (written here
 * again, not taken from the library). Weights fall by alpha at each
 * scattering and paths under 1e-4 end by Russian roulette. A small
 * generator of its own so the figure does not depend on the C library's
 * rand(). */
static uint64_t mc_state = 0x9E3779B97F4A7C15ull;
static double mc_uniform(void)
{
    mc_state ^= mc_state << 13;
    mc_state ^= mc_state >> 7;
    mc_state ^= mc_state << 17;
    return ((mc_state >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

static double fresnel(double ci, double n1, double n2)
{
    double st2 = (n1 / n2) * (n1 / n2) * (1 - ci * ci);
    if (st2 >= 1) return 1;
    double ct = sqrt(1 - st2), a = (n1 * ci - n2 * ct) / (n1 * ci + n2 * ct), b = (n1 * ct - n2 * ci) / (n1 * ct + n2 * ci);
    return 0.5 * (a * a + b * b);
}

/* One path from depth z going at cosine mu (positive: down): the weight
 * it leaves with (0: absorbed), *out_mu its inside cosine as it leaves. */
static double walk_path(double alpha, double eta, double z, double mu, double *out_mu)
{
    double w = 1;
    for (;;) {
        z += -log(mc_uniform()) * mu;
        if (z < 0) {
            if (mc_uniform() < fresnel(-mu, eta, 1.0)) { /* back in, mirrored */
                z = 0;
                mu = -mu;
                continue;
            }
            *out_mu = -mu;
            return w;
        }
        w *= alpha;
        if (w < 1e-4) {
            if (mc_uniform() > 0.1) return 0;
            w *= 10;
        }
        mu = 2 * mc_uniform() - 1;
    }
}

/* beam_mu: the outside's cosine of a beam, or negative for diffuse light. */
static double walk_albedo(double alpha, double eta, double beam_mu, int photons)
{
    double out = 0, mu_out;
    int entered = 0;
    for (int i = 0; i < photons; i++) {
        double mu_e = beam_mu >= 0 ? beam_mu : sqrt(mc_uniform()); /* diffuse: cosine-weighted */
        if (mc_uniform() < fresnel(mu_e, 1.0, eta)) continue; /* reflected outright */
        entered++;
        out += walk_path(alpha, eta, 0, sqrt(1 - (1 - mu_e * mu_e) / (eta * eta)), &mu_out);
    }
    return out / (entered ? entered : 1);
}

/* The same walk's light as it leaves: of the weight that comes out, the
 * share in each of the outside's cosine bins [i/10, (i+1)/10) over the share a
 * Lambertian surface sends there ((i+1)^2 - i^2) / 100, so 1 is Lambertian.
 * beam_mu as walk_albedo's, or 0 for light that starts `deep` mean free
 * paths down, isotropic (the law of darkening). */
static void walk_exit(double alpha, double eta, double beam_mu, double deep, int photons, double bins[10])
{
    double w_bin[10] = {0}, total = 0;
    for (int i = 0; i < photons; i++) {
        double z = deep, mu;
        if (deep > 0) mu = 2 * mc_uniform() - 1;
        else {
            if (mc_uniform() < fresnel(beam_mu, 1.0, eta)) continue;
            mu = sqrt(1 - (1 - beam_mu * beam_mu) / (eta * eta));
        }
        double mu_in = 0, w = walk_path(alpha, eta, z, mu, &mu_in);
        if (w <= 0) continue;
        double mu_e = sqrt(fmax(0.0, 1 - eta * eta * (1 - mu_in * mu_in)));
        int b = (int)(mu_e * 10);
        w_bin[b > 9 ? 9 : b] += w;
        total += w;
    }
    for (int b = 0; b < 10; b++) bins[b] = total > 0 ? w_bin[b] / total / (((b + 1) * (b + 1) - b * b) / 100.0) : 0;
}

static void test_exit(void)
{
    /* jd_halfspace_exit's laws on 101 cosines, averaged over a bin as the
     * walk counts (weighted by mu), against the walk: a beam at 0.5 and
     * light from deep below, at eta 1 and 1.3. */
    enum { N = 101 };
    static double deep[N], beam[N * N];
    const double alphas[] = {0.9, 0.99}, etas[] = {1.0, 1.3};
    double worst = 0;
    for (int e = 0; e < 2; e++)
        for (int k = 0; k < 2; k++) {
            CHECK(jd_halfspace_exit(alphas[k], etas[e], N, deep, beam) == 0, "the exit laws computed");
            for (int which = 0; which < 2; which++) {
                double mc[10];
                walk_exit(alphas[k], etas[e], 0.5, which ? 10.0 : 0.0, which ? 2000000 : 300000, mc);
                printf("eta %.1f, albedo %.2f, %s: bins at 0.15, 0.45, 0.75, 0.95: exact", etas[e], alphas[k],
                       which ? "from deep below" : "a beam at 0.5");
                double ex[10];
                for (int b = 0; b < 10; b++) {
                    double num = 0, den = 0;
                    for (int i = 10 * b; i <= 10 * b + 10; i++) {
                        double wt = (i == 10 * b || i == 10 * b + 10 ? 0.5 : 1.0) * i / (N - 1.0);
                        num += wt * (which ? deep[i] : beam[i * N + 50]);
                        den += wt;
                    }
                    ex[b] = num / den;
                }
                for (int b = 1; b < 10; b += 3) printf(" %.3f", ex[b]);
                printf(" %.3f, the walk's", ex[9]);
                for (int b = 1; b < 10; b += 3) printf(" %.3f", mc[b]);
                printf(" %.3f\n", mc[9]);
                /* Past the critical angle's bin at eta 1.3 the bins are compared alike. */
                for (int b = 1; b < 10; b++) worst = fmax(worst, fabs(ex[b] - mc[b]) / mc[b]);
            }
        }
    printf("the exit laws against the walk, bins 0.1 to 1: largest difference %.1f%%\n", 100 * worst);
    /* The walk's own noise in the narrow low bins is 2-4%; a Lambertian exit would be 20-80% off. */
    CHECK(worst < 0.06, "the exit laws within 6%% of the walk (%.1f%%)", 100 * worst);
}

static void test_albedo(void)
{
    const double alphas[] = {0.3, 0.68, 0.9, 0.99}, etas[] = {1.0, 1.3, 1.5};
    for (int e = 0; e < 3; e++)
        for (int k = 0; k < 4; k++) {
            double exact = jd_halfspace_albedo(alphas[k], etas[e]), mc = walk_albedo(alphas[k], etas[e], -1, 400000);
            double A = (1 + jd_dipole_fdr(etas[e])) / (1 - jd_dipole_fdr(etas[e])), dip = jd_dipole_rd_total(alphas[k], A);
            printf("eta %.1f, albedo %.2f: exact %.4f, Monte Carlo %.4f, dipole %.4f\n", etas[e], alphas[k], exact, mc, dip);
            CHECK(fabs(exact - mc) < 0.005 + 0.01 * mc, "half-space albedo at eta %.1f, %.2f: %.4f, the walk's %.4f", etas[e],
                  alphas[k], exact, mc);
        }
    /* A beam: normal and at 60 degrees, where the light goes deeper or
     * shallower than diffuse light's and less or more of it comes back. */
    for (int e = 0; e < 3; e += 2)
        for (int k = 2; k < 4; k++) {
            double b[3];
            double dif = 0;
            CHECK(jd_halfspace_albedo_beam(alphas[k], etas[e], 3, b, &dif) == 0 && fabs(dif - jd_halfspace_albedo(alphas[k], etas[e])) < 1e-9, "the beam's albedo computed, its diffuse figure the same");
            for (int q = 1; q < 3; q++) {
                double mc = walk_albedo(alphas[k], etas[e], 0.5 * q, 400000);
                printf("eta %.1f, albedo %.2f, a beam at cosine %.1f: exact %.4f, Monte Carlo %.4f\n", etas[e], alphas[k],
                       0.5 * q, b[q], mc);
                CHECK(fabs(b[q] - mc) < 0.005 + 0.01 * mc, "beam at %.1f, eta %.1f, albedo %.2f: %.4f, the walk's %.4f", 0.5 * q,
                      etas[e], alphas[k], b[q], mc);
            }
        }
    /* The renderer's table (core/albedo_table.c) between its points. */
    const double t_eta[] = {1.0, 1.13, 1.3, 1.5, 2.37}, t_alpha[] = {0.02, 0.3, 0.68, 0.9, 0.99, 0.9995};
    double worst = 0;
    for (int e = 0; e < 5; e++)
        for (int k = 0; k < 6; k++) {
            double A = (1 + jd_dipole_fdr(t_eta[e])) / (1 - jd_dipole_fdr(t_eta[e]));
            double want = jd_halfspace_albedo(t_alpha[k], t_eta[e]) / jd_dipole_rd_total(t_alpha[k], A);
            worst = fmax(worst, fabs(jd_albedo_ratio(t_alpha[k], t_eta[e]) / want - 1));
        }
    printf("the renderer's table of the exact albedo over the dipole's: largest error %.4f%%\n", 100 * worst);
    CHECK(worst < 0.005, "the table within 0.5%% of the solution between its points (%.4f%%)", 100 * worst);
    CHECK(jd_halfspace_albedo(0, 1.5) == 0 && jd_halfspace_albedo(1, 1.5) == 1, "no scattering: nothing back; no absorption: all");
}

int main(int argc, char **argv)
{
    int quick = argc > 1 && !strcmp(argv[1], "--quick");
    if (quick) argc--, argv++;
    if (!quick) {
        printf("the half-space's exact albedo:\n");
        test_albedo();
        printf("how the light leaves the half-space:\n");
        test_exit();
    }
    jd_mesh slab;
    make_slab(&slab);
    printf("slab under uniform light (100 mm square):\n");
    test_slab(&slab, "marble");
    test_slab(&slab, "skin1");
    test_slab(&slab, "ketchup");
    test_slab_colours(&slab);
    printf("thin slab (%.0f mm, 100 mm square) lit on one face:\n", THIN_D);
    test_thin_slab("marble");
    test_thin_slab("skin1");
    printf("the diffusion equation solved in the volume, a box lit on top:\n");
    test_volume_box("marble", THIN_D, 0.4f, 0.04);
    if (!quick) {
        test_volume_box("marble", 40.0f, 0.8f, 0.04);
        printf("two plates %.0f mm apart, one lit: the light between them:\n", PLATE_GAP);
        test_bounce("skin1");
        test_bounce("marble");
    }
    printf("Gaussian beam of 1 mm width on the same patch:\n");
    test_profile(&slab, "marble");
    test_profile(&slab, "skin1");
    test_profile(&slab, "ketchup");

    if (argc > 1) {
        static unsigned char mem[16 << 20];
        jd_arena a;
        jd_arena_init(&a, mem, sizeof mem);
        jd_load_desc ld = {.path = argv[1], .allow_32bit_indices = 1};
        jd_mesh m;
        jd_load_stats ls;
        jd_error err = {0};
        if (jd_mesh_load_draco(&ld, &a, &m, &ls, &err)) {
            CHECK(0, "load %s: %s", argv[1], err.msg);
        } else {
            printf("convergence on %s (%u triangles), back-lit:\n", argv[1], m.num_indices / 3);
            test_convergence(&m);
        }
    }
    return jd_check_summary("reference");
}
