#include "ref_volume.h"

#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

enum { JD_VOL_MAX_HITS = 512 };

static size_t cell_of(const jd_volume *v, int i, int j, int k)
{
    return ((size_t)k * v->ny + j) * v->nx + i;
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return x < y ? -1 : x > y;
}

/* Every crossing of the line o + t dir (t > 0, world units) with the mesh,
 * sorted; -1 when there are more than the room. */
static int crossings(const jd_bvh *b, const float o[3], const float dir[3], float *t, int room)
{
    int n = 0;
    float tmin = 0.0f;
    jd_hit hit;
    while (jd_bvh_intersect(b, o, dir, tmin, 1e30f, &hit)) {
        if (n == room) return -1;
        t[n++] = hit.t;
        /* Past this face only: a relative step, so the next face (even
         * one a hair further, a thin part's other side) is still found. */
        tmin = hit.t + 1e-6f * (1.0f + hit.t);
    }
    qsort(t, (size_t)n, sizeof *t, cmp_float);
    return n;
}

static jd_result boundary(jd_volume *v, const jd_volume_desc *d, jd_error *err);

jd_result jd_volume_init(jd_volume *v, const jd_volume_desc *d, jd_error *err)
{
    memset(v, 0, sizeof *v);
    if (!d->bvh || !d->bvh->num_nodes) return jd_fail(err, JD_ERR_ARG, "the volume needs a mesh");
    const jd_bvh_node *root = &d->bvh->nodes[0];
    float mm = d->mm_per_world, lo[3], ext[3];
    double box = 1;
    for (int a = 0; a < 3; a++) {
        lo[a] = root->lo[a] * mm;
        ext[a] = (root->hi[a] - root->lo[a]) * mm;
        box *= ext[a] > 0 ? ext[a] : 1e-3;
    }
    double cells = d->max_cells ? d->max_cells : 6e6;
    float h = d->cell_mm > 0 ? d->cell_mm : (float)fmax(0.25, cbrt(box / cells));
    int n[3];
    for (int a = 0; a < 3; a++) {
        /* Two cells of air each side: every boundary face has an outside. */
        double c = ceil(ext[a] / h) + 4;
        if (c > 4096) return jd_fail(err, JD_ERR_ARG, "%.3g mm cells: %.0f along an axis, over 4096", h, c);
        n[a] = (int)c;
        v->lo[a] = lo[a] - 2 * h;
    }
    double total = (double)n[0] * n[1] * n[2];
    /* About 110 bytes a cell inside and 5 a cell of the box: 16 million
     * keeps the worst (a box full) near 1.8 GB. */
    if (total > 16e6)
        return jd_fail(err, JD_ERR_BUDGET, "%.3g mm cells: %.0f in the box around the mesh, over 16 million (%.2g mm or more)",
                       h, total, 1.05 * cbrt(box / 16e6) + 0.01);
    v->nx = n[0], v->ny = n[1], v->nz = n[2], v->h = h;
    uint8_t *votes = calloc((size_t)total, 1);
    v->index = malloc(sizeof *v->index * (size_t)total);
    float *t = malloc(sizeof *t * JD_VOL_MAX_HITS);
    if (!votes || !v->index || !t) {
        free(votes);
        free(t);
        jd_volume_free(v);
        return jd_fail(err, JD_ERR_BUDGET, "out of memory for %.0f cells", total);
    }
    /* Parity along each axis, a row of cells at a time; a row through an
     * edge or a hole (odd crossings) votes for nothing. Offsets of a small
     * irrational share of a cell keep rays off the mesh's own grid. */
    for (int a = 0; a < 3; a++) {
        int b = (a + 1) % 3, c = (a + 2) % 3;
        for (int jb = 0; jb < n[b]; jb++)
            for (int jc = 0; jc < n[c]; jc++) {
                float o[3], dir[3] = {0, 0, 0};
                dir[a] = 1;
                o[a] = v->lo[a] / mm;
                o[b] = (v->lo[b] + (jb + 0.5f + 0.0137f) * h) / mm;
                o[c] = (v->lo[c] + (jc + 0.5f - 0.0219f) * h) / mm;
                int m = crossings(d->bvh, o, dir, t, JD_VOL_MAX_HITS);
                if (m <= 0 || (m & 1)) continue;
                int next = 0, inside = 0;
                for (int ja = 0; ja < n[a]; ja++) {
                    float ta = (ja + 0.5f) * h / mm;
                    while (next < m && t[next] < ta) { inside ^= 1; next++; }
                    if (!inside) continue;
                    int ijk[3];
                    ijk[a] = ja, ijk[b] = jb, ijk[c] = jc;
                    votes[cell_of(v, ijk[0], ijk[1], ijk[2])]++;
                }
            }
    }
    free(t);
    uint32_t count = 0;
    for (size_t i = 0; i < (size_t)total; i++) v->index[i] = votes[i] >= 2 ? (int32_t)count++ : -1;
    free(votes);
    if (!count) {
        jd_volume_free(v);
        return jd_fail(err, JD_ERR_ARG, "no cell of %.3g mm is inside the mesh (is it closed?)", h);
    }
    v->num_inside = count;
    v->phi = calloc(3 * (size_t)count, sizeof *v->phi);
    if (!v->phi) {
        jd_volume_free(v);
        return jd_fail(err, JD_ERR_BUDGET, "out of memory for %u cells' fluence", count);
    }
    for (int c = 0; c < 3; c++) {
        double st = d->dp->sigma_t[c];
        v->D[c] = st > 0 ? (float)(1.0 / (3.0 * st)) : 0.0f;
        v->zb[c] = (float)(2.0 * d->dp->A * v->D[c]);
    }
    jd_result res = boundary(v, d, err);
    if (res) jd_volume_free(v);
    return res;
}

void jd_volume_free(jd_volume *v)
{
    free(v->index);
    free(v->phi);
    free(v->nb);
    free(v->bw);
    free(v->first_face);
    free(v->faces);
    memset(v, 0, sizeof *v);
}

/* The eight cells around p (mm) whose centres bracket it, inside ones only:
 * their unknowns and weights, normalised. Returns how many. */
static int corners(const jd_volume *v, const float p[3], int32_t u[8], float w[8])
{
    float f[3];
    int i0[3];
    for (int a = 0; a < 3; a++) {
        float g = (p[a] - v->lo[a]) / v->h - 0.5f;
        i0[a] = (int)floorf(g);
        f[a] = g - (float)i0[a];
    }
    int n = 0;
    float sum = 0;
    for (int c = 0; c < 8; c++) {
        int ii = i0[0] + (c & 1), jj = i0[1] + (c >> 1 & 1), kk = i0[2] + (c >> 2);
        if (ii < 0 || jj < 0 || kk < 0 || ii >= v->nx || jj >= v->ny || kk >= v->nz) continue;
        int32_t x = v->index[cell_of(v, ii, jj, kk)];
        if (x < 0) continue;
        float wt = (c & 1 ? f[0] : 1 - f[0]) * (c >> 1 & 1 ? f[1] : 1 - f[1]) * (c >> 2 ? f[2] : 1 - f[2]);
        if (wt <= 0) continue;
        u[n] = x, w[n] = wt, sum += wt;
        n++;
    }
    for (int k = 0; k < n; k++) w[k] /= sum;
    return n;
}

/* Corners of p, or of p moved further along -n half a cell at a time
 * (a thin part's source may sit past the cells' centres). */
static int corners_inward(const jd_volume *v, const float p[3], const float nrm[3], int32_t u[8], float w[8])
{
    float q[3] = {p[0], p[1], p[2]};
    for (int step = 0; step < 4; step++) {
        int m = corners(v, q, u, w);
        if (m) return m;
        for (int a = 0; a < 3; a++) q[a] -= 0.5f * v->h * nrm[a];
    }
    return 0;
}

/* Neighbours, and per boundary face where the surface really is between
 * the cell's centre and the next (a cut cell: the boundary condition
 * there, not on the grid's steps) and how much of the true surface the
 * face stands for: |cos| of the surface's normal to the face's axis. Over
 * a slanted wall the steps' faces then add up to its area (sum of n_a^2),
 * and a cell on an edge keeps both of its walls. */
static jd_result boundary(jd_volume *v, const jd_volume_desc *d, jd_error *err)
{
    size_t N = v->num_inside;
    float h = v->h, mm = d->mm_per_world;
    v->nb = malloc(sizeof *v->nb * 6 * N);
    v->bw = malloc(sizeof *v->bw * 3 * N);
    v->first_face = malloc(sizeof *v->first_face * (N + 1));
    if (!v->nb || !v->bw || !v->first_face)
        return jd_fail(err, JD_ERR_BUDGET, "out of memory for the neighbours of %zu cells", N);
    uint32_t faces = 0, cap = 0;
    for (int k = 0; k < v->nz; k++)
        for (int j = 0; j < v->ny; j++)
            for (int i = 0; i < v->nx; i++) {
                int32_t x = v->index[cell_of(v, i, j, k)];
                if (x < 0) continue;
                static const int off[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
                float g[3] = {0, 0, 0};
                v->first_face[x] = faces;
                for (int f = 0; f < 6; f++) {
                    int a = i + off[f][0], b = j + off[f][1], c = k + off[f][2];
                    int32_t y = v->index[cell_of(v, a, b, c)]; /* the air margin keeps a..c in range */
                    v->nb[6 * (size_t)x + f] = y;
                    if (y >= 0) continue;
                    float o[3] = {(v->lo[0] + (i + 0.5f) * h) / mm, (v->lo[1] + (j + 0.5f) * h) / mm,
                                  (v->lo[2] + (k + 0.5f) * h) / mm};
                    float dir[3] = {(float)off[f][0], (float)off[f][1], (float)off[f][2]};
                    jd_hit hit;
                    float t = 0.5f * h, wf = 1.0f;
                    /* A ray through the crack along a shared edge misses both
                     * triangles: try again a hair to the side. */
                    int found = 0;
                    for (int tries = 0; tries < 3 && !found; tries++) {
                        float oo[3] = {o[0], o[1], o[2]};
                        oo[(f / 2 + 1) % 3] += tries * 0.0173f * h / mm;
                        oo[(f / 2 + 2) % 3] -= tries * 0.0241f * h / mm;
                        found = jd_bvh_intersect(d->bvh, oo, dir, 0.0f, 1.5f * h / mm, &hit);
                    }
                    if (found) {
                        t = hit.t * mm;
                        const float *pa = d->bvh->pos + 3 * (size_t)d->bvh->tri[3 * hit.tri],
                                    *pb = d->bvh->pos + 3 * (size_t)d->bvh->tri[3 * hit.tri + 1],
                                    *pc = d->bvh->pos + 3 * (size_t)d->bvh->tri[3 * hit.tri + 2];
                        float e1[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
                        float e2[3] = {pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]};
                        float cr[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                                       e1[0] * e2[1] - e1[1] * e2[0]};
                        float len = sqrtf(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
                        if (len > 0) wf = fabsf(cr[f / 2]) / len;
                    }
                    float at[3];
                    for (int e = 0; e < 3; e++) at[e] = o[e] * mm + t * dir[e];
                    t = t < 0.05f * h ? 0.05f * h : t > h ? h : t;
                    if (faces == cap) {
                        cap = cap ? 2 * cap : 65536;
                        jd_volume_face *nf = realloc(v->faces, sizeof *nf * cap);
                        if (!nf) return jd_fail(err, JD_ERR_BUDGET, "out of memory for %u boundary faces", cap);
                        v->faces = nf;
                    }
                    /* The wall's distance along its own normal: the flux
                     * through the face is D phi_s / zb (n . axis) h^2 with
                     * phi_s = phi zb / (t cos + zb). */
                    jd_volume_face *fc = &v->faces[faces++];
                    memcpy(fc->y, at, sizeof at);
                    fc->w = wf;
                    fc->axis = (uint8_t)f;
                    fc->t = t * wf;
                    for (int ch = 0; ch < 3; ch++) g[ch] += wf / (fc->t + v->zb[ch]);
                }
                /* The rows are divided by h: the faces' conductance per unit D, times h. */
                for (int ch = 0; ch < 3; ch++) v->bw[3 * (size_t)x + ch] = h * g[ch];
            }
    v->first_face[N] = faces;
    v->num_faces = faces;
    return JD_OK;
}

jd_result jd_volume_solve(jd_volume *v, const jd_volume_desc *d, const jd_ref_point *pts, const float *normals,
                          uint32_t n, jd_error *err)
{
    size_t N = v->num_inside;
    float h = v->h;
    const int32_t *nb = v->nb;
    const float *bw = v->bw;
    float *buf = malloc(sizeof *buf * 3 * N * 5);
    if (!buf) return jd_fail(err, JD_ERR_BUDGET, "out of memory for the solve over %zu cells", N);
    float *q = buf, *r = buf + 3 * N, *z = buf + 6 * N, *p = buf + 9 * N, *ap = buf + 12 * N;
    /* Sources: the reduced albedo of each sample's power at one reduced
     * mean free path in, per channel (the depth differs by channel). */
    memset(q, 0, sizeof *q * 3 * N);
    double lost = 0, all = 0;
    for (uint32_t s = 0; s < n; s++) {
        const float *nn = normals + 6 * (size_t)s;
        for (int c = 0; c < 3; c++) {
            float e = pts[s].ea[c] * (float)d->dp->alpha[c];
            if (e == 0) continue;
            float at[3];
            for (int a = 0; a < 3; a++) at[a] = pts[s].p[a] - (float)d->dp->zr[c] * nn[a];
            int32_t u[8];
            float w[8];
            int m = corners_inward(v, at, nn, u, w);
            all += e;
            if (!m) { lost += e; continue; }
            for (int k = 0; k < m; k++) q[3 * (size_t)u[k] + c] += w[k] * e;
        }
    }
    v->lost = all > 0 ? lost / all : 0;
    /* Finite volumes, each row divided by h: D sum(phi - phi_j) over inside
     * faces + D bw phi + sigma_a h^2 phi = Q / h (bw: boundary()). */
    float kin[3], ka[3];
    for (int c = 0; c < 3; c++) {
        kin[c] = v->D[c];
        double sa = d->dp->sigma_t[c] * (1.0 - d->dp->alpha[c]);
        ka[c] = (float)(sa * h * h);
    }
    /* phi = 0: r = b. */
    double rz[3] = {0, 0, 0}, bnorm[3] = {0, 0, 0};
    memset(v->phi, 0, sizeof *v->phi * 3 * N);
    for (size_t x = 0; x < N; x++) {
        int inner = 0;
        for (int f = 0; f < 6; f++) inner += nb[6 * x + f] >= 0;
        for (int c = 0; c < 3; c++) {
            float b = q[3 * x + c] / h, dg = kin[c] * inner + kin[c] * bw[3 * x + c] + ka[c];
            r[3 * x + c] = b;
            z[3 * x + c] = b / dg;
            p[3 * x + c] = z[3 * x + c];
            rz[c] += (double)b * z[3 * x + c];
            bnorm[c] += (double)b * b;
        }
    }
    int it = 0;
    double rel = 0;
    const int max_it = 4000;
    for (; it < max_it; it++) {
        double pap[3] = {0, 0, 0};
        for (size_t x = 0; x < N; x++) {
            const int32_t *nx = nb + 6 * x;
            int inner = 0;
            float s[3] = {0, 0, 0};
            for (int f = 0; f < 6; f++) {
                int32_t y = nx[f];
                if (y < 0) continue;
                inner++;
                for (int c = 0; c < 3; c++) s[c] += p[3 * (size_t)y + c];
            }
            for (int c = 0; c < 3; c++) {
                float px = p[3 * x + c];
                float a = kin[c] * (inner * px - s[c]) + (kin[c] * bw[3 * x + c] + ka[c]) * px;
                ap[3 * x + c] = a;
                pap[c] += (double)px * a;
            }
        }
        double alpha[3], rr[3] = {0, 0, 0}, rz2[3] = {0, 0, 0};
        for (int c = 0; c < 3; c++) alpha[c] = pap[c] > 0 ? rz[c] / pap[c] : 0;
        for (size_t x = 0; x < N; x++) {
            int inner = 0;
            for (int f = 0; f < 6; f++) inner += nb[6 * x + f] >= 0;
            for (int c = 0; c < 3; c++) {
                size_t i = 3 * x + c;
                v->phi[i] += (float)alpha[c] * p[i];
                r[i] -= (float)alpha[c] * ap[i];
                float dg = kin[c] * inner + kin[c] * bw[3 * x + c] + ka[c];
                z[i] = r[i] / dg;
                rr[c] += (double)r[i] * r[i];
                rz2[c] += (double)r[i] * z[i];
            }
        }
        rel = 0;
        for (int c = 0; c < 3; c++) {
            double e = bnorm[c] > 0 ? sqrt(rr[c] / bnorm[c]) : 0;
            if (e > rel) rel = e;
        }
        if (rel < 1e-5) { it++; break; }
        for (int c = 0; c < 3; c++) {
            double beta = rz[c] > 0 ? rz2[c] / rz[c] : 0;
            rz[c] = rz2[c];
            for (size_t x = 0; x < N; x++) p[3 * x + c] = z[3 * x + c] + (float)beta * p[3 * x + c];
        }
    }
    v->iterations = it;
    v->residual = rel;
    free(buf);
    return JD_OK;
}

void jd_volume_exitance(const jd_volume *v, const float x[3], const float n[3], float out[3])
{
    /* The boundary faces' own points on the surface within r of x, each
     * with the flux leaving there, D phi / (t + zb), weighted by the
     * surface it stands for and a smooth window: the grid's steps and
     * cells do not show through. */
    float r = 3.0f * v->h, r2 = r * r, acc[3] = {0, 0, 0}, wsum = 0;
    int ci[3];
    for (int a = 0; a < 3; a++) ci[a] = (int)floorf((x[a] - v->lo[a]) / v->h);
    int reach = (int)ceilf(r / v->h) + 1;
    for (int dk = -reach; dk <= reach; dk++)
        for (int dj = -reach; dj <= reach; dj++)
            for (int di = -reach; di <= reach; di++) {
                int i = ci[0] + di, j = ci[1] + dj, k = ci[2] + dk;
                if (i < 0 || j < 0 || k < 0 || i >= v->nx || j >= v->ny || k >= v->nz) continue;
                int32_t c = v->index[cell_of(v, i, j, k)];
                if (c < 0) continue;
                for (uint32_t f = v->first_face[c]; f < v->first_face[c + 1]; f++) {
                    const jd_volume_face *fc = &v->faces[f];
                    /* Only the walls facing as the surface at x does: not
                     * the other side of an edge. */
                    float facing = (fc->axis & 1 ? 1.0f : -1.0f) * n[fc->axis >> 1];
                    if (facing < 0.1f) continue;
                    float dx = fc->y[0] - x[0], dy = fc->y[1] - x[1], dz = fc->y[2] - x[2];
                    float d2 = dx * dx + dy * dy + dz * dz;
                    if (d2 >= r2) continue;
                    float k2 = 1.0f - d2 / r2, w = fc->w * k2 * k2;
                    wsum += w;
                    for (int ch = 0; ch < 3; ch++) acc[ch] += w * v->phi[3 * (size_t)c + ch] / (fc->t + v->zb[ch]);
                }
            }
    for (int ch = 0; ch < 3; ch++) out[ch] = wsum > 0 ? v->D[ch] * acc[ch] / wsum : 0.0f;
}
