/* jade metric A B [--mask M]: how far picture A is from the reference B,
 * in linear light, as JSON. PNGs are jade's display encoding (undone);
 * PFMs are linear already. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


#include "commands.h"
#include "display_curve.h"
#include "image_in.h"
#include "image_metric.h"
#include "json_out.h"
#include "options.h"

/* Chosen by content, not by name: a PFM starts "PF" and white space. */
static float *read_image(const char *path, int *w, int *h, char *why, size_t cap)
{
    size_t n;
    unsigned char *buf = jd_input_read(path, &n, why, cap);
    if (!buf) return NULL;
    if (n > 2 && buf[0] == 'P' && buf[1] == 'F' && isspace(buf[2])) {
        float *img = jd_pfm_decode(buf, n, w, h, why, cap);
        free(buf);
        return img;
    }
    unsigned char *px = jd_image_decode(buf, n, w, h, 4, why, cap);
    free(buf);
    if (!px) return NULL;
    float *out = malloc((size_t)*w * *h * 3 * sizeof(float));
    if (!out) { free(px); snprintf(why, cap, "out of memory"); return NULL; }
    for (long i = 0; i < (long)*w * *h; i++)
        for (int k = 0; k < 3; k++) out[3 * i + k] = jd_display_to_linear(px[4 * i + k]);
    free(px); /* only the linear copy is compared */
    return out;
}

static int metric(const char *paths[2], const char *mask_path)
{
    int w[2] = {0, 0}, h[2] = {0, 0}, rc = 1;
    unsigned char *mask = NULL, *m = NULL;
    float *img[2] = {NULL, NULL};
    char why[160];
    for (int k = 0; k < 2; k++) {
        img[k] = read_image(paths[k], &w[k], &h[k], why, sizeof why);
        if (!img[k]) {
            fprintf(stderr, "jade metric: %s: %s\n", paths[k], why);
            goto done;
        }
    }
    if (w[0] != w[1] || h[0] != h[1]) {
        fprintf(stderr, "jade metric: %s is %dx%d but %s is %dx%d\n", paths[0], w[0], h[0], paths[1], w[1], h[1]);
        goto done;
    }
    long n = (long)w[0] * h[0], pixels = 0;
    mask = malloc((size_t)n);
    if (!mask) { fprintf(stderr, "jade metric: out of memory for a %dx%d mask\n", w[0], h[0]); goto done; }
    if (mask_path) {
        int mw, mh;
        m = jd_image_load(mask_path, &mw, &mh, 1, why, sizeof why);
        if (!m || mw != w[0] || mh != h[0]) {
            fprintf(stderr, "jade metric: %s: %s\n", mask_path, m ? "not the pictures' size" : why);
            goto done;
        }
        for (long i = 0; i < n; i++) pixels += mask[i] = m[i] != 0;
    } else {
        for (long i = 0; i < n; i++) {
            int differs = 0;
            for (int k = 0; k < 2; k++)
                for (int c = 0; c < 3; c++)
                    if (fabsf(img[k][3 * i + c] - img[k][c]) > 1e-4f) differs = 1;
            pixels += mask[i] = (unsigned char)differs;
        }
    }
    /* No pixel to compare: any figure would be a made-up perfect score. */
    if (pixels == 0) {
        if (mask_path)
            fprintf(stderr, "jade metric: %s: the mask has no nonzero pixel; nothing to compare\n", mask_path);
        else
            fprintf(stderr, "jade metric: %s, %s: no pixel differs from its picture's corner, so there is no object "
                            "to compare; pass --mask\n", paths[0], paths[1]);
        goto done;
    }
    jd_metric r;
    jd_metric_compute(img[0], img[1], mask, w[0], h[0], &r);
    printf("{\"a\": ");
    jd_json_string(stdout, paths[0]);
    printf(", \"b\": ");
    jd_json_string(stdout, paths[1]);
    printf(", \"pixels\": %ld, \"rmse\": %.6f, \"psnr_db\": %.3f, \"ssim\": %.5f, "
           "\"best_scale\": %.5f, \"rmse_scaled\": %.6f, \"psnr_scaled_db\": %.3f, \"ssim_scaled\": %.5f, "
           "\"reference_peak\": %.5f, \"highpass_rmse\": %.6f, \"highpass_pixels\": %ld}\n",
           r.pixels, r.rmse, isfinite(r.psnr) ? r.psnr : 999.0, r.ssim, r.scale, r.rmse_scaled,
           isfinite(r.psnr_scaled) ? r.psnr_scaled : 999.0, r.ssim_scaled, r.peak, r.highpass, r.highpass_pixels);
    rc = fflush(stdout) == 0 && !ferror(stdout) ? 0 : 1;
done:
    for (int k = 0; k < 2; k++) free(img[k]);
    free(m);
    free(mask);
    return rc;
}

int jd_cmd_metric(int argc, char **argv)
{
    jd_options o;
    jd_options_defaults(&o);
    int rc = jd_options_command(
        &o, JD_OPT_METRIC, "metric",
        "Compares picture A with the reference B in linear light (PNGs in jade's display encoding, or\n"
        "linear PFMs): RMSE, PSNR and SSIM over the object's pixels, and the same after the single\n"
        "best global scale of A; and highpass_rmse, for blotches and steps: the RMS of the difference's\n"
        "luminance less its mean over the 9x9 pixels around, where they all lie on the object. The\n"
        "object is M's nonzero pixels, or where either picture differs\n"
        "from its top-left (background) pixel; no such pixel is an error. Prints JSON. jade's PNGs clip\n"
        "at linear 1.18 (its tone curve reaches white there): compare PFMs where brighter values matter.",
        argc, argv);
    if (rc >= 0) return rc;
    if (o.num_positional != 2) {
        fprintf(stderr, "jade metric: needs two pictures, A and the reference B\n");
        return 2;
    }
    return metric(o.positional, o.mask_in);
}
