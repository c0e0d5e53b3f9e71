/* The triangle order chosen at load (meshoptimizer, in the decoder's child):
 * the same triangles as the file's order, in an order that makes a
 * 16-entry FIFO vertex cache (a small GPU's post-transform cache) miss
 * less. Skipped where jade was built without meshoptimizer. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mesh_load.h"

static unsigned char mem[2][32 << 20];

static void sort3(uint32_t t[3])
{
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2 - a; b++)
            if (t[b] > t[b + 1]) { uint32_t x = t[b]; t[b] = t[b + 1]; t[b + 1] = x; }
}

static int cmp_triple(const void *a, const void *b)
{
    const uint32_t *p = a, *q = b;
    for (int k = 0; k < 3; k++)
        if (p[k] != q[k]) return p[k] < q[k] ? -1 : 1;
    return 0;
}

/* Vertex shader runs per triangle with a 16-entry FIFO cache. */
static double acmr(const jd_mesh *m)
{
    uint32_t cache[16];
    int n = 0, head = 0;
    unsigned long misses = 0;
    for (uint32_t i = 0; i < m->num_indices; i++) {
        uint32_t v = jd_mesh_index(m, i);
        int hit = 0;
        for (int k = 0; k < n; k++) hit |= cache[k] == v;
        if (hit) continue;
        misses++;
        cache[head] = v;
        head = (head + 1) % 16;
        if (n < 16) n++;
    }
    return (double)misses / (m->num_indices / 3);
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "assets/default.drc";
    jd_mesh m[2];
    for (int k = 0; k < 2; k++) {
        jd_arena a;
        jd_arena_init(&a, mem[k], sizeof mem[k]);
        jd_error err = {0};
        jd_load_desc d = {.path = path, .allow_32bit_indices = 1, .keep_face_order = k == 0};
        if (jd_mesh_load_draco(&d, &a, &m[k], NULL, &err)) { printf("%s\n", err.msg); return 1; }
    }
    double before = acmr(&m[0]), after = acmr(&m[1]);
    printf("%s: %u triangles; vertex shader runs per triangle (16-entry FIFO): %.3f in the file's order, %.3f reordered\n",
           path, m[0].num_indices / 3, before, after);
    if (before == after && !memcmp(m[0].indices, m[1].indices, (size_t)m[0].num_indices * m[0].index_size)) {
        printf("skipped: this build has no meshoptimizer (libmeshoptimizer-dev), so the file's order is kept\n");
        return 77;
    }
    uint32_t n = m[0].num_indices / 3;
    uint32_t(*t[2])[3];
    for (int k = 0; k < 2; k++) {
        t[k] = malloc(sizeof *t[k] * n);
        for (uint32_t f = 0; f < n; f++) {
            for (int c = 0; c < 3; c++) t[k][f][c] = jd_mesh_index(&m[k], 3 * f + (uint32_t)c);
            sort3(t[k][f]);
        }
        qsort(t[k], n, sizeof *t[k], cmp_triple);
    }
    CHECK(m[0].num_indices == m[1].num_indices && !memcmp(t[0], t[1], sizeof *t[0] * n),
          "the same %u triangles in both orders", n);
    CHECK(after < 0.85 * before, "fewer vertex shader runs: %.3f -> %.3f per triangle", before, after);
    free(t[0]);
    free(t[1]);
    return jd_check_summary("mesh order");
}
