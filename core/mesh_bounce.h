/* Light between parts: what the lit surfaces of one part of the object
 * send across the air to another, where it enters again (a path tracer's
 * paths that leave the object and meet it again; jade reference
 * --bounces 1). Made once at set-up, per vertex, as a transfer over the
 * light's direction that the vertex stage evaluates for any light. */
#ifndef JD_MESH_BOUNCE_H
#define JD_MESH_BOUNCE_H

#include "arena.h"
#include "mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Floats a vertex: (x, y, z, w) with G(l) = max(0, x l.x + y l.y + z l.z + w)
 * the irradiance, per unit of the light's, that the rest of the object
 * sends the vertex where each lit point gives out as much light as falls
 * on it (the renderer multiplies by the albedo there and at the vertex). */
enum { JD_BOUNCE_TERMS = 4 };

/* out: JD_BOUNCE_TERMS per vertex of m, the transfer of the vertex's
 * outer hemisphere with `rays` rays for each of its two steps (at most
 * 256). Scratch in the arena's top. */
jd_result jd_mesh_bounce(const jd_mesh *m, int rays, jd_arena *a, float *out, jd_error *err);

#ifdef __cplusplus
}
#endif
#endif
