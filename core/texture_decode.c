#include "texture_decode.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "picture_decode.h"

float jd_srgb_to_linear(uint8_t v)
{
    float c = v / 255.0f;
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

uint8_t jd_sqrt_encode(float linear)
{
    float s = linear > 0.0f ? sqrtf(linear < 1.0f ? linear : 1.0f) : 0.0f;
    return (uint8_t)(s * 255.0f + 0.5f);
}

/* The power of two nearest to n (in ratio), at most cap. */
static uint32_t nearest_pot(uint32_t n, uint32_t cap)
{
    uint32_t p = 1;
    while (p < n) p <<= 1;
    if (p > n && (double)p / n > (double)n / (p >> 1)) p >>= 1;
    while (p > cap) p >>= 1;
    return p ? p : 1;
}

int jd_texture_decode(const uint8_t *data, size_t n, const float factor[3], uint32_t max_side, const char *what,
                      jd_texture *out, char *err, size_t errlen)
{
    static const uint8_t png[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const jd_picture_limits lim = {JD_TEXTURE_MAX_SIDE, JD_TEXTURE_MAX_PIXELS};
    memset(out, 0, sizeof *out);
    int is_png = n >= 8 && !memcmp(data, png, 8), is_jpeg = n >= 3 && data[0] == 0xff && data[1] == 0xd8 && data[2] == 0xff;
    if (!is_png && !is_jpeg) {
        snprintf(err, errlen, "%s is not a PNG or a JPEG (jade reads colour textures in those two)", what);
        return -1;
    }
    uint8_t *px = NULL;
    uint32_t w = 0, h = 0;
    char why[256];
    int rc = is_png ? jd_png_decode(data, n, 4, &lim, &px, &w, &h, why, sizeof why)
                    : jd_jpeg_decode(data, n, 4, &lim, &px, &w, &h, why, sizeof why);
    if (rc != 0) {
        snprintf(err, errlen, "%s: %s", what, why);
        return -1;
    }
    float lut[256];
    for (int i = 0; i < 256; i++) lut[i] = jd_srgb_to_linear((uint8_t)i);
    uint32_t cap = max_side ? max_side : 1024;
    uint32_t tw = nearest_pot(w, cap), th = nearest_pot(h, cap);
    out->texels = malloc((size_t)tw * th * 4);
    if (!out->texels) {
        free(px);
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    /* Each texel the mean of the source pixels it covers (at least one):
     * a box filter down, nearest up; averaged in linear light. Top row
     * first, as glTF's and OBJ's texture coordinates address it (v = 0 at
     * the top for glTF; the OBJ reader flips its v to match). */
    for (uint32_t y = 0; y < th; y++) {
        uint32_t y0 = (uint32_t)((uint64_t)y * h / th), y1 = (uint32_t)((uint64_t)(y + 1) * h / th);
        if (y1 <= y0) y1 = y0 + 1;
        for (uint32_t x = 0; x < tw; x++) {
            uint32_t x0 = (uint32_t)((uint64_t)x * w / tw), x1 = (uint32_t)((uint64_t)(x + 1) * w / tw);
            if (x1 <= x0) x1 = x0 + 1;
            double sum[3] = {0, 0, 0};
            for (uint32_t sy = y0; sy < y1; sy++)
                for (uint32_t sx = x0; sx < x1; sx++) {
                    const uint8_t *s = px + 4 * ((size_t)sy * w + sx);
                    for (int c = 0; c < 3; c++) sum[c] += lut[s[c]];
                }
            double inv = 1.0 / ((double)(x1 - x0) * (y1 - y0));
            uint8_t *o = out->texels + 4 * ((size_t)y * tw + x);
            for (int c = 0; c < 3; c++) o[c] = jd_sqrt_encode((float)(sum[c] * inv) * factor[c]);
            o[3] = 255;
        }
    }
    free(px);
    out->w = tw;
    out->h = th;
    return 0;
}
