/* jade metric A B [--mask M]: how far picture A is from the reference B,
 * in linear light, as JSON. PNGs are jade's display encoding (undone);
 * PFMs are linear already. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>

#include "commands.h"
#include "display_curve.h"
#include "image_in.h"
#include "image_metric.h"

static float *read_image(const char *path, int *w, int *h, unsigned char **rgba, char *why, size_t cap)
{
    size_t len = strlen(path);
    if (len > 4 && !strcmp(path + len - 4, ".pfm")) return jd_read_pfm(path, w, h, why, cap);
    unsigned char *px = jd_image_load(path, w, h, 4, why, cap);
    if (!px) return NULL;
    float *out = malloc((size_t)*w * *h * 3 * sizeof(float));
    if (!out) { stbi_image_free(px); snprintf(why, cap, "out of memory"); return NULL; }
    for (long i = 0; i < (long)*w * *h; i++)
        for (int k = 0; k < 3; k++) out[3 * i + k] = jd_display_to_linear(px[4 * i + k]);
    if (rgba) *rgba = px; else stbi_image_free(px);
    return out;
}

int jd_cmd_metric(int argc, char **argv)
{
    const char *paths[2] = {NULL, NULL}, *mask_path = NULL;
    int np = 0;
    for (int i = 2; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            printf("usage: jade metric A B [--mask M.png]\n"
                   "Compares picture A with the reference B in linear light (PNGs in jade's display encoding, or\n"
                   "linear PFMs): RMSE, PSNR and SSIM over the object's pixels, and the same after the single\n"
                   "best global scale of A. The object is M's nonzero pixels, or where either picture differs\n"
                   "from its top-left (background) pixel. Prints JSON. jade's PNGs clip at linear 1.18 (its\n"
                   "tone curve reaches white there): compare PFMs where brighter values matter.\n");
            return 0;
        }
        if (!strcmp(argv[i], "--mask")) {
            if (i + 1 >= argc) { fprintf(stderr, "jade metric: --mask needs a value\n"); return 2; }
            mask_path = argv[++i];
        } else if (argv[i][0] == '-' && argv[i][1]) {
            fprintf(stderr, "jade metric: unknown option '%s' (see jade metric --help)\n", argv[i]);
            return 2;
        } else if (np < 2) {
            paths[np++] = argv[i];
        } else {
            fprintf(stderr, "jade metric: one picture too many: '%s'\n", argv[i]);
            return 2;
        }
    }
    if (np != 2) { fprintf(stderr, "jade metric: needs two pictures, A and the reference B\n"); return 2; }
    int w[2], h[2];
    unsigned char *rgba[2] = {NULL, NULL};
    float *img[2];
    char why[160];
    for (int k = 0; k < 2; k++) {
        img[k] = read_image(paths[k], &w[k], &h[k], &rgba[k], why, sizeof why);
        if (!img[k]) {
            fprintf(stderr, "jade metric: %s: %s\n", paths[k], why);
            return 1;
        }
    }
    if (w[0] != w[1] || h[0] != h[1]) {
        fprintf(stderr, "jade metric: %s is %dx%d but %s is %dx%d\n", paths[0], w[0], h[0], paths[1], w[1], h[1]);
        return 1;
    }
    long n = (long)w[0] * h[0];
    unsigned char *mask = malloc((size_t)n);
    if (mask_path) {
        int mw, mh;
        char why[160];
        unsigned char *m = jd_image_load(mask_path, &mw, &mh, 1, why, sizeof why);
        if (!m || mw != w[0] || mh != h[0]) {
            fprintf(stderr, "jade metric: %s: %s\n", mask_path, m ? "not the pictures' size" : why);
            stbi_image_free(m);
            return 1;
        }
        for (long i = 0; i < n; i++) mask[i] = m[i] != 0;
        stbi_image_free(m);
    } else {
        for (long i = 0; i < n; i++) {
            int differs = 0;
            for (int k = 0; k < 2; k++)
                for (int c = 0; c < 3; c++)
                    if (fabsf(img[k][3 * i + c] - img[k][c]) > 1e-4f) differs = 1;
            mask[i] = (unsigned char)differs;
        }
    }
    jd_metric m;
    jd_metric_compute(img[0], img[1], mask, w[0], h[0], &m);
    printf("{\"a\": \"%s\", \"b\": \"%s\", \"pixels\": %ld, \"rmse\": %.6f, \"psnr_db\": %.3f, \"ssim\": %.5f, "
           "\"best_scale\": %.5f, \"rmse_scaled\": %.6f, \"psnr_scaled_db\": %.3f, \"ssim_scaled\": %.5f, "
           "\"reference_peak\": %.5f}\n",
           paths[0], paths[1], m.pixels, m.rmse, isfinite(m.psnr) ? m.psnr : 999.0, m.ssim, m.scale, m.rmse_scaled,
           isfinite(m.psnr_scaled) ? m.psnr_scaled : 999.0, m.ssim_scaled, m.peak);
    for (int k = 0; k < 2; k++) { free(img[k]); if (rgba[k]) stbi_image_free(rgba[k]); }
    free(mask);
    return 0;
}
