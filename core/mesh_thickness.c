/* A part's thickness under each vertex, for full's light on thin parts: a
 * slab d mm thick returns R(d) of the half-space's light on its lit face
 * and sends T(d) out of its far face (core/slab.h), and the reference
 * takes d along the inward normal where the light enters
 * (reference/ref_slab.h). Made once at set-up: one ray a vertex through a
 * uniform grid of the triangles (mesh_grid.c). */
#include "mesh_thickness.h"

#include <math.h>

#include "mesh_carry.h"
#include "mesh_grid.h"

/* A ray a vertex reads the surface's detail: a ridge or a crease
 * measures thinner than the part around it, and the light the levels
 * keep followed it as dark lines along a back-lit ear's rim. Two passes
 * of jd_mesh_smooth spread it over the neighbourhood. */

jd_result jd_mesh_thickness(const jd_mesh *m, float cap, jd_arena *a, float *out, jd_error *err)
{
    size_t top = jd_arena_top_mark(a);
    jd_mesh_grid g;
    jd_result res = jd_mesh_grid_triangles(m, &g, a, "thickness grid", err);
    if (res) return res;
    /* A ray from the vertex itself meets its own triangles at 0: hits
     * nearer than a ten-thousandth of the box are its own. */
    float ext = fmaxf(m->bmax.x - m->bmin.x, fmaxf(m->bmax.y - m->bmin.y, m->bmax.z - m->bmin.z));
    float eps = 1e-4f * ext;
    for (uint32_t i = 0; i < m->num_vertices; i++) {
        const float *n = m->normals + 3 * (size_t)i;
        float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(len > 0.0f)) { out[i] = cap; continue; }
        float d[3] = {-n[0] / len, -n[1] / len, -n[2] / len};
        out[i] = jd_mesh_grid_cast(m, &g, m->positions + 3 * (size_t)i, d, eps, cap, NULL);
    }
    jd_arena_top_reset(a, top);
    jd_mesh_smooth(m, out, 1, 2, a);
    return JD_OK;
}

jd_result jd_mesh_thickness_from(const jd_mesh *m, const jd_mesh *coarse, const float *cthick, float reach, float cap,
                                 jd_arena *a, float *out, jd_error *err)
{
    /* Each vertex: the coarse vertices within reach that face its way (the
     * proxy keeps a thin part's two sides apart, core/mesh.c); cap where
     * there are none. */
    jd_result res = jd_mesh_carry(m, coarse, cthick, 1, reach, cap, a, out, err);
    if (res) return res;
    for (uint32_t i = 0; i < m->num_vertices; i++) out[i] = fminf(out[i], cap);
    jd_mesh_smooth(m, out, 1, 2, a);
    return JD_OK;
}
