#include "mesh.h"

#include <math.h>
#include <string.h>

uint32_t jd_mesh_index(const jd_mesh *m, uint32_t i)
{
    return m->index_size == 2 ? ((const uint16_t *)m->indices)[i] : ((const uint32_t *)m->indices)[i];
}

jd_result jd_mesh_validate(const jd_mesh *m, const char *name, jd_error *err)
{
    if (m->num_vertices == 0 || m->num_indices == 0 || m->num_indices % 3)
        return jd_fail(err, JD_ERR_FORMAT, "%s: mesh has no triangles", name);
    for (uint32_t i = 0; i < m->num_indices; i++) {
        uint32_t v = jd_mesh_index(m, i);
        if (v >= m->num_vertices)
            return jd_fail(err, JD_ERR_FORMAT,
                           "%s: face %u refers to vertex %u but the mesh has %u vertices", name,
                           i / 3, v, m->num_vertices);
    }
    for (uint32_t i = 0; i < 3 * m->num_vertices; i++) {
        float p = m->positions[i];
        if (!isfinite(p) || fabsf(p) > 1e6f)
            return jd_fail(err, JD_ERR_FORMAT, "%s: vertex %u has an unusable position (%g)",
                           name, i / 3, (double)p);
    }
    return JD_OK;
}

jd_result jd_mesh_check_finite(const float *v, uint32_t num_vertices, int comps, const char *what, const char *name,
                               jd_error *err)
{
    for (uint32_t i = 0; i < num_vertices * (uint32_t)comps; i++)
        if (!isfinite(v[i]))
            return jd_fail(err, JD_ERR_FORMAT, "%s: vertex %u has a non-finite %s (%g); refused", name,
                           i / (uint32_t)comps, what, (double)v[i]);
    return JD_OK;
}

void jd_mesh_compute_bounds(jd_mesh *m)
{
    const float *p = m->positions;
    jd_vec3 lo = jd_v3(p[0], p[1], p[2]), hi = lo;
    for (uint32_t i = 1; i < m->num_vertices; i++) {
        const float *q = p + 3 * i;
        lo.x = fminf(lo.x, q[0]); lo.y = fminf(lo.y, q[1]); lo.z = fminf(lo.z, q[2]);
        hi.x = fmaxf(hi.x, q[0]); hi.y = fmaxf(hi.y, q[1]); hi.z = fmaxf(hi.z, q[2]);
    }
    m->bmin = lo;
    m->bmax = hi;
}

void jd_mesh_placement(const jd_mesh *m, jd_vec3 *centre, float *radius)
{
    *centre = jd_v3_scale(jd_v3_add(m->bmin, m->bmax), 0.5f);
    *radius = 0.5f * jd_v3_len(jd_v3_sub(m->bmax, m->bmin));
    if (!(*radius > 0)) *radius = 1.0f; /* a single point */
}

jd_vec3 jd_unit_normal(const float n[3])
{
    float l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    return l > 1e-20f && isfinite(l) ? jd_v3(n[0] / l, n[1] / l, n[2] / l) : jd_v3(0.0f, 0.0f, 1.0f);
}

static void normalize_all(jd_mesh *m)
{
    for (uint32_t i = 0; i < m->num_vertices; i++) {
        float *n = m->normals + 3 * i;
        jd_vec3 u = jd_unit_normal(n);
        n[0] = u.x; n[1] = u.y; n[2] = u.z;
    }
}

void jd_mesh_compute_normals(jd_mesh *m)
{
    memset(m->normals, 0, sizeof(float) * 3 * m->num_vertices);
    for (uint32_t t = 0; t + 2 < m->num_indices; t += 3) {
        uint32_t ia = jd_mesh_index(m, t), ib = jd_mesh_index(m, t + 1), ic = jd_mesh_index(m, t + 2);
        const float *a = m->positions + 3 * ia, *b = m->positions + 3 * ib, *c = m->positions + 3 * ic;
        /* The unnormalised cross product is twice the area: area weighting for free. */
        jd_vec3 n = jd_v3_cross(jd_v3(b[0] - a[0], b[1] - a[1], b[2] - a[2]),
                                jd_v3(c[0] - a[0], c[1] - a[1], c[2] - a[2]));
        uint32_t v[3] = {ia, ib, ic};
        for (int k = 0; k < 3; k++) {
            float *o = m->normals + 3 * v[k];
            o[0] += n.x; o[1] += n.y; o[2] += n.z;
        }
    }
    normalize_all(m);
}

void jd_mesh_fix_normals(jd_mesh *m)
{
    for (uint32_t i = 0; i < 3 * m->num_vertices; i++)
        if (!isfinite(m->normals[i])) { jd_mesh_compute_normals(m); return; }
    normalize_all(m);
}

/* Triangle t's corners (t counts indices), relative to the box centre. */
static void triangle(const jd_mesh *m, uint32_t t, double p[3][3])
{
    for (int k = 0; k < 3; k++) {
        const float *v = m->positions + 3 * (size_t)jd_mesh_index(m, t + (uint32_t)k);
        p[k][0] = v[0] - 0.5 * ((double)m->bmin.x + m->bmax.x);
        p[k][1] = v[1] - 0.5 * ((double)m->bmin.y + m->bmax.y);
        p[k][2] = v[2] - 0.5 * ((double)m->bmin.z + m->bmax.z);
    }
}

int jd_mesh_orient_outward(jd_mesh *m)
{
    /* Six times the signed volume: the sum of a . (b x c) over the faces. */
    double vol6 = 0, p[3][3];
    for (uint32_t t = 0; t + 2 < m->num_indices; t += 3) {
        triangle(m, t, p);
        const double *a = p[0], *b = p[1], *c = p[2];
        vol6 += a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    double box = ((double)m->bmax.x - m->bmin.x) * ((double)m->bmax.y - m->bmin.y) * ((double)m->bmax.z - m->bmin.z);
    if (!(vol6 < -0.06 * box)) return 0;
    for (uint32_t t = 0; t + 2 < m->num_indices; t += 3) {
        if (m->index_size == 2) {
            uint16_t *ix = (uint16_t *)m->indices + t, s = ix[1];
            ix[1] = ix[2];
            ix[2] = s;
        } else {
            uint32_t *ix = (uint32_t *)m->indices + t, s = ix[1];
            ix[1] = ix[2];
            ix[2] = s;
        }
    }
    return 1;
}

int jd_mesh_normals_follow_winding(jd_mesh *m)
{
    double agree = 0, p[3][3];
    for (uint32_t t = 0; t + 2 < m->num_indices; t += 3) {
        triangle(m, t, p);
        const double *a = p[0], *b = p[1], *c = p[2];
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double fn[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        for (int k = 0; k < 3; k++) {
            const float *n = m->normals + 3 * (size_t)jd_mesh_index(m, t + (uint32_t)k);
            agree += fn[0] * n[0] + fn[1] * n[1] + fn[2] * n[2];
        }
    }
    if (!(agree < 0)) return 0;
    for (uint32_t i = 0; i < 3 * m->num_vertices; i++) m->normals[i] = -m->normals[i];
    return 1;
}

jd_result jd_mesh_set_indices(jd_mesh *m, const uint32_t *idx, uint32_t count, int allow_32,
                              jd_arena *a, jd_error *err)
{
    if (m->num_vertices <= 65536) {
        uint16_t *o = jd_arena_alloc(a, sizeof(uint16_t) * count, 4, "mesh indices", err);
        if (!o) return err ? err->code : JD_ERR_BUDGET;
        for (uint32_t i = 0; i < count; i++)
            o[i] = (uint16_t)(idx[i] < m->num_vertices ? idx[i] : 0xffffu);
        m->indices = o;
        m->index_size = 2;
    } else {
        if (!allow_32)
            return jd_fail(err, JD_ERR_UNSUPPORTED,
                           "mesh has %u vertices; above 65,536 it needs 32-bit indices "
                           "(OES_element_index_uint), which this device lacks",
                           m->num_vertices);
        uint32_t *o = jd_arena_alloc(a, sizeof(uint32_t) * count, 4, "mesh indices", err);
        if (!o) return err ? err->code : JD_ERR_BUDGET;
        memcpy(o, idx, sizeof(uint32_t) * count);
        m->indices = o;
        m->index_size = 4;
    }
    m->num_indices = count;
    return JD_OK;
}

jd_result jd_mesh_build_proxy(const jd_mesh *src, int cells, jd_arena *a, jd_mesh *out,
                              jd_error *err)
{
    if (cells < 2) cells = 2;
    if (cells > 64) cells = 64;
    size_t top = jd_arena_top_mark(a);
    size_t ncell = (size_t)cells * cells * cells;
    uint32_t *cell_of = jd_arena_alloc_top(a, sizeof(uint32_t) * src->num_vertices, 4, "proxy scratch", err);
    /* Two clusters a cell (0 means unused) and each cluster's first vertex
     * (65,536 at most: 16-bit indices). */
    uint32_t nfirst = src->num_vertices < 65536 ? (src->num_vertices ? src->num_vertices : 1) : 65536;
    uint32_t *slot = jd_arena_alloc_top(a, sizeof(uint32_t) * 2 * ncell, 4, "proxy grid", err);
    uint32_t *first = jd_arena_alloc_top(a, sizeof(uint32_t) * nfirst, 4, "proxy scratch", err);
    if (!cell_of || !slot || !first) { jd_arena_top_reset(a, top); return JD_ERR_BUDGET; }

    jd_vec3 ext = jd_v3_sub(src->bmax, src->bmin);
    float e = fmaxf(ext.x, fmaxf(ext.y, ext.z));
    float inv = e > 0 ? (float)cells / (e * 1.0001f) : 0.0f;
    uint32_t nv = 0;
    /* A cell holds the two sides of anything thinner than it (a floor slab,
     * an ear, a leaf): its vertices facing away from the cell's first one
     * form a second cluster. Merged, the sides' normals cancel, and the
     * light map's irradiance (n.l of the proxy's normal) came out at half or
     * less on a 2 mm floor whose underside had as many vertices as its top;
     * the merged sheet's depth lay midway between the sides. Where a cell's
     * normals all lie within 90 degrees of each other (smooth parts, box
     * edges) nothing changes. Where the second clusters would take the
     * proxy past 16-bit indices, one cluster a cell, as before. */
    for (int split = 1; split >= 0; split--) {
        memset(slot, 0, sizeof(uint32_t) * 2 * ncell);
        nv = 0;
        uint32_t i = 0;
        for (; i < src->num_vertices; i++) {
            const float *p = src->positions + 3 * i, *n = src->normals + 3 * i;
            int ix = (int)((p[0] - src->bmin.x) * inv), iy = (int)((p[1] - src->bmin.y) * inv),
                iz = (int)((p[2] - src->bmin.z) * inv);
            ix = ix < 0 ? 0 : ix >= cells ? cells - 1 : ix;
            iy = iy < 0 ? 0 : iy >= cells ? cells - 1 : iy;
            iz = iz < 0 ? 0 : iz >= cells ? cells - 1 : iz;
            size_t c = 2 * (size_t)(ix + cells * (iy + cells * iz));
            if (split && slot[c]) {
                const float *s = src->normals + 3 * first[slot[c] - 1];
                if (n[0] * s[0] + n[1] * s[1] + n[2] * s[2] < 0.0f) c++;
            }
            if (!slot[c]) {
                if (nv == nfirst) break;
                first[nv] = i;
                slot[c] = ++nv;
            }
            cell_of[i] = slot[c] - 1;
        }
        if (i == src->num_vertices && nv <= 65535) break;
        nv = 65536; /* too many: again without the split, or the error below */
    }
    if (nv > 65535) { jd_arena_top_reset(a, top); return jd_fail(err, JD_ERR_LIMIT, "proxy has too many vertices"); }

    memset(out, 0, sizeof *out);
    out->num_vertices = nv;
    out->positions = jd_arena_alloc(a, sizeof(float) * 3 * nv, 16, "proxy positions", err);
    out->normals = jd_arena_alloc(a, sizeof(float) * 3 * nv, 16, "proxy normals", err);
    float *count = jd_arena_alloc_top(a, sizeof(float) * nv, 4, "proxy scratch", err);
    if (!out->positions || !out->normals || !count) { jd_arena_top_reset(a, top); return JD_ERR_BUDGET; }
    for (uint32_t i = 0; i < src->num_vertices; i++) {
        uint32_t c = cell_of[i];
        for (int k = 0; k < 3; k++) {
            out->positions[3 * c + k] += src->positions[3 * i + k];
            out->normals[3 * c + k] += src->normals[3 * i + k];
        }
        count[c] += 1.0f;
    }
    for (uint32_t c = 0; c < nv; c++)
        for (int k = 0; k < 3; k++) out->positions[3 * c + k] /= count[c];
    normalize_all(out);

    /* Count surviving triangles before allocating them. */
    uint32_t ntri = 0;
    for (uint32_t t = 0; t + 2 < src->num_indices; t += 3) {
        uint32_t x = cell_of[jd_mesh_index(src, t)], y = cell_of[jd_mesh_index(src, t + 1)],
                 z = cell_of[jd_mesh_index(src, t + 2)];
        ntri += x != y && y != z && x != z;
    }
    uint16_t *idx = jd_arena_alloc(a, sizeof(uint16_t) * 3 * (ntri ? ntri : 1), 4, "proxy indices", err);
    if (!idx) { jd_arena_top_reset(a, top); return JD_ERR_BUDGET; }
    uint32_t k = 0;
    for (uint32_t t = 0; t + 2 < src->num_indices; t += 3) {
        uint32_t x = cell_of[jd_mesh_index(src, t)], y = cell_of[jd_mesh_index(src, t + 1)],
                 z = cell_of[jd_mesh_index(src, t + 2)];
        if (x != y && y != z && x != z) {
            idx[k++] = (uint16_t)x; idx[k++] = (uint16_t)y; idx[k++] = (uint16_t)z;
        }
    }
    out->indices = idx;
    out->index_size = 2;
    out->num_indices = k;
    out->bmin = src->bmin;
    out->bmax = src->bmax;
    jd_arena_top_reset(a, top);
    return JD_OK;
}
