#include "ref_samples.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Dart throwing stops after this many candidates per wanted point: the
 * last ones are mostly refused by then. */
enum { CANDIDATES_PER_POINT = 8 };

double jd_triangle_area(const float a[3], const float b[3], const float c[3])
{
    double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double x = e1[1] * e2[2] - e1[2] * e2[1], y = e1[2] * e2[0] - e1[0] * e2[2], z = e1[0] * e2[1] - e1[1] * e2[0];
    return 0.5 * sqrt(x * x + y * y + z * z);
}

static uint32_t hash32(uint32_t x)
{
    x ^= x >> 16; x *= 0x7feb352dU; x ^= x >> 15; x *= 0x846ca68bU; x ^= x >> 16;
    return x;
}

static double rand01(uint64_t *s)
{
    /* splitmix64 */
    uint64_t z = (*s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

static uint32_t cell_hash(int x, int y, int z, uint32_t mask)
{
    return hash32((uint32_t)x * 73856093u ^ hash32((uint32_t)y * 19349663u ^ hash32((uint32_t)z * 83492791u))) & mask;
}

jd_result jd_surface_samples(const float *pos, const uint32_t *tri, uint32_t num_tris, uint32_t target, uint32_t seed,
                             jd_surface_point **out, uint32_t *count, jd_error *err)
{
    *out = NULL;
    *count = 0;
    double *cdf = malloc(sizeof(double) * num_tris);
    jd_surface_point *pts = malloc(sizeof *pts * target);
    float *kept = malloc(sizeof(float) * 3 * target);
    uint32_t buckets = 1;
    while (buckets < 2 * target) buckets <<= 1;
    uint32_t *head = malloc(sizeof(uint32_t) * buckets), *next = malloc(sizeof(uint32_t) * target);
    if (!cdf || !pts || !kept || !head || !next) {
        free(cdf); free(pts); free(kept); free(head); free(next);
        return jd_fail(err, JD_ERR_BUDGET, "out of memory for %u sample points", target);
    }
    double total = 0;
    for (uint32_t t = 0; t < num_tris; t++) {
        total += jd_triangle_area(pos + 3 * (size_t)tri[3 * t], pos + 3 * (size_t)tri[3 * t + 1],
                                  pos + 3 * (size_t)tri[3 * t + 2]);
        cdf[t] = total;
    }
    /* Random sequential packing saturates near 0.7 points per d^2: a
     * minimum distance of 0.75 spacings lets the target be reached. */
    double d = 0.75 * sqrt(total / target), d2 = d * d, inv = 1.0 / d;
    for (uint32_t i = 0; i < buckets; i++) head[i] = UINT32_MAX;
    uint64_t rng = ((uint64_t)seed << 32) ^ 0x243f6a8885a308d3ULL;
    uint32_t n = 0;
    uint64_t tries = (uint64_t)target * CANDIDATES_PER_POINT;
    for (uint64_t k = 0; k < tries && n < target; k++) {
        double xi = rand01(&rng) * total;
        uint32_t lo = 0, hi = num_tris - 1;
        while (lo < hi) {
            uint32_t mid = lo + (hi - lo) / 2;
            if (cdf[mid] < xi) lo = mid + 1; else hi = mid;
        }
        float u = (float)rand01(&rng), v = (float)rand01(&rng);
        if (u + v > 1) { u = 1 - u; v = 1 - v; }
        const float *a = pos + 3 * (size_t)tri[3 * lo], *b = pos + 3 * (size_t)tri[3 * lo + 1],
                    *c = pos + 3 * (size_t)tri[3 * lo + 2];
        float p[3];
        for (int j = 0; j < 3; j++) p[j] = (1 - u - v) * a[j] + u * b[j] + v * c[j];
        int cx = (int)floor(p[0] * inv), cy = (int)floor(p[1] * inv), cz = (int)floor(p[2] * inv);
        int near = 0;
        for (int dz = -1; dz <= 1 && !near; dz++)
            for (int dy = -1; dy <= 1 && !near; dy++)
                for (int dx = -1; dx <= 1 && !near; dx++)
                    for (uint32_t q = head[cell_hash(cx + dx, cy + dy, cz + dz, buckets - 1)]; q != UINT32_MAX;
                         q = next[q]) {
                        float ex = kept[3 * q] - p[0], ey = kept[3 * q + 1] - p[1], ez = kept[3 * q + 2] - p[2];
                        if (ex * ex + ey * ey + ez * ez < d2) { near = 1; break; }
                    }
        if (near) continue;
        memcpy(kept + 3 * n, p, sizeof p);
        uint32_t h = cell_hash(cx, cy, cz, buckets - 1);
        next[n] = head[h];
        head[h] = n;
        pts[n].tri = lo;
        pts[n].u = u;
        pts[n].v = v;
        n++;
    }
    free(cdf); free(kept); free(head); free(next);
    *out = pts;
    *count = n;
    return JD_OK;
}
