/* What the GL tests set up before their renderers, once: the current
 * context's caps, an arena over the test's memory and the mesh at `path`
 * in it. */
#ifndef JD_GL_FIXTURE_H
#define JD_GL_FIXTURE_H
#include <stdio.h>

#include "gl_caps.h"
#include "mesh_load.h"

/* An RGBA pixel's luma, 0-255 (Rec. 601 weights). */
static inline int jd_test_luma(const unsigned char *p) { return (299 * p[0] + 587 * p[1] + 114 * p[2]) / 1000; }

/* 0, or 1 with what failed printed. */
static inline int jd_test_fixture(const char *path, unsigned char *mem, size_t size, jd_gl_caps *caps, jd_arena *a,
                                  jd_mesh *mesh)
{
    jd_error err = {0};
    if (jd_gl_caps_query(caps, &err)) { printf("%s\n", err.msg); return 1; }
    jd_arena_init(a, mem, size);
    jd_load_desc ld = {.path = path, .allow_32bit_indices = 1};
    if (jd_mesh_load_draco(&ld, a, mesh, NULL, &err)) { printf("%s: %s\n", path, err.msg); return 1; }
    return 0;
}
#endif
