#include "ref_single.h"

#include <math.h>

enum {
    JD_SINGLE_SEGMENTS = 16, /* parts along one camera ray, at most */
    JD_SINGLE_STEPS = 16,    /* points a part and a channel, stratified by the channel's own attenuation */
    JD_SINGLE_CROSSINGS = 64 /* faces one ray may cross: a mesh folded more than that is cut short */
};

static float dot3(const float a[3], const float b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Whether a ray along d leaves the medium where it hit: the face's outward
 * geometric normal (its winding's, turned to agree with its vertices'
 * normals) points along d. */
static int leaving(const jd_single *s, const jd_hit *h, const float d[3])
{
    const uint32_t *t = s->bvh->tri + 3 * (size_t)h->tri;
    const float *a = s->bvh->pos + 3 * (size_t)t[0], *b = s->bvh->pos + 3 * (size_t)t[1],
                *c = s->bvh->pos + 3 * (size_t)t[2];
    float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    float g[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    float n[3] = {0, 0, 0};
    for (int v = 0; v < 3; v++)
        for (int k = 0; k < 3; k++) n[k] += s->nrm[3 * (size_t)t[v] + k];
    float side = dot3(g, d);
    return dot3(g, n) < 0 ? side < 0 : side > 0;
}

/* The stretches of medium along the ray from o (inside the medium) in
 * direction d, as [start, end] in world units; the count, or -1 where the
 * ray ends inside (out through an open mesh's hole: where it left is not
 * known). */
static int inside_segments(const jd_single *s, const float o[3], const float d[3], float seg[][2], int max)
{
    float t0 = 0.0f, start = 0.0f;
    int inside = 1, n = 0;
    for (int i = 0; i < JD_SINGLE_CROSSINGS && n < max; i++) {
        jd_hit h;
        if (!jd_bvh_intersect(s->bvh, o, d, t0, 1e30f, &h)) break;
        int out = leaving(s, &h, d);
        if (inside && out) {
            seg[n][0] = start, seg[n][1] = h.t;
            n++;
            inside = 0;
        } else if (!inside && !out) {
            inside = 1;
            start = h.t;
        }
        t0 = h.t + 1e-4f; /* past the face (the object is 2 units across) */
    }
    return inside ? -1 : n;
}

/* Millimetres of medium between q (inside) and the light; negative where
 * the ray found no way out. */
static float medium_to_light(const jd_single *s, const float q[3], const float light[3])
{
    float seg[JD_SINGLE_SEGMENTS][2], len = 0.0f;
    int n = inside_segments(s, q, light, seg, JD_SINGLE_SEGMENTS);
    for (int i = 0; i < n; i++) len += seg[i][1] - seg[i][0];
    return n < 0 ? -1.0f : len * s->mm_per_world;
}

int jd_single_scatter(const jd_single *s, const float p[3], const float ng[3], const float dir[3],
                      const float light[3], float e, uint32_t seed, float out[3])
{
    out[0] = out[1] = out[2] = 0.0f;
    if (!(e > 0)) return 0;
    float o[3], seg[JD_SINGLE_SEGMENTS][2];
    for (int k = 0; k < 3; k++) o[k] = p[k] - 1e-4f * ng[k]; /* just inside */
    int ns = inside_segments(s, o, dir, seg, JD_SINGLE_SEGMENTS);
    if (ns < 0) return -1;
    float mm = s->mm_per_world, turn = (float)(seed * 2654435761u) * (1.0f / 4294967296.0f);
    for (int c = 0; c < 3; c++) {
        float st = (float)s->sigma_t[c], tau = 0.0f, acc = 0.0f;
        if (!(st > 0)) continue;
        float jit = fmodf(turn + 0.618034f * (float)c, 1.0f);
        for (int g = 0; g < ns; g++) {
            float len = (seg[g][1] - seg[g][0]) * mm, span = 1.0f - expf(-st * len), part = 0.0f;
            int got = 0;
            /* x drawn as exp(-st x) on [0, len], stratified: the integrand
             * exp(-st x) T(x) over that density is T(x) span / st. Points
             * whose way to the light ends inside (an open mesh) are left
             * out of the mean. */
            for (int i = 0; i < JD_SINGLE_STEPS; i++) {
                float u = ((float)i + jit) / (float)JD_SINGLE_STEPS, x = -logf(1.0f - u * span) / st, q[3];
                /* On the ray from p itself: from o every point would lie
                 * the offset deeper, 1-3% of marble's light. */
                for (int k = 0; k < 3; k++) q[k] = p[k] + dir[k] * (seg[g][0] + x / mm);
                float ml = medium_to_light(s, q, light);
                if (ml >= 0) part += expf(-st * ml), got++;
            }
            if (got) acc += expf(-tau) * part / (float)got * span / st;
            tau += st * len;
        }
        /* pi L = pi e (sigma_s / 4 pi) integral = e sigma_s / 4 integral */
        out[c] = e * (float)s->sigma_s[c] * 0.25f * acc;
    }
    return ns;
}
