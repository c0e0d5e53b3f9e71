#include "file_beside.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

uint8_t *jd_file_beside(const char *model_path, const char *name, size_t max_bytes, size_t *len, char *why,
                        size_t cap)
{
    if (!name[0] || name[0] == '/' || strstr(name, "..") || strchr(name, '\\') || strchr(name, ':') || strchr(name, '%')) {
        snprintf(why, cap, "'%.100s' is not a plain relative file name", name);
        return NULL;
    }
    char full[4096];
    const char *slash = strrchr(model_path, '/');
    int dir = slash ? (int)(slash - model_path + 1) : 0;
    if (snprintf(full, sizeof full, "%.*s%s", dir, model_path, name) >= (int)sizeof full) {
        snprintf(why, cap, "path too long");
        return NULL;
    }
    int fd = open(full, O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) {
        snprintf(why, cap, "cannot open %.200s: %s", full, strerror(errno));
        return NULL;
    }
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        snprintf(why, cap, "%.200s is not a regular file", full);
        close(fd);
        return NULL;
    }
    if (st.st_size <= 0 || (size_t)st.st_size > max_bytes) {
        snprintf(why, cap, "%.200s has %lld bytes: empty, or over the limit of %zu", full, (long long)st.st_size,
                 max_bytes);
        close(fd);
        return NULL;
    }
    size_t n = (size_t)st.st_size, got = 0;
    uint8_t *b = malloc(n + 1);
    while (b && got < n) {
        ssize_t k = read(fd, b + got, n - got);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) break;
        got += (size_t)k;
    }
    close(fd);
    if (!b || got != n) {
        snprintf(why, cap, "%.200s could not be read whole", full);
        free(b);
        return NULL;
    }
    b[n] = 0;
    *len = n;
    return b;
}

