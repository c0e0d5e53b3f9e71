/* libFuzzer: the picture readers of metric, --mask and --sheet-reference
 * (stb_image behind the pixel cap, and jade's PFM reader), chosen by
 * content as jade metric chooses. */
#pragma GCC diagnostic ignored "-Wunused-function"
#include <ctype.h>
#include <stdint.h>
#include <stdlib.h>

/* stb_image compiled here from Debian's header, so that its decoders are
 * instrumented too (libstb.so is not). */
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#include "image_in.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    int w, h;
    char why[160];
    if (size > 2 && data[0] == 'P' && data[1] == 'F' && isspace(data[2])) {
        free(jd_pfm_decode(data, size, &w, &h, why, sizeof why));
    } else {
        unsigned char *px = jd_image_decode(data, size, &w, &h, 4, why, sizeof why);
        if (px) stbi_image_free(px);
    }
    return 0;
}
