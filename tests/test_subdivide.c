/* Coarse meshes split at load (core/mesh_subdivide.c): a box of 12
 * triangles comes back with no edge longer than a twelfth of its diagonal,
 * the same surface (area, enclosed volume), closed (every edge in exactly
 * two triangles, once each way: no crack), within the caps asked for; and
 * as the file has it where the caller keeps the triangles (jade convert). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mesh_load.h"

static unsigned char mem[8 << 20];

static const char cube[] = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
                           "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
                           "f 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n";

static int load(int keep, uint32_t max_faces, jd_mesh *m)
{
    jd_arena a;
    jd_arena_init(&a, mem, sizeof mem);
    jd_error err = {0};
    jd_load_desc d = {.path = "the box", .data = cube, .size = sizeof cube - 1, .allow_32bit_indices = 1,
                      .keep_face_order = keep, .max_faces = max_faces};
    if (jd_mesh_load_draco(&d, &a, m, NULL, &err)) {
        printf("%s\n", err.msg);
        return -1;
    }
    return 0;
}

static const float *P(const jd_mesh *m, uint32_t i) { return m->positions + 3 * (size_t)jd_mesh_index(m, i); }

static int cmp_edge(const void *a, const void *b)
{
    const float *p = a, *q = b;
    for (int k = 0; k < 6; k++)
        if (p[k] != q[k]) return p[k] < q[k] ? -1 : 1;
    return 0;
}

int main(void)
{
    jd_mesh m;
    CHECK(load(1, 0, &m) == 0 && m.num_indices == 36, "kept as the file has it: %u triangles", m.num_indices / 3);

    CHECK(load(0, 0, &m) == 0, "loads split");
    uint32_t n = m.num_indices / 3;
    CHECK(n > 12 && n < 4000, "split: %u triangles, %u vertices", n, m.num_vertices);
    double longest = 0, area = 0, vol6 = 0;
    /* Each directed edge by its two end positions: closed means every
     * edge (a, b) has its (b, a), and no other edge takes it. */
    float(*e)[6] = malloc(sizeof *e * 3 * n);
    for (uint32_t t = 0; t < n; t++) {
        const float *v[3] = {P(&m, 3 * t), P(&m, 3 * t + 1), P(&m, 3 * t + 2)};
        double u[3], w[3];
        for (int c = 0; c < 3; c++) u[c] = (double)v[1][c] - v[0][c], w[c] = (double)v[2][c] - v[0][c];
        double x = u[1] * w[2] - u[2] * w[1], y = u[2] * w[0] - u[0] * w[2], z = u[0] * w[1] - u[1] * w[0];
        area += 0.5 * sqrt(x * x + y * y + z * z);
        vol6 += v[0][0] * x + v[0][1] * y + v[0][2] * z;
        for (int k = 0; k < 3; k++) {
            const float *a = v[k], *b = v[(k + 1) % 3];
            double l = sqrt(((double)a[0] - b[0]) * (a[0] - b[0]) + ((double)a[1] - b[1]) * (a[1] - b[1]) +
                            ((double)a[2] - b[2]) * (a[2] - b[2]));
            if (l > longest) longest = l;
            memcpy(e[3 * t + k], a, 12);
            memcpy(e[3 * t + k] + 3, b, 12);
        }
    }
    double limit = sqrt(12.0) / 12.0; /* the diagonal 2 sqrt(3), over 12 */
    CHECK(longest <= limit * 1.0001, "no edge longer than %.4f: %.4f", limit, longest);
    CHECK(fabs(area - 24.0) < 1e-3, "the same surface: area %.5f (24)", area);
    CHECK(fabs(fabs(vol6) / 6.0 - 8.0) < 1e-3, "the same volume: %.5f (8)", fabs(vol6) / 6.0);
    qsort(e, 3 * n, sizeof *e, cmp_edge);
    int open = 0;
    for (uint32_t i = 0; i < 3 * n; i++) {
        float r[6];
        memcpy(r, e[i] + 3, 12);
        memcpy(r + 3, e[i], 12);
        const float(*f)[6] = bsearch(r, e, 3 * n, sizeof *e, cmp_edge);
        int dup = (i > 0 && !cmp_edge(e[i - 1], e[i])) || (i + 1 < 3 * n && !cmp_edge(e[i + 1], e[i]));
        open += !f || dup;
    }
    CHECK(open == 0, "closed: %d of %u edges without their twin (a crack) or doubled", open, 3 * n);
    free(e);

    CHECK(load(0, 100, &m) == 0 && m.num_indices / 3 <= 100 && m.num_indices / 3 > 12,
          "split within 100 triangles when asked: %u", m.num_indices / 3);
    return jd_check_summary("subdivide");
}
