/* flicker_measure MASK FRAME... : how much a still object's pixels jump
 * from frame to frame while the light moves, the frames in order (the first
 * and last count only as neighbours). Over the mask's pixels, luminance in
 * linear light: `step`, the RMS of one frame's change to the next (the
 * light's own motion moves shading smoothly), and `jerk`, the RMS of the
 * second difference f(t+1) - 2 f(t) + f(t-1): a smooth change leaves almost
 * none, a pixel that pops (a shadow edge stepping a texel, a blotch
 * crossing) leaves it whole. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <stb_image.h>

#include "display_curve.h"

int main(int argc, char **argv)
{
    if (argc < 5) {
        fprintf(stderr, "usage: flicker_measure MASK FRAME FRAME FRAME...\n");
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
    if (!lum) { fprintf(stderr, "flicker_measure: out of memory for %d frames\n", n); return 1; }
    for (int k = 0; k < n; k++) {
        int fw, fh;
        unsigned char *img = stbi_load(argv[2 + k], &fw, &fh, &c, 3);
        if (!img || fw != w || fh != h) {
            fprintf(stderr, "flicker_measure: %s: %s\n", argv[2 + k], img ? "not the mask's size" : stbi_failure_reason());
            return 1;
        }
        for (size_t i = 0; i < px; i++)
            lum[k * px + i] = (float)jd_display_luminance(img + 3 * i);
        stbi_image_free(img);
    }
    double s1 = 0, s2 = 0;
    long cnt = 0;
    for (size_t i = 0; i < px; i++) {
        if (!mask[i]) continue;
        for (int k = 1; k + 1 < n; k++) {
            double prev = lum[(size_t)(k - 1) * px + i], cur = lum[(size_t)k * px + i], next = lum[(size_t)(k + 1) * px + i];
            s1 += (next - cur) * (next - cur);
            s2 += (next - 2 * cur + prev) * (next - 2 * cur + prev);
            cnt++;
        }
    }
    if (!cnt) { fprintf(stderr, "flicker_measure: %s: no pixel in the mask\n", argv[1]); return 1; }
    printf("{\"frames\": %d, \"pixels\": %ld, \"step\": %.6f, \"jerk\": %.6f}\n", n, cnt / (n - 2), sqrt(s1 / cnt),
           sqrt(s2 / cnt));
    free(lum);
    stbi_image_free(mask);
    return 0;
}
