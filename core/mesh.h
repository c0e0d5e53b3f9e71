/* A triangle mesh as the renderer consumes it, living in the arena. */
#ifndef JD_MESH_H
#define JD_MESH_H

#include <stdint.h>
#include "arena.h"
#include "vmath.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct jd_mesh {
    uint32_t num_vertices;
    uint32_t num_indices;   /* 3 per triangle */
    float *positions;       /* 3 per vertex */
    float *normals;         /* 3 per vertex, unit length, to the side the triangles face (counter-
                             * clockwise seen from it, GL's front): jade draws the front faces and
                             * lights the side the normals give (jd_mesh_normals_follow_winding) */
    float *uvs;             /* 2 per vertex, or NULL */
    void *indices;          /* uint16_t when index_size == 2, else uint32_t */
    int index_size;
    int normals_computed;   /* the file had none */
    /* The surface's colour as its file gives it (glTF's base colour, an
     * OBJ's Kd and map_Kd, PLY's vertex colours), read as the diffuse
     * reflectance; colors NULL: none, the material's alone. */
    uint8_t *colors;        /* 4 per vertex: sqrt of the linear reflectance in rgb, the texture's weight in a */
    uint8_t *texels;        /* texture_w x texture_h RGBA, sqrt of the linear reflectance, top row first; or NULL */
    uint32_t texture_w, texture_h; /* powers of two */
    float albedo_mean[3];   /* the reflectance's mean over the surface, by area (jd_mesh_albedo_prepare) */
    jd_vec3 bmin, bmax;
} jd_mesh;

uint32_t jd_mesh_index(const jd_mesh *m, uint32_t i);

/* Every index in range and every position finite and within +-1e6. */
jd_result jd_mesh_validate(const jd_mesh *m, const char *name, jd_error *err);
/* A file's normals or texture coordinates with a NaN or an infinity are
 * refused, not repaired: the file is broken and should be said to be. */
jd_result jd_mesh_check_finite(const float *v, uint32_t num_vertices, int comps, const char *what, const char *name,
                               jd_error *err);
void jd_mesh_compute_bounds(jd_mesh *m);
/* Where the renderer puts a mesh: its box centre at the origin and its half
 * box diagonal as the unit of length, world = (p - centre) / radius. */
void jd_mesh_placement(const jd_mesh *m, jd_vec3 *centre, float *radius);
/* Area-weighted vertex normals; degenerate vertices get +Z. */
void jd_mesh_compute_normals(jd_mesh *m);
/* n at unit length; (0, 0, 1) for one of no (or no finite) length. */
jd_vec3 jd_unit_normal(const float n[3]);
/* Normalises normals read from a file; zero or non-finite ones are recomputed. */
void jd_mesh_fix_normals(jd_mesh *m);
/* Turns a mesh wound inside out (its enclosed volume negative by more than
 * 1% of its box: open sheets are left alone) the right way round, so back
 * faces are culled and the light enters from outside. Returns 1 if it did.
 * Call before the normals are computed from the winding. */
int jd_mesh_orient_outward(jd_mesh *m);
/* Points the normals the way the winding faces, where most of them point
 * against it (a file whose normals and faces disagree). Returns 1 if it did. */
int jd_mesh_normals_follow_winding(jd_mesh *m);

/* Copies 32-bit indices into the mesh, narrowing to 16 bits when every vertex
 * fits; otherwise keeps 32 bits if allow_32 (the caller checked
 * OES_element_index_uint), else fails. */
jd_result jd_mesh_set_indices(jd_mesh *m, const uint32_t *idx, uint32_t count, int allow_32,
                              jd_arena *a, jd_error *err);

/* After loading a mesh with colours: texture coordinates moved by whole
 * tiles next to [0, 1) (under mediump a coordinate of 7.5 keeps fewer
 * bits than one of 0.5) and albedo_mean found. */
void jd_mesh_albedo_prepare(jd_mesh *m);
/* The linear reflectance the colours give at a point of triangle `tri`
 * (barycentrics u, v of its second and third vertex): the vertex colours
 * interpolated, times the texture (bilinear, repeating) where it applies;
 * 1 where the mesh has no colours. */
void jd_mesh_albedo_at(const jd_mesh *m, uint32_t tri, float u, float v, float out[3]);

/* A coarse stand-in made by vertex clustering on a grid of `cells` per axis,
 * for passes whose output is low-resolution or blurred anyway (cube capture,
 * light depth, the spread funnel): up to two clusters a cell, the vertices
 * facing with the cell's first one and those facing away (the two sides of
 * a part thinner than a cell). 16-bit indices always. */
jd_result jd_mesh_build_proxy(const jd_mesh *src, int cells, jd_arena *a, jd_mesh *out,
                              jd_error *err);

#ifdef __cplusplus
}
#endif

#endif
