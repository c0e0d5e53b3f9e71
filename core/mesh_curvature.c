/* The surface's curvature at each vertex, for full's local part past the
 * terminator: light that enters on the lit side of a curved surface
 * diffuses a few tenths of a millimetre round it, so the lit side's n.l
 * ramp is smoothed over the angle the local part's width spans at the
 * surface's radius (mesh.vert; Penner and Borshukov 2011, "Pre-integrated
 * skin shading", tabulate the same integral over curvature and n.l). Made
 * once at set-up, a pass over the triangles. */
#include "mesh_curvature.h"

#include <math.h>
#include <string.h>

#include "mesh_carry.h"

jd_result jd_mesh_curvature(const jd_mesh *m, jd_arena *a, float *out, jd_error *err)
{
    size_t top = jd_arena_top_mark(a);
    /* Per vertex: the sum of the edges' curvatures, of their squares, and
     * their count. */
    float *acc = jd_arena_alloc_top(a, sizeof(float) * 3 * (size_t)m->num_vertices, 16, "curvature", err);
    if (!acc) return JD_ERR_BUDGET;
    memset(acc, 0, sizeof(float) * 3 * (size_t)m->num_vertices);
    for (uint32_t t = 0; t + 2 < m->num_indices; t += 3) {
        uint32_t v[3] = {jd_mesh_index(m, t), jd_mesh_index(m, t + 1), jd_mesh_index(m, t + 2)};
        for (int e = 0; e < 3; e++) {
            /* Each edge of each triangle, at both its ends: an edge inside
             * the mesh counts twice at each, as all its neighbours' do. */
            uint32_t i = v[e], j = v[(e + 1) % 3];
            const float *pi = m->positions + 3 * (size_t)i, *pj = m->positions + 3 * (size_t)j;
            const float *ni = m->normals + 3 * (size_t)i, *nj = m->normals + 3 * (size_t)j;
            float d[3] = {pi[0] - pj[0], pi[1] - pj[1], pi[2] - pj[2]};
            float dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if (!(dd > 0.0f)) continue;
            float k = ((ni[0] - nj[0]) * d[0] + (ni[1] - nj[1]) * d[1] + (ni[2] - nj[2]) * d[2]) / dd;
            if (!isfinite(k)) continue;
            uint32_t ends[2] = {i, j};
            for (int s = 0; s < 2; s++) {
                float *c = acc + 3 * (size_t)ends[s];
                c[0] += k;
                c[1] += k * k;
                c[2] += 1.0f;
            }
        }
    }
    for (uint32_t i = 0; i < m->num_vertices; i++) {
        const float *c = acc + 3 * (size_t)i;
        if (c[2] < 1.0f) { out[i] = 0.0f; continue; }
        float mean = c[0] / c[2], var = fmaxf(c[1] / c[2] - mean * mean, 0.0f);
        out[i] = fmaxf(mean + sqrtf(2.0f * var), 0.0f);
    }
    jd_arena_top_reset(a, top);
    jd_mesh_smooth(m, out, 1, 1, a);
    return JD_OK;
}
