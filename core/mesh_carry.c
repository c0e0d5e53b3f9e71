/* Coarse vertices' values carried to a mesh's (mesh_carry.h). */
#include "mesh_carry.h"

#include <math.h>

#include "mesh_grid.h"

jd_result jd_mesh_carry(const jd_mesh *m, const jd_mesh *coarse, const float *cvals, int n, float reach, float none,
                        jd_arena *a, float *out, jd_error *err)
{
    enum { MOST = 8 };
    if (n < 1 || n > MOST) return jd_fail(err, JD_ERR_ARG, "carrying %d values a vertex (1 to %d)", n, MOST);
    size_t top = jd_arena_top_mark(a);
    float ext = fmaxf(coarse->bmax.x - coarse->bmin.x, fmaxf(coarse->bmax.y - coarse->bmin.y, coarse->bmax.z - coarse->bmin.z));
    if (!(ext > 0.0f)) ext = 1.0f;
    if (!(reach > 0.0f)) reach = ext;
    jd_mesh_grid g;
    jd_result res = jd_mesh_grid_vertices(coarse, reach, &g, a, "vertex transfer", err);
    if (res) { jd_arena_top_reset(a, top); return res; }
    float r2 = reach * reach, soft = 0.01f * r2;
    for (uint32_t i = 0; i < m->num_vertices; i++) {
        const float *p = m->positions + 3 * (size_t)i, *nv = m->normals + 3 * (size_t)i;
        int c[3] = {jd_mesh_grid_cell(&g, p[0], 0), jd_mesh_grid_cell(&g, p[1], 1), jd_mesh_grid_cell(&g, p[2], 2)};
        double sw = 0.0, st[MOST] = {0};
        for (int z = c[2] - 1; z <= c[2] + 1; z++)
            for (int y = c[1] - 1; y <= c[1] + 1; y++)
                for (int x = c[0] - 1; x <= c[0] + 1; x++) {
                    if (x < 0 || y < 0 || z < 0 || x >= g.n || y >= g.n || z >= g.n) continue;
                    size_t cell = jd_mesh_grid_index(&g, x, y, z);
                    for (uint32_t e = g.start[cell]; e < g.start[cell + 1]; e++) {
                        uint32_t j = g.items[e];
                        const float *q = coarse->positions + 3 * (size_t)j, *nq = coarse->normals + 3 * (size_t)j;
                        if (nv[0] * nq[0] + nv[1] * nq[1] + nv[2] * nq[2] <= 0.0f) continue;
                        float dx = q[0] - p[0], dy = q[1] - p[1], dz = q[2] - p[2], d2 = dx * dx + dy * dy + dz * dz;
                        if (d2 > r2) continue;
                        double w = 1.0 / (d2 + soft);
                        sw += w;
                        for (int k = 0; k < n; k++) st[k] += w * cvals[(size_t)n * j + (size_t)k];
                    }
                }
        for (int k = 0; k < n; k++) out[(size_t)n * i + (size_t)k] = sw > 0.0 ? (float)(st[k] / sw) : none;
    }
    jd_arena_top_reset(a, top);
    return JD_OK;
}

void jd_mesh_smooth(const jd_mesh *m, float *vals, int n, int passes, jd_arena *a)
{
    uint32_t ntri = m->num_indices / 3;
    size_t top = jd_arena_top_mark(a), nv = m->num_vertices;
    float *acc = jd_arena_alloc_top(a, sizeof(float) * (size_t)n * (nv ? nv : 1), 4, "vertex smoothing", NULL);
    float *cnt = jd_arena_alloc_top(a, sizeof(float) * (nv ? nv : 1), 4, "vertex smoothing", NULL);
    if (acc && cnt)
        for (int pass = 0; pass < passes; pass++) {
            for (size_t i = 0; i < nv; i++) cnt[i] = 1.0f;
            for (size_t i = 0; i < (size_t)n * nv; i++) acc[i] = vals[i];
            for (uint32_t t = 0; t < ntri; t++) {
                uint32_t v[3] = {jd_mesh_index(m, 3 * t), jd_mesh_index(m, 3 * t + 1), jd_mesh_index(m, 3 * t + 2)};
                for (int k = 0; k < 3; k++) {
                    size_t o = (size_t)n * v[k], p = (size_t)n * v[(k + 1) % 3], q = (size_t)n * v[(k + 2) % 3];
                    for (int c = 0; c < n; c++) acc[o + (size_t)c] += 0.5f * (vals[p + (size_t)c] + vals[q + (size_t)c]);
                    cnt[v[k]] += 1.0f;
                }
            }
            for (size_t i = 0; i < (size_t)n * nv; i++) vals[i] = acc[i] / cnt[i / (size_t)n];
        }
    jd_arena_top_reset(a, top);
}
