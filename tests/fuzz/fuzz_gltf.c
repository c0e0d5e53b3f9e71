/* libFuzzer: the glTF reader itself, in process (the loader runs it in a
 * child; here a crash or a leak is seen directly): GLB chunks, JSON, data:
 * URIs, accessors, strides, node trees and Draco-compressed primitives.
 * External buffers resolve beside a path that does not exist, so they fail
 * to open, as they should. */
#include <stdint.h>
#include <stdlib.h>

#include "gltf_read.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    jd_gltf_limits lim = {100000, 100000, 16u << 20, 64};
    jd_mesh_arrays m;
    char err[512];
    if (jd_gltf_read(data, size, "/nonexistent-jade-fuzz/x.gltf", &lim, &m, err, sizeof err) == 0)
        jd_mesh_arrays_free(&m);
    return 0;
}
