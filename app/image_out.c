#include "image_out.h"

#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <stb_image_write.h>

/* Files the run reads: an output never replaces one of them. */
static struct { dev_t dev; ino_t ino; } inputs[16];
static int num_inputs;

void jd_output_protect(const char *path)
{
    struct stat st;
    if (!path || num_inputs >= (int)(sizeof inputs / sizeof inputs[0]) || stat(path, &st) != 0) return;
    inputs[num_inputs].dev = st.st_dev;
    inputs[num_inputs].ino = st.st_ino;
    num_inputs++;
}

jd_result jd_output_check(const char *path, jd_error *err)
{
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", path);
    if (access(dirname(dir), W_OK) != 0)
        return jd_fail(err, JD_ERR_IO, "%s: cannot write there: %s", path, strerror(errno));
    struct stat st;
    if (lstat(path, &st) != 0) return JD_OK; /* a new file */
    if (S_ISLNK(st.st_mode))
        return jd_fail(err, JD_ERR_IO, "%s: is a symbolic link; jade writes only to a regular file or a new name",
                       path);
    if (!S_ISREG(st.st_mode))
        return jd_fail(err, JD_ERR_IO, "%s: is not a regular file (a device, a FIFO or a folder); refused", path);
    for (int i = 0; i < num_inputs; i++)
        if (inputs[i].dev == st.st_dev && inputs[i].ino == st.st_ino)
            return jd_fail(err, JD_ERR_IO, "%s: is one of this run's inputs; refused", path);
    return JD_OK;
}

/* The encoders write through this: every short write is remembered. */
typedef struct sink {
    FILE *f;
    int failed, err;
} sink;

static void sink_write(void *ctx, void *data, int size)
{
    sink *s = ctx;
    if (!s->failed && fwrite(data, 1, (size_t)size, s->f) != (size_t)size) {
        s->failed = 1;
        s->err = errno;
    }
}

typedef int (*writer)(sink *s, int w, int h, const void *px);

/* A new file beside `path` (same file system, so the rename is atomic),
 * created exclusively under an unpredictable name: nothing planted there
 * in advance can redirect the write. Written, flushed to the disk, then
 * renamed over `path`: a full disk or any other failure leaves the
 * previous picture as it was. */
static jd_result write_atomic(const char *path, const char *kind, writer fn, int w, int h, const void *px,
                              jd_error *err)
{
    jd_result r = jd_output_check(path, err);
    if (r) return r;
    char tmp[4096];
    if (snprintf(tmp, sizeof tmp, "%s.XXXXXX", path) >= (int)sizeof tmp)
        return jd_fail(err, JD_ERR_ARG, "%s: path too long", path);
    int fd = mkstemp(tmp);
    if (fd < 0) return jd_fail(err, JD_ERR_IO, "%s: cannot create a file beside it: %s", path, strerror(errno));
    fchmod(fd, 0644);
    sink s = {fdopen(fd, "wb"), 0, 0};
    if (!s.f) {
        int e = errno;
        close(fd);
        unlink(tmp);
        return jd_fail(err, JD_ERR_IO, "%s: cannot write %s: %s", path, kind, strerror(e));
    }
    int ok = fn(&s, w, h, px) && !s.failed;
    if (ok && fflush(s.f) != 0) { s.err = errno; ok = 0; }
    if (ok && fsync(fileno(s.f)) != 0) { s.err = errno; ok = 0; }
    if (fclose(s.f) != 0 && ok) { s.err = errno; ok = 0; }
    if (!ok) {
        unlink(tmp);
        return jd_fail(err, JD_ERR_IO, "%s: cannot write %s: %s", path, kind,
                       s.err ? strerror(s.err) : "encoder failed");
    }
    if (rename(tmp, path) != 0) {
        int e = errno;
        unlink(tmp);
        return jd_fail(err, JD_ERR_IO, "%s: cannot move %s into place: %s", path, kind, strerror(e));
    }
    return JD_OK;
}

static int png_fn(sink *s, int w, int h, const void *px)
{
    return stbi_write_png_to_func(sink_write, s, w, h, 4, px, w * 4);
}

static int pfm_fn(sink *s, int w, int h, const void *px)
{
    const float *rgb = px;
    char head[64];
    /* A negative scale says little-endian; jade's targets all are. */
    int n = snprintf(head, sizeof head, "PF\n%d %d\n-1.0\n", w, h);
    sink_write(s, head, n);
    for (int y = h - 1; y >= 0; y--) sink_write(s, (void *)(rgb + 3 * (size_t)y * w), (int)(sizeof(float) * 3) * w);
    return 1;
}

jd_result jd_png_write(const char *path, int w, int h, const uint8_t *rgba, jd_error *err)
{
    return write_atomic(path, "PNG", png_fn, w, h, rgba, err);
}

jd_result jd_pfm_write(const char *path, int w, int h, const float *rgb, jd_error *err)
{
    return write_atomic(path, "PFM", pfm_fn, w, h, rgb, err);
}
