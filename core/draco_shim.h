/* The C face of libdraco (which has no C API). The decoder writes a flat
 * record through a callback so it can run in a sandboxed child process and
 * stream its result back through a pipe. */
#ifndef JD_DRACO_SHIM_H
#define JD_DRACO_SHIM_H

#include <stddef.h>
#include <stdint.h>

#include "mesh_arrays.h"

#ifdef __cplusplus
extern "C" {
#endif

#define JD_DRACO_RECORD_MAGIC 0x314d444au /* "JDM1" */
enum { JD_DRACO_HAS_NORMALS = 1, JD_DRACO_HAS_UVS = 2, JD_DRACO_HAS_MATERIAL = 4, JD_DRACO_HAS_MEDIUM = 8,
       JD_DRACO_HAS_COLORS = 16, JD_DRACO_HAS_TEXTURE = 32 };

/* Followed by float pos[3*nv], [float nrm[3*nv]], [float uv[2*nv]],
 * uint32 idx[3*nf], [char material[32], NUL-terminated], [jd_file_medium],
 * [uint8 colour[4*nv]], [uint32 w, h, uint8 texels[4*w*h]]. */
typedef struct jd_draco_record_header {
    uint32_t magic, num_vertices, num_faces, flags;
    uint32_t faces_read; /* the file's triangles, before coarse ones were split (mesh_subdivide.c) */
} jd_draco_record_header;

typedef int (*jd_draco_write_fn)(void *user, const void *data, size_t n);

/* Decodes a mesh (format: a jd_mesh_format; libdraco reads Draco, OBJ, PLY
 * and STL) into heap arrays. Returns 0, or -1 with a reason in err. Never
 * throws: every C++ exception stops at this boundary. */
int jd_draco_read(const void *data, size_t size, int format, uint32_t max_vertices, uint32_t max_faces,
                  jd_mesh_arrays *out, char *err, size_t errlen);
/* A glTF KHR_draco_mesh_compression primitive: its position, normal and
 * texture coordinate attributes by their Draco unique ids (-1: absent). */
int jd_draco_read_ids(const void *data, size_t size, const int ids[3], uint32_t max_vertices, uint32_t max_faces,
                      jd_mesh_arrays *out, char *err, size_t errlen);
/* Writes the mesh as a Draco file (edgebreaker; positions at 14 bits). */
int jd_draco_encode(const jd_mesh_arrays *m, jd_draco_write_fn write, void *user, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif
#endif
