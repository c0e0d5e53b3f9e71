/* libFuzzer: the colour texture decoder itself, in process (the loader runs
 * it in a child): the PNG and JPEG headers' size checks, libpng's and
 * libjpeg-turbo's decoders behind them, the resampling to powers of two. */
#include <stdint.h>
#include <stdlib.h>

#include "png_crc.h"
#include "texture_decode.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const float one[3] = {1, 1, 1};
    jd_texture t;
    char err[256];
    uint8_t *d = fuzz_png_with_crcs(data, size);
    if (!d) return 0;
    if (jd_texture_decode(d, size, one, 64, "the fuzzed picture", &t, err, sizeof err) == 0) free(t.texels);
    free(d);
    return 0;
}
