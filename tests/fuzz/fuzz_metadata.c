/* libFuzzer: the metadata walker alone. The input follows a fixed Draco
 * 2.2 header with the metadata flag set, so every byte lands in the walk
 * (nesting, counts, names) instead of being spent on finding the header. */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "draco_header.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const uint8_t head[11] = {'D', 'R', 'A', 'C', 'O', 2, 2, 1, 0, 0, 0x80};
    if (size > (1u << 20)) return 0;
    uint8_t *buf = malloc(sizeof head + size);
    if (!buf) return 0;
    memcpy(buf, head, sizeof head);
    if (size) memcpy(buf + sizeof head, data, size);
    jd_draco_info info;
    jd_error err;
    jd_draco_peek(buf, sizeof head + size, "fuzz.drc", &info, &err);
    free(buf);
    return 0;
}
