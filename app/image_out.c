#define _GNU_SOURCE /* O_TMPFILE */
#include "image_out.h"

#include <errno.h>
#include <limits.h>
#include <stdint.h>
#include <time.h>
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

int jd_frame_name(const char *pattern, long frame, char *name, size_t cap, jd_error *err)
{
    const char *pc = strchr(pattern, '%');
    if (!pc) {
        if (snprintf(name, cap, "%s", pattern) >= (int)cap) goto too_long;
        return 0;
    }
    /* Parsed here, never handed to printf: a name is not a format. */
    const char *p = pc + 1;
    int zero = 0, width = 0;
    if (*p == '0' && p[1] >= '1' && p[1] <= '9') { zero = 1; width = p[1] - '0'; p += 2; }
    if (*p != 'd' || strchr(p + 1, '%')) {
        jd_fail(err, JD_ERR_ARG, "%s: a %% in the name numbers the frames, once, as %%d or %%0Nd (N 1-9)", pattern);
        return -1;
    }
    if (snprintf(name, cap, "%.*s%0*ld%s", (int)(pc - pattern), pattern, zero ? width : 0, frame, p + 1) >= (int)cap)
        goto too_long;
    return 1;
too_long:
    jd_fail(err, JD_ERR_ARG, "%s: the name is too long", pattern);
    return -1;
}

int jd_frame_names_check(const char *pattern, long frames, jd_error *err)
{
    char name[PATH_MAX];
    int sequence = pattern ? jd_frame_name(pattern, 0, name, sizeof name, err) : 0;
    for (long i = 0; sequence > 0 && i < frames; i++)
        if (jd_frame_name(pattern, i, name, sizeof name, err) < 0 || jd_output_check(name, err)) sequence = -1;
    return sequence;
}

/* The folder that holds `path`, for the new file and the final fsync. */
static void parent_dir(const char *path, char *dir, size_t cap)
{
    snprintf(dir, cap, "%s", path);
    char *d = dirname(dir);
    if (d != dir) memmove(dir, d, strlen(d) + 1);
}

jd_result jd_output_check(const char *path, jd_error *err)
{
    char dir[PATH_MAX];
    parent_dir(path, dir, sizeof dir);
    if (access(dir, W_OK) != 0)
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

/* The new file. Where the file system allows (ext4, xfs, btrfs, tmpfs), an
 * unnamed O_TMPFILE: a run killed mid-write leaves nothing behind at all.
 * Elsewhere a name made by mkstemp (O_EXCL, unpredictable): nothing planted
 * there in advance can redirect the write. */
static int create_temp(const char *path, const char *dir, char *tmp, size_t cap, int *named)
{
    *named = 0;
#ifdef O_TMPFILE
    int fd = open(dir, O_TMPFILE | O_WRONLY | O_CLOEXEC, 0644);
    if (fd >= 0) return fd;
#endif
    if (snprintf(tmp, cap, "%s.XXXXXX", path) >= (int)cap) {
        errno = ENAMETOOLONG;
        return -1;
    }
    fd = mkstemp(tmp);
    if (fd >= 0) {
        fchmod(fd, 0644);
        *named = 1;
    }
    return fd;
}

/* Gives the unnamed file a name beside `path`, so that it can be renamed
 * over it (linkat cannot replace a file). */
static int name_temp(int fd, const char *path, char *tmp, size_t cap)
{
    char proc[64];
    snprintf(proc, sizeof proc, "/proc/self/fd/%d", fd);
    for (int attempt = 0; attempt < 100; attempt++) {
        unsigned v = (unsigned)getpid() * 2654435761u ^ (unsigned)clock() ^ (unsigned)attempt * 40503u ^
                     (unsigned)(uintptr_t)&v;
        if (snprintf(tmp, cap, "%s.%08x", path, v) >= (int)cap) { errno = ENAMETOOLONG; return -1; }
        if (linkat(AT_FDCWD, proc, AT_FDCWD, tmp, AT_SYMLINK_FOLLOW) == 0) return 0;
        if (errno != EEXIST) return -1;
    }
    return -1;
}

/* Written, flushed to the disk, then renamed over `path`: a full disk, a
 * kill or any other failure leaves the previous picture as it was. */
static jd_result write_atomic(const char *path, const char *kind, writer fn, int w, int h, const void *px,
                              jd_error *err)
{
    jd_result r = jd_output_check(path, err);
    if (r) return r;
    char dir[PATH_MAX], tmp[PATH_MAX + 16];
    parent_dir(path, dir, sizeof dir);
    int named;
    int fd = create_temp(path, dir, tmp, sizeof tmp, &named);
    if (fd < 0) return jd_fail(err, JD_ERR_IO, "%s: cannot create a file beside it: %s", path, strerror(errno));
    sink s = {fdopen(fd, "wb"), 0, 0};
    if (!s.f) {
        int e = errno;
        close(fd);
        if (named) unlink(tmp);
        return jd_fail(err, JD_ERR_IO, "%s: cannot write %s: %s", path, kind, strerror(e));
    }
    int ok = fn(&s, w, h, px) && !s.failed;
    if (ok && fflush(s.f) != 0) { s.err = errno; ok = 0; }
    if (ok && fsync(fileno(s.f)) != 0) { s.err = errno; ok = 0; }
    if (ok && !named && name_temp(fileno(s.f), path, tmp, sizeof tmp) != 0) { s.err = errno; ok = 0; }
    else if (ok) named = 1;
    if (fclose(s.f) != 0 && ok) { s.err = errno; ok = 0; }
    if (!ok) {
        if (named) unlink(tmp);
        return jd_fail(err, JD_ERR_IO, "%s: cannot write %s: %s", path, kind,
                       s.err ? strerror(s.err) : "encoder failed");
    }
    if (rename(tmp, path) != 0) {
        int e = errno;
        unlink(tmp);
        return jd_fail(err, JD_ERR_IO, "%s: cannot move %s into place: %s", path, kind, strerror(e));
    }
    /* The rename itself reaches the disk with the folder. */
    int dfd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
        fsync(dfd);
        close(dfd);
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

static int jpg_fn(sink *s, int w, int h, const void *px)
{
    return stbi_write_jpg_to_func(sink_write, s, w, h, 4, px, 92);
}

/* The name's extension, lower-cased, or "" (at most 7 characters). */
static void extension(const char *path, char *ext, size_t cap)
{
    const char *slash = strrchr(path, '/'), *dot = strrchr(path, '.');
    ext[0] = 0;
    if (!dot || (slash && dot < slash) || strlen(dot + 1) >= cap) return;
    size_t i = 0;
    for (const char *p = dot + 1; *p; p++) ext[i++] = (char)(*p >= 'A' && *p <= 'Z' ? *p + 32 : *p);
    ext[i] = 0;
}

jd_picture_kind jd_picture_kind_of(const char *path, jd_error *err)
{
    char ext[8];
    extension(path, ext, sizeof ext);
    if (!strcmp(ext, "jpg") || !strcmp(ext, "jpeg")) return JD_PICTURE_JPEG;
    static const char *const other[] = {"bmp", "gif", "tga", "tif", "tiff", "webp", "ppm", "pgm", "exr", "hdr", "pfm", "avif"};
    for (size_t i = 0; i < sizeof other / sizeof other[0]; i++)
        if (!strcmp(ext, other[i])) {
            jd_fail(err, JD_ERR_ARG, "%s: jade writes pictures as PNG or JPEG (.png, .jpg), not .%s", path, ext);
            return JD_PICTURE_NONE;
        }
    return JD_PICTURE_PNG;
}

jd_result jd_png_write(const char *path, int w, int h, const uint8_t *rgba, jd_error *err)
{
    jd_picture_kind k = jd_picture_kind_of(path, err);
    if (k == JD_PICTURE_NONE) return JD_ERR_ARG;
    if (k == JD_PICTURE_JPEG) return write_atomic(path, "JPEG", jpg_fn, w, h, rgba, err);
    return write_atomic(path, "PNG", png_fn, w, h, rgba, err);
}

static int bytes_fn(sink *s, int w, int h, const void *px)
{
    /* The byte count comes as w * h with h = 1 chunk per call below. */
    (void)h;
    sink_write(s, (void *)px, w);
    return 1;
}

jd_result jd_bytes_write(const char *path, const char *kind, const void *data, size_t n, jd_error *err)
{
    if (n > INT_MAX) return jd_fail(err, JD_ERR_LIMIT, "%s: %zu bytes are more than jade writes in one file", path, n);
    return write_atomic(path, kind, bytes_fn, (int)n, 1, data, err);
}

jd_result jd_pfm_write(const char *path, int w, int h, const float *rgb, jd_error *err)
{
    return write_atomic(path, "PFM", pfm_fn, w, h, rgb, err);
}
