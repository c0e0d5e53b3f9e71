/* A fan of rays over a hemisphere, for what the renderer and the reference
 * trace once (not in a frame). Not installed: jade's own. */
#ifndef JD_RAY_FAN_H
#define JD_RAY_FAN_H

#ifdef __cplusplus
extern "C" {
#endif

/* A fan of rays over the hemisphere round the unit normal n,
 * cosine-distributed: a golden-angle spiral turned by `turn` (0..1, a hash
 * of the point, so that neighbours' fans differ). jd_hemisphere_frame
 * gives t and b, unit and at right angles to n and each other; ray k of
 * count is then jd_cosine_ray's d, which returns its cosine to n. jade
 * reference's light between parts and core's (mesh_bounce.c) both cast it. */
void jd_hemisphere_frame(const float n[3], float t[3], float b[3]);
float jd_cosine_ray(const float n[3], const float t[3], const float b[3], int k, int count, float turn, float d[3]);

#ifdef __cplusplus
}
#endif
#endif
