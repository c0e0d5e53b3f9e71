/* glTF 2.0 (.gltf text with data: or neighbouring .bin buffers, .glb
 * binary), read inside the decoder's child process. Internal: not installed. */
#ifndef JD_GLTF_READ_H
#define JD_GLTF_READ_H

#include <stddef.h>
#include <stdint.h>

#include "mesh_arrays.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct jd_gltf_limits {
    uint32_t max_vertices, max_faces; /* of the merged mesh */
    size_t max_buffer_bytes;          /* all external and data: buffers together, and an image's bytes */
    uint32_t max_texture_side;        /* the colour texture's largest side once resampled */
} jd_gltf_limits;

/* Every triangle primitive (triangles, strips, fans; plain or
 * KHR_draco_mesh_compression) of every mesh the default scene reaches,
 * placed by its node transforms, merged into one mesh. Normals and texture
 * coordinates are kept where every primitive has them. A material's
 * extras.jade_material names a jade material (out->material). External
 * buffers are read from beside `path` (relative names without ".."; with
 * path NULL, a glTF read from memory, they are refused); 0, or -1 with a
 * reason in err. */
int jd_gltf_read(const uint8_t *buf, size_t n, const char *path, const jd_gltf_limits *lim, jd_mesh_arrays *out,
                 char *err, size_t errlen);

#ifdef __cplusplus
}
#endif
#endif
