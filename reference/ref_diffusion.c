#include "ref_diffusion.h"
#include "ref_slab.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { LEAF_POINTS = 8, MAX_DEPTH = 40, TABLE_N = 2048, DISK_RINGS = 24, DISK_ANGLES = 48 };

/* The flux through a plane of a source at height h below it and its
 * negative image hv above (squares given), at squared distance r2 along the
 * plane, times k: Rd's form (Jensen et al. 2001). */
static inline float dipole_pair(float k, float s, float h, float h2, float hv, float hv2, float r2)
{
    float dr2 = r2 + h2, dv2 = r2 + hv2, dr = sqrtf(dr2), dv = sqrtf(dv2);
    return k * (h * (1.0f + s * dr) * expf(-s * dr) / (dr2 * dr) + hv * (1.0f + s * dv) * expf(-s * dv) / (dv2 * dv));
}

/* scale * Rd(r), three channels, at squared distance r2: jd_dipole_rd
 * (material.c) again, in floats with its constants squared ahead, because
 * this is the inner loop: calling the double version makes the 512x512
 * bunny take 20 s instead of 11. */
static inline void rd_scaled(const jd_diffusion *d, float r2, float scale, float out[3])
{
    for (int c = 0; c < 3; c++)
        out[c] = scale * dipole_pair(d->k[c], d->str[c], d->zr[c], d->zr2[c], d->zv[c], d->zv2[c], r2);
}

/* The light carried across a part `thick` mm thick, at squared distance
 * r2 from where it leaves: Rd's form with the real source at the height
 * ref_slab.h gives and its image 2 z_b above the face, so the profile is as
 * wide as the part is thick. Whole (no window): it is smooth where it
 * matters. */
static inline void kernel_carried(const jd_diffusion *d, float r2, float thick, float out[3])
{
    for (int c = 0; c < 3; c++) {
        float h = (float)jd_slab_carried_height(thick, d->zr[c]), hv = h + d->zb2[c];
        out[c] = dipole_pair(d->k[c], d->str[c], h, h * h, hv, hv * hv, r2);
    }
}

/* The window w(r) = (1 - r^2/r0^2)^2 inside r0, 0 outside. */
static inline float window(const jd_diffusion *d, float r2)
{
    float r02 = d->r0 * d->r0;
    if (r2 >= r02) return 0.0f;
    float q = 1.0f - r2 / r02;
    return q * q;
}

/* Rd (1 - w): the summed part. */
static inline void kernel_exact(const jd_diffusion *d, float r2, float out[3])
{
    rd_scaled(d, r2, 1.0f - window(d, r2), out);
}

/* Rd w: the window's part, point values (its weights only average). */
static inline void kernel_window(const jd_diffusion *d, float r2, float out[3])
{
    rd_scaled(d, r2, window(d, r2), out);
}

/* The point kernel near the samples, the exact one beyond the table. */
static inline void kernel(const jd_diffusion *d, float r2, float out[3])
{
    if (r2 >= d->table_rmax * d->table_rmax) { kernel_exact(d, r2, out); return; }
    float x = sqrtf(r2) * d->table_inv_dr;
    int i = (int)x;
    if (i >= d->table_n - 1) i = d->table_n - 2;
    float f = x - (float)i;
    const float *a = d->table + 3 * i;
    for (int c = 0; c < 3; c++) out[c] = a[c] + f * (a[3 + c] - a[c]);
}

/* Rd (1 - w) averaged over a disk of radius R whose centre is r away, in
 * the same plane: polar midpoint rule over the disk. */
static jd_result build_table(jd_diffusion *d, float disk_r, jd_error *err)
{
    d->table_n = TABLE_N;
    d->table = malloc(sizeof(float) * 3 * TABLE_N);
    if (!d->table) return jd_fail(err, JD_ERR_BUDGET, "out of memory for the kernel table");
    /* Past the window plus a few disks, the average and the point value
     * agree to well under 0.1%. */
    d->table_rmax = d->r0 + 8.0f * disk_r;
    float dr = d->table_rmax / (TABLE_N - 1);
    d->table_inv_dr = 1.0f / dr;
    for (int i = 0; i < TABLE_N; i++) {
        double r = i * dr, acc[3] = {0, 0, 0}, wsum = 0;
        for (int a = 0; a < DISK_RINGS; a++) {
            double rho = disk_r * sqrt((a + 0.5) / DISK_RINGS); /* equal-area rings */
            for (int b = 0; b < DISK_ANGLES; b++) {
                double th = (b + 0.5 * (a & 1)) * 2.0 * M_PI / DISK_ANGLES;
                double x = r + rho * cos(th), y = rho * sin(th);
                float k[3];
                kernel_exact(d, (float)(x * x + y * y), k);
                for (int c = 0; c < 3; c++) acc[c] += k[c];
                wsum += 1;
            }
        }
        for (int c = 0; c < 3; c++) d->table[3 * i + c] = (float)(acc[c] / wsum);
    }
    return JD_OK;
}

static int grow(jd_diffusion *d)
{
    uint32_t cap = d->cap_nodes ? d->cap_nodes * 2 : 1024;
    jd_octree_node *n = realloc(d->nodes, sizeof *n * cap);
    if (!n) return 0;
    d->nodes = n;
    d->cap_nodes = cap;
    return 1;
}

static void summarise(jd_diffusion *d, uint32_t ni, uint32_t first, uint32_t count)
{
    jd_octree_node *n = &d->nodes[ni];
    double c[3] = {0, 0, 0}, ca[3] = {0, 0, 0}, w = 0, area = 0, ea[3] = {0, 0, 0}, thick = 0;
    for (int k = 0; k < 3; k++) { n->lo[k] = FLT_MAX; n->hi[k] = -FLT_MAX; }
    for (uint32_t i = first; i < first + count; i++) {
        const jd_ref_point *p = &d->pts[i];
        double pw = (double)p->ea[0] + p->ea[1] + p->ea[2];
        for (int k = 0; k < 3; k++) {
            if (p->p[k] < n->lo[k]) n->lo[k] = p->p[k];
            if (p->p[k] > n->hi[k]) n->hi[k] = p->p[k];
            c[k] += pw * p->p[k];
            ca[k] += (double)p->area * p->p[k];
            ea[k] += p->ea[k];
        }
        w += pw;
        thick += pw * p->thick;
        area += p->area;
    }
    for (int k = 0; k < 3; k++) {
        n->c[k] = (float)(w > 0 ? c[k] / w : ca[k] / (area > 0 ? area : 1));
        n->ea[k] = (float)ea[k];
    }
    n->area = (float)area;
    n->thick = (float)(w > 0 ? thick / w : 0.0);
}

/* Recursive octant split; points are reordered so every node owns a range. */
static int build_node(jd_diffusion *d, uint32_t ni, uint32_t first, uint32_t count, int depth)
{
    summarise(d, ni, first, count);
    jd_octree_node *n = &d->nodes[ni];
    float ext = fmaxf(n->hi[0] - n->lo[0], fmaxf(n->hi[1] - n->lo[1], n->hi[2] - n->lo[2]));
    if (count <= LEAF_POINTS || depth >= MAX_DEPTH || !(ext > 0)) {
        n->leaf = 1; n->first = first; n->count = count;
        return 1;
    }
    float mid[3];
    for (int k = 0; k < 3; k++) mid[k] = 0.5f * (n->lo[k] + n->hi[k]);
    /* Counting sort into octants. */
    uint32_t cnt[8] = {0}, start[8];
    for (uint32_t i = first; i < first + count; i++) {
        const float *p = d->pts[i].p;
        cnt[(p[0] > mid[0]) | (p[1] > mid[1]) << 1 | (p[2] > mid[2]) << 2]++;
    }
    uint32_t s = first;
    for (int o = 0; o < 8; o++) { start[o] = s; s += cnt[o]; }
    uint32_t next[8];
    memcpy(next, start, sizeof next);
    for (int o = 0; o < 8; o++) {
        while (next[o] < start[o] + cnt[o]) {
            const float *p = d->pts[next[o]].p;
            int t = (p[0] > mid[0]) | (p[1] > mid[1]) << 1 | (p[2] > mid[2]) << 2;
            if (t == o) { next[o]++; continue; }
            jd_ref_point tmp = d->pts[next[t]];
            d->pts[next[t]++] = d->pts[next[o]];
            d->pts[next[o]] = tmp;
        }
    }
    int kids = 0;
    for (int o = 0; o < 8; o++) kids += cnt[o] > 0;
    while (d->num_nodes + kids > d->cap_nodes)
        if (!grow(d)) return 0;
    n = &d->nodes[ni];
    uint32_t child = d->num_nodes;
    d->num_nodes += kids;
    n->leaf = 0;
    n->first = child;
    n->count = (uint32_t)kids;
    for (int o = 0; o < 8; o++) {
        if (!cnt[o]) continue;
        if (!build_node(d, child++, start[o], cnt[o], depth + 1)) return 0;
    }
    return 1;
}

jd_result jd_diffusion_build(jd_diffusion *d, jd_ref_point *pts, uint32_t n, const jd_dipole *dp, float r0_mm,
                             float error, int carried, jd_error *err)
{
    memset(d, 0, sizeof *d);
    d->carried = carried;
    d->pts = pts;
    d->num_pts = n;
    d->r0 = r0_mm;
    d->error = error;
    for (int c = 0; c < 3; c++) {
        d->zr[c] = (float)dp->zr[c];
        d->zv[c] = (float)dp->zv[c];
        d->zr2[c] = d->zr[c] * d->zr[c];
        d->zv2[c] = d->zv[c] * d->zv[c];
        d->zb2[c] = d->zv[c] - d->zr[c];
        d->str[c] = (float)dp->sigma_tr[c];
        /* The profile is diffusion's own, unscaled, and the window's part
         * below takes the exact albedo's excess (jd_ref_diffusion_share):
         * on a 20 mm ketchup sphere the volume solve, scaled whole by the
         * red's ratio of 1.43, came out 41% over Cycles, 3% under without
         * it. The light carried across a thin part keeps the scale: its
         * weights are the slab's totals (ref_slab.c). */
        double share = jd_ref_diffusion_share(dp, c);
        d->k[c] = (float)(dp->alpha[c] / (carried ? share : 1.0) / (4.0 * M_PI));
        if (carried) continue; /* summed whole: no window, no table */
        /* Rd w over the plane, r in [0, r0]: Simpson on a fine grid (Rd is
         * smooth at the scale of z_r, and the grid is far finer). */
        const int steps = 4096;
        double h = r0_mm / steps, sum = 0;
        for (int i = 0; i <= steps; i++) {
            double r = i * h, q = 1.0 - (r * r) / ((double)r0_mm * r0_mm);
            double f = jd_dipole_rd(dp, c, r) * q * q * 2.0 * M_PI * r;
            sum += f * (i == 0 || i == steps ? 1 : (i & 1) ? 4 : 2);
        }
        /* jd_dipole_rd is the scaled profile: the window keeps diffusion's
         * share of it and the whole of the excess, so that a flat part under
         * uniform light still gives out Rd_total. */
        d->local[c] = (r0_mm > 0 ? sum * h / 3.0 : 0.0) * share + (1.0 - share) * dp->rd_total[c];
    }
    if (!n) return jd_fail(err, JD_ERR_ARG, "no irradiance samples");
    if (!carried) {
        jd_result res = build_table(d, sqrtf(pts[0].area / (float)M_PI), err);
        if (res) return res;
    }
    if (!grow(d)) { jd_diffusion_free(d); return jd_fail(err, JD_ERR_BUDGET, "out of memory for the octree"); }
    d->num_nodes = 1;
    if (!build_node(d, 0, 0, n, 0)) {
        jd_diffusion_free(d);
        return jd_fail(err, JD_ERR_BUDGET, "out of memory for the octree of %u samples", n);
    }
    return JD_OK;
}

void jd_diffusion_free(jd_diffusion *d)
{
    free(d->nodes);
    free(d->table);
    d->table = NULL;
    d->nodes = NULL;
    d->num_nodes = d->cap_nodes = 0;
}

uint32_t jd_diffusion_sum(const jd_diffusion *d, const float x[3], double out[3], double wnum[3], double wden[3])
{
    uint32_t stack[MAX_DEPTH * 8 + 8];
    int sp = 0;
    uint32_t evals = 0;
    double acc[3] = {0, 0, 0}, num[3] = {0, 0, 0}, den[3] = {0, 0, 0};
    float r02 = d->r0 * d->r0;
    stack[sp++] = 0;
    while (sp) {
        const jd_octree_node *n = &d->nodes[stack[--sp]];
        float dx = n->c[0] - x[0], dy = n->c[1] - x[1], dz = n->c[2] - x[2];
        float r2 = dx * dx + dy * dy + dz * dz, box2 = 0;
        for (int k = 0; k < 3; k++) {
            float e = x[k] < n->lo[k] ? n->lo[k] - x[k] : x[k] > n->hi[k] ? x[k] - n->hi[k] : 0.0f;
            box2 += e * e;
        }
        /* A node can stand for its points when it looks small from x and
         * lies wholly outside the window. */
        if (box2 > r02 && n->area < d->error * r2 && (n->leaf ? n->count > 1 : 1)) {
            float k[3];
            if (d->carried) kernel_carried(d, r2, n->thick, k);
            else kernel(d, r2, k);
            for (int c = 0; c < 3; c++) acc[c] += (double)k[c] * n->ea[c];
            evals++;
            continue;
        }
        if (n->leaf) {
            for (uint32_t i = n->first; i < n->first + n->count; i++) {
                const jd_ref_point *p = &d->pts[i];
                float ex = p->p[0] - x[0], ey = p->p[1] - x[1], ez = p->p[2] - x[2];
                float e2 = ex * ex + ey * ey + ez * ez, k[3];
                if (d->carried) {
                    kernel_carried(d, e2, p->thick, k);
                    for (int c = 0; c < 3; c++) acc[c] += (double)k[c] * p->ea[c];
                    continue;
                }
                kernel(d, e2, k);
                for (int c = 0; c < 3; c++) acc[c] += (double)k[c] * p->ea[c];
                if (e2 < r02) {
                    kernel_window(d, e2, k);
                    for (int c = 0; c < 3; c++) {
                        num[c] += (double)k[c] * p->ea[c];
                        den[c] += (double)k[c] * p->area;
                    }
                }
            }
            evals += n->count;
        } else {
            for (uint32_t c = 0; c < n->count; c++) stack[sp++] = n->first + c;
        }
    }
    memcpy(out, acc, sizeof acc);
    if (wnum) memcpy(wnum, num, sizeof num);
    if (wden) memcpy(wden, den, sizeof den);
    return evals;
}

uint32_t jd_diffusion_exitance(const jd_diffusion *d, const float x[3], const float e_local[3], float out[3])
{
    double s[3], num[3], den[3];
    uint32_t evals = jd_diffusion_sum(d, x, s, num, den);
    /* The window's part: its exact integral over the tangent plane times
     * the irradiance the samples inside it see, weighted as the integral
     * weights them (a ratio: uniform light gives exactly that light, however
     * the samples fell). With no sample inside, the light at x. */
    for (int c = 0; c < 3; c++) {
        double e = den[c] > 0 ? num[c] / den[c] : e_local[c];
        out[c] = (float)(d->carried ? s[c] : s[c] + d->local[c] * e);
    }
    return evals;
}
