#include "vmath.h"

#include <math.h>

jd_vec3 jd_v3(float x, float y, float z) { jd_vec3 v = {x, y, z}; return v; }
jd_vec3 jd_v3_add(jd_vec3 a, jd_vec3 b) { return jd_v3(a.x + b.x, a.y + b.y, a.z + b.z); }
jd_vec3 jd_v3_sub(jd_vec3 a, jd_vec3 b) { return jd_v3(a.x - b.x, a.y - b.y, a.z - b.z); }
jd_vec3 jd_v3_scale(jd_vec3 a, float s) { return jd_v3(a.x * s, a.y * s, a.z * s); }
float jd_v3_dot(jd_vec3 a, jd_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
jd_vec3 jd_v3_cross(jd_vec3 a, jd_vec3 b)
{
    return jd_v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
float jd_v3_len(jd_vec3 a) { return sqrtf(jd_v3_dot(a, a)); }
jd_vec3 jd_v3_norm(jd_vec3 a)
{
    float l = jd_v3_len(a);
    return l > 0.0f ? jd_v3_scale(a, 1.0f / l) : jd_v3(0, 0, 1);
}

jd_vec3 jd_v3_from_angles(float azimuth_deg, float elevation_deg)
{
    const float d2r = 3.14159265358979f / 180.0f;
    float az = azimuth_deg * d2r, el = elevation_deg * d2r;
    return jd_v3(cosf(el) * sinf(az), sinf(el), cosf(el) * cosf(az));
}

jd_mat4 jd_m4_identity(void)
{
    jd_mat4 r = {{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}};
    return r;
}

jd_mat4 jd_m4_mul(jd_mat4 a, jd_mat4 b)
{
    jd_mat4 r;
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++) {
            float s = 0;
            for (int k = 0; k < 4; k++)
                s += a.m[k * 4 + row] * b.m[c * 4 + k];
            r.m[c * 4 + row] = s;
        }
    return r;
}

jd_mat4 jd_m4_look_at(jd_vec3 eye, jd_vec3 target, jd_vec3 up)
{
    jd_vec3 f = jd_v3_norm(jd_v3_sub(target, eye));
    if (fabsf(jd_v3_dot(f, jd_v3_norm(up))) > 0.999f)
        up = fabsf(f.y) < 0.9f ? jd_v3(0, 1, 0) : jd_v3(1, 0, 0);
    jd_vec3 s = jd_v3_norm(jd_v3_cross(f, up));
    jd_vec3 u = jd_v3_cross(s, f);
    jd_mat4 r = jd_m4_identity();
    r.m[0] = s.x; r.m[4] = s.y; r.m[8] = s.z;
    r.m[1] = u.x; r.m[5] = u.y; r.m[9] = u.z;
    r.m[2] = -f.x; r.m[6] = -f.y; r.m[10] = -f.z;
    r.m[12] = -jd_v3_dot(s, eye);
    r.m[13] = -jd_v3_dot(u, eye);
    r.m[14] = jd_v3_dot(f, eye);
    return r;
}

jd_mat4 jd_m4_perspective(float fovy_deg, float aspect, float n, float f)
{
    float t = 1.0f / tanf(fovy_deg * 3.14159265358979f / 360.0f);
    jd_mat4 r = {{0}};
    r.m[0] = t / aspect;
    r.m[5] = t;
    r.m[10] = (f + n) / (n - f);
    r.m[11] = -1.0f;
    r.m[14] = 2.0f * f * n / (n - f);
    return r;
}

jd_mat4 jd_m4_ortho(float l, float r, float b, float t, float n, float f)
{
    jd_mat4 m = jd_m4_identity();
    m.m[0] = 2.0f / (r - l);
    m.m[5] = 2.0f / (t - b);
    m.m[10] = -2.0f / (f - n);
    m.m[12] = -(r + l) / (r - l);
    m.m[13] = -(t + b) / (t - b);
    m.m[14] = -(f + n) / (f - n);
    return m;
}

jd_vec3 jd_m4_point(jd_mat4 m, jd_vec3 p)
{
    float x = m.m[0] * p.x + m.m[4] * p.y + m.m[8] * p.z + m.m[12];
    float y = m.m[1] * p.x + m.m[5] * p.y + m.m[9] * p.z + m.m[13];
    float z = m.m[2] * p.x + m.m[6] * p.y + m.m[10] * p.z + m.m[14];
    float w = m.m[3] * p.x + m.m[7] * p.y + m.m[11] * p.z + m.m[15];
    if (w != 0.0f && w != 1.0f) { x /= w; y /= w; z /= w; }
    return jd_v3(x, y, z);
}
