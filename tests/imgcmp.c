/* Compares two PNGs: RMSE and largest difference over RGB (0-255 scale), and
 * the fraction of pixels off by more than a threshold. Prints the measured
 * figures and fails when they exceed the given tolerances. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>

/* imgcmp --frame A.png MIN_SPAN: where the object lies in a picture (the
 * pixels that differ from the top-left corner's colour by more than 8 in a
 * channel); fails when it touches an edge (cropped) or spans less than
 * MIN_SPAN of the picture along its longer extent (lost in the frame). */
static int frame_check(const char *path, double min_span)
{
    int w, h, c;
    unsigned char *a = stbi_load(path, &w, &h, &c, 4);
    if (!a) { fprintf(stderr, "imgcmp: cannot read %s\n", path); return 2; }
    int x0 = w, y0 = h, x1 = -1, y1 = -1;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const unsigned char *p = a + 4 * ((size_t)y * w + x);
            int d = 0;
            for (int k = 0; k < 3; k++) d = d > abs(p[k] - a[k]) ? d : abs(p[k] - a[k]);
            if (d > 8) {
                if (x < x0) x0 = x;
                if (x > x1) x1 = x;
                if (y < y0) y0 = y;
                if (y > y1) y1 = y;
            }
        }
    stbi_image_free(a);
    if (x1 < 0) { printf("%s: no object pixel\n", path); return 1; }
    double span = fmax((x1 - x0 + 1.0) / w, (y1 - y0 + 1.0) / h);
    int touches = x0 == 0 || y0 == 0 || x1 == w - 1 || y1 == h - 1;
    printf("%s: %dx%d, object x %d..%d y %d..%d, margins left %d right %d top %d bottom %d, spans %.2f (min %.2f): %s\n",
           path, w, h, x0, x1, y0, y1, x0, w - 1 - x1, y0, h - 1 - y1, span, min_span,
           touches ? "CROPPED" : span < min_span ? "TOO SMALL" : "ok");
    return touches || span < min_span;
}

/* imgcmp --count A.png: how many pixels differ from the top-left corner's
 * colour by more than 8 in a channel (the object's, on a plain background). */
static int count_object(const char *path)
{
    int w, h, c;
    unsigned char *a = stbi_load(path, &w, &h, &c, 4);
    if (!a) { fprintf(stderr, "imgcmp: cannot read %s\n", path); return 2; }
    long n = 0;
    for (long i = 0; i < (long)w * h; i++) {
        int d = 0;
        for (int k = 0; k < 3; k++) d = d > abs(a[4 * i + k] - a[k]) ? d : abs(a[4 * i + k] - a[k]);
        n += d > 8;
    }
    printf("%ld\n", n);
    stbi_image_free(a);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 3 && !strcmp(argv[1], "--count")) return count_object(argv[2]);
    if (argc == 4 && !strcmp(argv[1], "--frame")) return frame_check(argv[2], atof(argv[3]));
    if (argc < 3) {
        fprintf(stderr, "usage: imgcmp A.png B.png [--max-rmse X] [--max-bad-frac F] [--bad-threshold T]\n");
        return 2;
    }
    double max_rmse = 2.0, max_bad = 0.005, thr = 24;
    int rotate = 0; /* turn B clockwise by this many degrees first */
    for (int i = 3; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "--max-rmse")) max_rmse = atof(argv[i + 1]);
        else if (!strcmp(argv[i], "--max-bad-frac")) max_bad = atof(argv[i + 1]);
        else if (!strcmp(argv[i], "--bad-threshold")) thr = atof(argv[i + 1]);
        else if (!strcmp(argv[i], "--rotate-b")) rotate = atoi(argv[i + 1]);
    }
    int wa, ha, wb, hb, c;
    unsigned char *a = stbi_load(argv[1], &wa, &ha, &c, 4);
    unsigned char *b = stbi_load(argv[2], &wb, &hb, &c, 4);
    if (!a || !b) { fprintf(stderr, "imgcmp: cannot read %s\n", !a ? argv[1] : argv[2]); return 2; }
    if (rotate % 360) {
        if (wb != hb) { printf("imgcmp: --rotate-b needs a square image\n"); return 2; }
        unsigned char *r = malloc((size_t)wb * hb * 4);
        for (int y = 0; y < hb; y++)
            for (int x = 0; x < wb; x++) {
                int sx = x, sy = y;
                for (int k = 0; k < (rotate / 90) % 4; k++) { int t = sx; sx = sy; sy = wb - 1 - t; } /* one clockwise turn */
                memcpy(r + 4 * ((size_t)y * wb + x), b + 4 * ((size_t)sy * wb + sx), 4);
            }
        stbi_image_free(b);
        b = r;
    }
    if (wa != wb || ha != hb) { printf("imgcmp: sizes differ: %dx%d vs %dx%d\n", wa, ha, wb, hb); return 1; }
    double se = 0, worst = 0;
    long bad = 0, n = (long)wa * ha;
    for (long i = 0; i < n; i++) {
        double pix = 0;
        for (int k = 0; k < 3; k++) {
            double d = fabs((double)a[4 * i + k] - b[4 * i + k]);
            se += d * d;
            if (d > worst) worst = d;
            if (d > pix) pix = d;
        }
        if (pix > thr) bad++;
    }
    double rmse = sqrt(se / (3.0 * n)), frac = (double)bad / n;
    int ok = rmse <= max_rmse && frac <= max_bad;
    printf("imgcmp %s vs %s: rmse %.3f (max %.3f), largest difference %.0f, pixels off by >%.0f: %.4f%% (max %.4f%%) -> %s\n",
           argv[1], argv[2], rmse, max_rmse, worst, thr, 100 * frac, 100 * max_bad, ok ? "ok" : "DIFFERENT");
    stbi_image_free(a);
    if (rotate % 360) free(b); else stbi_image_free(b);
    return ok ? 0 : 1;
}
