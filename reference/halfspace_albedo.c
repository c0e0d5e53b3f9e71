#include "halfspace_albedo.h"

#include "material.h"

#include <math.h>
#include <stdlib.h>

enum { HS_POINTS = 400, HS_MAX_ITER = 20000 };

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

/* Gaussian elimination with partial pivoting: a (n x n, row-major) x = b
 * for m right-hand sides at once (b n x m, row-major), b replaced by x. The
 * matrix is I - K F with K's columns summing to under 1 and F <= 1: well
 * conditioned for every alpha < 1. */
static void solve_multi(double *a, double *b, int n, int m)
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
            for (int c = 0; c < m; c++) {
                double t = b[(size_t)k * m + c];
                b[(size_t)k * m + c] = b[(size_t)p * m + c];
                b[(size_t)p * m + c] = t;
            }
        }
        for (int i = k + 1; i < n; i++) {
            double f = a[(size_t)i * n + k] / a[(size_t)k * n + k];
            if (f == 0.0) continue;
            for (int j = k; j < n; j++) a[(size_t)i * n + j] -= f * a[(size_t)k * n + j];
            for (int c = 0; c < m; c++) b[(size_t)i * m + c] -= f * b[(size_t)k * m + c];
        }
    }
    for (int k = n - 1; k >= 0; k--)
        for (int c = 0; c < m; c++) {
            double s = b[(size_t)k * m + c];
            for (int j = k + 1; j < n; j++) s -= a[(size_t)k * n + j] * b[(size_t)j * m + c];
            b[(size_t)k * m + c] = s / a[(size_t)k * n + k];
        }
}

static void solve(double *a, double *b, int n) { solve_multi(a, b, n, 1); }

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

/* k of the diffusion mode e^(-k tau) of an isotropically scattering
 * medium at albedo alpha: alpha atanh(k) / k = 1, by bisection (atanh(k) / k
 * rises from 1 at k = 0 without end towards k = 1). */
static double mode_k(double alpha)
{
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 100; it++) {
        double k = 0.5 * (lo + hi);
        if (k <= 0.0 || atanh(k) / k < 1.0 / alpha) lo = k;
        else hi = k;
    }
    return 0.5 * (lo + hi);
}

/* Linear between the inside's points at the inside cosine of each of the
 * outside's cosines k / (n - 1) (Snell), held at the ends. */
static void at_outside(double eta, const double *v, int n, double *out)
{
    for (int k = 0; k < n; k++) {
        double mu_e = (double)k / (n - 1), mi = sqrt(fmax(0.0, 1.0 - (1.0 - mu_e * mu_e) / (eta * eta)));
        double x = mi * HS_POINTS - 0.5;
        if (x <= 0) out[k] = v[0];
        else if (x >= HS_POINTS - 1) out[k] = v[HS_POINTS - 1];
        else {
            int i = (int)x;
            out[k] = v[i] + (x - i) * (v[i + 1] - v[i]);
        }
    }
}

int jd_halfspace_exit(double alpha, double eta, int n, double *deep, double *beam)
{
    if (n < 2 || n > 256) return -1;
    if (!(eta > 0)) eta = 1.0;
    alpha = alpha < 1e-6 ? 1e-6 : alpha > 1.0 - 1e-9 ? 1.0 - 1e-9 : alpha;
    const int m = n + 1, matched = fabs(eta - 1.0) < 1e-9; /* columns: the n beams, then the deep light */
    const double w = 1.0 / HS_POINTS, kk = mode_k(alpha);
    double mu[HS_POINTS], h[HS_POINTS], f[HS_POINTS], tmp[HS_POINTS];
    double *u = malloc(sizeof(double) * HS_POINTS * m), *a = matched ? NULL : malloc(sizeof(double) * HS_POINTS * HS_POINTS);
    if (!u || (!matched && !a)) { free(u); free(a); return -1; }
    points(mu);
    h_function(alpha, mu, h, tmp);
    for (int i = 0; i < HS_POINTS; i++) f[i] = matched ? 0.0 : jd_fresnel_dielectric(mu[i], eta, 1.0);
#define K(i, j) (0.5 * alpha * h[i] * h[j] * mu[i] * w / (mu[i] + mu[j]))
    /* The flux coming up at the inside's points: for a beam that entered at
     * the inside cosine of the outside's c / (n - 1) (its unit flux split
     * between the two points beside it), the half-space's reflection K of
     * it; from light deep below, the Milne problem's law of darkening,
     * H(mu) / (1 - k mu) in radiance (Chandrasekhar 1960; tests/test_reference.c
     * holds both to a Monte Carlo walk). */
    for (int c = 0; c < n; c++) {
        double mu_e = (double)c / (n - 1), mi = sqrt(fmax(0.0, 1.0 - (1.0 - mu_e * mu_e) / (eta * eta)));
        double x = mi * HS_POINTS - 0.5;
        int j0 = x <= 0 ? 0 : x >= HS_POINTS - 1 ? HS_POINTS - 2 : (int)x;
        double t = x <= 0 ? 0.0 : x >= HS_POINTS - 1 ? 1.0 : x - j0;
        for (int i = 0; i < HS_POINTS; i++) u[(size_t)i * m + c] = (1.0 - t) * K(i, j0) + t * K(i, j0 + 1);
    }
    for (int i = 0; i < HS_POINTS; i++) u[(size_t)i * m + n] = h[i] / (1.0 - kk * mu[i]) * mu[i] * w;
    if (!matched) {
        /* What the boundary reflects back the half-space sends up again:
         * u = u0 + K F u. */
        for (int i = 0; i < HS_POINTS; i++)
            for (int j = 0; j < HS_POINTS; j++) a[(size_t)i * HS_POINTS + j] = (i == j ? 1.0 : 0.0) - K(i, j) * f[j];
        solve_multi(a, u, HS_POINTS, m);
    }
#undef K
    /* The flux that leaves, (1 - F) u, as radiance outside (mu_e dmu_e =
     * eta^2 mu dmu), over that of a Lambertian surface of the same exitance. */
    for (int c = 0; c < m; c++) {
        double total = 0, g[HS_POINTS], o[256];
        for (int i = 0; i < HS_POINTS; i++) total += (1.0 - f[i]) * u[(size_t)i * m + c];
        for (int i = 0; i < HS_POINTS; i++)
            g[i] = total > 0 ? (1.0 - f[i]) * u[(size_t)i * m + c] / (eta * eta * mu[i] * w) / (2.0 * total) : 1.0;
        at_outside(eta, g, n, o);
        for (int i = 0; i < n; i++) {
            if (c == n) { if (deep) deep[i] = o[i]; }
            else if (beam) beam[(size_t)i * n + c] = o[i];
        }
    }
    free(u);
    free(a);
    return 0;
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
    at_outside(eta, R, n, out);
    return 0;
}
