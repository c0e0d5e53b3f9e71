/* The cosine-distributed ray fan (ray_fan.h). */
#include "ray_fan.h"

#include <math.h>

void jd_hemisphere_frame(const float n[3], float t[3], float b[3])
{
    float a[3] = {fabsf(n[0]) < 0.9f ? 1.0f : 0.0f, fabsf(n[0]) < 0.9f ? 0.0f : 1.0f, 0.0f};
    t[0] = a[1] * n[2] - a[2] * n[1], t[1] = a[2] * n[0] - a[0] * n[2], t[2] = a[0] * n[1] - a[1] * n[0];
    float l = sqrtf(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    if (l > 0) { t[0] /= l; t[1] /= l; t[2] /= l; } else { t[0] = 0; t[1] = 0; t[2] = 1; }
    b[0] = n[1] * t[2] - n[2] * t[1], b[1] = n[2] * t[0] - n[0] * t[2], b[2] = n[0] * t[1] - n[1] * t[0];
}

float jd_cosine_ray(const float n[3], const float t[3], const float b[3], int k, int count, float turn, float d[3])
{
    float u1 = ((float)k + 0.5f) / (float)count, u2 = fmodf((float)k * 0.618034f + turn, 1.0f);
    float rr = sqrtf(u1), ph = 6.2831853f * u2, cz = sqrtf(1.0f - u1);
    for (int i = 0; i < 3; i++) d[i] = (t[i] * cosf(ph) + b[i] * sinf(ph)) * rr + n[i] * cz;
    return cz;
}
