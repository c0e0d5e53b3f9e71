#include "ref_slab.h"

#include <math.h>

/* Half the dipole's plane total for a source at signed height h. */
static double plane_total(double s, double h) { return (h > 0 ? 1.0 : h < 0 ? -1.0 : 0.0) * exp(-s * fabs(h)); }

void jd_slab_totals(const jd_dipole *dp, int c, double d, double *r, double *t)
{
    double zr = dp->zr[c], zv = dp->zv[c], zb = 0.5 * (zv - zr), s = dp->sigma_tr[c];
    double half = exp(-s * zr) + exp(-s * zv);
    *r = 1.0;
    *t = 0.0;
    if (!(d > 0) || !(half > 0) || !isfinite(d)) return;
    d = jd_slab_thickness(d, zr);
    /* Mirrors i and -i, outwards, until they add under 1e-9 of the sum:
     * pair i lies about 2 i (d + 2 z_b) away. Where sigma_tr is 0 their
     * terms do not shrink but cancel within each pair; 200 bounds that. */
    double rs = 0, ts = 0, period = 2.0 * (d + 2.0 * zb);
    for (int i = 0; i <= 200; i++) {
        double dr = 0, dt = 0;
        for (int sgn = i ? -1 : 1; sgn <= 1; sgn += 2) {
            double a = sgn * i * period + zr, b = sgn * i * period - zr - 2.0 * zb;
            dr += plane_total(s, a) - plane_total(s, b);
            dt += plane_total(s, d - a) - plane_total(s, d - b);
        }
        rs += dr;
        ts += dt;
        if (i && fabs(dr) + fabs(dt) < 1e-9 * (fabs(rs) + fabs(ts))) break;
    }
    *r = rs > 0 ? rs / half : 0.0;
    *t = ts > 0 ? ts / half : 0.0;
}

/* Of a dipole profile with its sources at heights h and hv (over the plane,
 * positive, as Rd's z_r and z_v), the share that lands past distance t: the
 * plane integral beyond t is (h / D e^(-s D)) / 2 per source, D = sqrt(t^2 + h^2). */
static double tail_share(double s, double h, double hv, double t)
{
    double dr = sqrt(t * t + h * h), dv = sqrt(t * t + hv * hv), all = exp(-s * h) + exp(-s * hv);
    return all > 0 ? (h / dr * exp(-s * dr) + hv / dv * exp(-s * dv)) / all : 0.0;
}

void jd_slab_weights(const jd_dipole *dp, int c, double d, double *sample, double *carried)
{
    double zr = dp->zr[c], zv = dp->zv[c], s = dp->sigma_tr[c], R, T;
    jd_slab_totals(dp, c, d, &R, &T);
    double h = jd_slab_carried_height(d, zr), hv = h + (zv - zr), half = exp(-s * zr) + exp(-s * zv);
    /* Each profile also reaches the opposite face at the straight distance
     * d: the sample's by its share past d (tau_s), the carried light's by
     * its own (tau_c). On a slab the faces then give out
     *   lit: w_s + tau_c w_c = R,   far: w_c + tau_s w_s = T,
     * solved here, so that they give out exactly R and T. */
    double tau_s = tail_share(s, zr, zv, d), tau_c = tail_share(s, h, hv, d), det = 1.0 - tau_s * tau_c;
    double ws = (R - tau_c * T) / det, wc = (T - tau_s * R) / det;
    *sample = ws > 0 ? ws : 0.0;
    /* The carried profile's total over the half-space's: its power is
     * divided by it so that it gives out wc of the half-space's light. */
    double own = half > 0 ? (exp(-s * h) + exp(-s * hv)) / half : 1.0;
    *carried = wc > 0 && own > 0 ? wc / own : 0.0;
}
