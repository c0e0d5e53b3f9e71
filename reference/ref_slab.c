#include "ref_slab.h"
#include "ref_diffusion.h"

#include <math.h>

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
    /* The sample's profile past d is diffusion's, unscaled (the exact
     * albedo's excess stays in the window near the entry), so its share of
     * the sample's whole light is the tail's times diffusion's share. */
    double tau_s = tail_share(s, zr, zv, d) * jd_ref_diffusion_share(dp, c);
    double tau_c = tail_share(s, h, hv, d), det = 1.0 - tau_s * tau_c;
    double ws = (R - tau_c * T) / det, wc = (T - tau_s * R) / det;
    *sample = ws > 0 ? ws : 0.0;
    /* The carried profile's total over the half-space's: its power is
     * divided by it so that it gives out wc of the half-space's light. */
    double own = half > 0 ? (exp(-s * h) + exp(-s * hv)) / half : 1.0;
    *carried = wc > 0 && own > 0 ? wc / own : 0.0;
}
