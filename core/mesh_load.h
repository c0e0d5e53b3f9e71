/* Loading a mesh (Draco, glTF, OBJ, PLY or STL, told apart by content) from a file
 * that may be corrupt or hostile. */
#ifndef JD_MESH_LOAD_H
#define JD_MESH_LOAD_H

#include <stddef.h>
#include <stdint.h>
#include "mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Zero fields take the defaults in brackets. */
typedef struct jd_load_desc {
    const char *path;           /* the file; with data, only the name used in messages ["the mesh in memory"] */
    const void *data;           /* or the file's bytes, from the caller's own asset system: a glTF
                                   read from memory must carry its buffers (GLB or data: URIs) */
    size_t size;                /* bytes at data */
    size_t max_file_bytes;      /* [64 MiB] */
    uint32_t max_vertices;      /* [4,000,000] */
    uint32_t max_faces;         /* [4,000,000] */
    int timeout_ms;             /* [jd_load_default_timeout_ms] wall time for the whole decode */
    size_t decode_memory_bytes; /* [192 MiB, and 160 bytes a triangle more where simplify_to asks for
                                   fewer than the file may hold] address space the decoder may add */
    int allow_32bit_indices;    /* the GL device has OES_element_index_uint */
    int keep_face_order;        /* [0: triangles longer than a twelfth of the mesh split, and reordered for the
                                   GPU's vertex cache and overdraw] 1: the file's triangles as they are */
    int keep_uvs;               /* [0: texture coordinates are dropped in the decoder unless a colour
                                   texture needs them] 1: jd_mesh.uvs has them (jade convert keeps them) */
    int max_texture_size;       /* [1024, JD_TEXTURE_MEDIUMP_SIDE] a colour texture's largest side once
                                   resampled (a power of two) */
    int format;                 /* set by the loader: the jd_mesh_format found in the file */
    uint32_t simplify_to;       /* [0: the file's triangles] a mesh of more is simplified towards this many
                                   (meshoptimizer's edge collapses, at most 2% of its extent; a build
                                   without meshoptimizer refuses it): a scan of a million triangles is
                                   bound by a Mali-400's vertex processor, 78 ms a frame */
} jd_load_desc;

/* The largest colour texture the renderer draws: its texture coordinates
 * are mediump in the fragment stage, 11 significant bits where that is fp16,
 * half a texel of a 1024-texel side. */
#define JD_TEXTURE_MEDIUMP_SIDE 1024

/* A scattering medium the file describes (glTF's KHR_materials_volume,
 * KHR_materials_volume_scatter, KHR_materials_ior), in jade's terms: per
 * channel, reduced scattering and absorption in mm^-1 of the file's own
 * units (glTF's are metres: 1 unit = 1000 mm), and the refractive index. */
enum { JD_MEDIUM_SIGMA = 1, JD_MEDIUM_ETA = 2, JD_MEDIUM_NOTE = 4 /* only `ignored` to say */ };
typedef struct jd_file_medium {
    uint32_t flags;            /* JD_MEDIUM_*: which fields the file gave */
    float sigma_s[3];          /* reduced scattering sigma_s (1 - g) */
    float sigma_a[3];
    float eta;
    float mm_per_unit;         /* the file's unit in millimetres (glTF: 1000) */
    char source[64];           /* the extensions it came from, e.g. "KHR_materials_volume_scatter" */
    char ignored[256];         /* what jade cannot show of the material, or "" */
} jd_file_medium;

typedef struct jd_load_stats {
    double decode_ms;   /* fork to last byte received */
    size_t file_bytes;
    uint32_t declared_faces; /* the file's triangles as read, before coarse ones were split (its header's
                                count where loading stopped before decoding) */
    int format;         /* jd_mesh_format: Draco, glTF, OBJ, PLY or STL, by content */
    char material[32];  /* a jade material the file names (glTF extras.jade_material), or "" */
    jd_file_medium medium; /* flags 0 when the file describes none */
    int coloured;       /* the file gives the surface colours (jd_mesh.colors) */
    float albedo_mean[3]; /* their mean reflectance, as jd_mesh.albedo_mean */
    uint32_t texture_w, texture_h; /* its colour texture as decoded, or 0 */
} jd_load_stats;

/* Reads desc->path, or desc->size bytes at desc->data (copied into the
 * arena first: the caller's buffer is never written and may go once this
 * returns). libdraco runs in a child process under an address-space and CPU limit and a
 * wall-clock deadline; its output streams back through a pipe straight into
 * the arena, and is validated (indices, finite positions) before anyone sees
 * it. Call before creating threads (a GL context): the child forks. */
jd_result jd_mesh_load_draco(const jd_load_desc *desc, jd_arena *a, jd_mesh *out,
                             jd_load_stats *stats, jd_error *err);

/* The deadline a decode gets where jd_load_desc.timeout_ms is 0, in ms:
 * 1500, and 1000 more per MiB of the file and 5 per thousand triangles its
 * header declares (time that grows with the work, as on a board's slower
 * cores it must), at most 600,000. */
int jd_load_default_timeout_ms(size_t file_bytes, uint32_t declared_faces);

#ifdef __cplusplus
}
#endif

#endif
