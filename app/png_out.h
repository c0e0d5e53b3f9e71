#ifndef JD_PNG_OUT_H
#define JD_PNG_OUT_H
#include <stdint.h>
#include "jd_result.h"
/* Writes to a temporary file beside `path` and renames it into place, so a
 * failed run never leaves a half-written PNG. */
jd_result jd_png_write(const char *path, int w, int h, const uint8_t *rgba, jd_error *err);
#endif
