/* A model's own colours, read as its diffuse reflectance. Vertex colours
 * and texels hold sqrt(linear reflectance) in 8 bits; the texture's weight
 * (0 or 1) rides in the vertex colour's alpha, so that a model whose
 * materials are partly untextured keeps one texture and one draw. */
#include "mesh.h"

#include <math.h>

static float decode(uint8_t s)
{
    float x = s / 255.0f;
    return x * x;
}

/* The texture's sqrt values, bilinear with repeat, at (s, t), t from the top row. */
static void texel_sqrt(const jd_mesh *m, float s, float t, float out[3])
{
    float x = s * (float)m->texture_w - 0.5f, y = t * (float)m->texture_h - 0.5f;
    float fx = floorf(x), fy = floorf(y), ax = x - fx, ay = y - fy;
    long ix = (long)fx, iy = (long)fy;
    long w = (long)m->texture_w, h = (long)m->texture_h;
    for (int c = 0; c < 3; c++) out[c] = 0.0f;
    for (int k = 0; k < 4; k++) {
        long px = ((ix + (k & 1)) % w + w) % w, py = ((iy + (k >> 1)) % h + h) % h;
        float wgt = ((k & 1) ? ax : 1.0f - ax) * ((k >> 1) ? ay : 1.0f - ay);
        const uint8_t *p = m->texels + 4 * ((size_t)py * (size_t)w + (size_t)px);
        for (int c = 0; c < 3; c++) out[c] += wgt * (p[c] / 255.0f);
    }
}

void jd_mesh_albedo_at(const jd_mesh *m, uint32_t tri, float u, float v, float out[3])
{
    if (!m->colors) {
        out[0] = out[1] = out[2] = 1.0f;
        return;
    }
    uint32_t i[3] = {jd_mesh_index(m, 3 * tri), jd_mesh_index(m, 3 * tri + 1), jd_mesh_index(m, 3 * tri + 2)};
    float b[3] = {1.0f - u - v, u, v}, weight = 0.0f, st[2] = {0, 0};
    for (int c = 0; c < 3; c++) out[c] = 0.0f;
    for (int k = 0; k < 3; k++) {
        const uint8_t *col = m->colors + 4 * (size_t)i[k];
        for (int c = 0; c < 3; c++) out[c] += b[k] * decode(col[c]);
        weight += b[k] * (col[3] / 255.0f);
        if (m->uvs) {
            st[0] += b[k] * m->uvs[2 * (size_t)i[k]];
            st[1] += b[k] * m->uvs[2 * (size_t)i[k] + 1];
        }
    }
    if (m->texels && m->uvs && weight > 0.0f) {
        float t[3];
        texel_sqrt(m, st[0], st[1], t);
        for (int c = 0; c < 3; c++) out[c] *= 1.0f - weight + weight * t[c] * t[c];
    }
}

static double triangle_area(const jd_mesh *m, uint32_t t)
{
    const float *p0 = m->positions + 3 * (size_t)jd_mesh_index(m, 3 * t),
                *p1 = m->positions + 3 * (size_t)jd_mesh_index(m, 3 * t + 1),
                *p2 = m->positions + 3 * (size_t)jd_mesh_index(m, 3 * t + 2);
    double e1[3], e2[3];
    for (int c = 0; c < 3; c++) {
        e1[c] = (double)p1[c] - p0[c];
        e2[c] = (double)p2[c] - p0[c];
    }
    double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2], cz = e1[0] * e2[1] - e1[1] * e2[0];
    return 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
}

void jd_mesh_albedo_prepare(jd_mesh *m)
{
    if (m->texels && m->uvs && m->num_vertices) {
        float lo[2] = {m->uvs[0], m->uvs[1]};
        for (uint32_t i = 1; i < m->num_vertices; i++)
            for (int k = 0; k < 2; k++) lo[k] = fminf(lo[k], m->uvs[2 * (size_t)i + k]);
        for (int k = 0; k < 2; k++) {
            float shift = floorf(lo[k]);
            for (uint32_t i = 0; shift != 0.0f && i < m->num_vertices; i++) m->uvs[2 * (size_t)i + k] -= shift;
        }
    }
    /* The mean by area, from four points of each triangle (its centroid
     * and the midpoints towards its corners). */
    static const float pts[4][2] = {{1.0f / 3, 1.0f / 3}, {1.0f / 6, 1.0f / 6}, {2.0f / 3, 1.0f / 6}, {1.0f / 6, 2.0f / 3}};
    double sum[3] = {0, 0, 0}, area = 0;
    for (uint32_t t = 0; t < m->num_indices / 3; t++) {
        double a = triangle_area(m, t);
        for (int k = 0; k < 4; k++) {
            float alb[3];
            jd_mesh_albedo_at(m, t, pts[k][0], pts[k][1], alb);
            for (int c = 0; c < 3; c++) sum[c] += a * 0.25 * alb[c];
        }
        area += a;
    }
    for (int c = 0; c < 3; c++) {
        float mean = area > 0 ? (float)(sum[c] / area) : 1.0f;
        /* A black model would divide by zero in the shading's 1 / mean. */
        m->albedo_mean[c] = mean > 1e-3f ? mean : 1e-3f;
    }
}
