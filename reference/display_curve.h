/* jade's display encoding, both ways, as its shader writes it (shade.frag):
 * a shoulder c / (1 + 0.15 c), then gamma 2 (a sqrt), in 8 bits. */
#ifndef JD_DISPLAY_CURVE_H
#define JD_DISPLAY_CURVE_H
#include <stdint.h>
uint8_t jd_display_encode(float linear);
/* Back to linear light; the top code values, where the shoulder's inverse
 * grows without bound, are held at t = 0.999. */
float jd_display_to_linear(unsigned char v);
/* An encoded RGB pixel's luminance (Rec. 709 weights) in linear light. */
double jd_display_luminance(const unsigned char rgb[3]);
/* The linear value whose shoulder is t (0 <= t < 1/0.15). */
float jd_shoulder_inverse(double t);
#endif
