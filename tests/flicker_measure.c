/* flicker_measure [--map OUT.pgm] MASK FRAME... : how much a still object's
 * pixels jump from frame to frame while the light moves, the frames in order
 * (the first and last count only as neighbours). Over the mask's pixels,
 * luminance in linear light: `step`, the RMS of one frame's change to the
 * next (the light's own motion moves shading smoothly), and `jerk`, the RMS
 * of the second difference f(t+1) - 2 f(t) + f(t-1): a smooth change leaves
 * almost none, a pixel that pops (a shadow edge stepping a texel, a blotch
 * crossing) leaves it whole. Beside them: `rounding`, the jerk that 8 bits
 * alone leave, each pixel ramped evenly from its first frame to its last and
 * rounded as the frames were (no picture of the sequence written in 8 bits
 * goes much below it), and `top1`, the share of the squared second
 * differences that the largest 1% of them hold (a few edges stepping, near
 * 1; pops spread over the surface, small). --map writes each pixel's RMS
 * second difference as a grey PGM, 2040 grey levels to one unit of
 * luminance (0.125 is white), outside the mask black. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>

#include "display_curve.h"

static int larger_first(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? 1 : x > y ? -1 : 0;
}

int main(int argc, char **argv)
{
    const char *map = NULL;
    if (argc > 2 && !strcmp(argv[1], "--map")) map = argv[2], argv += 2, argc -= 2;
    if (argc < 5) {
        fprintf(stderr, "usage: flicker_measure [--map OUT.pgm] MASK FRAME FRAME FRAME...\n");
        return 2;
    }
    int w, h, c, n = argc - 2;
    unsigned char *mask = stbi_load(argv[1], &w, &h, &c, 1);
    if (!mask) {
        fprintf(stderr, "flicker_measure: %s: %s\n", argv[1], stbi_failure_reason());
        return 1;
    }
    size_t px = (size_t)w * h;
    float *lum = malloc(sizeof(float) * px * (size_t)n);
    unsigned char *first = malloc(3 * px), *last = malloc(3 * px);
    double *pixel = calloc(px, sizeof(double)), *events = malloc(sizeof(double) * px * (size_t)(n - 2));
    if (!lum || !first || !last || !pixel || !events) {
        fprintf(stderr, "flicker_measure: out of memory for %d frames\n", n);
        return 1;
    }
    for (int k = 0; k < n; k++) {
        int fw, fh;
        unsigned char *img = stbi_load(argv[2 + k], &fw, &fh, &c, 3);
        if (!img || fw != w || fh != h) {
            fprintf(stderr, "flicker_measure: %s: %s\n", argv[2 + k], img ? "not the mask's size" : stbi_failure_reason());
            return 1;
        }
        for (size_t i = 0; i < px; i++)
            lum[k * px + i] = (float)jd_display_luminance(img + 3 * i);
        if (k == 0) memcpy(first, img, 3 * px);
        if (k == n - 1) memcpy(last, img, 3 * px);
        stbi_image_free(img);
    }
    double s1 = 0, s2 = 0, s3 = 0;
    long cnt = 0;
    for (size_t i = 0; i < px; i++) {
        if (!mask[i]) continue;
        double ramp[3] = {0, 0, 0}; /* the rounded ramp's last three frames */
        for (int k = 0; k < n; k++) {
            unsigned char q[3];
            for (int ch = 0; ch < 3; ch++)
                q[ch] = (unsigned char)lrint(first[3 * i + ch] + (last[3 * i + ch] - first[3 * i + ch]) * (double)k / (n - 1));
            ramp[0] = ramp[1], ramp[1] = ramp[2], ramp[2] = jd_display_luminance(q);
            if (k >= 2) s3 += (ramp[2] - 2 * ramp[1] + ramp[0]) * (ramp[2] - 2 * ramp[1] + ramp[0]);
        }
        for (int k = 1; k + 1 < n; k++) {
            double prev = lum[(size_t)(k - 1) * px + i], cur = lum[(size_t)k * px + i], next = lum[(size_t)(k + 1) * px + i];
            double d2 = (next - 2 * cur + prev) * (next - 2 * cur + prev);
            s1 += (next - cur) * (next - cur);
            s2 += d2;
            pixel[i] += d2;
            events[cnt++] = d2;
        }
    }
    if (!cnt) { fprintf(stderr, "flicker_measure: %s: no pixel in the mask\n", argv[1]); return 1; }
    qsort(events, (size_t)cnt, sizeof(double), larger_first);
    double top = 0;
    for (long k = 0; k < cnt / 100; k++) top += events[k];
    if (map) {
        FILE *o = fopen(map, "wb");
        if (!o) { fprintf(stderr, "flicker_measure: %s: cannot write it\n", map); return 1; }
        fprintf(o, "P5\n%d %d\n255\n", w, h);
        for (size_t i = 0; i < px; i++) {
            double v = mask[i] ? 2040.0 * sqrt(pixel[i] / (n - 2)) : 0.0;
            fputc(v > 255.0 ? 255 : (int)v, o);
        }
        if (fclose(o)) { fprintf(stderr, "flicker_measure: %s: the write failed\n", map); return 1; }
    }
    printf("{\"frames\": %d, \"pixels\": %ld, \"step\": %.6f, \"rounding\": %.6f, \"top1\": %.3f, \"jerk\": %.6f}\n", n,
           cnt / (n - 2), sqrt(s1 / cnt), sqrt(s3 / cnt), s2 > 0 ? top / s2 : 0.0, sqrt(s2 / cnt));
    free(lum), free(first), free(last), free(pixel), free(events);
    stbi_image_free(mask);
    return 0;
}
