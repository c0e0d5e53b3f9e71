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

#ifdef __cplusplus
}
#endif
#endif
