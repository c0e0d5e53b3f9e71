/* Which mesh format a file holds, by its content (not its name), and the
 * sizes it declares before anything decodes it. */
#ifndef JD_MESH_FORMAT_H
#define JD_MESH_FORMAT_H

#include <stddef.h>
#include <stdint.h>

#include "jd_result.h"

typedef enum jd_mesh_format {
    JD_FORMAT_UNKNOWN = 0,
    JD_FORMAT_DRACO,
    JD_FORMAT_OBJ,
    JD_FORMAT_PLY,
    JD_FORMAT_STL,
    JD_FORMAT_GLTF /* .gltf text or .glb binary */
} jd_mesh_format;

const char *jd_mesh_format_name(jd_mesh_format f);

/* The format, and the faces and vertices it declares (0 where the format
 * declares none: OBJ, ASCII STL). Refuses what is none of them, a PLY header
 * that does not end or a binary STL whose size contradicts its count. */
jd_result jd_mesh_peek(const uint8_t *buf, size_t n, const char *name, jd_mesh_format *format, uint32_t *faces,
                       uint32_t *vertices, jd_error *err);

#endif
