/* Small vector and matrix helpers. Matrices are column-major, as GL expects. */
#ifndef JD_VMATH_H
#define JD_VMATH_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct jd_vec3 { float x, y, z; } jd_vec3;
typedef struct jd_mat4 { float m[16]; } jd_mat4;

jd_vec3 jd_v3(float x, float y, float z);
jd_vec3 jd_v3_add(jd_vec3 a, jd_vec3 b);
jd_vec3 jd_v3_sub(jd_vec3 a, jd_vec3 b);
jd_vec3 jd_v3_scale(jd_vec3 a, float s);
float jd_v3_dot(jd_vec3 a, jd_vec3 b);
jd_vec3 jd_v3_cross(jd_vec3 a, jd_vec3 b);
float jd_v3_len(jd_vec3 a);
jd_vec3 jd_v3_norm(jd_vec3 a);
/* Unit vector from azimuth (about +Y, from +Z towards +X) and elevation, in degrees. */
jd_vec3 jd_v3_from_angles(float azimuth_deg, float elevation_deg);

jd_mat4 jd_m4_identity(void);
jd_mat4 jd_m4_mul(jd_mat4 a, jd_mat4 b);
jd_mat4 jd_m4_look_at(jd_vec3 eye, jd_vec3 target, jd_vec3 up);
jd_mat4 jd_m4_perspective(float fovy_deg, float aspect, float znear, float zfar);
jd_mat4 jd_m4_ortho(float l, float r, float b, float t, float n, float f);
jd_vec3 jd_m4_point(jd_mat4 m, jd_vec3 p); /* with perspective divide */

#ifdef __cplusplus
}
#endif

#endif
