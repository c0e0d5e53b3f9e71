/* libFuzzer: jade's own checks on text meshes, in process (the loader runs
 * them in its child, where fuzz_mesh_load's coverage does not reach): PLY
 * triangle strips rewritten with faces, and OBJ comments cut and face
 * corners checked before libdraco reads them. */
#include <stdint.h>
#include <stdlib.h>

#include "obj_check.h"
#include "ply_strips.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *out;
    size_t n;
    char err[256];
    if (jd_ply_strips_to_faces((const char *)data, size, &out, &n, err, sizeof err) > 0) {
        /* What libdraco then reads: the same check again finds nothing new. */
        free(out);
    }
    if (jd_obj_for_draco((const char *)data, size, &out, &n) > 0) {
        jd_obj_check(out, n, err, sizeof err);
        free(out);
    } else {
        jd_obj_check((const char *)data, size, err, sizeof err);
    }
    return 0;
}
