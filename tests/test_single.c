/* Is the reference's single scattering (reference/ref_single.h) right?
 * Against closed forms for boxes, index-matched, a directional light:
 *   1. a thick box lit and seen through its top face: the half-space's
 *      e alpha / 4 mu0 / (mu0 + mu) (jd_single_halfspace), within 1%, at
 *      three angles of the light and two of the view;
 *   2. a slab d mm thick lit straight from behind and seen straight on:
 *      e sigma_s / 4 d e^(-sigma_t d), within 1%;
 *   3. two such slabs one behind the other, with air between: the sum, the
 *      far one's light dimmed by the near one's e^(-sigma_t d), within 1%;
 *   4. a lone face (an open mesh, no way out behind it): no figure (-1).
 * Usage: test_single. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "ref_bvh.h"
#include "ref_single.h"

enum { MAX_BOXES = 2 };
static float pos[MAX_BOXES * 24 * 3], nrm[MAX_BOXES * 24 * 3];
static uint32_t idx[MAX_BOXES * 36];
static int boxes;

/* An axis-aligned box from lo to hi (world units), each face its own four
 * vertices with the face's outward normal, wound outward. */
static void add_box(const float lo[3], const float hi[3])
{
    for (int f = 0; f < 6; f++) {
        int ax = f / 2, sgn = f % 2 ? 1 : -1, u = (ax + 1) % 3, v = (ax + 2) % 3;
        int base = boxes * 24 + f * 4;
        for (int c = 0; c < 4; c++) {
            float *p = pos + 3 * (base + c), *n = nrm + 3 * (base + c);
            p[ax] = sgn > 0 ? hi[ax] : lo[ax];
            p[u] = (c == 1 || c == 2) ? hi[u] : lo[u];
            p[v] = (c >= 2) ? hi[v] : lo[v];
            n[0] = n[1] = n[2] = 0;
            n[ax] = (float)sgn;
        }
        /* (u, v) corners 0 (lo, lo), 1 (hi, lo), 2 (hi, hi), 3 (lo, hi):
         * counter-clockwise about +ax; turned for the face at -ax. */
        uint32_t q[6] = {0, 1, 2, 0, 2, 3}, r[6] = {0, 2, 1, 0, 3, 2}, *t = idx + boxes * 36 + f * 6;
        for (int k = 0; k < 6; k++) t[k] = (uint32_t)base + (sgn > 0 ? q[k] : r[k]);
    }
    boxes++;
}

static jd_bvh bvh;
static jd_single one(float mm, double sigma_s, double sigma_a)
{
    jd_single s = {.bvh = &bvh, .nrm = nrm, .mm_per_world = mm};
    for (int c = 0; c < 3; c++) {
        s.sigma_t[c] = sigma_s + sigma_a;
        s.sigma_s[c] = sigma_s;
    }
    return s;
}

static void build(void)
{
    jd_error err = {0};
    jd_bvh_free(&bvh);
    memset(&bvh, 0, sizeof bvh);
    CHECK(!jd_bvh_build(&bvh, pos, idx, (uint32_t)boxes * 12, &err), "bvh: %s", err.msg);
}

/* The mean over seeds (the stratification's jitter) of channel 0. */
static double mean_single(const jd_single *s, const float p[3], const float ng[3], const float dir[3],
                          const float light[3], int *ret)
{
    double sum = 0;
    for (uint32_t seed = 0; seed < 32; seed++) {
        float out[3];
        *ret = jd_single_scatter(s, p, ng, dir, light, 1.0f, seed * 7919u + 1u, out);
        sum += out[0];
    }
    return sum / 32;
}

int main(void)
{
    const float up[3] = {0, 1, 0};
    /* 1. A box 200 mm wide and deep, 100 mm thick (1 world unit = 100 mm),
     * marble's green (sigma_s 2.62, sigma_a 0.0029 per mm): deep enough
     * that nothing comes from its other faces. */
    const float lo1[3] = {-1, -1, -1}, hi1[3] = {1, 0, 1};
    boxes = 0;
    add_box(lo1, hi1);
    build();
    jd_single s = one(100.0f, 2.62, 0.0029);
    float top[3] = {0, 0, 0};
    const float light_deg[3] = {0, 40, 70}, view_deg[2] = {0, 50};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 2; j++) {
            float a = light_deg[i] * 3.14159265f / 180, b = view_deg[j] * 3.14159265f / 180;
            float light[3] = {sinf(a), cosf(a), 0}, dir[3] = {0, -cosf(b), sinf(b)};
            int ret;
            double got = mean_single(&s, top, up, dir, light, &ret);
            double alpha = 2.62 / (2.62 + 0.0029), want = jd_single_halfspace(1.0f, (float)alpha, cosf(a), cosf(b));
            printf("  half-space, light %.0f, view %.0f degrees: %.5f, closed form %.5f\n", light_deg[i], view_deg[j],
                   got, want);
            CHECK(ret == 1 && fabs(got / want - 1) < 0.01, "half-space at light %.0f, view %.0f: %.5f against %.5f",
                  light_deg[i], view_deg[j], got, want);
        }

    /* 2. A slab 4 mm thick (0.04 units), 200 mm wide, ketchup's red
     * (sigma_s 0.18, sigma_a 0.061): lit from below, seen from above. */
    const float lo2[3] = {-1, -0.04f, -1}, hi2[3] = {1, 0, 1};
    boxes = 0;
    add_box(lo2, hi2);
    build();
    s = one(100.0f, 0.18, 0.061);
    const float below[3] = {0, -1, 0}, down[3] = {0, -1, 0};
    int ret;
    double got = mean_single(&s, top, up, down, below, &ret), st = 0.241, d = 4;
    double want = 0.18 / 4 * d * exp(-st * d);
    printf("  slab 4 mm, back-lit: %.5f, closed form %.5f\n", got, want);
    CHECK(ret == 1 && fabs(got / want - 1) < 0.01, "slab back-lit: %.5f against %.5f", got, want);

    /* 3. A second such slab 10 mm below the first. */
    const float lo3[3] = {-1, -0.18f, -1}, hi3[3] = {1, -0.14f, 1};
    add_box(lo3, hi3);
    build();
    got = mean_single(&s, top, up, down, below, &ret);
    want = 0.18 / 4 * d * exp(-st * 2 * d) * 2; /* each slab's light through both slabs */
    printf("  two slabs, back-lit: %.5f, closed form %.5f (%d parts)\n", got, want, ret);
    CHECK(ret == 2 && fabs(got / want - 1) < 0.01, "two slabs back-lit: %.5f against %.5f", got, want);

    /* 4. A lone face: the first box's top face alone. */
    jd_bvh_free(&bvh);
    memset(&bvh, 0, sizeof bvh);
    jd_error err = {0};
    uint32_t lone[6];
    memcpy(lone, idx + 3 * 6, sizeof lone); /* face 3: the box's +y face */
    CHECK(!jd_bvh_build(&bvh, pos, lone, 2, &err), "bvh of a lone face: %s", err.msg);
    float out[3] = {1, 1, 1};
    ret = jd_single_scatter(&s, top, up, down, up, 1.0f, 1, out);
    CHECK(ret == -1 && out[0] == 0, "a lone face: no figure (returned %d, %g)", ret, out[0]);

    jd_bvh_free(&bvh);
    return jd_check_summary("single");
}
