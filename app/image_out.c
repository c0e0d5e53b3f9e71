#include "image_out.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include <stb_image_write.h>

typedef int (*writer)(const char *tmp, int w, int h, const void *px);

static jd_result write_atomic(const char *path, const char *kind, writer fn, int w, int h, const void *px,
                              jd_error *err)
{
    char tmp[4096];
    if (snprintf(tmp, sizeof tmp, "%s.tmp.%ld", path, (long)getpid()) >= (int)sizeof tmp)
        return jd_fail(err, JD_ERR_ARG, "%s: path too long", path);
    errno = 0;
    if (!fn(tmp, w, h, px)) {
        int e = errno;
        unlink(tmp);
        return jd_fail(err, JD_ERR_IO, "%s: cannot write %s: %s", path, kind, e ? strerror(e) : "encoder failed");
    }
    if (rename(tmp, path) != 0) {
        int e = errno;
        unlink(tmp);
        return jd_fail(err, JD_ERR_IO, "%s: cannot move %s into place: %s", path, kind, strerror(e));
    }
    return JD_OK;
}

static int png_fn(const char *tmp, int w, int h, const void *px)
{
    return stbi_write_png(tmp, w, h, 4, px, w * 4);
}

static int pfm_fn(const char *tmp, int w, int h, const void *px)
{
    const float *rgb = px;
    FILE *f = fopen(tmp, "wb");
    if (!f) return 0;
    /* A negative scale says little-endian; jade's targets all are. */
    int ok = fprintf(f, "PF\n%d %d\n-1.0\n", w, h) > 0;
    for (int y = h - 1; y >= 0 && ok; y--)
        ok = fwrite(rgb + 3 * (size_t)y * w, sizeof(float) * 3, (size_t)w, f) == (size_t)w;
    if (fclose(f) != 0) ok = 0;
    return ok;
}

jd_result jd_png_write(const char *path, int w, int h, const uint8_t *rgba, jd_error *err)
{
    return write_atomic(path, "PNG", png_fn, w, h, rgba, err);
}

jd_result jd_pfm_write(const char *path, int w, int h, const float *rgb, jd_error *err)
{
    return write_atomic(path, "PFM", pfm_fn, w, h, rgb, err);
}
