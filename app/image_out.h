/* Pictures out: written to a new file beside `path`, flushed to the disk and
 * renamed into place, so a failed run (a full disk included) never leaves a
 * half-written file and never loses the previous one. An output is never
 * written over anything but a regular file, nor over one of the run's
 * inputs, nor through a symbolic link. */
#ifndef JD_IMAGE_OUT_H
#define JD_IMAGE_OUT_H
#include <stddef.h>
#include <stdint.h>
#include "jd_result.h"
/* A picture of w*h RGBA pixels: JPEG (quality 92) when the name ends in .jpg
 * or .jpeg, PNG otherwise; a name ending in another picture format's
 * extension is refused rather than given a PNG under that name. */
jd_result jd_png_write(const char *path, int w, int h, const uint8_t *rgba, jd_error *err);
typedef enum { JD_PICTURE_NONE, JD_PICTURE_PNG, JD_PICTURE_JPEG } jd_picture_kind;
/* What jd_png_write would write to `path`; JD_PICTURE_NONE and a reason. */
jd_picture_kind jd_picture_kind_of(const char *path, jd_error *err);
/* A sequence's picture name: `pattern` with its one %d or %0Nd (N 1-9)
 * replaced by `frame`. 0 and `name` = `pattern` when it has no %; -1 and a
 * reason when it has another % or more than one, or the name is too long. */
int jd_frame_name(const char *pattern, long frame, char *name, size_t cap, jd_error *err);
/* jd_frame_name for frames 0 to frames - 1, each name checked as
 * jd_output_check does, before any work: 1 for a sequence, 0 for one
 * name (not checked here), -1 and a reason. */
int jd_frame_names_check(const char *pattern, long frames, jd_error *err);
/* Little-endian colour PFM of w*h*3 floats given top row first (PFM files
 * store the bottom row first). */
jd_result jd_pfm_write(const char *path, int w, int h, const float *rgb, jd_error *err);
/* Any other file (kind names it in messages), written the same way. */
jd_result jd_bytes_write(const char *path, const char *kind, const void *data, size_t n, jd_error *err);
/* Remembers a file the run reads, so no output replaces it. */
void jd_output_protect(const char *path);
/* Whether `path` may be written: absent, or a regular file that is not an
 * input. For checking outputs before the work starts. */
jd_result jd_output_check(const char *path, jd_error *err);
#endif
