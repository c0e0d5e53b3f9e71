#include "sh.h"

#include <math.h>
#include <stddef.h>

void jd_cube_face_frame(int f, float a[3], float u[3], float v[3])
{
    static const float frames[6][9] = {
        {1, 0, 0, 0, 0, -1, 0, 1, 0},  {-1, 0, 0, 0, 0, 1, 0, 1, 0},
        {0, 1, 0, 1, 0, 0, 0, 0, -1},  {0, -1, 0, 1, 0, 0, 0, 0, 1},
        {0, 0, 1, 1, 0, 0, 0, 1, 0},   {0, 0, -1, -1, 0, 0, 0, 1, 0},
    };
    for (int i = 0; i < 3; i++) {
        a[i] = frames[f][i];
        u[i] = frames[f][3 + i];
        v[i] = frames[f][6 + i];
    }
}

void jd_sh_basis(const double w[3], double y[9])
{
    double x = w[0], yy = w[1], z = w[2];
    y[0] = 0.282095;
    y[1] = 0.488603 * yy;
    y[2] = 0.488603 * z;
    y[3] = 0.488603 * x;
    y[4] = 1.092548 * x * yy;
    y[5] = 1.092548 * yy * z;
    y[6] = 0.315392 * (3.0 * z * z - 1.0);
    y[7] = 1.092548 * x * z;
    y[8] = 0.546274 * (x * x - yy * yy);
}

void jd_sh_project_atlas(const uint8_t *rgba, int n, double out[9][3])
{
    for (int k = 0; k < 9; k++) out[k][0] = out[k][1] = out[k][2] = 0.0;
    int width = 3 * n;
    for (int f = 0; f < 6; f++) {
        float a[3], u[3], v[3];
        jd_cube_face_frame(f, a, u, v);
        int ox = (f % 3) * n, oy = (f / 3) * n;
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                double fu = (i + 0.5) / n * 2.0 - 1.0, fv = (j + 0.5) / n * 2.0 - 1.0;
                double q = 1.0 + fu * fu + fv * fv;
                double dw = 4.0 / ((double)n * n * q * sqrt(q));
                double w[3], y[9];
                for (int c = 0; c < 3; c++) w[c] = a[c] + fu * u[c] + fv * v[c];
                double l = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
                for (int c = 0; c < 3; c++) w[c] /= l;
                jd_sh_basis(w, y);
                const uint8_t *px = rgba + 4 * ((size_t)(oy + j) * width + ox + i);
                for (int k = 0; k < 9; k++)
                    for (int c = 0; c < 3; c++) out[k][c] += px[c] / 255.0 * y[k] * dw;
            }
    }
}

double jd_unpack_bytes(const uint8_t *px, int highp)
{
    double v = px[0] / 255.0 + px[1] / 65025.0;
    if (highp) v += px[2] / (255.0 * 65025.0);
    return v;
}

double jd_unpack_signed_bytes(const uint8_t *px, int highp)
{
    if (highp) return jd_unpack_bytes(px, 1) * 2.0 - 1.0;
    return (px[0] / 255.0 + px[1] / 65025.0) - (px[2] / 255.0 + px[3] / 65025.0);
}

void jd_sh_decode(const uint8_t *rgba27, int highp, jd_sh9 *out)
{
    /* Stored: the mean over all texels of L Y dw 6N^2/(4 pi), divided by 1.5. */
    for (int r = 0; r < 27; r++) {
        double mean = jd_unpack_signed_bytes(rgba27 + 4 * r, highp) * 1.5;
        out->c[r / 3][r % 3] = (float)(mean * 4.0 * M_PI);
    }
}
