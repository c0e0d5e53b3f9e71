#include "texture_decode.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>

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
    memset(out, 0, sizeof *out);
    int is_png = n >= 8 && !memcmp(data, png, 8), is_jpeg = n >= 3 && data[0] == 0xff && data[1] == 0xd8 && data[2] == 0xff;
    if (!is_png && !is_jpeg) {
        snprintf(err, errlen, "%s is not a PNG or a JPEG (jade reads colour textures in those two)", what);
        return -1;
    }
    if (n > 0x7fffffffu) {
        snprintf(err, errlen, "%s: %zu bytes, more than a picture jade reads", what, n);
        return -1;
    }
    /* The header first: a picture that declares a size it has no bytes for
     * (a decode bomb) costs nothing to refuse. */
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(data, (int)n, &w, &h, &comp)) {
        /* stb_image refuses a PNG over 2^30 bytes decoded without saying
         * its size: the IHDR chunk says it (width, height, big-endian). */
        if (is_png && n >= 24 && !memcmp(data + 12, "IHDR", 4)) {
            uint32_t pw = (uint32_t)data[16] << 24 | (uint32_t)data[17] << 16 | (uint32_t)data[18] << 8 | data[19];
            uint32_t ph = (uint32_t)data[20] << 24 | (uint32_t)data[21] << 16 | (uint32_t)data[22] << 8 | data[23];
            if (pw > JD_TEXTURE_MAX_SIDE || ph > JD_TEXTURE_MAX_SIDE || (uint64_t)pw * ph > JD_TEXTURE_MAX_PIXELS) {
                snprintf(err, errlen, "%s declares %u x %u pixels, over jade's limit of %u pixels (%d a side); refused",
                         what, pw, ph, JD_TEXTURE_MAX_PIXELS, JD_TEXTURE_MAX_SIDE);
                return -1;
            }
        }
        snprintf(err, errlen, "%s: the %s header does not parse (%s)", what, is_png ? "PNG" : "JPEG",
                 stbi_failure_reason() ? stbi_failure_reason() : "corrupt");
        return -1;
    }
    if (w < 1 || h < 1 || w > JD_TEXTURE_MAX_SIDE || h > JD_TEXTURE_MAX_SIDE ||
        (uint64_t)w * (uint64_t)h > JD_TEXTURE_MAX_PIXELS) {
        snprintf(err, errlen, "%s declares %d x %d pixels, over jade's limit of %u pixels (%d a side); refused", what, w,
                 h, JD_TEXTURE_MAX_PIXELS, JD_TEXTURE_MAX_SIDE);
        return -1;
    }
    int gw = 0, gh = 0, gc = 0;
    uint8_t *px = stbi_load_from_memory(data, (int)n, &gw, &gh, &gc, 4);
    if (!px || gw != w || gh != h) {
        snprintf(err, errlen, "%s: the %s data does not decode (%s)", what, is_png ? "PNG" : "JPEG",
                 px ? "its size changed" : stbi_failure_reason() ? stbi_failure_reason() : "corrupt");
        stbi_image_free(px);
        return -1;
    }
    float lut[256];
    for (int i = 0; i < 256; i++) lut[i] = jd_srgb_to_linear((uint8_t)i);
    uint32_t cap = max_side ? max_side : 1024;
    uint32_t tw = nearest_pot((uint32_t)w, cap), th = nearest_pot((uint32_t)h, cap);
    out->texels = malloc((size_t)tw * th * 4);
    if (!out->texels) {
        stbi_image_free(px);
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    /* Each texel the mean of the source pixels it covers (at least one):
     * a box filter down, nearest up; averaged in linear light. Top row
     * first, as glTF's and OBJ's texture coordinates address it (v = 0 at
     * the top for glTF; the OBJ reader flips its v to match). */
    for (uint32_t y = 0; y < th; y++) {
        uint32_t y0 = (uint32_t)((uint64_t)y * (uint32_t)h / th), y1 = (uint32_t)((uint64_t)(y + 1) * (uint32_t)h / th);
        if (y1 <= y0) y1 = y0 + 1;
        for (uint32_t x = 0; x < tw; x++) {
            uint32_t x0 = (uint32_t)((uint64_t)x * (uint32_t)w / tw), x1 = (uint32_t)((uint64_t)(x + 1) * (uint32_t)w / tw);
            if (x1 <= x0) x1 = x0 + 1;
            double sum[3] = {0, 0, 0};
            for (uint32_t sy = y0; sy < y1; sy++)
                for (uint32_t sx = x0; sx < x1; sx++) {
                    const uint8_t *s = px + 4 * ((size_t)sy * (uint32_t)w + sx);
                    for (int c = 0; c < 3; c++) sum[c] += lut[s[c]];
                }
            double inv = 1.0 / ((double)(x1 - x0) * (y1 - y0));
            uint8_t *o = out->texels + 4 * ((size_t)y * tw + x);
            for (int c = 0; c < 3; c++) o[c] = jd_sqrt_encode((float)(sum[c] * inv) * factor[c]);
            o[3] = 255;
        }
    }
    stbi_image_free(px);
    out->w = tw;
    out->h = th;
    return 0;
}
