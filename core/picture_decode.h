/* PNG and JPEG pictures from memory, decoded with Debian's libpng and
 * libjpeg-turbo: both are built for hostile input and fuzzed upstream.
 * stb_image, which jade used before, is not (its own README says so):
 * Debian 12's copy crashed under fuzz_texture on JPEGs with a bad Huffman
 * table, asserted on others and asked for 2 GiB for a 119-byte PNG.
 * Internal: not installed. */
#ifndef JD_PICTURE_DECODE_H
#define JD_PICTURE_DECODE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct jd_picture_limits {
    uint32_t max_side;   /* widest and tallest picture decoded */
    uint64_t max_pixels; /* and at most this many pixels */
} jd_picture_limits;

/* The picture as w * h * channels bytes (1 grey, 3 RGB, 4 RGBA; colour as
 * stored, sRGB-encoded), top row first, malloc'd into *px. The size the
 * header declares is checked against `lim` before any pixel is decoded.
 * 0, or -1 with a reason in err (which does not name the picture: the
 * caller does). */
int jd_png_decode(const uint8_t *data, size_t n, int channels, const jd_picture_limits *lim, uint8_t **px,
                  uint32_t *w, uint32_t *h, char *err, size_t errlen);
int jd_jpeg_decode(const uint8_t *data, size_t n, int channels, const jd_picture_limits *lim, uint8_t **px,
                   uint32_t *w, uint32_t *h, char *err, size_t errlen);

/* The refusal both write for a picture over `lim`. */
void jd_picture_too_big(uint32_t w, uint32_t h, const jd_picture_limits *lim, char *err, size_t errlen);
int jd_picture_fits(uint32_t w, uint32_t h, const jd_picture_limits *lim);

#ifdef __cplusplus
}
#endif
#endif
