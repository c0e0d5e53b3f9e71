#include "slab.h"

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
