/* Generates jade's default asset as OBJ on stdout: a (2,3) torus knot whose
 * tube swells and pinches, so one closed surface has thick parts that stay
 * dark when back-lit and thin parts that glow. 720 x 64 quads, 92,160
 * triangles. tools/make_default_asset.sh encodes it with draco_encoder. */
#include <math.h>
#include <stdio.h>

#define SEG 720
#define RING 64

typedef struct { double x, y, z; } v3;
static v3 add(v3 a, v3 b) { return (v3){a.x + b.x, a.y + b.y, a.z + b.z}; }
static v3 sub(v3 a, v3 b) { return (v3){a.x - b.x, a.y - b.y, a.z - b.z}; }
static v3 mul(v3 a, double s) { return (v3){a.x * s, a.y * s, a.z * s}; }
static double dot(v3 a, v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static v3 cross(v3 a, v3 b) { return (v3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
static v3 norm(v3 a) { return mul(a, 1.0 / sqrt(dot(a, a))); }

static v3 curve(double t)
{
    double r = 2.0 + cos(3.0 * t);
    return (v3){r * cos(2.0 * t), 1.1 * sin(3.0 * t), r * sin(2.0 * t)};
}

static double tube_radius(double t)
{
    /* Three swellings and three pinches around the knot. */
    double s = 0.5 + 0.5 * sin(3.0 * t + 0.7);
    return 0.12 + 0.55 * s * s;
}

int main(void)
{
    static v3 c[SEG], tan_[SEG], nrm[SEG];
    for (int i = 0; i < SEG; i++) {
        double t = 2.0 * M_PI * i / SEG;
        c[i] = curve(t);
        tan_[i] = norm(sub(curve(t + 1e-4), curve(t - 1e-4)));
    }
    /* Rotation-minimising frame by double reflection (Wang et al. 2008). */
    v3 up = {0, 1, 0};
    nrm[0] = norm(cross(cross(tan_[0], up), tan_[0]));
    for (int i = 0; i + 1 < SEG; i++) {
        v3 v1 = sub(c[i + 1], c[i]);
        double c1 = dot(v1, v1);
        v3 rl = sub(nrm[i], mul(v1, 2.0 / c1 * dot(v1, nrm[i])));
        v3 tl = sub(tan_[i], mul(v1, 2.0 / c1 * dot(v1, tan_[i])));
        v3 v2 = sub(tan_[i + 1], tl);
        double c2 = dot(v2, v2);
        nrm[i + 1] = norm(sub(rl, mul(v2, 2.0 / c2 * dot(v2, rl))));
    }
    /* The frame comes back twisted after one loop: spread the twist evenly. */
    v3 last = nrm[SEG - 1];
    v3 b0 = cross(tan_[0], nrm[0]);
    double twist = atan2(dot(last, b0), dot(last, nrm[0]));
    for (int i = 0; i < SEG; i++) {
        double a = -twist * i / SEG;
        v3 b = cross(tan_[i], nrm[i]);
        nrm[i] = add(mul(nrm[i], cos(a)), mul(b, sin(a)));
    }
    printf("# jade default asset: swelling (2,3) torus knot, %d triangles\n", 2 * SEG * RING);
    for (int i = 0; i < SEG; i++) {
        double t = 2.0 * M_PI * i / SEG, rad = tube_radius(t);
        v3 b = cross(tan_[i], nrm[i]);
        for (int j = 0; j < RING; j++) {
            double a = 2.0 * M_PI * j / RING;
            v3 p = add(c[i], mul(add(mul(nrm[i], cos(a)), mul(b, sin(a))), rad));
            printf("v %.6f %.6f %.6f\n", p.x, p.y, p.z);
        }
    }
    /* Outward winding: with (n, b, t) right-handed, (i,j) (i,j+1) (i+1,j) faces out. */
    for (int i = 0; i < SEG; i++)
        for (int j = 0; j < RING; j++) {
            int a = i * RING + j + 1, b = i * RING + (j + 1) % RING + 1;
            int cc = ((i + 1) % SEG) * RING + j + 1, d = ((i + 1) % SEG) * RING + (j + 1) % RING + 1;
            printf("f %d %d %d\nf %d %d %d\n", a, cc, b, b, cc, d);
        }
    return 0;
}
