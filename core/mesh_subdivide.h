/* Coarse meshes split where they are coarse (mesh_subdivide.c), in the
 * decoder's child. Internal: not installed. */
#ifndef JD_MESH_SUBDIVIDE_H
#define JD_MESH_SUBDIVIDE_H

#include <stdint.h>

#include "mesh_arrays.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Halves every edge longer than a twelfth of the mesh's box diagonal,
 * pass after pass, without cracks, within max_vertices and max_faces (and
 * 65,536 vertices, 131,072 triangles: a mesh already past them is left as
 * it is). Positions, normals, texture coordinates and colours are
 * interpolated. 0, or -1 out of memory (the mesh as the last pass left
 * it, whole). */
int jd_mesh_arrays_subdivide(jd_mesh_arrays *m, uint32_t max_vertices, uint32_t max_faces);

#ifdef __cplusplus
}
#endif
#endif
