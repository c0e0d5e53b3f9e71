#include "image_metric.h"
#include "image_in.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double luminance(const float *p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

/* SSIM on luminance with an 8x8 window sliding by 4, windows counted when
 * their centre pixel is in the mask; constants from the reference's peak. */
static double ssim(const float *a, const float *b, const unsigned char *mask, int w, int h, double k, double peak)
{
    const double c1 = (0.01 * peak) * (0.01 * peak), c2 = (0.03 * peak) * (0.03 * peak);
    double sum = 0;
    long n = 0;
    for (int y = 0; y + 8 <= h; y += 4)
        for (int x = 0; x + 8 <= w; x += 4) {
            if (mask && !mask[(y + 4) * w + x + 4]) continue;
            double ma = 0, mb = 0, va = 0, vb = 0, cov = 0;
            for (int j = 0; j < 8; j++)
                for (int i = 0; i < 8; i++) {
                    size_t o = (size_t)(y + j) * w + x + i;
                    double la = k * luminance(a + 3 * o), lb = luminance(b + 3 * o);
                    ma += la; mb += lb; va += la * la; vb += lb * lb; cov += la * lb;
                }
            ma /= 64; mb /= 64;
            va = va / 64 - ma * ma; vb = vb / 64 - mb * mb; cov = cov / 64 - ma * mb;
            sum += ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
            n++;
        }
    return n ? sum / n : 1.0;
}

static void errors(const float *a, const float *b, const unsigned char *mask, int w, int h, double k, double peak,
                   double *rmse, double *psnr)
{
    double se = 0;
    long n = 0;
    for (long i = 0; i < (long)w * h; i++) {
        if (mask && !mask[i]) continue;
        for (int c = 0; c < 3; c++) {
            double d = k * a[3 * i + c] - b[3 * i + c];
            se += d * d;
        }
        n++;
    }
    *rmse = n ? sqrt(se / (3.0 * n)) : 0.0;
    *psnr = *rmse > 0 ? 20.0 * log10(peak / *rmse) : INFINITY;
}

/* The luminance of A - B less its mean over the box around each pixel,
 * RMS over the pixels whose whole box lies in the mask (the outline, where
 * a pixel's coverage differs, is the RMSE's business). Box sums from a
 * summed-area table: one pass whatever the radius. */
static void highpass(const float *a, const float *b, const unsigned char *mask, int w, int h, double *rms, long *count)
{
    const int r = JD_HIGHPASS_RADIUS, side = 2 * r + 1;
    size_t stride = (size_t)w + 1;
    double *sd = calloc(stride * (h + 1), sizeof *sd); /* sums of the difference */
    long *sm = calloc(stride * (h + 1), sizeof *sm);   /* counts of mask pixels */
    *rms = 0;
    *count = 0;
    if (!sd || !sm) { free(sd); free(sm); return; }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * w + x, o = (size_t)(y + 1) * stride + x + 1;
            int in = !mask || mask[i];
            double d = in ? luminance(a + 3 * i) - luminance(b + 3 * i) : 0.0;
            sd[o] = d + sd[o - 1] + sd[o - stride] - sd[o - stride - 1];
            sm[o] = in + sm[o - 1] + sm[o - stride] - sm[o - stride - 1];
        }
    double se = 0;
    long n = 0;
    for (int y = r; y + r < h; y++)
        for (int x = r; x + r < w; x++) {
            size_t y0 = (size_t)(y - r) * stride, y1 = (size_t)(y + r + 1) * stride;
            size_t x0 = (size_t)(x - r), x1 = (size_t)(x + r + 1);
            if (sm[y1 + x1] - sm[y1 + x0] - sm[y0 + x1] + sm[y0 + x0] != (long)side * side) continue;
            double mean = (sd[y1 + x1] - sd[y1 + x0] - sd[y0 + x1] + sd[y0 + x0]) / ((double)side * side);
            size_t i = (size_t)y * w + x;
            double hp = luminance(a + 3 * i) - luminance(b + 3 * i) - mean;
            se += hp * hp;
            n++;
        }
    free(sd);
    free(sm);
    *rms = n ? sqrt(se / n) : 0.0;
    *count = n;
}

void jd_metric_compute(const float *a, const float *b, const unsigned char *mask, int w, int h, jd_metric *m)
{
    memset(m, 0, sizeof *m);
    double ab = 0, aa = 0, peak = 0;
    for (long i = 0; i < (long)w * h; i++) {
        if (mask && !mask[i]) continue;
        m->pixels++;
        for (int c = 0; c < 3; c++) {
            ab += (double)a[3 * i + c] * b[3 * i + c];
            aa += (double)a[3 * i + c] * a[3 * i + c];
            if (b[3 * i + c] > peak) peak = b[3 * i + c];
        }
    }
    m->peak = peak > 0 ? peak : 1.0;
    m->scale = aa > 0 ? ab / aa : 1.0;
    errors(a, b, mask, w, h, 1.0, m->peak, &m->rmse, &m->psnr);
    errors(a, b, mask, w, h, m->scale, m->peak, &m->rmse_scaled, &m->psnr_scaled);
    m->ssim = ssim(a, b, mask, w, h, 1.0, m->peak);
    m->ssim_scaled = ssim(a, b, mask, w, h, m->scale, m->peak);
    highpass(a, b, mask, w, h, &m->highpass, &m->highpass_pixels);
}
