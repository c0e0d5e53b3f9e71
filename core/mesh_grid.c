/* A uniform grid of a mesh's triangles or vertices, and rays through it
 * (mesh_grid.h). */
#include "mesh_grid.h"

#include <math.h>
#include <string.h>

int jd_mesh_grid_cell(const jd_mesh_grid *g, float x, int k)
{
    int c = (int)floorf((x - g->lo[k]) / g->size);
    return c < 0 ? 0 : c >= g->n ? g->n - 1 : c;
}

size_t jd_mesh_grid_index(const jd_mesh_grid *g, int x, int y, int z)
{
    return (size_t)x + (size_t)g->n * ((size_t)y + (size_t)g->n * (size_t)z);
}

static size_t point_cell(const jd_mesh_grid *g, const float *p)
{
    return jd_mesh_grid_index(g, jd_mesh_grid_cell(g, p[0], 0), jd_mesh_grid_cell(g, p[1], 1),
                              jd_mesh_grid_cell(g, p[2], 2));
}

/* Each cell's count in start[] becomes its first entry (start[ncell]: the
 * total), and cursor[] a copy to fill the entries by. */
static void counts_to_starts(uint32_t *start, uint32_t *cursor, size_t ncell)
{
    uint32_t sum = 0;
    for (size_t i = 0; i < ncell; i++) {
        uint32_t k = start[i];
        start[i] = cursor[i] = sum;
        sum += k;
    }
    start[ncell] = sum;
}

static void tri_cells(const jd_mesh *m, const jd_mesh_grid *g, uint32_t t, int c0[3], int c1[3])
{
    for (int k = 0; k < 3; k++) {
        float lo = INFINITY, hi = -INFINITY;
        for (int v = 0; v < 3; v++) {
            float x = m->positions[3 * (size_t)jd_mesh_index(m, 3 * t + (uint32_t)v) + (size_t)k];
            lo = fminf(lo, x), hi = fmaxf(hi, x);
        }
        c0[k] = jd_mesh_grid_cell(g, lo, k), c1[k] = jd_mesh_grid_cell(g, hi, k);
    }
}

jd_result jd_mesh_grid_triangles(const jd_mesh *m, jd_mesh_grid *g, jd_arena *a, const char *what, jd_error *err)
{
    uint32_t ntri = m->num_indices / 3;
    size_t top = jd_arena_top_mark(a);
    /* About a triangle a cell over the box, at most 64 a side. */
    g->n = (int)ceilf(cbrtf((float)(ntri ? ntri : 1)));
    g->n = g->n < 4 ? 4 : g->n > 64 ? 64 : g->n;
    float ext = fmaxf(m->bmax.x - m->bmin.x, fmaxf(m->bmax.y - m->bmin.y, m->bmax.z - m->bmin.z));
    g->size = (ext > 0.0f ? ext : 1.0f) * 1.0001f / (float)g->n;
    g->lo[0] = m->bmin.x, g->lo[1] = m->bmin.y, g->lo[2] = m->bmin.z;
    size_t ncell = (size_t)g->n * (size_t)g->n * (size_t)g->n;
    g->start = jd_arena_alloc_top(a, sizeof(uint32_t) * (ncell + 1), 4, what, err);
    if (!g->start) return JD_ERR_BUDGET;
    memset(g->start, 0, sizeof(uint32_t) * (ncell + 1));
    /* Count each cell's triangles (their boxes' cells), then place them. */
    size_t total = 0;
    for (uint32_t t = 0; t < ntri; t++) {
        int c0[3], c1[3];
        tri_cells(m, g, t, c0, c1);
        for (int z = c0[2]; z <= c1[2]; z++)
            for (int y = c0[1]; y <= c1[1]; y++)
                for (int x = c0[0]; x <= c1[0]; x++) {
                    g->start[jd_mesh_grid_index(g, x, y, z)]++;
                    total++;
                }
    }
    if (total > UINT32_MAX) { jd_arena_top_reset(a, top); return jd_fail(err, JD_ERR_LIMIT, "%s too large", what); }
    g->items = jd_arena_alloc_top(a, sizeof(uint32_t) * (total ? total : 1), 4, what, err);
    uint32_t *cursor = g->items ? jd_arena_alloc_top(a, sizeof(uint32_t) * ncell, 4, what, err) : NULL;
    if (!cursor) { jd_arena_top_reset(a, top); return JD_ERR_BUDGET; }
    counts_to_starts(g->start, cursor, ncell);
    for (uint32_t t = 0; t < ntri; t++) {
        int c0[3], c1[3];
        tri_cells(m, g, t, c0, c1);
        for (int z = c0[2]; z <= c1[2]; z++)
            for (int y = c0[1]; y <= c1[1]; y++)
                for (int x = c0[0]; x <= c1[0]; x++)
                    g->items[cursor[jd_mesh_grid_index(g, x, y, z)]++] = t;
    }
    return JD_OK;
}

jd_result jd_mesh_grid_vertices(const jd_mesh *m, float reach, jd_mesh_grid *g, jd_arena *a, const char *what,
                                jd_error *err)
{
    float ext = fmaxf(m->bmax.x - m->bmin.x, fmaxf(m->bmax.y - m->bmin.y, m->bmax.z - m->bmin.z));
    if (!(ext > 0.0f)) ext = 1.0f; /* a flat or empty box: any grid does */
    if (!(reach > 0.0f)) reach = ext;
    float fit = floorf(ext / reach), most = 2.0f * cbrtf((float)m->num_vertices) + 1.0f;
    int n = (int)fminf(fminf(fit, most), 64.0f);
    g->n = n < 1 ? 1 : n;
    g->size = ext * 1.0001f / (float)g->n;
    g->lo[0] = m->bmin.x, g->lo[1] = m->bmin.y, g->lo[2] = m->bmin.z;
    size_t ncell = (size_t)g->n * (size_t)g->n * (size_t)g->n;
    g->start = jd_arena_alloc_top(a, sizeof(uint32_t) * (ncell + 1), 4, what, err);
    uint32_t *cursor = jd_arena_alloc_top(a, sizeof(uint32_t) * ncell, 4, what, err);
    g->items = jd_arena_alloc_top(a, sizeof(uint32_t) * (m->num_vertices ? m->num_vertices : 1), 4, what, err);
    if (!g->start || !cursor || !g->items) return JD_ERR_BUDGET;
    memset(g->start, 0, sizeof(uint32_t) * (ncell + 1));
    for (uint32_t j = 0; j < m->num_vertices; j++) g->start[point_cell(g, m->positions + 3 * (size_t)j)]++;
    counts_to_starts(g->start, cursor, ncell);
    for (uint32_t j = 0; j < m->num_vertices; j++) g->items[cursor[point_cell(g, m->positions + 3 * (size_t)j)]++] = j;
    return JD_OK;
}

/* Moller-Trumbore: the ray's parameter at triangle t, or -1; *u, *v the
 * hit's weights of the second and third corners. */
static float hit(const jd_mesh *m, uint32_t t, const float o[3], const float d[3], float *uu, float *vv)
{
    const float *a = m->positions + 3 * (size_t)jd_mesh_index(m, 3 * t),
                *b = m->positions + 3 * (size_t)jd_mesh_index(m, 3 * t + 1),
                *c = m->positions + 3 * (size_t)jd_mesh_index(m, 3 * t + 2);
    float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    float p[3] = {d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2], d[0] * e2[1] - d[1] * e2[0]};
    float det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (fabsf(det) < 1e-20f) return -1.0f;
    float inv = 1.0f / det, s[3] = {o[0] - a[0], o[1] - a[1], o[2] - a[2]};
    float u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) * inv;
    if (u < 0.0f || u > 1.0f) return -1.0f;
    float q[3] = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0]};
    float v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) * inv;
    if (v < 0.0f || u + v > 1.0f) return -1.0f;
    *uu = u, *vv = v;
    return (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) * inv;
}

/* The cells along o + t d in order, each one's triangles tested: the
 * nearest hit, or with `any` the first found. */
static jd_mesh_hit walk(const jd_mesh *m, const jd_mesh_grid *g, const float o[3], const float d[3], float eps,
                        float cap, int any)
{
    int c[3], step[3];
    float next[3], delta[3];
    for (int k = 0; k < 3; k++) {
        c[k] = jd_mesh_grid_cell(g, o[k], k);
        step[k] = d[k] > 0 ? 1 : -1;
        float edge = g->lo[k] + (float)(c[k] + (d[k] > 0)) * g->size;
        next[k] = d[k] != 0.0f ? (edge - o[k]) / d[k] : INFINITY;
        delta[k] = d[k] != 0.0f ? g->size / fabsf(d[k]) : INFINITY;
    }
    jd_mesh_hit best = {cap, 0.0f, 0.0f, UINT32_MAX};
    for (;;) {
        size_t cell = jd_mesh_grid_index(g, c[0], c[1], c[2]);
        for (uint32_t i = g->start[cell]; i < g->start[cell + 1]; i++) {
            float u = 0.0f, v = 0.0f, t = hit(m, g->items[i], o, d, &u, &v);
            if (t > eps && t < best.t) {
                best.t = t, best.u = u, best.v = v, best.tri = g->items[i];
                if (any) return best;
            }
        }
        int k = next[0] < next[1] ? (next[0] < next[2] ? 0 : 2) : (next[1] < next[2] ? 1 : 2);
        /* Every nearer hit lies in the cells passed; or the ray left. */
        if (next[k] >= best.t || (c[k] += step[k]) < 0 || c[k] >= g->n) return best;
        next[k] += delta[k];
    }
}

float jd_mesh_grid_cast(const jd_mesh *m, const jd_mesh_grid *g, const float o[3], const float d[3], float eps,
                        float cap, jd_mesh_hit *out)
{
    jd_mesh_hit best = walk(m, g, o, d, eps, cap, 0);
    if (out) *out = best;
    return best.t;
}

int jd_mesh_grid_blocked(const jd_mesh *m, const jd_mesh_grid *g, const float o[3], const float d[3], float eps,
                         float cap)
{
    return walk(m, g, o, d, eps, cap, 1).tri != UINT32_MAX;
}
