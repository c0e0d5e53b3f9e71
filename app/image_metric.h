/* Image comparison in linear light: what jade's pictures are judged by
 * against a reference. */
#ifndef JD_IMAGE_METRIC_H
#define JD_IMAGE_METRIC_H

#include <stddef.h>

typedef struct jd_metric {
    long pixels;           /* pixels compared (the mask) */
    double rmse, psnr, ssim;
    double scale;          /* best single factor k for k*A against B */
    double rmse_scaled, psnr_scaled, ssim_scaled;
    double peak;           /* the largest linear value of B in the mask */
    double highpass;       /* blotches: RMS of A - B's luminance less its local mean (JD_HIGHPASS_RADIUS) */
    long highpass_pixels;  /* where that is measured: mask pixels whose whole box is in the mask */
} jd_metric;

/* The box (2r + 1 pixels a side) whose mean the high-pass measure takes out:
 * what is left are blotches, streaks and steps a few pixels wide, not the
 * smooth differences the RMSE already counts. */
#define JD_HIGHPASS_RADIUS 4

/* A and B: w*h*3 linear floats; mask: w*h bytes, nonzero = compared (NULL: all). */
void jd_metric_compute(const float *a, const float *b, const unsigned char *mask, int w, int h, jd_metric *out);

#endif
