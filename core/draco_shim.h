/* The C face of libdraco (which has no C API). The decoder writes a flat
 * record through a callback so it can run in a sandboxed child process and
 * stream its result back through a pipe. */
#ifndef JD_DRACO_SHIM_H
#define JD_DRACO_SHIM_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define JD_DRACO_RECORD_MAGIC 0x314d444au /* "JDM1" */
enum { JD_DRACO_HAS_NORMALS = 1, JD_DRACO_HAS_UVS = 2 };

/* Followed by float pos[3*nv], [float nrm[3*nv]], [float uv[2*nv]], uint32 idx[3*nf]. */
typedef struct jd_draco_record_header {
    uint32_t magic, num_vertices, num_faces, flags;
} jd_draco_record_header;

typedef int (*jd_draco_write_fn)(void *user, const void *data, size_t n);

/* Decodes a mesh (format: a jd_mesh_format; libdraco reads Draco, OBJ, PLY
 * and STL) and streams it out, its triangles in the order a GPU
 * draws best unless keep_order (where built with meshoptimizer). Returns 0,
 * or -1 with a reason in err. Never throws: every C++ exception stops at
 * this boundary. */
int jd_draco_decode(const void *data, size_t size, int format, uint32_t max_vertices, uint32_t max_faces,
                    int keep_order, jd_draco_write_fn write, void *user, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif
#endif
