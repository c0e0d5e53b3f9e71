/* Pictures in (metric inputs, masks, the sheet's reference), bounded: only a
 * regular file (a FIFO or a device would block or never end), at most
 * 64 MiB of it, and at most 4096 x 4096 pixels as its header declares,
 * checked before anything is decoded (a 551-byte BMP can declare 1.6 GB). */
#ifndef JD_IMAGE_IN_H
#define JD_IMAGE_IN_H
#include <stddef.h>

enum { JD_IMAGE_MAX_SIDE = 4096 };

/* 0 and a reason in `why` unless `path` is a regular file. */
int jd_input_regular(const char *path, char *why, size_t cap);
/* stb_image's pixels (free with stbi_image_free) with `channels` per pixel,
 * or NULL and a reason. */
unsigned char *jd_image_load(const char *path, int *w, int *h, int channels, char *why, size_t cap);

#endif
