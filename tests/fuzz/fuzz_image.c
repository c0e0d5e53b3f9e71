/* libFuzzer: the picture readers of metric, --mask and --sheet-reference
 * (libpng behind the pixel cap, and jade's PFM reader), chosen by
 * content as jade metric chooses. */
#include <ctype.h>
#include <stdint.h>
#include <stdlib.h>

#include "image_in.h"
#include "png_crc.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    int w, h;
    char why[160];
    if (size > 2 && data[0] == 'P' && data[1] == 'F' && isspace(data[2])) {
        free(jd_pfm_decode(data, size, &w, &h, why, sizeof why));
    } else {
        uint8_t *d = fuzz_png_with_crcs(data, size);
        /* 4 channels as metric reads, 1 as --mask does. */
        if (d) free(jd_image_decode(d, size, &w, &h, size && data[size - 1] & 1 ? 1 : 4, why, sizeof why));
        free(d);
    }
    return 0;
}
