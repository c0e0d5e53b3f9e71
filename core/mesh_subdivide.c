/* Coarse meshes split where they are coarse, in the decoder's child.
 *
 * full sums the diffusion's levels per vertex on GPUs whose vertex stage
 * reads textures (VideoCore IV, Vivante GC3000 on, desktops) and
 * takes its Fresnel factors per vertex everywhere; single and dual find the
 * refraction per vertex. All of it assumes vertices about as close as the
 * levels' texels. A box of 12 triangles broke that: its faces came out 36%
 * too dark in full (22% under the mali400 profile) against jade reference,
 * the levels' light read only at the corners, where it is least. Each face
 * split in 4 x 4 came within 1%.
 *
 * Edges longer than a twelfth of the mesh's box diagonal are halved, pass
 * after pass (red-green refinement: a triangle with one, two or three such
 * edges becomes two, three or four), each edge's midpoint shared by the
 * triangles that use it, so no crack opens. Dense meshes have no such edge
 * and are left as they are. */
#include "mesh_subdivide.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"

/* An edge's midpoint, found by its two vertex indices. */
typedef struct edge_map {
    uint64_t *keys; /* (lo << 32 | hi) + 1; 0: empty */
    uint32_t *mid;
    size_t cap;     /* a power of two */
} edge_map;

static uint64_t edge_key(uint32_t a, uint32_t b)
{
    uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
    return (((uint64_t)lo << 32) | hi) + 1;
}

static size_t slot(const edge_map *e, uint64_t k)
{
    size_t i = (size_t)((k * 0x9E3779B97F4A7C15ull) >> 17) & (e->cap - 1);
    while (e->keys[i] && e->keys[i] != k) i = (i + 1) & (e->cap - 1);
    return i;
}

static double edge_len2(const float *pos, uint32_t a, uint32_t b)
{
    double s = 0;
    for (int c = 0; c < 3; c++) {
        double d = (double)pos[3 * (size_t)a + c] - pos[3 * (size_t)b + c];
        s += d * d;
    }
    return s;
}

static int grow(void **p, size_t bytes)
{
    void *q = realloc(*p, bytes ? bytes : 1);
    if (!q) return -1;
    *p = q;
    return 0;
}

/* One pass: every edge longer than sqrt(limit2) halved. 1: something was
 * split; 0: nothing to split, or the caps would be passed; -1: out of
 * memory (the mesh as it was). */
static int pass(jd_mesh_arrays *m, double limit2, uint32_t cap_v, uint32_t cap_f)
{
    size_t nf = m->nf, marked = 0, new_f = 0;
    for (size_t t = 0; t < nf; t++) {
        const uint32_t *v = m->idx + 3 * t;
        int k = 0;
        for (int e = 0; e < 3; e++) k += edge_len2(m->pos, v[e], v[(e + 1) % 3]) > limit2;
        marked += (size_t)k;
        new_f += (size_t)k;
    }
    if (!marked) return 0;
    /* marked counts shared edges twice: a bound on the new vertices. */
    if ((size_t)m->nv + marked > cap_v || nf + new_f > cap_f) return 0;
    edge_map e = {0};
    e.cap = 16;
    while (e.cap < 2 * marked) e.cap <<= 1;
    e.keys = calloc(e.cap, sizeof *e.keys);
    e.mid = malloc(e.cap * sizeof *e.mid);
    if (!e.keys || !e.mid) {
        free(e.keys);
        free(e.mid);
        return -1;
    }
    size_t nv_max = (size_t)m->nv + marked;
    if (grow((void **)&m->pos, sizeof(float) * 3 * nv_max) ||
        (m->nrm && grow((void **)&m->nrm, sizeof(float) * 3 * nv_max)) ||
        (m->uv && grow((void **)&m->uv, sizeof(float) * 2 * nv_max)) || (m->col && grow((void **)&m->col, 4 * nv_max))) {
        free(e.keys);
        free(e.mid);
        return -1;
    }
    uint32_t *idx = malloc(sizeof(uint32_t) * 3 * (nf + new_f));
    if (!idx) {
        free(e.keys);
        free(e.mid);
        return -1;
    }
    uint32_t nv = m->nv;
    size_t out = 0;
    for (size_t t = 0; t < nf; t++) {
        uint32_t v[3] = {m->idx[3 * t], m->idx[3 * t + 1], m->idx[3 * t + 2]};
        uint32_t mid[3]; /* on edge v[e] v[e+1], or UINT32_MAX */
        int k = 0;
        for (int j = 0; j < 3; j++) {
            uint32_t a = v[j], b = v[(j + 1) % 3];
            mid[j] = UINT32_MAX;
            if (edge_len2(m->pos, a, b) <= limit2) continue;
            k++;
            uint64_t key = edge_key(a, b);
            size_t s = slot(&e, key);
            if (!e.keys[s]) {
                e.keys[s] = key;
                e.mid[s] = nv;
                /* The midpoint of (a, b) in each attribute, the same whichever
                 * triangle asks first. */
                uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
                for (int c = 0; c < 3; c++)
                    m->pos[3 * (size_t)nv + c] = 0.5f * (m->pos[3 * (size_t)lo + c] + m->pos[3 * (size_t)hi + c]);
                if (m->nrm)
                    for (int c = 0; c < 3; c++)
                        m->nrm[3 * (size_t)nv + c] = 0.5f * (m->nrm[3 * (size_t)lo + c] + m->nrm[3 * (size_t)hi + c]);
                if (m->uv)
                    for (int c = 0; c < 2; c++)
                        m->uv[2 * (size_t)nv + c] = 0.5f * (m->uv[2 * (size_t)lo + c] + m->uv[2 * (size_t)hi + c]);
                if (m->col)
                    for (int c = 0; c < 4; c++)
                        m->col[4 * (size_t)nv + c] =
                            (uint8_t)((m->col[4 * (size_t)lo + c] + m->col[4 * (size_t)hi + c] + 1) / 2);
                nv++;
            }
            mid[j] = e.mid[s];
        }
        uint32_t *o = idx + 3 * out;
#define TRI(x, y, z) (o[0] = (x), o[1] = (y), o[2] = (z), o += 3, out++)
        if (k == 0) {
            TRI(v[0], v[1], v[2]);
        } else if (k == 3) {
            TRI(v[0], mid[0], mid[2]);
            TRI(mid[0], v[1], mid[1]);
            TRI(mid[2], mid[1], v[2]);
            TRI(mid[0], mid[1], mid[2]);
        } else {
            /* Turned so that edge 0 (v0 v1) is split and, with two, edge 1
             * too: the winding kept. */
            int r = 0;
            if (k == 1) r = mid[0] != UINT32_MAX ? 0 : mid[1] != UINT32_MAX ? 1 : 2;
            else r = mid[2] == UINT32_MAX ? 0 : mid[0] == UINT32_MAX ? 1 : 2;
            uint32_t a = v[r], b = v[(r + 1) % 3], c = v[(r + 2) % 3];
            uint32_t mab = mid[r], mbc = mid[(r + 1) % 3];
            if (k == 1) {
                TRI(a, mab, c);
                TRI(mab, b, c);
            } else {
                TRI(mab, b, mbc);
                /* The quad a mab mbc c, by its shorter diagonal. */
                if (edge_len2(m->pos, a, mbc) <= edge_len2(m->pos, mab, c)) {
                    TRI(a, mab, mbc);
                    TRI(a, mbc, c);
                } else {
                    TRI(a, mab, c);
                    TRI(mab, mbc, c);
                }
            }
        }
#undef TRI
    }
    free(e.keys);
    free(e.mid);
    free(m->idx);
    m->idx = idx;
    m->nf = (uint32_t)out;
    m->nv = nv;
    return 1;
}

int jd_mesh_arrays_subdivide(jd_mesh_arrays *m, uint32_t max_vertices, uint32_t max_faces)
{
    size_t n3 = 3 * (size_t)m->nv;
    for (size_t i = 0; i < 3 * (size_t)m->nf; i++)
        if (m->idx[i] >= m->nv) return 0; /* the parent refuses these */
    if (!m->nv) return 0;
    float lo[3], hi[3];
    for (int c = 0; c < 3; c++) lo[c] = hi[c] = m->pos[c];
    for (size_t i = 0; i < n3; i++) {
        if (!isfinite(m->pos[i])) return 0; /* refused by the parent too */
        int c = (int)(i % 3);
        lo[c] = fminf(lo[c], m->pos[i]);
        hi[c] = fmaxf(hi[c], m->pos[i]);
    }
    double d2 = 0;
    for (int c = 0; c < 3; c++) d2 += ((double)hi[c] - lo[c]) * ((double)hi[c] - lo[c]);
    if (!(d2 > 0)) return 0;
    /* A coarse mesh grows to a few thousand triangles; the caps keep a
     * mesh of long slivers (extruded lettering) within what was asked for,
     * split less where it would pass them. */
    uint32_t cap_v = max_vertices < 65536 ? max_vertices : 65536, cap_f = max_faces < 131072 ? max_faces : 131072;
    if (m->nv > cap_v || m->nf > cap_f) return 0;
    double limit2 = d2 / (12.0 * 12.0);
    int coarse = 0;
    for (size_t t = 0; t < m->nf && !coarse; t++)
        for (int k = 0; k < 3; k++) coarse |= edge_len2(m->pos, m->idx[3 * t + k], m->idx[3 * t + (k + 1) % 3]) > limit2;
    if (!coarse) return 0;
    /* A file without normals gets the parent's (jd_mesh_compute_normals:
     * area-weighted, by the file's winding, which the parent turns round
     * with the normals where it is inside out) before it is split, so the
     * new vertices carry the shading the corners gave, not their flat
     * faces' (a smooth low-poly shape stays smooth). */
    if (!m->nrm) {
        m->nrm = malloc(sizeof(float) * (n3 ? n3 : 1));
        if (!m->nrm) return -1;
        /* The parent's own normals, over these arrays (unit length: a
         * midpoint takes the mean direction). */
        jd_mesh view = {.num_vertices = m->nv, .num_indices = 3 * m->nf, .positions = m->pos, .normals = m->nrm,
                        .indices = m->idx, .index_size = 4};
        jd_mesh_compute_normals(&view);
    }
    for (int i = 0; i < 16; i++) {
        int r = pass(m, limit2, cap_v, cap_f);
        if (r <= 0) return r;
    }
    return 0;
}
