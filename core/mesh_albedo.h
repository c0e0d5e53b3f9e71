/* The colour a model's file gives its surface: lookups shared by the
 * renderer's upload and jade reference (declared in mesh.h). */
#ifndef JD_MESH_ALBEDO_H
#define JD_MESH_ALBEDO_H
#include "mesh.h"
#endif
