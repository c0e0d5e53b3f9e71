/* libFuzzer: the Draco header check that runs in jade's own process
 * before libdraco sees a byte (counts, versions, the metadata walk). */
#include <stddef.h>
#include <stdint.h>

#include "draco_header.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    jd_draco_info info;
    jd_error err;
    jd_draco_peek(data, size, "fuzz.drc", &info, &err);
    return 0;
}
