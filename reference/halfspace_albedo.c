#include "halfspace_albedo.h"

#include <math.h>

enum { HS_POINTS = 400, HS_MAX_ITER = 20000 };

double jd_halfspace_albedo(double alpha)
{
    if (!(alpha > 0)) return 0.0;
    if (alpha >= 1.0) return 1.0; /* nothing absorbed: all of it comes back */
    /* Midpoint rule on [0, 1]: H is smooth there (H(0) = 1). */
    static const double w = 1.0 / HS_POINTS;
    double mu[HS_POINTS], h[HS_POINTS], next[HS_POINTS];
    for (int i = 0; i < HS_POINTS; i++) {
        mu[i] = (i + 0.5) * w;
        h[i] = 1.0;
    }
    double s0 = sqrt(1.0 - alpha);
    for (int it = 0; it < HS_MAX_ITER; it++) {
        double change = 0;
        for (int i = 0; i < HS_POINTS; i++) {
            double sum = 0;
            for (int j = 0; j < HS_POINTS; j++) sum += mu[j] * h[j] / (mu[i] + mu[j]);
            next[i] = 1.0 / (s0 + 0.5 * alpha * w * sum);
            change = fmax(change, fabs(next[i] - h[i]));
        }
        for (int i = 0; i < HS_POINTS; i++) h[i] = next[i];
        if (change < 1e-10) break;
    }
    double m1 = 0;
    for (int i = 0; i < HS_POINTS; i++) m1 += h[i] * mu[i] * w;
    return 1.0 - 2.0 * s0 * m1;
}
