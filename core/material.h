/* Measured scattering materials (Jensen et al. 2001) and the dipole terms
 * derived from them. Coefficients are per RGB channel in mm^-1. */
#ifndef JD_MATERIAL_H
#define JD_MATERIAL_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct jd_material {
    const char *name;
    float sigma_s[3]; /* reduced scattering sigma_s' */
    float sigma_a[3]; /* absorption */
    float eta;
    const char *source;   /* where the numbers come from */
} jd_material;

extern const jd_material jd_materials[];
extern const int jd_material_count;
const jd_material *jd_material_find(const char *name);

typedef struct jd_dipole {
    double sigma_t[3], alpha[3], sigma_tr[3], zr[3], zv[3];
    double fdr, A;
    /* ratio: the exact half-space albedo over the dipole's at this eta
     * (jd_albedo_ratio), which scales the profile; rd_total: its integral. */
    double ratio[3], rd_total[3];
} jd_dipole;

/* density scales both coefficients. */
void jd_dipole_init(jd_dipole *d, const float sigma_s[3], const float sigma_a[3], float eta,
                    float density);
double jd_dipole_fdr(double eta);
/* The material whose total diffuse reflectance is rd and whose diffuse mean
 * free path (1 / sigma_tr) is ld_mm, per channel: Jensen and Buhler 2002's
 * inversion (jd_albedo_total(alpha') = rd solved for the reduced albedo alpha' by
 * bisection, then sigma_t' = 1 / (ld sqrt(3 (1 - alpha')))). rd is held to
 * 0.001..0.95. */
void jd_material_from_reflectance(const float rd[3], const float ld_mm[3], float eta, float sigma_s[3],
                                  float sigma_a[3]);
/* Unpolarised Fresnel reflectance of a smooth boundary, going from index n1
 * into n2 at the cosine cos_i; 1 past the critical angle. */
double jd_fresnel_dielectric(double cos_i, double n1, double n2);
/* The transmittance into a smooth boundary of index eta under diffuse light:
 * 2 integral of (1 - F(mu)) mu dmu (1 at eta 1). */
double jd_fresnel_mean(double eta);
/* The Fresnel transmittance of a smooth boundary of index eta (the inside's
 * over the outside's) at the outside's cosine mu, the same for light going
 * in as for light coming out towards mu (reciprocity), over its mean under
 * diffuse light (2 integral of T mu dmu), fitted as ab[0] - ab[1] (1 - mu)^5
 * with the mean kept 1: what the full mode's shaders take for the light
 * entering and leaving (jd_fresnel_tc, shaders_es2/light.glsl). At eta 1
 * exactly 1 and 0; at 1.3 1.043 and 0.912 (the true curve 1.047, 1.008,
 * 0.76 at mu 1, 0.5, 0.2; the fit 1.043, 1.015, 0.745), where Schlick's form,
 * 1.05 - 1.05 (1 - mu)^5 whatever eta, was 1.05, 1.017, 0.706 and at eta 1
 * darkened the rim that no boundary darkens. ab[0] is at most 1.049 over
 * eta 1..3. */
void jd_fresnel_fit(double eta, float ab[2]);
/* The classical dipole's total diffuse reflectance (Jensen et al. 2001). */
double jd_dipole_rd_total(double alpha, double A);
/* The exact albedo of an isotropically scattering half-space behind a
 * smooth boundary of index eta, under diffuse light (of the light that
 * entered), over jd_dipole_rd_total: from the transport equation
 * (reference/halfspace_albedo.c), tabulated in core/albedo_table.c and read
 * bilinearly; eta held to 1..3. */
double jd_albedo_ratio(double alpha, double eta);
/* jd_dipole_rd_total at eta's A times jd_albedo_ratio: the albedo jade
 * renders with. */
double jd_albedo_total(double alpha, double eta);
/* Exitance from unit irradiance on every entry point at distance >= t mm. */
double jd_dipole_tail(const jd_dipole *d, int channel, double t_mm);
/* Diffusion profile Rd(r), r in mm. */
double jd_dipole_rd(const jd_dipole *d, int channel, double r_mm);

#ifdef __cplusplus
}
#endif

#endif
