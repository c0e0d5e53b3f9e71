#include "image_in.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "picture_decode.h"

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

unsigned char *jd_input_read(const char *path, size_t *len, char *why, size_t cap)
{
    struct stat st;
    int fd = open_regular(path, &st, why, cap);
    if (fd < 0) return NULL;
    if (st.st_size <= 0 || (unsigned long long)st.st_size > JD_IMAGE_MAX_BYTES) {
        snprintf(why, cap, "%lld bytes: not a picture jade reads (at most %u MiB)", (long long)st.st_size,
                 JD_IMAGE_MAX_BYTES >> 20);
        close(fd);
        return NULL;
    }
    size_t n = (size_t)st.st_size, got = 0;
    unsigned char *buf = malloc(n);
    while (buf && got < n) {
        ssize_t r = read(fd, buf + got, n - got);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) break;
        got += (size_t)r;
    }
    close(fd);
    if (!buf || got != n) {
        snprintf(why, cap, buf ? "cannot read it (it changed size while being read)" : "out of memory");
        free(buf);
        return NULL;
    }
    *len = n;
    return buf;
}

unsigned char *jd_image_decode(const unsigned char *buf, size_t n, int *w, int *h, int channels, char *why,
                               size_t cap)
{
    /* PNG only: every picture jade writes or compares is a PNG or a PFM. */
    static const unsigned char png_magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const jd_picture_limits lim = {JD_IMAGE_MAX_SIDE, (uint64_t)JD_IMAGE_MAX_SIDE * JD_IMAGE_MAX_SIDE};
    if (n < 8 || n > JD_IMAGE_MAX_BYTES || memcmp(buf, png_magic, 8) != 0) {
        snprintf(why, cap, "not a PNG (jade reads PNG and PFM pictures)");
        return NULL;
    }
    uint8_t *px = NULL;
    uint32_t pw = 0, ph = 0;
    if (jd_png_decode(buf, n, channels, &lim, &px, &pw, &ph, why, cap) != 0) return NULL;
    *w = (int)pw;
    *h = (int)ph;
    return px;
}

unsigned char *jd_image_load(const char *path, int *w, int *h, int channels, char *why, size_t cap)
{
    size_t n;
    unsigned char *buf = jd_input_read(path, &n, why, cap);
    if (!buf) return NULL;
    unsigned char *px = jd_image_decode(buf, n, w, h, channels, why, cap);
    free(buf);
    return px;
}

/* PFM header tokens: "PF", width, height, scale, each ended by white space;
 * the last by exactly one white-space character, or CR LF as Windows tools
 * write it. */
static int pfm_token(const unsigned char *buf, size_t n, size_t *at, char *tok, size_t cap)
{
    while (*at < n && isspace(buf[*at])) (*at)++;
    size_t k = 0;
    while (*at < n && !isspace(buf[*at])) {
        if (k + 1 >= cap) return 0;
        tok[k++] = (char)buf[(*at)++];
    }
    tok[k] = 0;
    return k > 0 && *at < n;
}

static int pfm_side(const char *tok, int *v)
{
    long x = 0;
    for (const char *p = tok; *p; p++) {
        if (*p < '0' || *p > '9') return 0;
        x = x * 10 + (*p - '0');
        if (x > JD_IMAGE_MAX_SIDE) return 0;
    }
    *v = (int)x;
    return x > 0;
}

float *jd_pfm_decode(const unsigned char *buf, size_t n, int *w, int *h, char *why, size_t cap)
{
    char kind[8], ws[24], hs[24], ss[64];
    size_t at = 0;
    if (!pfm_token(buf, n, &at, kind, sizeof kind) || strcmp(kind, "PF") ||
        !pfm_token(buf, n, &at, ws, sizeof ws) || !pfm_token(buf, n, &at, hs, sizeof hs) ||
        !pfm_token(buf, n, &at, ss, sizeof ss)) {
        snprintf(why, cap, "not a colour PFM (no \"PF width height scale\" header)");
        return NULL;
    }
    if (!pfm_side(ws, w) || !pfm_side(hs, h)) {
        snprintf(why, cap, "PFM declares %s x %s pixels: sides must be 1 to %d", ws, hs, JD_IMAGE_MAX_SIDE);
        return NULL;
    }
    char *end;
    double scale = strtod(ss, &end);
    if (*end || !(scale < 0)) {
        snprintf(why, cap, "PFM scale '%s': jade reads little-endian PFMs (a negative scale) only", ss);
        return NULL;
    }
    if (buf[at] == '\r' && at + 1 < n && buf[at + 1] == '\n') at++;
    at++; /* the one white-space character that ends the header */
    size_t count = (size_t)*w * (size_t)*h * 3;
    if (n - at != count * sizeof(float)) {
        snprintf(why, cap, "PFM of %dx%d pixels should hold %zu bytes of data, has %zu", *w, *h,
                 count * sizeof(float), n - at);
        return NULL;
    }
    float *out = malloc(count * sizeof(float));
    if (!out) { snprintf(why, cap, "out of memory"); return NULL; }
    for (int y = 0; y < *h; y++) /* rows are stored bottom first; PNGs top first */
        memcpy(out + (size_t)y * *w * 3, buf + at + (size_t)(*h - 1 - y) * *w * 3 * sizeof(float),
               sizeof(float) * 3 * (size_t)*w);
    for (size_t i = 0; i < count; i++)
        if (!isfinite(out[i]) || out[i] < 0) {
            snprintf(why, cap, "PFM pixel %zu has a negative or non-finite value", i / 3);
            free(out);
            return NULL;
        }
    return out;
}

float *jd_pfm_load(const char *path, int *w, int *h, char *why, size_t cap)
{
    size_t n;
    unsigned char *buf = jd_input_read(path, &n, why, cap);
    if (!buf) return NULL;
    float *px = jd_pfm_decode(buf, n, w, h, why, cap);
    free(buf);
    return px;
}
