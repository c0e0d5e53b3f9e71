/* A decoded mesh as plain heap arrays, inside the decoder's child process:
 * what every format's reader produces, ordered for the GPU and streamed to
 * the parent as one record (see draco_shim.h). Internal: not installed. */
#ifndef JD_MESH_ARRAYS_H
#define JD_MESH_ARRAYS_H

#include <stddef.h>
#include <stdint.h>

#include "mesh_load.h"
#include "texture_decode.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct jd_mesh_arrays {
    uint32_t nv, nf;
    uint32_t nf_read; /* the file's triangles, where splitting made nf more; or 0 */
    float *pos;      /* 3 per vertex */
    float *nrm;      /* 3 per vertex, or NULL */
    float *uv;       /* 2 per vertex, or NULL */
    uint32_t *idx;   /* 3 per face */
    uint8_t *col;    /* 4 per vertex: sqrt of the linear reflectance, texture weight (0 or 255); or NULL */
    jd_texture tex;  /* the colour texture (texels NULL: none) */
    char material[32]; /* a material the file asks for (glTF extras), or "" */
    jd_file_medium medium; /* the medium the file describes (flags 0: none) */
} jd_mesh_arrays;

typedef int (*jd_record_write_fn)(void *user, const void *data, size_t n);

void jd_mesh_arrays_free(jd_mesh_arrays *m);
/* Texture coordinates gone: the record will not carry them. */
void jd_mesh_arrays_drop_uvs(jd_mesh_arrays *m);

/* Triangles in the order a GPU draws best (meshoptimizer's vertex cache,
 * then overdraw order) where built with meshoptimizer; otherwise, or for
 * indices out of range (the parent refuses those), left as they are. */
void jd_mesh_arrays_order(jd_mesh_arrays *m);

/* A mesh of more than `target` triangles (0: none) simplified towards that
 * many where built with meshoptimizer (its vertices those still used, in
 * first-use order); 0, or -1 with msg set (no meshoptimizer, no memory). */
int jd_mesh_arrays_simplify(jd_mesh_arrays *m, uint32_t target, char *msg, size_t cap);

/* Streams the record: header, positions, [normals], [uvs], indices,
 * [material], [medium], [colours], [texture: w, h, texels]. 0, or -1 when the pipe closed. */
int jd_mesh_arrays_emit(const jd_mesh_arrays *m, jd_record_write_fn write, void *user);

#ifdef __cplusplus
}
#endif
#endif
