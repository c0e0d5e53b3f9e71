#include "image_in.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <stb_image.h>

#define MAX_BYTES (64u << 20)

/* Opened without blocking (a FIFO with no writer would hang the open), then
 * looked at. */
static int open_regular(const char *path, struct stat *st, char *why, size_t cap)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) {
        snprintf(why, cap, "cannot open: %s", strerror(errno));
        return -1;
    }
    if (fstat(fd, st) != 0 || !S_ISREG(st->st_mode)) {
        snprintf(why, cap, "not a regular file");
        close(fd);
        return -1;
    }
    return fd;
}

int jd_input_regular(const char *path, char *why, size_t cap)
{
    struct stat st;
    int fd = open_regular(path, &st, why, cap);
    if (fd < 0) return 0;
    close(fd);
    return 1;
}

unsigned char *jd_image_load(const char *path, int *w, int *h, int channels, char *why, size_t cap)
{
    struct stat st;
    int fd = open_regular(path, &st, why, cap);
    if (fd < 0) return NULL;
    if (st.st_size <= 0 || (unsigned long long)st.st_size > MAX_BYTES) {
        snprintf(why, cap, "%lld bytes: not a picture jade reads (at most %u MiB)", (long long)st.st_size,
                 MAX_BYTES >> 20);
        close(fd);
        return NULL;
    }
    size_t n = (size_t)st.st_size, got = 0;
    unsigned char *buf = malloc(n);
    while (buf && got < n) {
        ssize_t r = read(fd, buf + got, n - got);
        if (r <= 0) break;
        got += (size_t)r;
    }
    close(fd);
    if (!buf || got != n) {
        snprintf(why, cap, buf ? "cannot read it" : "out of memory");
        free(buf);
        return NULL;
    }
    int c = 0;
    if (!stbi_info_from_memory(buf, (int)n, w, h, &c)) {
        snprintf(why, cap, "not a picture stb_image reads (PNG, BMP, ...)");
        free(buf);
        return NULL;
    }
    if (*w <= 0 || *h <= 0 || *w > JD_IMAGE_MAX_SIDE || *h > JD_IMAGE_MAX_SIDE) {
        snprintf(why, cap, "declares %dx%d pixels, over the limit of %dx%d", *w, *h, JD_IMAGE_MAX_SIDE,
                 JD_IMAGE_MAX_SIDE);
        free(buf);
        return NULL;
    }
    unsigned char *px = stbi_load_from_memory(buf, (int)n, w, h, &c, channels);
    free(buf);
    if (!px) snprintf(why, cap, "cannot decode it: %s", stbi_failure_reason());
    return px;
}
