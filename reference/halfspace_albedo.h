/* The exact albedo of a half-space of isotropically scattering medium under
 * diffuse light, behind an index-matched or a smooth dielectric boundary:
 * what the dipole's total diffuse reflectance approximates, from the
 * transport equation itself. */
#ifndef JD_HALFSPACE_ALBEDO_H
#define JD_HALFSPACE_ALBEDO_H

#ifdef __cplusplus
extern "C" {
#endif

/* alpha: the single-scattering albedo (0..1); eta: the medium's refractive
 * index over the outside's. The part of the diffuse light that entered
 * which comes back out (the light the boundary reflects outright is not in
 * it, as it is not in the dipole's Rd_total). Chandrasekhar's H-function on
 * 400 points (a few to 60 ms); at eta other than 1 the boundary added by
 * solving a 400 x 400 system (another 20 ms). Negative when out of memory
 * (eta other than 1 takes 1.3 MB for the system). */
double jd_halfspace_albedo(double alpha, double eta);

/* The same for a beam: out[k], of the light of a beam at the outside's
 * cosine k / (n - 1) that entered, the part that comes back out (n >= 2);
 * *diffuse, when not NULL, jd_halfspace_albedo's figure from the same
 * solution. 0, or -1 when out of memory or n < 2. */
int jd_halfspace_albedo_beam(double alpha, double eta, int n, double *out, double *diffuse);

/* How the light leaves the surface, as radiance at the outside's cosine
 * mu_i = i / (n - 1) over that of a Lambertian surface with the same
 * exitance (so 2 * integral of it * mu dmu = 1), n in 2..256, either out
 * may be NULL:
 * deep[i], for light that diffused up from deep below (far from where it
 * entered): the Milne problem's H(mu) / (1 - k mu) inside;
 * beam[i * n + j], for the light of a beam that entered at the outside's
 * cosine mu_j, all of it, as a half-space under that beam gives it back
 * (index-matched, H(mu) H(mu_j) / (mu + mu_j) as Chandrasekhar's law of
 * diffuse reflection has it).
 * Behind a smooth dielectric the boundary's internal reflections are added
 * as in jd_halfspace_albedo (1.3 MB; 13-39 ms at eta 1.3, as long as the
 * albedo's). 0, or -1 when out of memory. */
int jd_halfspace_exit(double alpha, double eta, int n, double *deep, double *beam);

#ifdef __cplusplus
}
#endif

#endif
