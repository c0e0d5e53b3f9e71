/* PLY files that store their surface as triangle strips ("element
 * tristrips", a list of vertex indices with -1 between strips, as the
 * Stanford repository's scans are stored): rewritten with an equivalent
 * "element face" of triangles, which libdraco's PLY reader reads.
 * Internal: runs in the decoder's child process. */
#ifndef JD_PLY_STRIPS_H
#define JD_PLY_STRIPS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* 0: the file has no tristrips element, or has faces too (nothing done);
 * 1: *out (malloc'd, *out_n bytes) is the same PLY with faces; -1: the
 * strips cannot be read, err says why. ASCII and both binary orders; in a
 * binary file the elements before the strips must be all scalars. */
int jd_ply_strips_to_faces(const char *data, size_t n, char **out, size_t *out_n, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif

#endif
