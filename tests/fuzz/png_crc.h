/* For the fuzz targets only: libpng refuses a chunk whose CRC is wrong
 * before it looks inside, so nearly every mutation of a PNG would stop
 * there. The harness copies the input and gives each chunk that lies inside
 * it its right CRC, as libpng's own fuzzer turns the check off, so that the
 * decoder behind the check is what gets fuzzed. The caller frees the copy. */
#ifndef JD_FUZZ_PNG_CRC_H
#define JD_FUZZ_PNG_CRC_H
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <zlib.h> /* crc32: PNG's own CRC */

static uint8_t *fuzz_png_with_crcs(const uint8_t *data, size_t size)
{
    uint8_t *d = malloc(size ? size : 1);
    if (!d) return NULL;
    memcpy(d, data, size);
    if (size < 8 || memcmp(d, "\x89PNG\r\n\x1a\n", 8) != 0) return d;
    for (size_t at = 8; size - at >= 12;) {
        uint32_t len = (uint32_t)d[at] << 24 | (uint32_t)d[at + 1] << 16 | (uint32_t)d[at + 2] << 8 | d[at + 3];
        if (len > size - at - 12) break;
        uint32_t c = (uint32_t)crc32(0L, d + at + 4, 4u + len);
        uint8_t *o = d + at + 8 + len;
        o[0] = (uint8_t)(c >> 24); o[1] = (uint8_t)(c >> 16); o[2] = (uint8_t)(c >> 8); o[3] = (uint8_t)c;
        at += 12 + (size_t)len;
    }
    return d;
}
#endif
