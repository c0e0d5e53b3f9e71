#include "halfspace_albedo.h"

#include <math.h>
#include <stdlib.h>

enum { HS_POINTS = 400, HS_MAX_ITER = 20000 };

double jd_fresnel_dielectric(double cos_i, double n1, double n2)
{
    double sin_t = n1 / n2 * sqrt(fmax(0.0, 1.0 - cos_i * cos_i));
    if (sin_t >= 1.0) return 1.0; /* total internal reflection */
    double cos_t = sqrt(1.0 - sin_t * sin_t);
    double rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    double rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

/* Chandrasekhar's H(mu) for isotropic scattering at albedo alpha, on the
 * midpoint rule's points mu[i] = (i + 0.5) / HS_POINTS (H is smooth on
 * [0, 1], H(0) = 1), by iterating 1 / H(mu) = sqrt(1 - alpha) + alpha / 2 *
 * integral of mu' H(mu') / (mu + mu') dmu', a form that converges near
 * alpha = 1. */
static void h_function(double alpha, const double *mu, double *h, double *next)
{
    const double w = 1.0 / HS_POINTS, s0 = sqrt(1.0 - alpha);
    for (int i = 0; i < HS_POINTS; i++) h[i] = 1.0;
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
}

/* Gaussian elimination with partial pivoting: a (n x n, row-major) x = b,
 * b replaced by x. The matrix is I - K F with K's columns summing to under
 * 1 and F <= 1: well conditioned for every alpha < 1. */
static void solve(double *a, double *b, int n)
{
    for (int k = 0; k < n; k++) {
        int p = k;
        for (int i = k + 1; i < n; i++)
            if (fabs(a[(size_t)i * n + k]) > fabs(a[(size_t)p * n + k])) p = i;
        if (p != k) {
            for (int j = 0; j < n; j++) {
                double t = a[(size_t)k * n + j];
                a[(size_t)k * n + j] = a[(size_t)p * n + j];
                a[(size_t)p * n + j] = t;
            }
            double t = b[k];
            b[k] = b[p];
            b[p] = t;
        }
        for (int i = k + 1; i < n; i++) {
            double f = a[(size_t)i * n + k] / a[(size_t)k * n + k];
            if (f == 0.0) continue;
            for (int j = k; j < n; j++) a[(size_t)i * n + j] -= f * a[(size_t)k * n + j];
            b[i] -= f * b[k];
        }
    }
    for (int k = n - 1; k >= 0; k--) {
        double s = b[k];
        for (int j = k + 1; j < n; j++) s -= a[(size_t)k * n + j] * b[j];
        b[k] = s / a[(size_t)k * n + k];
    }
}

double jd_halfspace_albedo(double alpha, double eta)
{
    if (!(alpha > 0) || !(eta > 0)) return 0.0;
    if (alpha >= 1.0) return 1.0; /* nothing absorbed: all that entered comes back */
    const double w = 1.0 / HS_POINTS;
    double mu[HS_POINTS], h[HS_POINTS], tmp[HS_POINTS];
    for (int i = 0; i < HS_POINTS; i++) mu[i] = (i + 0.5) * w;
    h_function(alpha, mu, h, tmp);
    if (fabs(eta - 1.0) < 1e-9) {
        /* Index-matched: Chandrasekhar's closed form, R = 1 - 2 sqrt(1 - alpha)
         * * integral of H(mu) mu dmu. */
        double m1 = 0;
        for (int i = 0; i < HS_POINTS; i++) m1 += h[i] * mu[i] * w;
        return 1.0 - 2.0 * sqrt(1.0 - alpha) * m1;
    }
    /* A smooth dielectric boundary, by adding the interface to the matched
     * half-space (the adding method of radiative transfer, over the inside's
     * direction cosines). K[i][j], the half-space's reflection: of unit flux
     * going in at mu_j, the part coming back at mu_i, alpha / 2 H(mu_i)
     * H(mu_j) mu_i dmu / (mu_i + mu_j) (Chandrasekhar 1960, ch. IV). F(mu),
     * the interface's reflectance seen from inside (1 past the critical
     * angle). Diffuse light outside enters at mu with flux 2 eta^2 mu dmu
     * (1 - F(mu)) (Snell: mu_e dmu_e = eta^2 mu dmu), d0. The upward flux u
     * then solves u = K (d0 + F u), and (1 - F) u leaves. */
    double *a = malloc(sizeof(double) * HS_POINTS * HS_POINTS), *u = malloc(sizeof(double) * HS_POINTS);
    double f[HS_POINTS];
    if (!a || !u) {
        free(a);
        free(u);
        return -1.0;
    }
    double entered = 0;
    for (int i = 0; i < HS_POINTS; i++) {
        f[i] = jd_fresnel_dielectric(mu[i], eta, 1.0);
        tmp[i] = 2.0 * eta * eta * mu[i] * w * (1.0 - f[i]);
        entered += tmp[i];
    }
    for (int i = 0; i < HS_POINTS; i++) {
        double kd = 0;
        for (int j = 0; j < HS_POINTS; j++) {
            double k = 0.5 * alpha * h[i] * h[j] * mu[i] * w / (mu[i] + mu[j]);
            kd += k * tmp[j];
            a[(size_t)i * HS_POINTS + j] = (i == j ? 1.0 : 0.0) - k * f[j];
        }
        u[i] = kd;
    }
    solve(a, u, HS_POINTS);
    double out = 0;
    for (int i = 0; i < HS_POINTS; i++) out += (1.0 - f[i]) * u[i];
    free(a);
    free(u);
    /* Of the light that entered: the part the surface reflects outright is
     * jade's highlight, not its subsurface light. */
    return entered > 0 ? out / entered : 0.0;
}
