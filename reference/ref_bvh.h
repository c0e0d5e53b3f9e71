/* A bounding volume hierarchy over a triangle mesh, for the reference
 * renderer's camera and shadow rays. Built once; queries are read-only and
 * safe from many threads. */
#ifndef JD_REF_BVH_H
#define JD_REF_BVH_H

#include <stdint.h>
#include "jd_result.h"

typedef struct jd_bvh_node {
    float lo[3], hi[3];
    uint32_t first;  /* leaf: first triangle in order[]; inner: left child (right is first + 1) */
    uint32_t count;  /* triangles in a leaf, 0 for an inner node */
} jd_bvh_node;

typedef struct jd_bvh {
    const float *pos;        /* 3 per vertex */
    const uint32_t *tri;     /* 3 per triangle */
    uint32_t num_tris;
    uint32_t *order;         /* triangle indices, leaves' ranges */
    jd_bvh_node *nodes;
    uint32_t num_nodes;
    int depth;
} jd_bvh;

typedef struct jd_hit {
    uint32_t tri;
    float t, u, v;           /* p = (1-u-v) a + u b + v c */
} jd_hit;

/* pos and tri must outlive the BVH. */
jd_result jd_bvh_build(jd_bvh *b, const float *pos, const uint32_t *tri, uint32_t num_tris, jd_error *err);
void jd_bvh_free(jd_bvh *b);
/* Nearest hit with t in (tmin, tmax); 0 when there is none. */
int jd_bvh_intersect(const jd_bvh *b, const float org[3], const float dir[3], float tmin, float tmax, jd_hit *hit);
/* Any hit with t in (tmin, tmax). */
int jd_bvh_occluded(const jd_bvh *b, const float org[3], const float dir[3], float tmin, float tmax);

#endif
