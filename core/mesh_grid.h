/* A uniform grid over a mesh's triangles and the nearest hit of a ray
 * through it (Amanatides and Woo 1987), made at set-up for what the
 * renderer measures on its meshes once: a part's thickness under each
 * vertex (mesh_thickness.c) and the light one part sends another
 * (mesh_bounce.c). Counted, then filled, in the arena's top. */
#ifndef JD_MESH_GRID_H
#define JD_MESH_GRID_H

#include "arena.h"
#include "mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct jd_mesh_grid {
    int n;              /* cells per axis */
    float lo[3], size;  /* the grid's corner and its cell's size */
    uint32_t *start;    /* n^3 + 1: each cell's first entry in items */
    uint32_t *items;    /* triangles (jd_mesh_grid_triangles) or vertices (jd_mesh_grid_vertices) */
} jd_mesh_grid;

/* Where a ray met the mesh: its parameter, the triangle and the hit's
 * barycentric weights of the triangle's second and third corners. */
typedef struct jd_mesh_hit {
    float t, u, v;
    uint32_t tri;
} jd_mesh_hit;

int jd_mesh_grid_cell(const jd_mesh_grid *g, float x, int axis);
size_t jd_mesh_grid_index(const jd_mesh_grid *g, int x, int y, int z);

/* The triangles of m in about one cell each, at most 64 a side; what: the
 * arena's label. In the arena's top (jd_arena_top_reset frees it). */
jd_result jd_mesh_grid_triangles(const jd_mesh *m, jd_mesh_grid *g, jd_arena *a, const char *what, jd_error *err);

/* The vertices of m in cells at least reach wide (a point's neighbours
 * within reach lie in its cell and the 26 round it), at most 64 a side
 * and about a vertex a cell. In the arena's top. */
jd_result jd_mesh_grid_vertices(const jd_mesh *m, float reach, jd_mesh_grid *g, jd_arena *a, const char *what,
                                jd_error *err);

/* The nearest hit past eps along o + t d (d of unit length) of the
 * triangles in g, at most cap: its parameter (cap where none), and where
 * hit is not NULL the triangle and the point on it (tri UINT32_MAX: none). */
float jd_mesh_grid_cast(const jd_mesh *m, const jd_mesh_grid *g, const float o[3], const float d[3], float eps,
                        float cap, jd_mesh_hit *hit);

/* Whether any triangle in g lies along o + t d between eps and cap (the
 * first found ends the walk: a shadow ray's question). */
int jd_mesh_grid_blocked(const jd_mesh *m, const jd_mesh_grid *g, const float o[3], const float d[3], float eps,
                         float cap);

#ifdef __cplusplus
}
#endif
#endif
