/* A model's colour texture (PNG or JPEG), decoded inside the loader's child
 * process and handed to the parent as pixels. Internal: not installed. */
#ifndef JD_TEXTURE_DECODE_H
#define JD_TEXTURE_DECODE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The largest picture jade decodes: a side and a pixel count (16.7 M pixels
 * take 64 MiB as RGBA8 while they are resampled). */
#define JD_TEXTURE_MAX_SIDE 16384
#define JD_TEXTURE_MAX_PIXELS (4096u * 4096u)

typedef struct jd_texture {
    uint32_t w, h;   /* powers of two */
    uint8_t *texels; /* w * h RGBA: sqrt of the linear reflectance in rgb, 255 in a (malloc'd) */
} jd_texture;

/* Decodes `data` (PNG or JPEG by content; anything else is refused), after
 * its header's size has been checked against the limits above, into linear
 * reflectance times `factor` (glTF's baseColorFactor, MTL's Kd), resampled
 * to the nearest powers of two of at most max_side a side (GLES 2.0 repeats
 * and mipmaps only those), and stored as sqrt(linear) in 8 bits: the dark
 * colours keep their steps. 0, or -1 with a reason in err (`what` names the
 * picture). */
int jd_texture_decode(const uint8_t *data, size_t n, const float factor[3], uint32_t max_side, const char *what,
                      jd_texture *out, char *err, size_t errlen);

/* sRGB-encoded 8-bit value to linear, and linear to jade's sqrt encoding. */
float jd_srgb_to_linear(uint8_t v);
uint8_t jd_sqrt_encode(float linear);

#ifdef __cplusplus
}
#endif
#endif
