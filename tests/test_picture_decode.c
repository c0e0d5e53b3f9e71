/* The picture decoders' limits, with pictures made here by libjpeg and
 * libpng themselves: a progressive JPEG of 100 scans decodes and one of
 * 127 is refused (each scan is a pass over the whole picture; jpegtran
 * cannot write more than 100, so the test writes its own); a picture over
 * the caller's limit is refused from its header; a 16-bit PNG decodes to
 * the same 8-bit values as its 8-bit twin. */
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <jpeglib.h>
#include <png.h>

#include "picture_decode.h"

static int failures;

static void check(int ok, const char *what, const char *detail)
{
    printf("%s %s%s%s\n", ok ? "ok  " : "FAIL", what, detail && *detail ? ": " : "", detail ? detail : "");
    if (!ok) failures++;
}

/* A 32 x 32 grey JPEG, progressive: DC, then each of the 63 AC bands with
 * successive approximation (Al 1), then the refinement of the first
 * `refined` bands: 64 + refined scans. */
static unsigned char *progressive_jpeg(int refined, unsigned long *size)
{
    static jpeg_scan_info scans[1 + 63 + 63];
    struct jpeg_compress_struct c;
    struct jpeg_error_mgr e;
    unsigned char *out = NULL, px[32 * 32];
    for (int i = 0; i < 32 * 32; i++) px[i] = (unsigned char)((i * 37) ^ (i >> 3));
    int n = 0;
    scans[n++] = (jpeg_scan_info){1, {0}, 0, 0, 0, 0};
    for (int k = 1; k <= 63; k++) scans[n++] = (jpeg_scan_info){1, {0}, k, k, 0, 1};
    for (int k = 1; k <= refined; k++) scans[n++] = (jpeg_scan_info){1, {0}, k, k, 1, 0};
    c.err = jpeg_std_error(&e);
    jpeg_create_compress(&c);
    jpeg_mem_dest(&c, &out, size);
    c.image_width = c.image_height = 32;
    c.input_components = 1;
    c.in_color_space = JCS_GRAYSCALE;
    jpeg_set_defaults(&c);
    c.scan_info = scans;
    c.num_scans = n;
    jpeg_start_compress(&c, TRUE);
    while (c.next_scanline < 32) {
        JSAMPROW row = px + 32 * c.next_scanline;
        jpeg_write_scanlines(&c, &row, 1);
    }
    jpeg_finish_compress(&c);
    jpeg_destroy_compress(&c);
    return out;
}

typedef struct membuf { uint8_t *p; size_t n, cap; } membuf;

static void mem_write(png_structp png, png_bytep data, png_size_t n)
{
    membuf *m = png_get_io_ptr(png);
    if (m->n + n > m->cap) {
        uint8_t *grown = realloc(m->p, 2 * (m->n + n));
        if (!grown) png_error(png, "out of memory");
        m->p = grown;
        m->cap = 2 * (m->n + n);
    }
    memcpy(m->p + m->n, data, n);
    m->n += n;
}

static void mem_flush(png_structp png) { (void)png; }

/* An RGB PNG of `depth` bits a channel (big-endian rows, as PNG stores
 * them), with no gamma, sRGB or ICC chunk. */
static uint8_t *plain_png(const uint8_t *rows, int w, int h, int depth, size_t *size)
{
    membuf m = {NULL, 0, 0};
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        free(m.p);
        return NULL;
    }
    png_set_write_fn(png, &m, mem_write, mem_flush);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, depth, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < h; y++) png_write_row(png, rows + (size_t)y * w * 3 * (depth / 8));
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    *size = m.n;
    return m.p;
}

int main(void)
{
    static const jd_picture_limits lim = {64, 64 * 64}, small = {16, 16 * 16};
    char err[256], detail[320];
    uint8_t *px;
    uint32_t w, h;

    unsigned long n100 = 0, n127 = 0;
    unsigned char *j100 = progressive_jpeg(36, &n100), *j127 = progressive_jpeg(63, &n127);
    int rc = jd_jpeg_decode(j100, n100, 3, &lim, &px, &w, &h, err, sizeof err);
    snprintf(detail, sizeof detail, "%s", rc ? err : "32 x 32");
    check(rc == 0 && w == 32 && h == 32, "a progressive JPEG of 100 scans decodes", detail);
    free(px);
    rc = jd_jpeg_decode(j127, n127, 3, &lim, &px, &w, &h, err, sizeof err);
    check(rc != 0 && strstr(err, "more than 100 progressive scans") && !px, "one of 127 scans is refused",
          rc ? err : "decoded");
    rc = jd_jpeg_decode(j100, n100, 4, &small, &px, &w, &h, err, sizeof err);
    check(rc != 0 && strstr(err, "over jade's limit"), "a JPEG over the caller's limit is refused", err);
    free(j100);
    free(j127);

    /* The same 24 x 20 RGB picture as 8 and 16 bits a channel, neither
     * with a gamma chunk (as most tools write them). */
    enum { PW = 24, PH = 20 };
    uint8_t p8[PW * PH * 3], p16[PW * PH * 6];
    for (int i = 0; i < PW * PH * 3; i++) p16[2 * i] = p16[2 * i + 1] = p8[i] = (uint8_t)(i * 29 + (i >> 4));
    size_t s8 = 0, s16 = 0;
    uint8_t *b8 = plain_png(p8, PW, PH, 8, &s8), *b16 = plain_png(p16, PW, PH, 16, &s16);
    uint8_t *a = NULL, *b = NULL;
    uint32_t aw, ah, bw, bh;
    int ra = jd_png_decode(b8, s8, 3, &lim, &a, &aw, &ah, err, sizeof err);
    int rb = jd_png_decode(b16, s16, 3, &lim, &b, &bw, &bh, err, sizeof err);
    int same = ra == 0 && rb == 0 && aw == PW && bw == PW && ah == PH && bh == PH && !memcmp(a, p8, sizeof p8) &&
               !memcmp(b, p8, sizeof p8);
    check(same, "a 16-bit PNG decodes to its 8-bit twin's values", ra || rb ? err : "");
    free(a);
    free(b);
    rc = jd_png_decode(b8, s8, 3, &small, &px, &w, &h, err, sizeof err);
    check(rc != 0 && strstr(err, "declares 24 x 20 pixels, over jade's limit") && !px,
          "a PNG over the caller's limit is refused", err);
    free(b8);
    free(b16);
    printf("picture decode: %d failed\n", failures);
    return failures ? 1 : 0;
}
