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

/* R[j]: of unit flux going in at the inside's cosine mu[j], the part that
 * comes back out. Index-matched, Chandrasekhar's 1 - H(mu) sqrt(1 - alpha).
 * Else by adding the interface to the matched half-space (the adding
 * method of radiative transfer, over the inside's direction cosines):
 * K[i][j], the half-space's reflection, of unit flux going in at mu_j the
 * part coming back at mu_i, alpha / 2 H(mu_i) H(mu_j) mu_i dmu / (mu_i +
 * mu_j) (Chandrasekhar 1960, ch. IV); F(mu), the interface's reflectance
 * seen from inside (1 past the critical angle). Flux d going in makes the
 * upward flux u = K (d + F u), of which (1 - F) u leaves: (1 - F)^T (I -
 * K F)^-1 K d. So y = (I - K F)^-T (1 - F) is solved once and R = y^T K.
 * f[] gets F. 0, or -1 when out of memory. */
static int beam_albedo(double alpha, double eta, const double *mu, double *R, double *f)
{
    const double w = 1.0 / HS_POINTS, s0 = sqrt(1.0 - alpha);
    double h[HS_POINTS], tmp[HS_POINTS];
    h_function(alpha, mu, h, tmp);
    if (fabs(eta - 1.0) < 1e-9) {
        for (int j = 0; j < HS_POINTS; j++) {
            R[j] = 1.0 - h[j] * s0;
            f[j] = 0.0;
        }
        return 0;
    }
    double *a = malloc(sizeof(double) * HS_POINTS * HS_POINTS);
    if (!a) return -1;
    for (int i = 0; i < HS_POINTS; i++) f[i] = jd_fresnel_dielectric(mu[i], eta, 1.0);
#define K(i, j) (0.5 * alpha * h[i] * h[j] * mu[i] * w / (mu[i] + mu[j]))
    /* (I - K F) transposed: row j, column i. */
    for (int i = 0; i < HS_POINTS; i++)
        for (int j = 0; j < HS_POINTS; j++) a[(size_t)j * HS_POINTS + i] = (i == j ? 1.0 : 0.0) - K(i, j) * f[j];
    double y[HS_POINTS];
    for (int i = 0; i < HS_POINTS; i++) y[i] = 1.0 - f[i];
    solve(a, y, HS_POINTS);
    for (int j = 0; j < HS_POINTS; j++) {
        double r = 0;
        for (int i = 0; i < HS_POINTS; i++) r += y[i] * K(i, j);
        R[j] = r;
    }
#undef K
    free(a);
    return 0;
}

static void points(double *mu)
{
    for (int i = 0; i < HS_POINTS; i++) mu[i] = (i + 0.5) / HS_POINTS;
}

/* Of diffuse light that entered, the part that comes back, from R and F.
 * Index-matched (F = 0) this is Chandrasekhar's 1 - 2 sqrt(1 - alpha) times
 * the first moment of H, exactly, on the same points. */
static double diffuse_albedo(double eta, const double *mu, const double *R, const double *f)
{
    const double w = 1.0 / HS_POINTS;
    /* Diffuse light outside enters at mu with flux 2 eta^2 mu dmu (1 -
     * F(mu)) (Snell: mu_e dmu_e = eta^2 mu dmu); of what entered, the part
     * that comes back. The part the surface reflects outright is jade's
     * highlight, not its subsurface light (nor in the dipole's Rd_total). */
    double in = 0, out = 0;
    for (int j = 0; j < HS_POINTS; j++) {
        double d = 2.0 * eta * eta * mu[j] * w * (1.0 - f[j]);
        in += d;
        out += d * R[j];
    }
    return in > 0 ? out / in : 0.0;
}

double jd_halfspace_albedo(double alpha, double eta)
{
    if (!(alpha > 0) || !(eta > 0)) return 0.0;
    if (alpha >= 1.0) return 1.0; /* nothing absorbed: all that entered comes back */
    double mu[HS_POINTS], R[HS_POINTS], f[HS_POINTS];
    points(mu);
    if (beam_albedo(alpha, eta, mu, R, f)) return -1.0;
    return diffuse_albedo(eta, mu, R, f);
}

int jd_halfspace_albedo_beam(double alpha, double eta, int n, double *out, double *diffuse)
{
    if (n < 2) return -1;
    double mu[HS_POINTS], R[HS_POINTS], f[HS_POINTS];
    points(mu);
    if (!(alpha > 0) || !(eta > 0) || alpha >= 1.0) {
        for (int k = 0; k < n; k++) out[k] = alpha >= 1.0 ? 1.0 : 0.0;
        if (diffuse) *diffuse = alpha >= 1.0 ? 1.0 : 0.0;
        return 0;
    }
    if (beam_albedo(alpha, eta, mu, R, f)) return -1;
    if (diffuse) *diffuse = diffuse_albedo(eta, mu, R, f);
    for (int k = 0; k < n; k++) {
        /* The outside's cosine to the inside's (Snell), then linear between
         * the points, held at the ends. */
        double mu_e = (double)k / (n - 1), mi = sqrt(fmax(0.0, 1.0 - (1.0 - mu_e * mu_e) / (eta * eta)));
        double x = mi * HS_POINTS - 0.5;
        if (x <= 0) out[k] = R[0];
        else if (x >= HS_POINTS - 1) out[k] = R[HS_POINTS - 1];
        else {
            int i = (int)x;
            out[k] = R[i] + (x - i) * (R[i + 1] - R[i]);
        }
    }
    return 0;
}
