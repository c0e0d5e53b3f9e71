#include "ref_bvh.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { LEAF_MAX = 4, BINS = 12, MAX_DEPTH = 64 };

typedef struct box { float lo[3], hi[3]; } box;

static void box_empty(box *b)
{
    for (int k = 0; k < 3; k++) { b->lo[k] = FLT_MAX; b->hi[k] = -FLT_MAX; }
}

static void box_add(box *b, const float p[3])
{
    for (int k = 0; k < 3; k++) {
        if (p[k] < b->lo[k]) b->lo[k] = p[k];
        if (p[k] > b->hi[k]) b->hi[k] = p[k];
    }
}

static void box_merge(box *b, const box *o)
{
    for (int k = 0; k < 3; k++) {
        if (o->lo[k] < b->lo[k]) b->lo[k] = o->lo[k];
        if (o->hi[k] > b->hi[k]) b->hi[k] = o->hi[k];
    }
}

static float box_area(const box *b)
{
    float d[3];
    for (int k = 0; k < 3; k++) d[k] = b->hi[k] > b->lo[k] ? b->hi[k] - b->lo[k] : 0.0f;
    return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
}

typedef struct build_ctx {
    jd_bvh *b;
    box *tbox;      /* per triangle */
    float *cent;    /* 3 per triangle */
} build_ctx;

static void range_bounds(const build_ctx *c, uint32_t first, uint32_t count, box *bb, box *cb)
{
    box_empty(bb);
    box_empty(cb);
    for (uint32_t i = first; i < first + count; i++) {
        uint32_t t = c->b->order[i];
        box_merge(bb, &c->tbox[t]);
        box_add(cb, c->cent + 3 * t);
    }
}

/* Binned surface-area heuristic; returns the split position in order[] or 0
 * when the range should stay a leaf. */
static uint32_t split_range(build_ctx *c, uint32_t first, uint32_t count, const box *bb, const box *cb)
{
    if (count <= LEAF_MAX) return 0;
    int axis = 0;
    float ext = cb->hi[0] - cb->lo[0];
    for (int k = 1; k < 3; k++)
        if (cb->hi[k] - cb->lo[k] > ext) { ext = cb->hi[k] - cb->lo[k]; axis = k; }
    uint32_t *ord = c->b->order;
    uint32_t mid;
    if (!(ext > 0)) {
        mid = first + count / 2; /* coincident centroids: halve by count */
    } else {
        box bins[BINS];
        uint32_t n[BINS] = {0};
        for (int i = 0; i < BINS; i++) box_empty(&bins[i]);
        float scale = BINS / ext;
        for (uint32_t i = first; i < first + count; i++) {
            uint32_t t = ord[i];
            int bi = (int)((c->cent[3 * t + axis] - cb->lo[axis]) * scale);
            if (bi >= BINS) bi = BINS - 1;
            n[bi]++;
            box_merge(&bins[bi], &c->tbox[t]);
        }
        float right_area[BINS];
        uint32_t right_n[BINS];
        box acc;
        box_empty(&acc);
        uint32_t an = 0;
        for (int i = BINS - 1; i > 0; i--) {
            box_merge(&acc, &bins[i]);
            an += n[i];
            right_area[i] = box_area(&acc);
            right_n[i] = an;
        }
        box_empty(&acc);
        an = 0;
        float best = FLT_MAX;
        int best_i = -1;
        for (int i = 1; i < BINS; i++) {
            box_merge(&acc, &bins[i - 1]);
            an += n[i - 1];
            if (!an || !right_n[i]) continue;
            float cost = box_area(&acc) * an + right_area[i] * right_n[i];
            if (cost < best) { best = cost; best_i = i; }
        }
        if (best_i < 0) {
            mid = first + count / 2;
        } else {
            if (count <= 2 * LEAF_MAX && best >= box_area(bb) * count) return 0;
            uint32_t i = first, j = first + count;
            while (i < j) {
                uint32_t t = ord[i];
                int bi = (int)((c->cent[3 * t + axis] - cb->lo[axis]) * scale);
                if (bi >= BINS) bi = BINS - 1;
                if (bi < best_i) i++;
                else { ord[i] = ord[--j]; ord[j] = t; }
            }
            mid = i;
            if (mid == first || mid == first + count) mid = first + count / 2;
        }
    }
    return mid;
}

jd_result jd_bvh_build(jd_bvh *b, const float *pos, const uint32_t *tri, uint32_t num_tris, jd_error *err)
{
    memset(b, 0, sizeof *b);
    b->pos = pos;
    b->tri = tri;
    b->num_tris = num_tris;
    if (!num_tris) return jd_fail(err, JD_ERR_ARG, "the mesh has no triangles");
    build_ctx c = {b, malloc(sizeof(box) * num_tris), malloc(sizeof(float) * 3 * num_tris)};
    b->order = malloc(sizeof(uint32_t) * num_tris);
    b->nodes = malloc(sizeof(jd_bvh_node) * (2 * (size_t)num_tris));
    if (!c.tbox || !c.cent || !b->order || !b->nodes) {
        free(c.tbox); free(c.cent); jd_bvh_free(b);
        return jd_fail(err, JD_ERR_BUDGET, "out of memory for the BVH of %u triangles", num_tris);
    }
    for (uint32_t t = 0; t < num_tris; t++) {
        box_empty(&c.tbox[t]);
        for (int k = 0; k < 3; k++) box_add(&c.tbox[t], pos + 3 * (size_t)tri[3 * t + k]);
        for (int k = 0; k < 3; k++) c.cent[3 * t + k] = 0.5f * (c.tbox[t].lo[k] + c.tbox[t].hi[k]);
        b->order[t] = t;
    }
    /* Children in pairs: an inner node names the left, the right follows. */
    struct { uint32_t node, first, count; int depth; } stack[MAX_DEPTH + 2];
    int sp = 0;
    b->num_nodes = 1;
    stack[sp].node = 0; stack[sp].first = 0; stack[sp].count = num_tris; stack[sp].depth = 1; sp++;
    while (sp) {
        sp--;
        uint32_t ni = stack[sp].node, first = stack[sp].first, count = stack[sp].count;
        int depth = stack[sp].depth;
        if (depth > b->depth) b->depth = depth;
        box bb, cb;
        range_bounds(&c, first, count, &bb, &cb);
        jd_bvh_node *n = &b->nodes[ni];
        memcpy(n->lo, bb.lo, sizeof n->lo);
        memcpy(n->hi, bb.hi, sizeof n->hi);
        uint32_t mid = depth < MAX_DEPTH ? split_range(&c, first, count, &bb, &cb) : 0;
        if (!mid) { n->first = first; n->count = count; continue; }
        uint32_t left = b->num_nodes, right = b->num_nodes + 1;
        b->num_nodes += 2;
        n->count = 0;
        n->first = left; /* right is left + 1 */
        stack[sp].node = right; stack[sp].first = mid; stack[sp].count = first + count - mid; stack[sp].depth = depth + 1; sp++;
        stack[sp].node = left; stack[sp].first = first; stack[sp].count = mid - first; stack[sp].depth = depth + 1; sp++;
    }
    free(c.tbox);
    free(c.cent);
    return JD_OK;
}

void jd_bvh_free(jd_bvh *b)
{
    free(b->order);
    free(b->nodes);
    b->order = NULL;
    b->nodes = NULL;
}

static int slab_test(const jd_bvh_node *n, const float org[3], const float inv[3], float tmin, float tmax)
{
    for (int k = 0; k < 3; k++) {
        float t0 = (n->lo[k] - org[k]) * inv[k], t1 = (n->hi[k] - org[k]) * inv[k];
        if (t0 > t1) { float s = t0; t0 = t1; t1 = s; }
        if (t0 > tmin) tmin = t0;
        if (t1 < tmax) tmax = t1;
        if (tmin > tmax) return 0;
    }
    return 1;
}

/* Moller-Trumbore, two-sided. */
static int hit_tri(const jd_bvh *b, uint32_t t, const float o[3], const float d[3], float tmin, float tmax,
                   float *tt, float *uu, float *vv)
{
    const float *a = b->pos + 3 * (size_t)b->tri[3 * t], *p1 = b->pos + 3 * (size_t)b->tri[3 * t + 1],
                *p2 = b->pos + 3 * (size_t)b->tri[3 * t + 2];
    float e1[3] = {p1[0] - a[0], p1[1] - a[1], p1[2] - a[2]};
    float e2[3] = {p2[0] - a[0], p2[1] - a[1], p2[2] - a[2]};
    float p[3] = {d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2], d[0] * e2[1] - d[1] * e2[0]};
    float det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (fabsf(det) < 1e-20f) return 0;
    float inv = 1.0f / det;
    float s[3] = {o[0] - a[0], o[1] - a[1], o[2] - a[2]};
    float u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) * inv;
    if (u < 0 || u > 1) return 0;
    float q[3] = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0]};
    float v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) * inv;
    if (v < 0 || u + v > 1) return 0;
    float t_ = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) * inv;
    if (t_ <= tmin || t_ >= tmax) return 0;
    *tt = t_; *uu = u; *vv = v;
    return 1;
}

static int traverse(const jd_bvh *b, const float org[3], const float dir[3], float tmin, float tmax, jd_hit *hit,
                    int any)
{
    float inv[3];
    for (int k = 0; k < 3; k++) inv[k] = 1.0f / (fabsf(dir[k]) > 1e-30f ? dir[k] : copysignf(1e-30f, dir[k]));
    uint32_t stack[MAX_DEPTH * 2 + 4];
    int sp = 0, found = 0;
    uint32_t ni = 0;
    for (;;) {
        const jd_bvh_node *n = &b->nodes[ni];
        if (slab_test(n, org, inv, tmin, tmax)) {
            if (n->count) {
                for (uint32_t i = n->first; i < n->first + n->count; i++) {
                    float t, u, v;
                    if (hit_tri(b, b->order[i], org, dir, tmin, tmax, &t, &u, &v)) {
                        if (any) return 1;
                        tmax = t;
                        hit->tri = b->order[i]; hit->t = t; hit->u = u; hit->v = v;
                        found = 1;
                    }
                }
            } else {
                /* Nearer child first. */
                uint32_t l = n->first, r = n->first + 1;
                const jd_bvh_node *ln = &b->nodes[l], *rn = &b->nodes[r];
                float lc = 0, rc = 0;
                for (int k = 0; k < 3; k++) {
                    lc += (ln->lo[k] + ln->hi[k]) * dir[k];
                    rc += (rn->lo[k] + rn->hi[k]) * dir[k];
                }
                if (lc <= rc) { stack[sp++] = r; ni = l; } else { stack[sp++] = l; ni = r; }
                continue;
            }
        }
        if (!sp) break;
        ni = stack[--sp];
    }
    return found;
}

int jd_bvh_intersect(const jd_bvh *b, const float org[3], const float dir[3], float tmin, float tmax, jd_hit *hit)
{
    return traverse(b, org, dir, tmin, tmax, hit, 0);
}

int jd_bvh_occluded(const jd_bvh *b, const float org[3], const float dir[3], float tmin, float tmax)
{
    jd_hit h;
    return traverse(b, org, dir, tmin, tmax, &h, 1);
}
