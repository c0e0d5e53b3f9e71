/* Order-2 spherical harmonics on the CPU: the reference the GPU reduction is
 * tested against, and the decoding of what the GPU reduction reads back. */
#ifndef JD_SH_H
#define JD_SH_H

#include <stdint.h>

typedef struct jd_sh9 { float c[9][3]; } jd_sh9; /* coefficient x RGB */

/* Face f of the capture: axis a, and u, v across it (+X -X +Y -Y +Z -Z). */
void jd_cube_face_frame(int f, float a[3], float u[3], float v[3]);
void jd_sh_basis(const double w[3], double y[9]);

/* Projects an RGBA8 atlas of 3N x 2N texels (rows bottom-up, as glReadPixels
 * returns them) in double precision, with the same solid-angle formula as the
 * shader. */
void jd_sh_project_atlas(const uint8_t *rgba, int n, double out[9][3]);

/* The GPU reduction's last step reads back 27 packed pixels (row k*3+c). */
void jd_sh_decode(const uint8_t *rgba27, int highp, jd_sh9 *out);
/* The value the packing stored, in [0,1]. */
double jd_unpack_bytes(const uint8_t *px, int highp);
/* The signed packing of the SH reduction, in [-1,1]. */
double jd_unpack_signed_bytes(const uint8_t *px, int highp);

#endif
