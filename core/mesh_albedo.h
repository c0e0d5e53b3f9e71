/* The colour a model's file gives its surface: lookups shared by the
 * renderer's upload and jade reference (the public ones declared in
 * mesh.h). Internal: not installed. */
#ifndef JD_MESH_ALBEDO_H
#define JD_MESH_ALBEDO_H
#include "mesh.h"

/* Texels of a w x h texture per unit of the mesh's surface (its own
 * units), from the areas of its triangles in both spaces: how wide a
 * millimetre is in the texture. 0 without texture coordinates. */
double jd_mesh_texels_per_unit(const jd_mesh *m, uint32_t w, uint32_t h);
#endif
