/* The colour an OBJ's material library gives it (MTL's Kd and map_Kd),
 * read inside the loader's child process. Internal: not installed. */
#ifndef JD_OBJ_MATERIAL_H
#define JD_OBJ_MATERIAL_H

#include <stddef.h>
#include <stdint.h>

#include "mesh_arrays.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Reads the MTL named by the OBJ's first `mtllib` from beside obj_path (a
 * plain relative name, as glTF buffers are), takes the material of the
 * first `usemtl` (or its first), and gives every vertex of m its colour:
 * map_Kd's texture where the mesh has texture coordinates (v turned to
 * count from the top, as the texture is stored), else Kd. Nothing when the
 * OBJ names no library; a library that cannot be read is said in
 * m->medium.ignored, not refused (the shape stands without it); a texture
 * that is hostile or broken is refused. 0, or -1 with a reason in err. */
int jd_obj_material(const uint8_t *obj, size_t n, const char *obj_path, uint32_t max_side, size_t max_bytes,
                    jd_mesh_arrays *m, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif
#endif
