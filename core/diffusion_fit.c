#include "diffusion_fit.h"

#include <math.h>
#include <string.h>

#define FIT_SAMPLES 384

static double gauss2d(double s, double r) { return exp(-r * r / (2.0 * s * s)) / (2.0 * M_PI * s * s); }

void jd_diffusion_fit_profile(const jd_dipole *d, const float *sigma_mm, int count, jd_diffusion_fit *out)
{
    memset(out, 0, sizeof *out);
    if (count > JD_DIFFUSION_MAX_GAUSSIANS) count = JD_DIFFUSION_MAX_GAUSSIANS;
    if (count < 1) return;
    out->count = count;
    memcpy(out->sigma_mm, sigma_mm, sizeof(float) * (size_t)count);
    double widest = sigma_mm[count - 1];
    for (int c = 0; c < 3; c++) {
        out->rd_total[c] = (float)d->rd_total[c];
        /* Past 8 mean free paths of the diffuse light Rd is negligible; past
         * three widest sigmas no weight could carry it anyway. */
        double reach = d->sigma_tr[c] > 0 ? 8.0 / d->sigma_tr[c] : 3.0 * widest;
        if (reach > 3.0 * widest) reach = 3.0 * widest;
        out->reach_mm[c] = (float)reach;
        /* A Gaussian wider than half the reach is flat over it: the fit
         * could only use it as a small offset, which rescaled to Rd_total
         * would carry light far beyond where the profile goes. */
        int usable = 1;
        while (usable < count && sigma_mm[usable] <= 0.5 * reach) usable++;
        /* Normal equations of min sum_i dr (r_i (sum_k w_k G_k(r_i) - Rd(r_i)))^2. */
        double ata[JD_DIFFUSION_MAX_GAUSSIANS][JD_DIFFUSION_MAX_GAUSSIANS] = {{0}};
        double atb[JD_DIFFUSION_MAX_GAUSSIANS] = {0}, btb = 0;
        double dr = reach / FIT_SAMPLES;
        for (int i = 0; i < FIT_SAMPLES; i++) {
            double r = (i + 0.5) * dr;
            double b = r * jd_dipole_rd(d, c, r), g[JD_DIFFUSION_MAX_GAUSSIANS];
            for (int k = 0; k < usable; k++) g[k] = r * gauss2d(sigma_mm[k], r);
            for (int k = 0; k < usable; k++) {
                atb[k] += g[k] * b;
                for (int l = 0; l < usable; l++) ata[k][l] += g[k] * g[l];
            }
            btb += b * b;
        }
        /* Projected Gauss-Seidel: a handful of unknowns, symmetric positive
         * definite, non-negativity by clamping. */
        double w[JD_DIFFUSION_MAX_GAUSSIANS] = {0};
        for (int it = 0; it < 2000; it++) {
            for (int k = 0; k < usable; k++) {
                if (ata[k][k] <= 0) continue;
                double s = atb[k];
                for (int l = 0; l < usable; l++)
                    if (l != k) s -= ata[k][l] * w[l];
                w[k] = s > 0 ? s / ata[k][k] : 0.0;
            }
        }
        double res = btb, sum = 0;
        for (int k = 0; k < count; k++) {
            res -= 2.0 * w[k] * atb[k];
            for (int l = 0; l < count; l++) res += w[k] * w[l] * ata[k][l];
            sum += w[k];
        }
        out->fit_error[c] = btb > 0 ? (float)sqrt(fmax(res, 0.0) / btb) : 0.0f;
        /* The fitted weights integrate to sum; the profile to Rd_total. */
        double scale = sum > 0 ? d->rd_total[c] / sum : 0.0;
        if (sum <= 0) w[0] = d->rd_total[c], scale = 1.0;
        for (int k = 0; k < count; k++) out->weight[k][c] = (float)(w[k] * scale);
    }
}
