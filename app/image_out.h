/* Pictures out: written to a temporary file beside `path` and renamed into
 * place, so a failed run never leaves a half-written file. */
#ifndef JD_IMAGE_OUT_H
#define JD_IMAGE_OUT_H
#include <stdint.h>
#include "jd_result.h"
jd_result jd_png_write(const char *path, int w, int h, const uint8_t *rgba, jd_error *err);
/* Little-endian colour PFM of w*h*3 floats given top row first (PFM files
 * store the bottom row first). */
jd_result jd_pfm_write(const char *path, int w, int h, const float *rgb, jd_error *err);
#endif
