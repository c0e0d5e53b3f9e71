#include "material.h"

#include "albedo_table.h"

#include <math.h>
#include <string.h>

/* Jensen, Marschner, Levoy, Hanrahan 2001, "A Practical Model for Subsurface
 * Light Transport", Table 2: sigma_s' and sigma_a measured in mm^-1 for red,
 * green and blue (the same numbers as pbrt's). The paper uses eta 1.3 for
 * every material; marble takes calcite's 1.5. */
#define JD_JENSEN "Jensen et al. 2001, Table 2 (measured); eta 1.3 as in the paper"
#define JD_JENSEN_CALCITE "Jensen et al. 2001, Table 2 (measured); eta 1.5 (calcite)"
const jd_material jd_materials[] = {
    {"apple", {2.29f, 2.39f, 1.97f}, {0.0030f, 0.0034f, 0.046f}, 1.3f, JD_JENSEN},
    {"chicken1", {0.15f, 0.21f, 0.38f}, {0.015f, 0.077f, 0.19f}, 1.3f, JD_JENSEN},
    {"chicken2", {0.19f, 0.25f, 0.32f}, {0.018f, 0.088f, 0.20f}, 1.3f, JD_JENSEN},
    {"cream", {7.38f, 5.47f, 3.15f}, {0.0002f, 0.0028f, 0.0163f}, 1.3f, JD_JENSEN},
    {"ketchup", {0.18f, 0.07f, 0.03f}, {0.061f, 0.97f, 1.45f}, 1.3f, JD_JENSEN},
    {"marble", {2.19f, 2.62f, 3.00f}, {0.0021f, 0.0041f, 0.0071f}, 1.5f, JD_JENSEN_CALCITE},
    {"potato", {0.68f, 0.70f, 0.55f}, {0.0024f, 0.0090f, 0.12f}, 1.3f, JD_JENSEN},
    {"skimmilk", {0.70f, 1.22f, 1.90f}, {0.0014f, 0.0025f, 0.0142f}, 1.3f, JD_JENSEN},
    {"skin1", {0.74f, 0.88f, 1.01f}, {0.032f, 0.17f, 0.48f}, 1.3f, JD_JENSEN},
    {"skin2", {1.09f, 1.59f, 1.79f}, {0.013f, 0.070f, 0.145f}, 1.3f, JD_JENSEN},
    {"wholemilk", {2.55f, 3.21f, 3.77f}, {0.0011f, 0.0024f, 0.014f}, 1.3f, JD_JENSEN},
};
const int jd_material_count = (int)(sizeof jd_materials / sizeof jd_materials[0]);

const jd_material *jd_material_find(const char *name)
{
    for (int i = 0; i < jd_material_count; i++)
        if (strcmp(jd_materials[i].name, name) == 0) return &jd_materials[i];
    return NULL;
}

double jd_dipole_fdr(double eta)
{
    return -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
}

double jd_fresnel_dielectric(double cos_i, double n1, double n2)
{
    double sin_t = n1 / n2 * sqrt(fmax(0.0, 1.0 - cos_i * cos_i));
    if (sin_t >= 1.0) return 1.0; /* total internal reflection */
    double cos_t = sqrt(1.0 - sin_t * sin_t);
    double rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    double rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

enum { FRESNEL_POINTS = 256 }; /* the midpoint rule's, over the cosine */

double jd_fresnel_mean(double eta)
{
    double mean = 0;
    for (int i = 0; i < FRESNEL_POINTS; i++) {
        double mu = (i + 0.5) / FRESNEL_POINTS;
        mean += 2.0 * mu * (1.0 - jd_fresnel_dielectric(mu, 1.0, eta)) / FRESNEL_POINTS;
    }
    return mean;
}

void jd_fresnel_fit(double eta, float ab[2])
{
    /* t(mu) = T(mu) / Tmean (jd_fresnel_mean). a - b x^5 has the mean
     * a - b / 21 (2 integral of (1 - mu)^5 mu dmu = 1/21): held to 1,
     * a = 1 + b / 21, and t - 1 = b g with g = 1/21 - x^5, solved for b by
     * least squares weighted as the mean weighs (by mu). One pass over T:
     * sum mu g (T / Tmean - 1) = sum(mu g T) / Tmean - sum(mu g), and Tmean
     * is the same pass's 2 sum(mu T) / N: a few microseconds, which the
     * renderer spends only when eta changes. */
    double mean = 0, mgt = 0, mg = 0, den = 0;
    for (int i = 0; i < FRESNEL_POINTS; i++) {
        double mu = (i + 0.5) / FRESNEL_POINTS, x = 1.0 - mu, g = 1.0 / 21.0 - x * x * x * x * x;
        double t = 1.0 - jd_fresnel_dielectric(mu, 1.0, eta);
        mean += 2.0 * mu * t / FRESNEL_POINTS;
        mgt += mu * g * t;
        mg += mu * g;
        den += mu * g * g;
    }
    double num = mgt / mean - mg;
    double b = num / den;
    ab[0] = (float)(1.0 + b / 21.0);
    ab[1] = (float)b;
}

double jd_dipole_rd_total(double alpha, double A)
{
    double s = sqrt(3.0 * (1.0 - alpha));
    return 0.5 * alpha * (1.0 + exp(-(4.0 / 3.0) * A * s)) * exp(-s);
}

double jd_albedo_ratio(double alpha, double eta)
{
    double x = sqrt(1.0 - (alpha < 0 ? 0 : alpha > 1 ? 1 : alpha)) * (JD_ALBEDO_XS - 1);
    double e = ((eta < 1 ? 1 : eta > 3 ? 3 : eta) - 1.0) / 0.05;
    int i = x >= JD_ALBEDO_XS - 1 ? JD_ALBEDO_XS - 2 : (int)x, k = e >= JD_ALBEDO_ETAS - 1 ? JD_ALBEDO_ETAS - 2 : (int)e;
    double fx = x - i, fe = e - k;
    const float *a = jd_albedo_ratio_table[k], *b = jd_albedo_ratio_table[k + 1];
    return (1 - fe) * ((1 - fx) * a[i] + fx * a[i + 1]) + fe * ((1 - fx) * b[i] + fx * b[i + 1]);
}

double jd_albedo_total(double alpha, double eta)
{
    double fdr = jd_dipole_fdr(eta), A = (1.0 + fdr) / (1.0 - fdr);
    return jd_dipole_rd_total(alpha, A) * jd_albedo_ratio(alpha, eta);
}

void jd_material_from_reflectance(const float rd[3], const float ld_mm[3], float eta, float sigma_s[3],
                                  float sigma_a[3])
{
    for (int c = 0; c < 3; c++) {
        double want = rd[c] < 0.001f ? 0.001 : rd[c] > 0.95f ? 0.95 : rd[c];
        /* The albedo rises from 0 to 1 as alpha' goes from 0 to 1. */
        double lo = 0.0, hi = 1.0;
        for (int i = 0; i < 60; i++) {
            double mid = 0.5 * (lo + hi);
            if (jd_albedo_total(mid, eta) < want) lo = mid; else hi = mid;
        }
        double alpha = 0.5 * (lo + hi), ld = ld_mm[c] > 1e-3f ? ld_mm[c] : 1e-3;
        double sigma_t = 1.0 / (ld * sqrt(3.0 * (1.0 - alpha)));
        sigma_s[c] = (float)(alpha * sigma_t);
        sigma_a[c] = (float)((1.0 - alpha) * sigma_t);
    }
}

void jd_dipole_init(jd_dipole *d, const float sigma_s[3], const float sigma_a[3], float eta,
                    float density)
{
    d->fdr = jd_dipole_fdr(eta);
    d->A = (1.0 + d->fdr) / (1.0 - d->fdr);
    for (int c = 0; c < 3; c++) {
        double ss = sigma_s[c] * (double)density, sa = sigma_a[c] * (double)density;
        d->sigma_t[c] = sa + ss;
        d->alpha[c] = d->sigma_t[c] > 0 ? ss / d->sigma_t[c] : 0.0;
        d->sigma_tr[c] = sqrt(3.0 * sa * d->sigma_t[c]);
        d->zr[c] = d->sigma_t[c] > 0 ? 1.0 / d->sigma_t[c] : 0.0;
        d->zv[c] = d->zr[c] * (1.0 + 4.0 * d->A / 3.0);
        /* The profile's shape is the dipole's, its total the transport
         * equation's (docs/quality.md, "At jade's own eta"). */
        d->ratio[c] = jd_albedo_ratio(d->alpha[c], eta);
        d->rd_total[c] = jd_dipole_rd_total(d->alpha[c], d->A) * d->ratio[c];
    }
}

double jd_dipole_tail(const jd_dipole *d, int c, double t)
{
    double dr = sqrt(t * t + d->zr[c] * d->zr[c]), dv = sqrt(t * t + d->zv[c] * d->zv[c]);
    if (dr <= 0 || dv <= 0) return 0.0;
    return 0.5 * d->alpha[c] * d->ratio[c] *
           (d->zr[c] / dr * exp(-d->sigma_tr[c] * dr) + d->zv[c] / dv * exp(-d->sigma_tr[c] * dv));
}

double jd_dipole_rd(const jd_dipole *d, int c, double r)
{
    double dr = sqrt(r * r + d->zr[c] * d->zr[c]), dv = sqrt(r * r + d->zv[c] * d->zv[c]);
    double s = d->sigma_tr[c];
    return d->alpha[c] * d->ratio[c] / (4.0 * M_PI) *
           (d->zr[c] * (1.0 + s * dr) * exp(-s * dr) / (dr * dr * dr) +
            d->zv[c] * (1.0 + s * dv) * exp(-s * dv) / (dv * dv * dv));
}
