/* OBJ faces checked before libdraco's reader sees them: libdraco 1.5.5
 * indexes its arrays with a face's numbers unchecked (a normal index past
 * the normals, or a corner like "4/1-1", crashed it in fuzzing), so a bad
 * index is named here, with its line. Internal: runs in the decoder's
 * child process. */
#ifndef JD_OBJ_CHECK_H
#define JD_OBJ_CHECK_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* 0: every face corner is v, v/vt, v//vn or v/vt/vn, each index naming an
 * element defined before its line; -1: err says the first that is not. */
int jd_obj_check(const char *data, size_t n, char *err, size_t errlen);

/* The OBJ as libdraco should see it. libdraco reads a comment after a
 * face's corners ("f 1 2 3 # top") as more corners, and opens an `mtllib`
 * by its name relative to the working directory (blocking on a FIFO of
 * that name there) although jade reads the material library itself, from
 * the OBJ's own folder (obj_material.h): 1 with *out (malloc'd, *out_n
 * bytes) the file with every comment cut from its line and every mtllib
 * line emptied, 0 where there is nothing to change, -1 out of memory. */
int jd_obj_for_draco(const char *data, size_t n, char **out, size_t *out_n);

#ifdef __cplusplus
}
#endif

#endif
