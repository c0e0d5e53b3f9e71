/* JPEG through libjpeg-turbo. Its errors longjmp back here; its warnings
 * (corrupt or cut data, which it would paint grey) are refusals too, but
 * for stray bytes before a marker, which many cameras write. A progressive
 * JPEG may declare thousands of scans, each one a pass over the whole
 * picture: more than JD_JPEG_MAX_SCANS are refused (libjpeg-turbo's own
 * advice for untrusted input), and its memory manager stops at a budget. */
#include "picture_decode.h"

#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <jpeglib.h>
#include <jerror.h>

enum { JD_JPEG_MAX_SCANS = 100 };

typedef struct jpeg_failure {
    struct jpeg_error_mgr mgr;
    jmp_buf back;
    char why[JMSG_LENGTH_MAX + 64];
} jpeg_failure;

static void on_error(j_common_ptr c)
{
    jpeg_failure *f = (jpeg_failure *)c->err;
    c->err->format_message(c, f->why);
    longjmp(f->back, 1);
}

static void on_message(j_common_ptr c, int level)
{
    if (level < 0 && c->err->msg_code != JWRN_EXTRANEOUS_DATA) on_error(c);
}

static void on_progress(j_common_ptr c)
{
    j_decompress_ptr d = (j_decompress_ptr)c;
    if (d->input_scan_number > JD_JPEG_MAX_SCANS) {
        jpeg_failure *f = (jpeg_failure *)c->err;
        snprintf(f->why, sizeof f->why, "more than %d progressive scans", JD_JPEG_MAX_SCANS);
        longjmp(f->back, 1);
    }
}

int jd_jpeg_decode(const uint8_t *data, size_t n, int channels, const jd_picture_limits *lim, uint8_t **px,
                   uint32_t *w, uint32_t *h, char *err, size_t errlen)
{
    *px = NULL;
    *w = *h = 0;
    if (n > 0xffffffffu) {
        snprintf(err, errlen, "%zu bytes, more than a JPEG jade reads", n);
        return -1;
    }
    struct jpeg_decompress_struct d;
    jpeg_failure f;
    struct jpeg_progress_mgr progress;
    /* Everything the jump back reads is volatile or set before setjmp. */
    uint8_t *volatile buf = NULL;
    volatile int stage = 0; /* 0 header, 1 pixels */
    memset(&d, 0, sizeof d);
    memset(&f, 0, sizeof f);
    d.err = jpeg_std_error(&f.mgr);
    f.mgr.error_exit = on_error;
    f.mgr.emit_message = on_message;
    if (setjmp(f.back)) {
        /* The frame header may have been read before the failure: a
         * declared size over the limit is the better reason. */
        if (stage == 0 && d.image_width && !jd_picture_fits(d.image_width, d.image_height, lim))
            jd_picture_too_big(d.image_width, d.image_height, lim, err, errlen);
        else
            snprintf(err, errlen, "the JPEG %s does not %s (%s)", stage ? "data" : "header",
                     stage ? "decode" : "parse", f.why);
        free(buf);
        jpeg_destroy_decompress(&d);
        return -1;
    }
    jpeg_create_decompress(&d);
    /* The coefficients of a 4096 x 4096 progressive 4:4:4 picture take
     * 96 MiB; more than 160 MiB is refused, not swapped. */
    d.mem->max_memory_to_use = 160L << 20;
    progress.progress_monitor = on_progress;
    d.progress = &progress;
    jpeg_mem_src(&d, data, (unsigned long)n);
    jpeg_read_header(&d, TRUE); /* TRUE: a stream of tables only is an error */
    if (!jd_picture_fits(d.image_width, d.image_height, lim)) {
        jd_picture_too_big(d.image_width, d.image_height, lim, err, errlen);
        jpeg_destroy_decompress(&d);
        return -1;
    }
    stage = 1;
    d.out_color_space = channels == 1 ? JCS_GRAYSCALE : channels == 3 ? JCS_RGB : JCS_EXT_RGBA;
    jpeg_start_decompress(&d);
    size_t stride = (size_t)d.output_width * (size_t)channels;
    buf = malloc(stride * d.output_height);
    if (!buf) {
        snprintf(f.why, sizeof f.why, "out of memory for %u x %u pixels", d.output_width, d.output_height);
        longjmp(f.back, 1);
    }
    while (d.output_scanline < d.output_height) {
        JSAMPROW row = buf + stride * d.output_scanline;
        jpeg_read_scanlines(&d, &row, 1);
    }
    jpeg_finish_decompress(&d);
    *px = buf;
    *w = d.output_width;
    *h = d.output_height;
    jpeg_destroy_decompress(&d);
    return 0;
}
