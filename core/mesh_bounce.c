/* Light between parts (mesh_bounce.h), as precomputed radiance transfer
 * (Sloan, Kautz and Snyder 2002) in spherical harmonics of the first two
 * orders, which hold a cosine lobe to within a few percent of its energy.
 *
 * Two steps, each one ray fan a vertex over its outer hemisphere,
 * cosine-distributed (a golden-angle spiral turned by a hash of the
 * vertex):
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

/* Y_0^0 and the three of order 1, in the order x, y, z, constant. */
static void basis(const float d[3], float y[JD_BOUNCE_TERMS])
{
    y[0] = 0.488603f * d[0], y[1] = 0.488603f * d[1], y[2] = 0.488603f * d[2], y[3] = 0.282095f;
}

/* Ray k of `rays` over the hemisphere round n (t1, t2: a frame with it),
 * cosine-distributed; rot turns the spiral. */
static void fan_ray(int k, int rays, float rot, const jd_vec3 *t1, const jd_vec3 *t2, const jd_vec3 *n, float d[3])
{
    float u = ((float)k + 0.5f) / (float)rays, phi = 6.2831853f * fmodf(0.618034f * (float)k + rot, 1.0f);
    float s = sqrtf(u), z = sqrtf(1.0f - u), cx = s * cosf(phi), cy = s * sinf(phi);
    d[0] = cx * t1->x + cy * t2->x + z * n->x;
    d[1] = cx * t1->y + cy * t2->y + z * n->y;
    d[2] = cx * t1->z + cy * t2->z + z * n->z;
}

static void frame_of(jd_vec3 n, jd_vec3 *t1, jd_vec3 *t2)
{
    *t1 = jd_v3_norm(jd_v3_cross(n, fabsf(n.x) < 0.9f ? jd_v3(1, 0, 0) : jd_v3(0, 1, 0)));
    *t2 = jd_v3_cross(n, *t1);
}

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
            jd_vec3 n = jd_unit_normal(m->normals + 3 * (size_t)i), t1, t2;
            frame_of(n, &t1, &t2);
            const float *p = m->positions + 3 * (size_t)i;
            float o[3] = {p[0] + 2.0f * eps * n.x, p[1] + 2.0f * eps * n.y, p[2] + 2.0f * eps * n.z};
            float rot = (float)((i * 2654435761u) >> 16) / 65536.0f;
            double acc[JD_BOUNCE_TERMS] = {0};
            for (int k = 0; k < rays; k++) {
                float d[3];
                fan_ray(k, rays, rot, &t1, &t2, &n, d);
                if (step == 0) { /* the sky open towards d */
                    if (jd_mesh_grid_blocked(m, &g, o, d, eps, cap)) continue;
                    float y[JD_BOUNCE_TERMS];
                    basis(d, y);
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
            /* Step 2's sums take the basis's constants again: G(l) is then
             * one dot product with (l, 1) in the vertex stage. */
            static const double again[JD_BOUNCE_TERMS] = {0.488603, 0.488603, 0.488603, 0.282095};
            float *dst = (step == 0 ? t : out) + JD_BOUNCE_TERMS * (size_t)i;
            for (int b = 0; b < JD_BOUNCE_TERMS; b++)
                dst[b] = (float)(step == 0 ? acc[b] * 3.14159265358979 / rays : acc[b] * again[b] / rays);
        }
    jd_arena_top_reset(a, top);
    return JD_OK;
}
