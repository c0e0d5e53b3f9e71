/* Light between parts (mesh_bounce.h), as precomputed radiance transfer
 * (Sloan, Kautz and Snyder 2002) in spherical harmonics of the first two
 * orders (on the knot as close to Cycles as the first three:
 * docs/quality.md).
 *
 * Two steps, each one ray fan a vertex over its outer hemisphere,
 * cosine-distributed (jd_cosine_ray, the fan of jade reference's own
 * light between parts):
 * 1. the light a vertex Q takes in as a function of the light's direction
 *    l, n.l where the sky above Q is open towards l and 0 where another
 *    part shadows it, projected: T_Q = integral of n.l V(l) Y(l) over l,
 *    by the fan (pdf n.l / pi: pi / rays times Y at each open direction);
 * 2. what a vertex P takes from the others: each ray of its fan that meets
 *    the object from outside brings the radiance of a Lambertian surface
 *    giving out what it took in, 1 / pi of it, and a cosine-distributed
 *    fan sums irradiance as the plain mean, so g_P is the mean of T at the
 *    hits (the hit's triangle's corners, by their weights).
 * Left out (docs/quality.md, "Light between parts in full"): the
 * diffusion of that light under the hit's and the vertex's surfaces (a
 * dipole's profile over the mesh on both ends took the knot no closer to
 * Cycles, measured); unmeasured, the Fresnel transmittance at both
 * boundaries (its mean under diffuse light is jade's unit), the colours of
 * the surfaces it came from, the ambient light's share, and further
 * bounces (the reference's second brought a tenth of its first). */
#include "mesh_bounce.h"

#include <math.h>

#include "mesh_grid.h"
#include "sh.h"
#include "ray_fan.h"

jd_result jd_mesh_bounce(const jd_mesh *m, int rays, jd_arena *a, float *out, jd_error *err)
{
    if (rays < 1 || rays > 256) return jd_fail(err, JD_ERR_ARG, "light between parts: %d rays a vertex (1 to 256)", rays);
    size_t top = jd_arena_top_mark(a);
    uint32_t nv = m->num_vertices;
    float *t = jd_arena_alloc_top(a, sizeof(float) * JD_BOUNCE_TERMS * (nv ? nv : 1), 16, "light between parts", err);
    if (!t) return JD_ERR_BUDGET;
    jd_mesh_grid g;
    jd_result res = jd_mesh_grid_triangles(m, &g, a, "light between parts grid", err);
    if (res) { jd_arena_top_reset(a, top); return res; }
    float ext = fmaxf(m->bmax.x - m->bmin.x, fmaxf(m->bmax.y - m->bmin.y, m->bmax.z - m->bmin.z));
    /* Rays leave a little above the vertex, off its own triangles. */
    float eps = 1e-4f * ext, cap = 4.0f * ext;
    for (int step = 0; step < 2; step++)
        for (uint32_t i = 0; i < nv; i++) {
            jd_vec3 un = jd_unit_normal(m->normals + 3 * (size_t)i);
            float n[3] = {un.x, un.y, un.z}, t1[3], t2[3];
            jd_hemisphere_frame(n, t1, t2);
            const float *p = m->positions + 3 * (size_t)i;
            float o[3] = {p[0] + 2.0f * eps * n[0], p[1] + 2.0f * eps * n[1], p[2] + 2.0f * eps * n[2]};
            float turn = (float)(i * 2654435761u) * (1.0f / 4294967296.0f);
            double acc[JD_BOUNCE_TERMS] = {0};
            for (int k = 0; k < rays; k++) {
                float d[3];
                jd_cosine_ray(n, t1, t2, k, rays, turn, d);
                if (step == 0) { /* the sky open towards d */
                    if (jd_mesh_grid_blocked(m, &g, o, d, eps, cap)) continue;
                    double w[3] = {d[0], d[1], d[2]}, y[9];
                    jd_sh_basis(w, y); /* y[0]: the constant; y[1], y[2], y[3]: y, z, x */
                    for (int b = 0; b < JD_BOUNCE_TERMS; b++) acc[b] += y[b];
                    continue;
                }
                jd_mesh_hit h;
                jd_mesh_grid_cast(m, &g, o, d, eps, cap, &h);
                if (h.tri == UINT32_MAX) continue; /* the sky: no light */
                uint32_t c[3] = {jd_mesh_index(m, 3 * h.tri), jd_mesh_index(m, 3 * h.tri + 1),
                                 jd_mesh_index(m, 3 * h.tri + 2)};
                float w[3] = {1.0f - h.u - h.v, h.u, h.v}, facing = 0.0f;
                for (int j = 0; j < 3; j++) {
                    const float *nh = m->normals + 3 * (size_t)c[j];
                    facing += w[j] * (nh[0] * d[0] + nh[1] * d[1] + nh[2] * d[2]);
                }
                if (facing >= 0.0f) continue; /* met from inside: a crack in the mesh */
                for (int j = 0; j < 3; j++)
                    for (int b = 0; b < JD_BOUNCE_TERMS; b++) acc[b] += w[j] * t[JD_BOUNCE_TERMS * (size_t)c[j] + (size_t)b];
            }
            if (step == 0) {
                for (int b = 0; b < JD_BOUNCE_TERMS; b++)
                    t[JD_BOUNCE_TERMS * (size_t)i + (size_t)b] = (float)(acc[b] * 3.14159265358979 / rays);
                continue;
            }
            /* Step 2's sums (jd_sh_basis's order) take the basis's
             * constants again, in the order x, y, z, constant: G(l) is then
             * one dot product with (l, 1) in the vertex stage. */
            float *dst = out + JD_BOUNCE_TERMS * (size_t)i;
            dst[0] = (float)(acc[3] * 0.488603 / rays), dst[1] = (float)(acc[1] * 0.488603 / rays);
            dst[2] = (float)(acc[2] * 0.488603 / rays), dst[3] = (float)(acc[0] * 0.282095 / rays);
        }
    jd_arena_top_reset(a, top);
    return JD_OK;
}
