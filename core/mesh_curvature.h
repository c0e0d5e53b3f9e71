/* How curved the surface is at each vertex (mesh_curvature.c). Internal:
 * not installed. */
#ifndef JD_MESH_CURVATURE_H
#define JD_MESH_CURVATURE_H

#include "arena.h"
#include "mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* out[i]: an estimate of the larger principal curvature at vertex i, in the
 * mesh's units^-1, 0 where the surface is flat or bends only inwards
 * (concave both ways). From the normal curvature along each edge of the
 * vertex's triangles, (n_i - n_j).(p_i - p_j) / |p_i - p_j|^2 (positive
 * where the surface bends away from its normal's side, as a sphere's
 * outside): their mean H plus sqrt(2) times their spread, which for edges
 * spread evenly round the vertex is H + (k1 - k2) / 2 = k1 (a tube's
 * 1 / r, where the mean alone gives half of it). Then averaged once with
 * the neighbours. Scratch in the arena's top: JD_ERR_BUDGET when it does
 * not fit, out untouched. */
jd_result jd_mesh_curvature(const jd_mesh *m, jd_arena *a, float *out, jd_error *err);

#ifdef __cplusplus
}
#endif
#endif
