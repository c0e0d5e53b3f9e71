/* jade metric's arithmetic on synthetic pictures. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "display_curve.h"
#include "image_in.h"
#include "image_metric.h"

enum { W = 64, H = 48 };
static float a[W * H * 3], b[W * H * 3];

static void write_pfm(const char *path, const char *header, const float *v, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f) return;
    fputs(header, f);
    fwrite(v, sizeof(float), n, f);
    fclose(f);
}

int main(void)
{
    srand(7);
    for (int i = 0; i < W * H * 3; i++) b[i] = 0.1f + 0.6f * (float)((i / 3) % W) / W + 0.05f * (float)(i % 3);
    jd_metric m;
    jd_metric_compute(b, b, NULL, W, H, &m);
    CHECK(m.rmse == 0 && fabs(m.ssim - 1) < 1e-9 && fabs(m.scale - 1) < 1e-9, "identical pictures");
    for (int i = 0; i < W * H * 3; i++) a[i] = 2.0f * b[i];
    jd_metric_compute(a, b, NULL, W, H, &m);
    CHECK(fabs(m.scale - 0.5) < 1e-6 && m.rmse_scaled < 1e-6 && fabs(m.ssim_scaled - 1) < 1e-6 && m.rmse > 0.1,
          "a pure gain is found and removed (scale %.4f, rmse %.4f -> %.6f)", m.scale, m.rmse, m.rmse_scaled);
    for (int i = 0; i < W * H * 3; i++) a[i] = b[i] + 0.05f * ((float)rand() / RAND_MAX - 0.5f);
    jd_metric_compute(a, b, NULL, W, H, &m);
    CHECK(m.ssim < 0.999 && m.ssim > 0.5 && m.psnr > 20 && m.psnr < 60, "noise: ssim %.4f psnr %.1f dB", m.ssim, m.psnr);
    unsigned char mask[W * H] = {0};
    for (int i = 0; i < W * H; i++) mask[i] = (i % W) < W / 2;
    for (int i = 0; i < W * H * 3; i++) a[i] = ((i / 3) % W) < W / 2 ? b[i] : 0.0f;
    jd_metric_compute(a, b, mask, W, H, &m);
    CHECK(m.pixels == W * H / 2 && m.rmse == 0, "the mask confines the comparison (%ld px)", m.pixels);
    /* The high-pass measure: a smooth difference (a ramp, a gain) is not a
     * blotch; a 4-pixel blotch is, whatever the mask's edge does. */
    for (int i = 0; i < W * H * 3; i++) a[i] = b[i] + 0.002f * (float)((i / 3) % W);
    jd_metric_compute(a, b, NULL, W, H, &m);
    CHECK(m.highpass < 1e-6 && m.rmse > 0.01 && m.highpass_pixels == (W - 8) * (H - 8),
          "a ramp of difference is no blotch (highpass %.2g over %ld px)", m.highpass, m.highpass_pixels);
    memcpy(a, b, sizeof a);
    for (int y = 20; y < 24; y++)
        for (int x = 10; x < 14; x++)
            for (int c = 0; c < 3; c++) a[3 * (y * W + x) + c] += 0.1f;
    jd_metric_compute(a, b, mask, W, H, &m);
    CHECK(m.highpass > 0.01 && m.highpass_pixels == (W / 2 - 8) * (H - 8), "a blotch is (highpass %.4f over %ld px)",
          m.highpass, m.highpass_pixels);
    /* jade writes sqrt(min(1, c / (1 + 0.15 c))); the metric undoes it up
     * to where it clips (c = 1/0.85). */
    double worst = 0;
    for (double c = 0.0; c <= 1.1; c += 0.01) {
        double t = c / (1 + 0.15 * c);
        unsigned char v = (unsigned char)(sqrt(t) * 255.0 + 0.5);
        double back = jd_display_to_linear(v);
        if (fabs(back - c) / (c + 0.05) > worst) worst = fabs(back - c) / (c + 0.05);
    }
    CHECK(worst < 0.03, "display encoding undone within 8-bit rounding (worst %.4f relative)", worst);
    /* PFM: rows stored bottom-up, read back top-down. */
    char path[] = "/tmp/jade-metric-XXXXXX";
    close(mkstemp(path));
    float rows[12] = {0, 0, 0, 1, 1, 1, /* bottom row */ 2, 2, 2, 3, 3, 3 /* top row */};
    int w = 0, h = 0;
    char why[120] = "";
    write_pfm(path, "PF\n2 2\n-1.0\n", rows, 12);
    float *img = jd_pfm_load(path, &w, &h, why, sizeof why);
    CHECK(img && w == 2 && h == 2 && img[0] == 2 && img[3] == 3 && img[9] == 1, "PFM read top-down: %s", why);
    free(img);
    write_pfm(path, "PF\n2 2\n-1.0\n", rows, 5);
    CHECK(!jd_pfm_load(path, &w, &h, why, sizeof why) && strstr(why, "should hold 48 bytes"), "truncated PFM refused: %s", why);
    /* Windows tools end header lines with CR LF: one byte more, not one off. */
    write_pfm(path, "PF\r\n2 2\r\n-1.0\r\n", rows, 12);
    img = jd_pfm_load(path, &w, &h, why, sizeof why);
    CHECK(img && img[0] == 2 && img[3] == 3 && img[9] == 1, "PFM with CR LF read exactly: %s", why);
    free(img);
    /* 2^32 + 2 must not wrap round to 2. */
    write_pfm(path, "PF\n4294967298 2\n-1.0\n", rows, 12);
    CHECK(!jd_pfm_load(path, &w, &h, why, sizeof why) && strstr(why, "4294967298"), "PFM width past 2^32 refused: %s", why);
    unlink(path);
    CHECK(!jd_pfm_decode((const unsigned char *)"PF", 2, &w, &h, why, sizeof why), "a bare PF refused: %s", why);
    return jd_check_summary("metric");
}
