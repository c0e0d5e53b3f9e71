/* A part's thickness under each vertex, for full's light on thin parts: a
 * slab d mm thick returns R(d) of the half-space's light on its lit face
 * and sends T(d) out of its far face (core/slab.h), and the reference
 * takes d along the inward normal where the light enters
 * (reference/ref_slab.h). Made once at set-up: one ray a vertex through a
 * uniform grid of the triangles (counted, then filled), a cell's
 * triangles tested in turn, the cells walked in the ray's order (Amanatides
 * and Woo 1987) until the nearest hit lies within the cells passed. */
#include "mesh_thickness.h"

#include <math.h>
#include <string.h>

typedef struct grid {
    int n;              /* cells per axis */
    float lo[3], size;  /* the grid's corner and its cell's size */
    uint32_t *start;    /* n^3 + 1: each cell's first entry in tris */
    uint32_t *tris;
} grid;

static int cell_of(const grid *g, float x, int k)
{
    int c = (int)floorf((x - g->lo[k]) / g->size);
    return c < 0 ? 0 : c >= g->n ? g->n - 1 : c;
}

static size_t cell_index(const grid *g, int x, int y, int z)
{
    return (size_t)x + (size_t)g->n * ((size_t)y + (size_t)g->n * (size_t)z);
}

static size_t point_cell(const grid *g, const float *p)
{
    return cell_index(g, cell_of(g, p[0], 0), cell_of(g, p[1], 1), cell_of(g, p[2], 2));
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

static void tri_cells(const jd_mesh *m, const grid *g, uint32_t t, int c0[3], int c1[3])
{
    for (int k = 0; k < 3; k++) {
        float lo = INFINITY, hi = -INFINITY;
        for (int v = 0; v < 3; v++) {
            float x = m->positions[3 * (size_t)jd_mesh_index(m, 3 * t + (uint32_t)v) + (size_t)k];
            lo = fminf(lo, x), hi = fmaxf(hi, x);
        }
        c0[k] = cell_of(g, lo, k), c1[k] = cell_of(g, hi, k);
    }
}

/* Moller-Trumbore: the ray's parameter at triangle t, or -1. */
static float hit(const jd_mesh *m, uint32_t t, const float o[3], const float d[3])
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
    return (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) * inv;
}

/* The nearest hit past eps along o + t d (d of unit length), at most cap. */
static float cast(const jd_mesh *m, const grid *g, const float o[3], const float d[3], float eps, float cap)
{
    int c[3], step[3];
    float next[3], delta[3];
    for (int k = 0; k < 3; k++) {
        c[k] = cell_of(g, o[k], k);
        step[k] = d[k] > 0 ? 1 : -1;
        float edge = g->lo[k] + (float)(c[k] + (d[k] > 0)) * g->size;
        next[k] = d[k] != 0.0f ? (edge - o[k]) / d[k] : INFINITY;
        delta[k] = d[k] != 0.0f ? g->size / fabsf(d[k]) : INFINITY;
    }
    float best = cap;
    for (;;) {
        size_t cell = cell_index(g, c[0], c[1], c[2]);
        for (uint32_t i = g->start[cell]; i < g->start[cell + 1]; i++) {
            float t = hit(m, g->tris[i], o, d);
            if (t > eps && t < best) best = t;
        }
        int k = next[0] < next[1] ? (next[0] < next[2] ? 0 : 2) : (next[1] < next[2] ? 1 : 2);
        if (next[k] >= best) return best; /* every nearer hit lies in the cells passed */
        c[k] += step[k];
        if (c[k] < 0 || c[k] >= g->n) return best;
        next[k] += delta[k];
    }
}

/* A ray a vertex reads the surface's detail: a ridge or a crease
 * measures thinner than the part around it, and the light the levels
 * keep followed it as dark lines along a back-lit ear's rim. Two passes
 * of each vertex averaged with its triangles' other corners (a corner
 * shared by k triangles counted k times) spread it over the
 * neighbourhood. In the arena's top; skipped where it does not fit. */
static void smooth(const jd_mesh *m, float *out, jd_arena *a, jd_error *err)
{
    uint32_t ntri = m->num_indices / 3;
    size_t top = jd_arena_top_mark(a);
    float *acc = jd_arena_alloc_top(a, sizeof(float) * m->num_vertices, 4, "thickness smoothing", err);
    float *cnt = jd_arena_alloc_top(a, sizeof(float) * m->num_vertices, 4, "thickness smoothing", err);
    if (acc && cnt)
        for (int pass = 0; pass < 2; pass++) {
            for (uint32_t i = 0; i < m->num_vertices; i++) acc[i] = out[i], cnt[i] = 1.0f;
            for (uint32_t t = 0; t < ntri; t++) {
                uint32_t v[3] = {jd_mesh_index(m, 3 * t), jd_mesh_index(m, 3 * t + 1), jd_mesh_index(m, 3 * t + 2)};
                for (int k = 0; k < 3; k++) {
                    acc[v[k]] += 0.5f * (out[v[(k + 1) % 3]] + out[v[(k + 2) % 3]]);
                    cnt[v[k]] += 1.0f;
                }
            }
            for (uint32_t i = 0; i < m->num_vertices; i++) out[i] = acc[i] / cnt[i];
        }
    jd_arena_top_reset(a, top);
}

jd_result jd_mesh_thickness(const jd_mesh *m, float cap, jd_arena *a, float *out, jd_error *err)
{
    uint32_t ntri = m->num_indices / 3;
    size_t top = jd_arena_top_mark(a);
    grid g;
    /* About a triangle a cell over the box, at most 64 a side. */
    g.n = (int)ceilf(cbrtf((float)(ntri ? ntri : 1)));
    g.n = g.n < 4 ? 4 : g.n > 64 ? 64 : g.n;
    float ext = fmaxf(m->bmax.x - m->bmin.x, fmaxf(m->bmax.y - m->bmin.y, m->bmax.z - m->bmin.z));
    g.size = (ext > 0.0f ? ext : 1.0f) * 1.0001f / (float)g.n;
    g.lo[0] = m->bmin.x, g.lo[1] = m->bmin.y, g.lo[2] = m->bmin.z;
    size_t ncell = (size_t)g.n * (size_t)g.n * (size_t)g.n;
    g.start = jd_arena_alloc_top(a, sizeof(uint32_t) * (ncell + 1), 4, "thickness grid", err);
    if (!g.start) return JD_ERR_BUDGET;
    memset(g.start, 0, sizeof(uint32_t) * (ncell + 1));
    /* Count each cell's triangles (their boxes' cells), then place them. */
    size_t total = 0;
    for (uint32_t t = 0; t < ntri; t++) {
        int c0[3], c1[3];
        tri_cells(m, &g, t, c0, c1);
        for (int z = c0[2]; z <= c1[2]; z++)
            for (int y = c0[1]; y <= c1[1]; y++)
                for (int x = c0[0]; x <= c1[0]; x++) {
                    g.start[cell_index(&g, x, y, z)]++;
                    total++;
                }
    }
    if (total > UINT32_MAX) { jd_arena_top_reset(a, top); return jd_fail(err, JD_ERR_LIMIT, "thickness grid too large"); }
    g.tris = jd_arena_alloc_top(a, sizeof(uint32_t) * (total ? total : 1), 4, "thickness grid", err);
    if (!g.tris) { jd_arena_top_reset(a, top); return JD_ERR_BUDGET; }
    uint32_t *cursor = jd_arena_alloc_top(a, sizeof(uint32_t) * ncell, 4, "thickness grid", err);
    if (!cursor) { jd_arena_top_reset(a, top); return JD_ERR_BUDGET; }
    counts_to_starts(g.start, cursor, ncell);
    for (uint32_t t = 0; t < ntri; t++) {
        int c0[3], c1[3];
        tri_cells(m, &g, t, c0, c1);
        for (int z = c0[2]; z <= c1[2]; z++)
            for (int y = c0[1]; y <= c1[1]; y++)
                for (int x = c0[0]; x <= c1[0]; x++)
                    g.tris[cursor[cell_index(&g, x, y, z)]++] = t;
    }
    /* A ray from the vertex itself meets its own triangles at 0: hits
     * nearer than a ten-thousandth of the box are its own. */
    float eps = 1e-4f * ext;
    for (uint32_t i = 0; i < m->num_vertices; i++) {
        const float *n = m->normals + 3 * (size_t)i;
        float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(len > 0.0f)) { out[i] = cap; continue; }
        float d[3] = {-n[0] / len, -n[1] / len, -n[2] / len};
        out[i] = cast(m, &g, m->positions + 3 * (size_t)i, d, eps, cap);
    }
    jd_arena_top_reset(a, top);
    smooth(m, out, a, err);
    return JD_OK;
}

jd_result jd_mesh_thickness_from(const jd_mesh *m, const jd_mesh *coarse, const float *cthick, float reach, float cap,
                                 jd_arena *a, float *out, jd_error *err)
{
    size_t top = jd_arena_top_mark(a);
    float ext = fmaxf(coarse->bmax.x - coarse->bmin.x, fmaxf(coarse->bmax.y - coarse->bmin.y, coarse->bmax.z - coarse->bmin.z));
    if (!(ext > 0.0f)) ext = 1.0f; /* a flat or empty box: any grid does */
    if (!(reach > 0.0f)) reach = ext;
    /* The coarse vertices in cells at least `reach` wide (a vertex's
     * candidates lie in its cell and the 26 round it), at most 64 a side
     * and about a coarse vertex a cell. */
    float fit = floorf(ext / reach), most = 2.0f * cbrtf((float)coarse->num_vertices) + 1.0f;
    int n = (int)fminf(fminf(fit, most), 64.0f);
    n = n < 1 ? 1 : n;
    float size = ext * 1.0001f / (float)n, lo[3] = {coarse->bmin.x, coarse->bmin.y, coarse->bmin.z};
    size_t ncell = (size_t)n * (size_t)n * (size_t)n;
    uint32_t *start = jd_arena_alloc_top(a, sizeof(uint32_t) * (ncell + 1), 4, "thickness transfer", err);
    uint32_t *cursor = jd_arena_alloc_top(a, sizeof(uint32_t) * ncell, 4, "thickness transfer", err);
    uint32_t *verts = jd_arena_alloc_top(a, sizeof(uint32_t) * (coarse->num_vertices ? coarse->num_vertices : 1), 4,
                                         "thickness transfer", err);
    if (!start || !cursor || !verts) { jd_arena_top_reset(a, top); return JD_ERR_BUDGET; }
    grid g = {n, {lo[0], lo[1], lo[2]}, size, start, verts};
    memset(start, 0, sizeof(uint32_t) * (ncell + 1));
    for (uint32_t j = 0; j < coarse->num_vertices; j++) start[point_cell(&g, coarse->positions + 3 * (size_t)j)]++;
    counts_to_starts(start, cursor, ncell);
    for (uint32_t j = 0; j < coarse->num_vertices; j++) verts[cursor[point_cell(&g, coarse->positions + 3 * (size_t)j)]++] = j;
    /* Each vertex: the coarse vertices within reach that face its way (the
     * proxy keeps a thin part's two sides apart, core/mesh.c), weighted
     * by the inverse square of their distance; cap where there are none. */
    float r2 = reach * reach, soft = 0.01f * r2;
    for (uint32_t i = 0; i < m->num_vertices; i++) {
        const float *p = m->positions + 3 * (size_t)i, *nv = m->normals + 3 * (size_t)i;
        int c[3] = {cell_of(&g, p[0], 0), cell_of(&g, p[1], 1), cell_of(&g, p[2], 2)};
        double sw = 0.0, st = 0.0;
        for (int z = c[2] - 1; z <= c[2] + 1; z++)
            for (int y = c[1] - 1; y <= c[1] + 1; y++)
                for (int x = c[0] - 1; x <= c[0] + 1; x++) {
                    if (x < 0 || y < 0 || z < 0 || x >= n || y >= n || z >= n) continue;
                    size_t cell = cell_index(&g, x, y, z);
                    for (uint32_t e = start[cell]; e < start[cell + 1]; e++) {
                        uint32_t j = verts[e];
                        const float *q = coarse->positions + 3 * (size_t)j, *nq = coarse->normals + 3 * (size_t)j;
                        if (nv[0] * nq[0] + nv[1] * nq[1] + nv[2] * nq[2] <= 0.0f) continue;
                        float dx = q[0] - p[0], dy = q[1] - p[1], dz = q[2] - p[2], d2 = dx * dx + dy * dy + dz * dz;
                        if (d2 > r2) continue;
                        double w = 1.0 / (d2 + soft);
                        sw += w, st += w * cthick[j];
                    }
                }
        out[i] = sw > 0.0 ? (float)fmin(st / sw, cap) : cap;
    }
    jd_arena_top_reset(a, top);
    smooth(m, out, a, err);
    return JD_OK;
}
