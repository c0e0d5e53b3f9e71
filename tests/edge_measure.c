/* edge_measure PICTURE X0 X1 Y0 Y1 MM_PER_PX: a shadow's edge that crosses
 * every column from X0 to X1 once between rows Y0 and Y1 (one end lit, the
 * other in the shadow). Per column: the rows where the luminance (linear)
 * crosses 20%, 50% and 80% of the way from the shadow's level to the lit
 * level. Prints the mean width from 20% to 80% and how far the 50% line
 * strays from a straight line (RMS; a shadow in stair steps strays by the
 * steps), both in millimetres. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <stb_image.h>

#include "display_curve.h"

/* The first row after y0 where the profile passes level t, between rows. */
static double crossing(const double *prof, int n, double t)
{
    for (int i = 0; i + 1 < n; i++) {
        double a = prof[i] - t, b = prof[i + 1] - t;
        if (a == 0) return i;
        if ((a < 0) != (b < 0)) return i + a / (a - b);
    }
    return -1;
}

int main(int argc, char **argv)
{
    if (argc != 7) {
        fprintf(stderr, "usage: edge_measure PICTURE X0 X1 Y0 Y1 MM_PER_PX\n");
        return 2;
    }
    int w, h, c;
    unsigned char *img = stbi_load(argv[1], &w, &h, &c, 3);
    if (!img) {
        fprintf(stderr, "edge_measure: %s: %s\n", argv[1], stbi_failure_reason());
        return 1;
    }
    int x0 = atoi(argv[2]), x1 = atoi(argv[3]), y0 = atoi(argv[4]), y1 = atoi(argv[5]);
    double mm = atof(argv[6]);
    if (x0 < 0 || x1 >= w || x0 > x1 || y0 < 0 || y1 >= h || y1 - y0 < 8 || !(mm > 0)) {
        fprintf(stderr, "edge_measure: %s: the window %d..%d x %d..%d is not inside %dx%d\n", argv[1], x0, x1, y0, y1, w, h);
        return 2;
    }
    int n = y1 - y0 + 1, cols = 0;
    double *prof = malloc(sizeof(double) * (size_t)n), *pos = malloc(sizeof(double) * 2 * (size_t)(x1 - x0 + 1));
    if (!prof || !pos) { fprintf(stderr, "edge_measure: out of memory\n"); return 1; }
    double width = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int x = x0; x <= x1; x++) {
        for (int i = 0; i < n; i++) prof[i] = jd_display_luminance(img + 3 * ((size_t)(y0 + i) * w + x));
        double a = (prof[0] + prof[1] + prof[2]) / 3, b = (prof[n - 1] + prof[n - 2] + prof[n - 3]) / 3;
        double p20 = crossing(prof, n, a + 0.2 * (b - a)), p50 = crossing(prof, n, a + 0.5 * (b - a)),
               p80 = crossing(prof, n, a + 0.8 * (b - a));
        if (p20 < 0 || p50 < 0 || p80 < 0 || fabs(b - a) < 0.02) continue; /* no edge in this column */
        width += fabs(p80 - p20);
        pos[2 * cols] = x;
        pos[2 * cols + 1] = p50;
        sx += x; sy += p50; sxx += (double)x * x; sxy += x * p50;
        cols++;
    }
    if (cols < 8) {
        fprintf(stderr, "edge_measure: %s: an edge in only %d of the window's columns\n", argv[1], cols);
        return 1;
    }
    /* The 50% line's least-squares straight line, and the RMS about it. */
    double slope = (cols * sxy - sx * sy) / (cols * sxx - sx * sx), icpt = (sy - slope * sx) / cols, se = 0;
    for (int k = 0; k < cols; k++) {
        double r = pos[2 * k + 1] - (slope * pos[2 * k] + icpt);
        se += r * r;
    }
    printf("{\"picture\": \"%s\", \"columns\": %d, \"width_mm\": %.3f, \"stray_mm\": %.3f}\n", argv[1], cols,
           width / cols * mm, sqrt(se / cols) * mm);
    free(prof);
    free(pos);
    stbi_image_free(img);
    return 0;
}
