/* How thick the object is under each vertex (mesh_thickness.c). Internal:
 * not installed. */
#ifndef JD_MESH_THICKNESS_H
#define JD_MESH_THICKNESS_H

#include "arena.h"
#include "mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* out[i]: the distance from vertex i along its inward normal to where the
 * ray leaves the mesh (the part's thickness there, in the mesh's units), at
 * most `cap`; `cap` where the ray leaves through nothing (an open mesh).
 * A uniform grid over the triangles, in the arena's top (freed on return):
 * JD_ERR_BUDGET when it does not fit, out untouched. */
jd_result jd_mesh_thickness(const jd_mesh *m, float cap, jd_arena *a, float *out, jd_error *err);

/* The same for a mesh too large for a ray a vertex at set-up, from the
 * thickness cthick already measured at the vertices of a coarser mesh over
 * the same surface (the light map's proxy): each vertex takes the mean of
 * the coarse vertices within `reach` whose normals face its way, weighted
 * by the inverse square of their distance (`cap` where there are none),
 * then the same averaging with its neighbours. JD_ERR_BUDGET when the
 * coarse vertices' grid does not fit, out untouched. */
jd_result jd_mesh_thickness_from(const jd_mesh *m, const jd_mesh *coarse, const float *cthick, float reach, float cap,
                                 jd_arena *a, float *out, jd_error *err);

#ifdef __cplusplus
}
#endif
#endif
