#include "mesh_arrays.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "draco_shim.h"

#ifdef JD_HAVE_MESHOPT
#include <meshoptimizer.h>
#endif

void jd_mesh_arrays_free(jd_mesh_arrays *m)
{
    free(m->pos);
    free(m->nrm);
    free(m->uv);
    free(m->idx);
    free(m->col);
    free(m->tex.texels);
    memset(m, 0, sizeof *m);
}

void jd_mesh_arrays_drop_uvs(jd_mesh_arrays *m)
{
    free(m->uv);
    m->uv = NULL;
}

#ifdef JD_HAVE_MESHOPT
/* What meshoptimizer may be given: indices in range and finite positions
 * (a mesh with either is refused later by the parent, and must not reach
 * the overdraw sort or the simplifier's quadrics first). */
static int meshopt_safe(const jd_mesh_arrays *m)
{
    for (size_t i = 0; i < 3 * (size_t)m->nf; i++)
        if (m->idx[i] >= m->nv) return 0;
    for (size_t i = 0; i < 3 * (size_t)m->nv; i++)
        if (!isfinite(m->pos[i])) return 0;
    return 1;
}

static void turn_round(uint32_t *idx, size_t n)
{
    for (size_t t = 0; t + 2 < n; t += 3) {
        uint32_t s = idx[t + 1];
        idx[t + 1] = idx[t + 2];
        idx[t + 2] = s;
    }
}
#endif

void jd_mesh_arrays_order(jd_mesh_arrays *m)
{
#ifdef JD_HAVE_MESHOPT
    size_t n = 3 * (size_t)m->nf;
    if (!meshopt_safe(m)) return;
    /* The overdraw order sorts by which way triangles face: a mesh wound
     * inside out (the parent turns it round later) is ordered turned round. */
    double vol6 = 0;
    for (size_t t = 0; t + 2 < n; t += 3) {
        const float *a = m->pos + 3 * (size_t)m->idx[t], *b = m->pos + 3 * (size_t)m->idx[t + 1],
                    *c = m->pos + 3 * (size_t)m->idx[t + 2];
        vol6 += a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) - a[1] * ((double)b[0] * c[2] - (double)b[2] * c[0]) +
                a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0]);
    }
    /* Ordering is a nicety: a mesh near the child's memory limit keeps its
     * file order rather than failing to load. */
    uint32_t *tmp = malloc(sizeof(uint32_t) * (n ? n : 1));
    if (!tmp) return;
    /* meshoptimizer's own scratch (about 40 bytes per vertex and index) is
     * not checked by it: try it first. */
    void *probe = malloc(48 * ((size_t)m->nv + n) + 4096);
    if (!probe) {
        free(tmp);
        return;
    }
    free(probe);
    if (vol6 < 0) turn_round(m->idx, n);
    meshopt_optimizeVertexCache(tmp, m->idx, n, m->nv);
    meshopt_optimizeOverdraw(m->idx, tmp, n, m->pos, m->nv, 3 * sizeof(float), 1.05f);
    if (vol6 < 0) turn_round(m->idx, n); /* the file's winding: the parent decides what to do with it */
    free(tmp);
#else
    (void)m;
#endif
}

#ifdef JD_HAVE_MESHOPT
/* One vertex stream (NULL: none) into a new array of the vertices remap
 * keeps; 0, or -1 without memory (the stream as it was). */
static int remap_stream(void **stream, size_t nv_old, size_t nv_new, size_t size, const uint32_t *remap)
{
    if (!*stream) return 0;
    void *out = malloc(size * (nv_new ? nv_new : 1));
    if (!out) return -1;
    meshopt_remapVertexBuffer(out, *stream, nv_old, size, remap);
    free(*stream);
    *stream = out;
    return 0;
}
#endif

int jd_mesh_arrays_simplify(jd_mesh_arrays *m, uint32_t target, char *msg, size_t cap)
{
    if (!target || m->nf <= target) return 0;
#ifdef JD_HAVE_MESHOPT
    size_t n = 3 * (size_t)m->nf;
    if (!meshopt_safe(m)) return 0; /* the parent refuses it */
    uint32_t *dst = malloc(sizeof(uint32_t) * n), *remap = malloc(sizeof(uint32_t) * (size_t)m->nv);
    /* meshoptimizer's own scratch (its simplifier keeps about 90 bytes a
     * vertex and 30 an index) is not checked by it: tried first. */
    void *probe = dst && remap ? malloc(96 * (size_t)m->nv + 32 * n + 4096) : NULL;
    if (!probe) {
        free(dst);
        free(remap);
        snprintf(msg, cap, "out of memory simplifying its %u triangles", m->nf);
        return -1;
    }
    free(probe);
    /* Edge collapses that keep the surface's topology and its attribute
     * seams (meshoptimizer tells a seam by equal positions), moving it by
     * at most 2% of the mesh's extent: where that stops short of the target
     * the mesh keeps more triangles, not a torn surface. */
    size_t kept = meshopt_simplify(dst, m->idx, n, m->pos, m->nv, 3 * sizeof(float), 3 * (size_t)target, 0.02f, 0, NULL);
    if (kept == 0) {
        free(dst);
        free(remap);
        return 0; /* nothing left that the error allows: the mesh as it was */
    }
    /* The vertices still used, in first-use order; every stream remapped. */
    size_t nv = meshopt_optimizeVertexFetchRemap(remap, dst, kept, m->nv);
    meshopt_remapIndexBuffer(dst, dst, kept, remap);
    if (remap_stream((void **)&m->pos, m->nv, nv, 3 * sizeof(float), remap) ||
        remap_stream((void **)&m->nrm, m->nv, nv, 3 * sizeof(float), remap) ||
        remap_stream((void **)&m->uv, m->nv, nv, 2 * sizeof(float), remap) || remap_stream((void **)&m->col, m->nv, nv, 4, remap)) {
        free(dst);
        free(remap);
        snprintf(msg, cap, "out of memory simplifying its %u triangles", m->nf);
        return -1;
    }
    free(remap);
    free(m->idx);
    m->idx = dst;
    m->nf = (uint32_t)(kept / 3);
    m->nv = (uint32_t)nv;
    return 0;
#else
    snprintf(msg, cap, "this jade was built without meshoptimizer, so it cannot simplify the mesh to %u triangles", target);
    return -1;
#endif
}

int jd_mesh_arrays_emit(const jd_mesh_arrays *m, jd_record_write_fn write, void *user)
{
    jd_draco_record_header h = {JD_DRACO_RECORD_MAGIC, m->nv, m->nf,
                                (m->nrm ? (uint32_t)JD_DRACO_HAS_NORMALS : 0u) |
                                    (m->uv ? (uint32_t)JD_DRACO_HAS_UVS : 0u) |
                                    (m->material[0] ? (uint32_t)JD_DRACO_HAS_MATERIAL : 0u) |
                                    (m->medium.flags ? (uint32_t)JD_DRACO_HAS_MEDIUM : 0u) |
                                    (m->col ? (uint32_t)JD_DRACO_HAS_COLORS : 0u) |
                                    (m->tex.texels ? (uint32_t)JD_DRACO_HAS_TEXTURE : 0u),
                                m->nf_read ? m->nf_read : m->nf};
    uint32_t tex_size[2] = {m->tex.w, m->tex.h};
    size_t nv = m->nv;
    if (write(user, &h, sizeof h) || write(user, m->pos, sizeof(float) * 3 * nv) ||
        (m->nrm && write(user, m->nrm, sizeof(float) * 3 * nv)) || (m->uv && write(user, m->uv, sizeof(float) * 2 * nv)) ||
        write(user, m->idx, sizeof(uint32_t) * 3 * (size_t)m->nf) ||
        (m->material[0] && write(user, m->material, sizeof m->material)) ||
        (m->medium.flags && write(user, &m->medium, sizeof m->medium)) || (m->col && write(user, m->col, 4 * nv)) ||
        (m->tex.texels && (write(user, tex_size, sizeof tex_size) ||
                           write(user, m->tex.texels, (size_t)m->tex.w * m->tex.h * 4))))
        return -1;
    return 0;
}
