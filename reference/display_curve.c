#include "display_curve.h"

#include <math.h>

uint8_t jd_display_encode(float c)
{
    if (!(c > 0)) return 0;
    float y = c / (1.0f + 0.15f * c);
    if (y > 1) y = 1;
    return (uint8_t)(sqrtf(y) * 255.0f + 0.5f);
}

float jd_shoulder_inverse(double t) { return (float)(t / (1.0 - 0.15 * t)); }

float jd_display_to_linear(unsigned char v)
{
    double d = v / 255.0, t = d * d;
    return jd_shoulder_inverse(t > 0.999 ? 0.999 : t);
}

double jd_display_luminance(const unsigned char rgb[3])
{
    return 0.2126 * jd_display_to_linear(rgb[0]) + 0.7152 * jd_display_to_linear(rgb[1]) +
           0.0722 * jd_display_to_linear(rgb[2]);
}
