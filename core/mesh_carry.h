/* Values made at the vertices of a coarse mesh (the light map's proxy)
 * carried to the vertices of the mesh it stands for, where making them
 * at every vertex would cost seconds at set-up. */
#ifndef JD_MESH_CARRY_H
#define JD_MESH_CARRY_H

#include "arena.h"
#include "mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* out[n i + k] for each vertex i of m: the mean of cvals[n j + k] over the
 * coarse vertices j within reach whose normals face i's way (a thin part's
 * two sides stay apart), weighted by the inverse square of their distance;
 * none where there are none. Scratch in the arena's top. */
jd_result jd_mesh_carry(const jd_mesh *m, const jd_mesh *coarse, const float *cvals, int n, float reach, float none,
                        jd_arena *a, float *out, jd_error *err);

/* Each vertex's n values averaged with its triangles' other corners (a
 * corner shared by k triangles counted k times), `passes` times: a
 * neighbourhood's mean in place of what one vertex's rays or its own
 * detail made. Scratch in the arena's top; skipped where it does not fit. */
void jd_mesh_smooth(const jd_mesh *m, float *vals, int n, int passes, jd_arena *a);

#ifdef __cplusplus
}
#endif
#endif
