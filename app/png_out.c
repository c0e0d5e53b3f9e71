#include "png_out.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include <stb_image_write.h>

jd_result jd_png_write(const char *path, int w, int h, const uint8_t *rgba, jd_error *err)
{
    char tmp[4096];
    if (snprintf(tmp, sizeof tmp, "%s.tmp.%ld", path, (long)getpid()) >= (int)sizeof tmp)
        return jd_fail(err, JD_ERR_ARG, "%s: path too long", path);
    if (!stbi_write_png(tmp, w, h, 4, rgba, w * 4)) {
        int e = errno;
        unlink(tmp);
        return jd_fail(err, JD_ERR_IO, "%s: cannot write PNG: %s", path, e ? strerror(e) : "encoder failed");
    }
    if (rename(tmp, path) != 0) {
        int e = errno;
        unlink(tmp);
        return jd_fail(err, JD_ERR_IO, "%s: cannot move PNG into place: %s", path, strerror(e));
    }
    return JD_OK;
}
