/* PNG through libpng's simplified API: it validates every chunk's length
 * and CRC, inflates only as many bytes as the rows the header declares, and
 * reports errors in png_image.message instead of longjmp-ing into us. */
#include "picture_decode.h"

#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int jd_picture_fits(uint32_t w, uint32_t h, const jd_picture_limits *lim)
{
    return w >= 1 && h >= 1 && w <= lim->max_side && h <= lim->max_side && (uint64_t)w * h <= lim->max_pixels;
}

void jd_picture_too_big(uint32_t w, uint32_t h, const jd_picture_limits *lim, char *err, size_t errlen)
{
    snprintf(err, errlen, "declares %u x %u pixels, over jade's limit of %llu pixels (%u a side); refused", w, h,
             (unsigned long long)lim->max_pixels, lim->max_side);
}

int jd_png_decode(const uint8_t *data, size_t n, int channels, const jd_picture_limits *lim, uint8_t **px,
                  uint32_t *w, uint32_t *h, char *err, size_t errlen)
{
    *px = NULL;
    *w = *h = 0;
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_memory(&im, data, n)) {
        snprintf(err, errlen, "the PNG header does not parse (%s)", im.message[0] ? im.message : "corrupt");
        png_image_free(&im);
        return -1;
    }
    /* The size first: a picture that declares a size it has no bytes for
     * (a decode bomb) costs nothing to refuse. */
    if (!jd_picture_fits(im.width, im.height, lim)) {
        jd_picture_too_big(im.width, im.height, lim, err, errlen);
        png_image_free(&im);
        return -1;
    }
    im.format = channels == 1 ? PNG_FORMAT_GRAY : channels == 3 ? PNG_FORMAT_RGB : PNG_FORMAT_RGBA;
    /* A 16-bit PNG without a gamma chunk is sRGB-encoded as an 8-bit one
     * is (libpng would otherwise take it as linear and brighten it). */
    im.flags |= PNG_IMAGE_FLAG_16BIT_sRGB;
    size_t size = PNG_IMAGE_SIZE(im);
    uint8_t *buf = malloc(size);
    if (!buf) {
        snprintf(err, errlen, "out of memory for %u x %u pixels", im.width, im.height);
        png_image_free(&im);
        return -1;
    }
    /* Without a background, alpha left out of `channels` is composited on
     * black; every caller that asks for fewer than 4 wants opaque pixels. */
    if (!png_image_finish_read(&im, NULL, buf, 0, NULL)) {
        snprintf(err, errlen, "the PNG data does not decode (%s)", im.message[0] ? im.message : "corrupt");
        free(buf);
        png_image_free(&im);
        return -1;
    }
    *px = buf;
    *w = im.width;
    *h = im.height;
    png_image_free(&im);
    return 0;
}
