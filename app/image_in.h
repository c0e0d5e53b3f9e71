/* Pictures in (metric inputs, masks, the sheet's reference), bounded: only a
 * regular file (a FIFO or a device would block or never end), at most
 * 64 MiB of it, and at most 4096 x 4096 pixels as its header declares,
 * checked before anything is decoded (a 551-byte BMP can declare 1.6 GB). */
#ifndef JD_IMAGE_IN_H
#define JD_IMAGE_IN_H
#include <stddef.h>

enum { JD_IMAGE_MAX_SIDE = 4096 };
#define JD_IMAGE_MAX_BYTES (64u << 20)

/* 0 and a reason in `why` unless `path` is a regular file. */
int jd_input_regular(const char *path, char *why, size_t cap);
/* The whole of a regular file of at most JD_IMAGE_MAX_BYTES (free() it),
 * or NULL and a reason. */
unsigned char *jd_input_read(const char *path, size_t *n, char *why, size_t cap);

/* A PNG's pixels (free() them) with `channels` (1, 3 or 4) per pixel, or
 * NULL and a reason. */
unsigned char *jd_image_load(const char *path, int *w, int *h, int channels, char *why, size_t cap);
unsigned char *jd_image_decode(const unsigned char *buf, size_t n, int *w, int *h, int channels, char *why,
                               size_t cap);

/* A little-endian colour PFM as w*h*3 floats, top row first (free() it);
 * values must be finite and not negative. */
float *jd_pfm_load(const char *path, int *w, int *h, char *why, size_t cap);
float *jd_pfm_decode(const unsigned char *buf, size_t n, int *w, int *h, char *why, size_t cap);

#endif
