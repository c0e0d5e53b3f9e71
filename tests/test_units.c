/* GL-free units: arena, math, mesh helpers, materials, Draco header, SH. */
#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <string.h>

#include "arena.h"
#include "check.h"
#include "mesh_curvature.h"
#include "mesh_thickness.h"
#include "mesh_bounce.h"
#include "mesh_grid.h"
#include "draco_header.h"
#include "frame_cost.h"
#include "gl_caps.h"
#include "material.h"
#include "mesh.h"
#include "profile.h"
#include "sh.h"
#include "vmath.h"

static void test_arena(void)
{
    static unsigned char mem[1024];
    jd_arena a;
    jd_error err = {0};
    jd_arena_init(&a, mem, sizeof mem);
    void *p = jd_arena_alloc(&a, 10, 64, "x", &err);
    CHECK(p && ((uintptr_t)p & 63) == 0, "aligned allocation");
    void *t = jd_arena_alloc_top(&a, 100, 16, "t", &err);
    CHECK(t && ((uintptr_t)t & 15) == 0 && (unsigned char *)t + 100 <= mem + sizeof mem, "top allocation inside");
    size_t mark = jd_arena_top_mark(&a);
    CHECK(jd_arena_alloc_top(&a, 200, 16, "t2", &err) != NULL, "second top allocation");
    jd_arena_top_reset(&a, mark);
    CHECK(a.top == mark, "top reset");
    CHECK(jd_arena_alloc(&a, 5000, 16, "the big thing", &err) == NULL, "over budget fails");
    CHECK(err.code == JD_ERR_BUDGET && strstr(err.msg, "the big thing"), "budget error names the allocation: %s", err.msg);
    CHECK(a.peak >= 10 + 300, "peak tracks both ends (%zu)", a.peak);
    jd_arena_reset(&a, 0);
    CHECK(jd_arena_used(&a) == a.top, "reset bottom");
}

static void test_math(void)
{
    jd_mat4 v = jd_m4_look_at(jd_v3(0, 0, 5), jd_v3(0, 0, 0), jd_v3(0, 1, 0));
    jd_vec3 p = jd_m4_point(v, jd_v3(0, 0, 0));
    CHECK(fabsf(p.z + 5) < 1e-5f && fabsf(p.x) < 1e-6f, "look_at puts the target at -5 z (%g)", (double)p.z);
    jd_mat4 pr = jd_m4_perspective(90, 1, 1, 10);
    jd_vec3 n = jd_m4_point(pr, jd_v3(0, 0, -1)), f = jd_m4_point(pr, jd_v3(0, 0, -10));
    CHECK(fabsf(n.z + 1) < 1e-5f && fabsf(f.z - 1) < 1e-4f, "perspective maps near/far to -1/1");
    jd_mat4 o = jd_m4_ortho(-1, 1, -1, 1, 1, 3);
    jd_vec3 mid = jd_m4_point(o, jd_v3(0.5f, 0, -2));
    CHECK(fabsf(mid.z) < 1e-6f && fabsf(mid.x - 0.5f) < 1e-6f, "ortho is linear in depth");
    jd_vec3 d = jd_v3_from_angles(90, 0);
    CHECK(fabsf(d.x - 1) < 1e-6f, "azimuth 90 is +X");
}

static void test_mesh(void)
{
    static unsigned char mem[1 << 16];
    jd_arena a;
    jd_error err = {0};
    jd_arena_init(&a, mem, sizeof mem);
    float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    float nrm[12];
    uint32_t idx[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    jd_mesh m = {0};
    m.num_vertices = 4;
    m.positions = pos;
    m.normals = nrm;
    CHECK(jd_mesh_set_indices(&m, idx, 12, 0, &a, &err) == JD_OK && m.index_size == 2, "narrowed to 16-bit");
    CHECK(jd_mesh_validate(&m, "tet", &err) == JD_OK, "tetrahedron validates");
    jd_mesh_compute_normals(&m);
    jd_mesh_compute_bounds(&m);
    CHECK(nrm[0] < -0.5f && nrm[1] < -0.5f && nrm[2] < -0.5f, "corner normal points out (%g %g %g)", (double)nrm[0],
          (double)nrm[1], (double)nrm[2]);
    CHECK(m.bmax.x == 1 && m.bmin.y == 0, "bounds");
    ((uint16_t *)m.indices)[4] = 9;
    CHECK(jd_mesh_validate(&m, "bad.drc", &err) == JD_ERR_FORMAT && strstr(err.msg, "bad.drc") &&
              strstr(err.msg, "vertex 9"),
          "out-of-range index refused: %s", err.msg);
    ((uint16_t *)m.indices)[4] = 1;
    pos[5] = NAN;
    CHECK(jd_mesh_validate(&m, "nan.drc", &err) == JD_ERR_FORMAT, "non-finite position refused: %s", err.msg);
    pos[5] = 0;
    jd_mesh proxy;
    CHECK(jd_mesh_build_proxy(&m, 8, &a, &proxy, &err) == JD_OK && proxy.num_indices == 12, "proxy of a tiny mesh keeps it");
    m.num_vertices = 70000;
    CHECK(jd_mesh_set_indices(&m, idx, 12, 0, &a, &err) == JD_ERR_UNSUPPORTED && strstr(err.msg, "OES_element_index_uint"),
          "32-bit indices refused without the extension: %s", err.msg);
}

/* A slab thinner than a proxy cell, its top and underside gridded alike: the
 * proxy keeps the two sides apart (their normals summed would cancel, and
 * the light map's irradiance, n.l of the proxy's normals, came out at half
 * or less on such a floor), each side at its own height. */
static void test_proxy_thin(void)
{
    static unsigned char mem[1 << 16];
    jd_arena a;
    jd_error err = {0};
    jd_arena_init(&a, mem, sizeof mem);
    enum { N = 5 }; /* vertices per side of each grid */
    float pos[2 * N * N * 3], nrm[2 * N * N * 3];
    uint32_t idx[2 * (N - 1) * (N - 1) * 6];
    uint32_t k = 0;
    for (int side = 0; side < 2; side++)
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++) {
                int v = side * N * N + j * N + i;
                pos[3 * v] = 10.0f * (float)i / (N - 1);
                pos[3 * v + 1] = side ? -0.1f : 0.1f;
                pos[3 * v + 2] = 10.0f * (float)j / (N - 1);
                nrm[3 * v] = nrm[3 * v + 2] = 0.0f;
                nrm[3 * v + 1] = side ? -1.0f : 1.0f;
                if (i + 1 < N && j + 1 < N) {
                    uint32_t a0 = (uint32_t)v, a1 = a0 + 1, b0 = a0 + N, b1 = b0 + 1;
                    uint32_t t[6] = {a0, b0, b1, a0, b1, a1}; /* +y; the underside reversed */
                    for (int q = 0; q < 6; q++) idx[k++] = side ? t[q % 3 == 1 ? q + 1 : q % 3 == 2 ? q - 1 : q] : t[q];
                }
            }
    jd_mesh m = {0};
    m.num_vertices = 2 * N * N;
    m.positions = pos;
    m.normals = nrm;
    CHECK(jd_mesh_set_indices(&m, idx, k, 0, &a, &err) == JD_OK, "slab indices");
    jd_mesh_compute_bounds(&m);
    jd_mesh proxy;
    CHECK(jd_mesh_build_proxy(&m, 4, &a, &proxy, &err) == JD_OK, "slab proxy: %s", err.msg);
    int apart = proxy.num_vertices > 0 && proxy.num_indices > 0;
    for (uint32_t v = 0; v < proxy.num_vertices; v++) {
        float y = proxy.positions[3 * v + 1], ny = proxy.normals[3 * v + 1];
        apart &= (y > 0.09f && ny > 0.99f) || (y < -0.09f && ny < -0.99f);
    }
    CHECK(apart, "a slab thinner than a cell keeps both sides in its proxy (%u vertices, %u triangles)",
          proxy.num_vertices, proxy.num_indices / 3);

    /* The part's thickness along each vertex's inward normal: 0.2 from
     * either sheet; with the underside's triangles gone, the top's rays
     * leave through nothing (the cap) and the underside's still meet the
     * top. */
    float th[2 * N * N];
    int thick_ok = jd_mesh_thickness(&m, 5.0f, &a, th, &err) == JD_OK;
    for (int v = 0; v < 2 * N * N; v++) thick_ok &= fabsf(th[v] - 0.2f) < 1e-4f;
    CHECK(thick_ok, "a 0.2 thick slab measures 0.2 under every vertex (%g, %g)", (double)th[0], (double)th[N * N]);
    m.num_indices = k / 2;
    thick_ok = jd_mesh_thickness(&m, 5.0f, &a, th, &err) == JD_OK;
    for (int v = 0; v < 2 * N * N; v++) thick_ok &= fabsf(th[v] - (v < N * N ? 5.0f : 0.2f)) < 1e-4f;
    CHECK(thick_ok, "one sheet: the cap above it, 0.2 below (%g, %g)", (double)th[0], (double)th[N * N]);
    m.num_indices = k;

    /* A mesh too large for a ray a vertex takes the proxy's thickness round
     * each vertex, from the proxy vertices facing its way: 0.2 under both
     * sheets (the other sheet's proxy vertices, 0.2 away, face the other
     * way); with no proxy vertex within reach, the cap. */
    float pth[64];
    int from_ok = proxy.num_vertices <= 64 && jd_mesh_thickness(&proxy, 5.0f, &a, pth, &err) == JD_OK &&
                  jd_mesh_thickness_from(&m, &proxy, pth, 4.0f, 5.0f, &a, th, &err) == JD_OK;
    for (int v = 0; from_ok && v < 2 * N * N; v++) from_ok &= fabsf(th[v] - 0.2f) < 0.01f;
    CHECK(from_ok, "from the proxy: a 0.2 slab measures 0.2 under every vertex (%g, %g; %u proxy vertices)",
          (double)th[0], (double)th[N * N], proxy.num_vertices);
    jd_mesh coarse; /* 2 cells: its vertices at the means of its cells', none on the mesh's */
    from_ok = jd_mesh_build_proxy(&m, 2, &a, &coarse, &err) == JD_OK && coarse.num_vertices <= 64 &&
              jd_mesh_thickness(&coarse, 5.0f, &a, pth, &err) == JD_OK &&
              jd_mesh_thickness_from(&m, &coarse, pth, 1e-3f, 5.0f, &a, th, &err) == JD_OK;
    int capped = 0;
    for (int v = 0; v < 2 * N * N; v++) capped += th[v] > 1.0f; /* the cap, averaged with neighbours after */
    CHECK(from_ok && capped > 0, "from the proxy: vertices with none within reach take the cap (%d of %d over 1; %s)", capped,
          2 * N * N, err.msg);

    /* Two opposed vertices in each of 40,000 cells: the sides kept apart
     * would take 80,000 vertices, past 16-bit indices; the proxy is made
     * with one cluster a cell instead of failing. */
    enum { CELLS = 40000 };
    static float bp[2 * CELLS * 3], bn[2 * CELLS * 3];
    static unsigned char big[6 << 20];
    for (int c = 0; c < CELLS; c++)
        for (int side = 0; side < 2; side++) {
            float *p = bp + 3 * (2 * c + side), *n = bn + 3 * (2 * c + side);
            p[0] = (float)(c % 64) + 0.5f, p[1] = (float)((c / 64) % 64) + 0.5f, p[2] = (float)(c / 4096) + 0.5f;
            n[0] = n[2] = 0.0f, n[1] = side ? -1.0f : 1.0f;
        }
    jd_mesh b = {0};
    b.num_vertices = 2 * CELLS;
    b.positions = bp;
    b.normals = bn;
    b.bmin = (jd_vec3){0, 0, 0};
    b.bmax = (jd_vec3){64, 64, 64};
    jd_arena_init(&a, big, sizeof big);
    CHECK(jd_mesh_build_proxy(&b, 64, &a, &proxy, &err) == JD_OK && proxy.num_vertices == CELLS,
          "past 65,535 clusters the proxy takes one a cell (%u vertices): %s", proxy.num_vertices, err.msg);
}

/* The surface's curvature at each vertex (mesh_curvature.c), the larger
 * principal one: a sphere of radius 2 is 1/2 everywhere, a tube of radius
 * 1 is 1 (round it; 0 along it), a flat grid 0. On a latitude-longitude
 * grid of each, away from the sphere's poles and the tube's open ends. */
static void test_curvature(void)
{
    static unsigned char mem[1 << 18];
    jd_arena a;
    jd_error err = {0};
    enum { R = 24, C = 48 }; /* rows (latitude or along the tube), columns round it */
    static float pos[(R + 1) * C * 3], nrm[(R + 1) * C * 3], k[(R + 1) * C];
    static uint32_t idx[R * C * 6];
    for (int shape = 0; shape < 3; shape++) {
        jd_arena_init(&a, mem, sizeof mem);
        uint32_t n = 0;
        for (int i = 0; i <= R; i++)
            for (int j = 0; j < C; j++) {
                float *p = pos + 3 * (i * C + j), *q = nrm + 3 * (i * C + j);
                double ph = 2.0 * M_PI * j / C, th = M_PI * i / R;
                if (shape == 0) { /* sphere, radius 2 */
                    q[0] = (float)(sin(th) * cos(ph)), q[1] = (float)cos(th), q[2] = (float)(sin(th) * sin(ph));
                    p[0] = 2.0f * q[0], p[1] = 2.0f * q[1], p[2] = 2.0f * q[2];
                } else if (shape == 1) { /* tube along y, radius 1, 0.25 a row */
                    q[0] = (float)cos(ph), q[1] = 0.0f, q[2] = (float)sin(ph);
                    p[0] = q[0], p[1] = 0.25f * (float)i, p[2] = q[2];
                } else { /* a flat grid, y up */
                    q[0] = q[2] = 0.0f, q[1] = 1.0f;
                    p[0] = 0.25f * (float)j, p[1] = 0.0f, p[2] = 0.25f * (float)i;
                }
            }
        for (int i = 0; i < R; i++)
            for (int j = 0; j + (shape == 2) < C; j++) {
                uint32_t a0 = (uint32_t)(i * C + j), a1 = (uint32_t)(i * C + (j + 1) % C), b0 = a0 + C, b1 = a1 + C;
                uint32_t t[6] = {a0, b0, a1, a1, b0, b1};
                for (int e = 0; e < 6; e++) idx[n++] = t[e];
            }
        jd_mesh m = {0};
        m.num_vertices = (R + 1) * C;
        m.positions = pos;
        m.normals = nrm;
        CHECK(jd_mesh_set_indices(&m, idx, n, 1, &a, &err) == JD_OK, "curvature test indices: %s", err.msg);
        CHECK(jd_mesh_curvature(&m, &a, k, &err) == JD_OK, "curvature: %s", err.msg);
        float want = shape == 0 ? 0.5f : shape == 1 ? 1.0f : 0.0f, lo = 1e9f, hi = -1e9f;
        for (int i = 4; i <= R - 4; i++)
            for (int j = 4; j < C - 4; j++) {
                lo = fminf(lo, k[i * C + j]);
                hi = fmaxf(hi, k[i * C + j]);
            }
        CHECK(lo >= want * 0.85f - 1e-4f && hi <= want * 1.15f + 1e-4f, "%s: curvature %g to %g, want %g",
              shape == 0 ? "a sphere of radius 2" : shape == 1 ? "a tube of radius 1" : "a flat grid", (double)lo,
              (double)hi, (double)want);
    }
}

/* The light between parts (mesh_bounce.c) on an L of a floor and a wall,
 * 10 x 10 each: its transfer at floor vertices near the wall against the
 * same quantities found another way here, by brute force over the light's
 * directions, at 256 rays a step (within 2-7% of it; the renderer's 32 are
 * within 12%, before its smoothing). For each of 200 directions l: a fan
 * of 400 rays from the vertex, each one that meets the wall bringing the
 * wall's n.l where a ray from the hit towards l leaves free (G(l),
 * irradiance per unit of the light's). The transfer's four terms are G's
 * projections on the first two orders of harmonics, exactly: the mean of
 * G over the sphere's directions, and 3 times the mean of G l. And a floor
 * alone (nothing to see) takes nothing. */
static void test_bounce(void)
{
    static unsigned char mem[1 << 20];
    jd_arena a;
    jd_error err = {0};
    jd_arena_init(&a, mem, sizeof mem);
    enum { N = 17, V = 2 * N * N, T = 2 * (N - 1) * (N - 1) * 2 };
    static float pos[3 * V], nrm[3 * V], out[JD_BOUNCE_TERMS * V];
    static uint32_t idx[3 * T];
    uint32_t k = 0;
    for (int side = 0; side < 2; side++) /* 0: the floor z = 0, up; 1: the wall x = 0, facing +x */
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++) {
                int v = side * N * N + j * N + i;
                float u = 10.0f * (float)i / (N - 1), w = 10.0f * (float)j / (N - 1) - 5.0f;
                float *p = pos + 3 * v, *n = nrm + 3 * v;
                p[0] = side ? 0.0f : u, p[1] = w, p[2] = side ? u : 0.0f;
                n[0] = side ? 1.0f : 0.0f, n[1] = 0.0f, n[2] = side ? 0.0f : 1.0f;
                if (i + 1 < N && j + 1 < N) {
                    uint32_t a0 = (uint32_t)v, a1 = a0 + 1, b0 = a0 + N, b1 = b0 + 1;
                    /* counter-clockwise seen from the normal's side */
                    uint32_t t[6] = {a0, a1, b1, a0, b1, b0}, r[6] = {a0, b1, a1, a0, b0, b1};
                    for (int q = 0; q < 6; q++) idx[k++] = side ? r[q] : t[q];
                }
            }
    jd_mesh m = {0};
    m.num_vertices = V;
    m.positions = pos;
    m.normals = nrm;
    CHECK(jd_mesh_set_indices(&m, idx, k, 0, &a, &err) == JD_OK, "L indices");
    jd_mesh_compute_bounds(&m);
    CHECK(jd_mesh_bounce(&m, 256, &a, out, &err) == JD_OK, "light between parts: %s", err.msg);
    jd_mesh_grid g;
    size_t top = jd_arena_top_mark(&a);
    CHECK(jd_mesh_grid_triangles(&m, &g, &a, "test grid", &err) == JD_OK, "grid: %s", err.msg);
    const int at[3] = {2, 3, 5}; /* floor vertices (i, N / 2): 1.25, 1.875 and 3.125 from the wall */
    for (int c = 0; c < 3; c++) {
        int v = (N / 2) * N + at[c];
        const float *p = pos + 3 * v;
        float o[3] = {p[0], p[1], p[2] + 1e-3f};
        double m0 = 0.0, m1[3] = {0, 0, 0};
        enum { NL = 200, NR = 400 };
        for (int li = 0; li < NL; li++) { /* the light's directions, evenly over the sphere */
            float lz = 1.0f - 2.0f * ((float)li + 0.5f) / NL, lr = sqrtf(1.0f - lz * lz), lp = 2.3999632f * (float)li;
            float l[3] = {lr * cosf(lp), lr * sinf(lp), lz};
            double gl = 0.0;
            for (int r = 0; r < NR; r++) {
                float uz = ((float)r + 0.5f) / NR, s = sqrtf(uz), ph = 2.3999632f * (float)r;
                float d[3] = {s * cosf(ph), s * sinf(ph), sqrtf(1.0f - uz)};
                jd_mesh_hit h;
                jd_mesh_grid_cast(&m, &g, o, d, 1e-4f, 100.0f, &h);
                if (h.tri == UINT32_MAX || !(d[0] < 0.0f) || !(l[0] > 0.0f)) continue; /* the wall, lit from its side */
                float q[3] = {o[0] + h.t * d[0] + 1e-3f, o[1] + h.t * d[1], o[2] + h.t * d[2]};
                if (!jd_mesh_grid_blocked(&m, &g, q, l, 1e-4f, 100.0f)) gl += l[0];
            }
            gl /= NR;
            m0 += gl;
            for (int x = 0; x < 3; x++) m1[x] += gl * l[x];
        }
        /* Y_0^0 squared over the sphere's 4 pi is 1, Y_1's 3 (times l). */
        double w_exact = m0 / NL, x_exact = 3.0 * m1[0] / NL, z_exact = 3.0 * m1[2] / NL;
        const float *b = out + JD_BOUNCE_TERMS * v;
        CHECK(fabs(b[3] - w_exact) < 0.1 * w_exact && fabs(b[0] - x_exact) < 0.1 * fabs(x_exact) &&
                  fabs(b[2] - z_exact) < 0.1 * fabs(z_exact) && fabs(b[1]) < 0.01,
              "floor vertex %g from the wall: transfer (%.4f, %.4f, %.4f, %.4f), brute force (%.4f, 0, %.4f, %.4f)",
              (double)p[0], (double)b[0], (double)b[1], (double)b[2], (double)b[3], x_exact, z_exact, w_exact);
    }
    jd_arena_top_reset(&a, top);
    m.num_indices = k / 2; /* the floor alone */
    jd_mesh_compute_bounds(&m);
    CHECK(jd_mesh_bounce(&m, 32, &a, out, &err) == JD_OK, "light between parts: %s", err.msg);
    double most = 0.0;
    for (int v = 0; v < N * N; v++)
        for (int t = 0; t < JD_BOUNCE_TERMS; t++) most = fmax(most, fabs(out[JD_BOUNCE_TERMS * v + t]));
    CHECK(most == 0.0, "a floor alone takes no light from itself (largest term %g)", most);
    CHECK(jd_mesh_bounce(&m, 0, &a, out, &err) != JD_OK, "0 rays a vertex is refused");
}

/* A cube wound inside out is turned round; its normals, from a file that
 * agrees with the old winding, follow; a flat sheet is left as it is. */
static void test_orientation(void)
{
    float pos[8 * 3], nrm[8 * 3];
    for (int i = 0; i < 8; i++) {
        pos[3 * i] = (float)(i & 1);
        pos[3 * i + 1] = (float)((i >> 1) & 1);
        pos[3 * i + 2] = (float)((i >> 2) & 1);
        for (int k = 0; k < 3; k++) nrm[3 * i + k] = -(pos[3 * i + k] - 0.5f); /* inward, as the winding below */
    }
    /* Outward faces of the unit cube, then every triangle reversed. */
    static const uint16_t out[36] = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                     2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    uint16_t in[36];
    for (int t = 0; t < 36; t += 3) { in[t] = out[t]; in[t + 1] = out[t + 2]; in[t + 2] = out[t + 1]; }
    jd_mesh m = {.num_vertices = 8, .num_indices = 36, .positions = pos, .normals = nrm, .indices = in, .index_size = 2};
    jd_mesh_compute_bounds(&m);
    CHECK(jd_mesh_orient_outward(&m) == 1, "an inside-out cube is turned round");
    CHECK(memcmp(in, out, sizeof in) == 0, "to the outward winding");
    CHECK(jd_mesh_orient_outward(&m) == 0, "an outward cube is left alone");
    CHECK(jd_mesh_normals_follow_winding(&m) == 1 && nrm[0] < 0 && nrm[21] > 0, "inward normals follow the winding");
    CHECK(jd_mesh_normals_follow_winding(&m) == 0, "agreeing normals are left alone");
    float sheet[4 * 3] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    uint16_t tri[6] = {0, 2, 1, 1, 2, 3};
    jd_mesh s = {.num_vertices = 4, .num_indices = 6, .positions = sheet, .normals = nrm, .indices = tri, .index_size = 2};
    jd_mesh_compute_bounds(&s);
    CHECK(jd_mesh_orient_outward(&s) == 0, "an open sheet keeps its winding");
}

static void test_materials(void)
{
    /* The table's last column, Rd total (Jensen et al. 2001). */
    static const struct { const char *name; float rd[3]; } expect[] = {
        {"apple", {.85f, .84f, .53f}},    {"chicken1", {.31f, .16f, .13f}}, {"chicken2", {.32f, .16f, .11f}},
        {"cream", {.98f, .90f, .72f}},    {"ketchup", {.16f, .01f, .00f}},  {"marble", {.83f, .79f, .75f}},
        {"potato", {.76f, .61f, .21f}},   {"skimmilk", {.81f, .81f, .68f}}, {"skin1", {.44f, .23f, .13f}},
        {"skin2", {.62f, .43f, .34f}},    {"wholemilk", {.91f, .88f, .76f}},
    };
    CHECK(jd_material_count == 11, "eleven materials");
    for (size_t i = 0; i < sizeof expect / sizeof expect[0]; i++) {
        const jd_material *m = jd_material_find(expect[i].name);
        CHECK(m != NULL, "material %s exists", expect[i].name);
        if (!m) continue;
        jd_dipole d;
        jd_dipole_init(&d, m->sigma_s, m->sigma_a, m->eta, 1.0f);
        /* The table's figure is the classical dipole's; jade renders with
         * it times the exact half-space's ratio (within 0.93-1.05 here). */
        for (int c = 0; c < 3; c++) {
            double dip = jd_dipole_rd_total(d.alpha[c], d.A), ratio = jd_albedo_ratio(d.alpha[c], m->eta);
            CHECK(fabs(dip - expect[i].rd[c]) <= 0.011, "%s Rd[%d] = %.3f, table %.2f", m->name, c, dip,
                  (double)expect[i].rd[c]);
            CHECK(fabs(d.rd_total[c] - dip * ratio) < 1e-9 && ratio > 0.92 && ratio < 1.06,
                  "%s albedo[%d] = %.3f, the dipole's times %.3f", m->name, c, d.rd_total[c], ratio);
        }
        /* M(0) is the total diffuse reflectance, and the tail decreases. */
        CHECK(fabs(jd_dipole_tail(&d, 1, 0.0) - d.rd_total[1]) < 1e-9, "%s M(0) = Rd", m->name);
        CHECK(jd_dipole_tail(&d, 1, 5.0) < jd_dipole_tail(&d, 1, 1.0), "%s M decreases", m->name);
    }
    CHECK(fabs(1.0 - jd_dipole_fdr(1.3) - 0.555) < 0.002, "1-Fdr at eta 1.3 is 0.555");
    CHECK(fabs(1.0 - jd_dipole_fdr(1.5) - 0.403) < 0.002, "1-Fdr at eta 1.5 is 0.403");
    /* full's Fresnel factor: exactly 1 where the boundary is index-matched;
     * elsewhere its mean under diffuse light 1, closer to the true
     * transmittance over its mean than Schlick's 1.05 - 1.05 x^5 (RMS,
     * cosine-weighted: what the light map and the exit sum), within 0.05 of
     * it at every cosine from 0.2 to 1, and never over the light map's 21/20. */
    CHECK(fabs(jd_fresnel_dielectric(1.0, 1.0, 1.5) - 0.04) < 1e-9, "4%% reflected head-on at eta 1.5");
    float ab[2];
    jd_fresnel_fit(1.0, ab);
    CHECK(ab[0] == 1.0f && ab[1] == 0.0f, "the fit at eta 1 is 1 (%.6f - %.6f x^5)", ab[0], ab[1]);
    for (int k = 11; k <= 30; k++) {
        double eta = k / 10.0, mean = 0, fit_mean = 0, e_fit = 0, e_schlick = 0, worst = 0;
        jd_fresnel_fit(eta, ab);
        for (int i = 0; i < 1000; i++) {
            double mu = (i + 0.5) / 1000;
            mean += 2 * mu * (1 - jd_fresnel_dielectric(mu, 1.0, eta)) / 1000;
        }
        CHECK(fabs(jd_fresnel_mean(eta) - mean) < 1e-5, "eta %.1f: the mean transmittance %.6f (1000 points: %.6f)",
              eta, jd_fresnel_mean(eta), mean);
        for (int i = 0; i < 1000; i++) {
            double mu = (i + 0.5) / 1000, x = 1 - mu, x5 = x * x * x * x * x;
            double t = (1 - jd_fresnel_dielectric(mu, 1.0, eta)) / mean, f = ab[0] - ab[1] * x5;
            fit_mean += 2 * mu * f / 1000;
            e_fit += 2 * mu * (f - t) * (f - t) / 1000;
            e_schlick += 2 * mu * (1.05 - 1.05 * x5 - t) * (1.05 - 1.05 * x5 - t) / 1000;
            if (mu >= 0.2) worst = fmax(worst, fabs(f - t));
        }
        CHECK(fabs(fit_mean - 1) < 1e-3 && e_fit < e_schlick && worst < 0.05 && ab[0] <= 1.05f,
              "eta %.1f: the fit's mean %.4f, RMS off the true curve %.4f (Schlick's %.4f), at most %.4f from "
              "a cosine of 0.2, %.4f head-on", eta, fit_mean, sqrt(e_fit), sqrt(e_schlick), worst, ab[0]);
    }
}

static void test_draco_header(void)
{
    jd_draco_info info;
    jd_error err = {0};
    /* Sequential 2.2 mesh declaring a billion faces in a 16-byte file. */
    uint8_t seq[] = {'D', 'R', 'A', 'C', 'O', 2, 2, 1, 0, 0, 0, 0x80, 0x94, 0xeb, 0xdc, 0x03, 3};
    CHECK(jd_draco_peek(seq, sizeof seq, "seq.drc", &info, &err) == JD_OK && info.num_faces == 1000000000u,
          "declared faces read (%u)", info.num_faces);
    uint8_t pc[] = {'D', 'R', 'A', 'C', 'O', 2, 2, 0, 0, 0, 0, 1, 1};
    CHECK(jd_draco_peek(pc, sizeof pc, "pc.drc", &info, &err) == JD_ERR_FORMAT && strstr(err.msg, "point cloud"),
          "point cloud refused by name: %s", err.msg);
    CHECK(jd_draco_peek(seq, 0, "e.drc", &info, &err) == JD_ERR_FORMAT && strstr(err.msg, "empty"), "empty: %s", err.msg);
    uint8_t bad[] = "PNG\r\n whatever";
    CHECK(jd_draco_peek(bad, sizeof bad, "x.png", &info, &err) == JD_ERR_FORMAT && strstr(err.msg, "magic"), "magic: %s", err.msg);
    CHECK(jd_draco_peek(seq, 12, "t.drc", &info, &err) == JD_ERR_FORMAT && strstr(err.msg, "truncated"), "truncated: %s", err.msg);
    uint8_t ver[] = {'D', 'R', 'A', 'C', 'O', 9, 0, 1, 0, 0, 0, 1, 1};
    CHECK(jd_draco_peek(ver, sizeof ver, "v.drc", &info, &err) == JD_ERR_FORMAT && strstr(err.msg, "version 9.0"), "version: %s", err.msg);
    /* Metadata claiming 2^32-1 attribute entries in a few bytes. */
    uint8_t meta[] = {'D', 'R', 'A', 'C', 'O', 2, 2, 1, 0, 0, 0x80, 0xff, 0xff, 0xff, 0xff, 0x0f, 0, 0};
    CHECK(jd_draco_peek(meta, sizeof meta, "m.drc", &info, &err) == JD_ERR_FORMAT && strstr(err.msg, "metadata"),
          "absurd metadata counts refused: %s", err.msg);
    /* Valid metadata nested as deep as libdraco reads (1,001 levels below
     * the top) passes; one level more is refused by name; 100,000 levels
     * (300 KB) neither recurse nor overflow anything. */
    static uint8_t deep[11 + 3 + 3 * 100000 + 2 + 8];
    int depths[] = {17, 1001, 1002, 100000};
    for (int k = 0; k < 4; k++) {
        size_t n = 0;
        static const uint8_t head[11] = {'D', 'R', 'A', 'C', 'O', 2, 2, 1, 0, 0, 0x80};
        memcpy(deep, head, sizeof head);
        n = sizeof head;
        deep[n++] = 0; /* no attribute metadata */
        for (int d = 0; d < depths[k]; d++) {
            deep[n++] = 0;  /* entries */
            deep[n++] = 1;  /* one sub-metadata */
            deep[n++] = 0;  /* with an empty name */
        }
        deep[n++] = 0; /* the innermost: no entries */
        deep[n++] = 0; /* and no subs */
        deep[n++] = 4; /* 4 faces, 4 vertices (sequential 2.2: varints) */
        deep[n++] = 4;
        jd_result r = jd_draco_peek(deep, n, "deep.drc", &info, &err);
        if (depths[k] <= 1001)
            CHECK(r == JD_OK && info.num_faces == 4, "metadata %d deep accepted: %s", depths[k], r ? err.msg : "ok");
        else
            CHECK(r == JD_ERR_FORMAT && strstr(err.msg, "1001 levels"), "metadata %d deep refused: %s", depths[k],
                  err.msg);
    }
}

static void test_sh(void)
{
    /* A uniform white environment projects to DC = sqrt(4 pi) (Y00 * 4 pi)
     * and nothing else; the texel solid angles must sum to about 4 pi. */
    enum { N = 16 };
    static uint8_t atlas[3 * N * 2 * N * 4];
    memset(atlas, 255, sizeof atlas);
    double c[9][3];
    jd_sh_project_atlas(atlas, N, c);
    CHECK(fabs(c[0][0] - 0.282095 * 4 * M_PI) < 0.02 * 0.282095 * 4 * M_PI, "DC of white = %.4f", c[0][0]);
    double rest = 0;
    for (int k = 1; k < 9; k++) rest += fabs(c[k][1]);
    CHECK(rest < 0.02, "higher bands of a constant vanish (%.4f)", rest);
    /* Packing decode: a stored 0.5 in both precisions. */
    uint8_t px[4] = {127, 128, 0, 255};
    CHECK(fabs(jd_unpack_bytes(px, 0) - (127 / 255.0 + 128 / 65025.0)) < 1e-12, "mediump decode");
}

/* GPUs known by their strings: the drivers' own (Mesa's under its
 * drm-shims, the vendors' from their documentation and users' logs). */
static void test_recognise(void)
{
    static const struct { const char *vendor, *renderer; int utgard, small, vivante, adreno, limit; const char *tier; } gpus[] = {
        {"lima", "Mali400", 1, 1, 0, 0, 0, "Mali-400/450"},
        {"ARM", "Mali-450 MP", 1, 1, 0, 0, 0, "Mali-400/450"},
        {"Broadcom", "VC4 V3D 2.1", 0, 1, 0, 0, 0, "VideoCore IV"},
        {"Broadcom", "VideoCore IV HW", 0, 1, 0, 0, 0, "VideoCore IV"},
        {"etnaviv", "Vivante GC2000 rev 5108", 0, 0, 2000, 0, 256, "Vivante GC400-GC2000"},
        {"etnaviv", "Vivante GC400 rev 4652", 0, 0, 400, 0, 256, "Vivante GC400-GC2000"},
        {"Vivante Corporation", "GC2000 core", 0, 0, 2000, 0, 256, "Vivante GC400-GC2000"},
        {"etnaviv", "Vivante GC3000 rev 5450", 0, 0, 3000, 0, 0, "Vivante GC3000-GC7000"},
        {"etnaviv", "Vivante GC7000 rev 6214", 0, 0, 7000, 0, 0, "Vivante GC3000-GC7000"},
        {"freedreno", "FD307", 0, 0, 0, 307, 0, "Adreno 3xx"},
        {"Qualcomm", "Adreno (TM) 306", 0, 0, 0, 306, 0, "Adreno 3xx"},
        {"Mesa", "llvmpipe (LLVM 15.0.6, 256 bits)", 0, 0, 0, 0, 0, ""},
        {"NVIDIA Corporation", "NVIDIA H100 80GB HBM3/PCIe/SSE2", 0, 0, 0, 0, 0, ""},
    };
    for (size_t i = 0; i < sizeof gpus / sizeof gpus[0]; i++) {
        jd_gl_caps c;
        memset(&c, 0, sizeof c);
        snprintf(c.vendor, sizeof c.vendor, "%s", gpus[i].vendor);
        snprintf(c.renderer, sizeof c.renderer, "%s", gpus[i].renderer);
        c.frag_highp_precision = 23;
        jd_gl_caps_recognise(&c);
        CHECK(c.utgard == gpus[i].utgard && c.small_register_file == gpus[i].small && c.vivante == gpus[i].vivante &&
                  c.adreno == gpus[i].adreno && c.max_program_instructions == gpus[i].limit,
              "%s / %s: utgard %d small %d vivante %d adreno %d limit %d", gpus[i].vendor, gpus[i].renderer, c.utgard,
              c.small_register_file, c.vivante, c.adreno, c.max_program_instructions);
        CHECK((c.frag_highp_precision == 0) == gpus[i].utgard, "%s: highp %d", gpus[i].renderer, c.frag_highp_precision);
        CHECK(!strcmp(c.tier, gpus[i].tier), "%s: tier '%s', want '%s'", gpus[i].renderer, c.tier, gpus[i].tier);
        /* Only Adreno 3xx, VideoCore IV and Vivante from GC3000 sum full's
         * levels per fragment by their names, on meshes from their sizes on. */
        int from = gpus[i].adreno >= 300 && gpus[i].adreno < 400 ? JD_ADRENO3XX_LEVELS_PER_FRAGMENT_FROM
                   : !strcmp(gpus[i].tier, "VideoCore IV")       ? JD_VC4_LEVELS_PER_FRAGMENT_FROM
                   : gpus[i].vivante >= 3000                     ? JD_VIVANTE_LEVELS_PER_FRAGMENT_FROM
                                                                  : 0;
        CHECK(c.levels_per_fragment_from == from, "%s: levels per fragment from %d vertices", gpus[i].renderer,
              c.levels_per_fragment_from);
    }
    /* The adreno3xx, vc4 and gc7000l profiles as their names would; no other
     * profile. With the vertex stage's textures (the device's own, 16 here,
     * lowered by the profile), per vertex below the count and per fragment
     * from it. */
    for (int i = 0; i < jd_profile_count; i++) {
        jd_gl_caps c;
        memset(&c, 0, sizeof c);
        c.max_vertex_texture_units = c.max_texture_units = 16;
        jd_profile_apply(&jd_profiles[i], &c);
        int from = !strcmp(jd_profiles[i].name, "adreno3xx") ? JD_ADRENO3XX_LEVELS_PER_FRAGMENT_FROM
                   : !strcmp(jd_profiles[i].name, "vc4")     ? JD_VC4_LEVELS_PER_FRAGMENT_FROM
                   : !strcmp(jd_profiles[i].name, "gc7000l") ? JD_VIVANTE_LEVELS_PER_FRAGMENT_FROM
                                                              : 0;
        CHECK(c.levels_per_fragment_from == from, "profile %s: levels per fragment from %d vertices",
              jd_profiles[i].name, c.levels_per_fragment_from);
        int vt = c.max_vertex_texture_units >= JD_DIFFUSION_VERTEX_UNITS;
        unsigned below = from ? (unsigned)from - 1 : 1225, at = from ? (unsigned)from : 46080;
        CHECK(jd_gl_caps_levels_per_vertex(&c, below, 0) == vt && jd_gl_caps_levels_per_vertex(&c, at, 0) == (vt && !from),
              "profile %s: levels per vertex %d for %u vertices, %d for %u", jd_profiles[i].name,
              jd_gl_caps_levels_per_vertex(&c, below, 0), below, jd_gl_caps_levels_per_vertex(&c, at, 0), at);
        /* With a colour texture, not where the light through thin parts'
         * table would find no unit (vc4's 8). */
        int room = c.max_texture_units > JD_FULL_VERTEX_LEVELS_UNITS;
        CHECK(jd_gl_caps_levels_per_vertex(&c, below, 1) == (vt && room), "profile %s: textured, levels per vertex %d",
              jd_profiles[i].name, jd_gl_caps_levels_per_vertex(&c, below, 1));
    }
}

/* The frame-cost model on cases whose answers are published: a program
 * of one instruction over a whole 1080p screen runs at the board's fill
 * rate; a bare vertex program over a mesh of shared vertices at its
 * triangle rate. Each through jd_frame_cost_estimate, with a compiler
 * table holding just those programs. */
static void test_frame_cost(void)
{
    static const char table[] =
        "lima           0:fill.vert+fill.frag  vs    1 fs    1 spills   0 fills   0 cost vc    1 fc    1 f1    1 f2    1 - ok\n"
        "vc4            0:fill.vert+fill.frag  vs    1 fs    1 spills   0 fills   0 cost vc    1 fc    1 f1    1 f2    1 - ok\n"
        "panfrost-t860  0:fill.vert+fill.frag  vs    1 fs    1 spills   0 fills   0 cost vc    1 fc    1 f1    1 f2    1 - ok\n"
        "etnaviv-gc2000 0:fill.vert+fill.frag  vs    1 fs    1 spills   0 fills   0 cost vc    1 fc    1 f1    1 f2    1 - ok\n"
        "etnaviv-gc7000l 0:fill.vert+fill.frag vs    1 fs    1 spills   0 fills   0 cost vc    1 fc    1 f1    1 f2    1 - ok\n"
        "freedreno-a306 0:fill.vert+fill.frag  vs    1 fs    1 spills   0 fills   0 cost vc    1 fc    1 f1    1 f2    1 - ok\n"
        "lima           1:loop.vert+loop.frag  vs    1 fs   69 spills   0 fills   0 cost vc    1 fc   69 f1   56 f2   77 - ok\n";
    static const struct { const char *board; double mpix, mtri; } published[] = {
        {"mali400-mp2", 1000.0, 55.0}, /* ARM: 500 Mpix/s and 55 Mtri/s per pixel processor / GP at 500 MHz */
        {"mali450-mp3", 2250.0, 165.0}, /* 3 x 750 Mpix/s; 55 Mtri/s x 1.5 (clock) x 2 (vertex throughput) */
        {"vc4", 1600.0, 0.0},          /* BCM2835: 1 Gpix/s at 250 MHz, scaled to 400 */
        {"t860-mp4", 3200.0, 0.0},     /* one pixel per clock per core */
        {"imx6q-gc2000", 1188.0, 200.0}, /* 2 pixel pipes at 594 MHz; Freescale: 200 Mtri/s */
        {"sd410-a306", 800.0, 0.0},      /* 0.8 Gpix/s at 400 MHz */
        {"imx8mq-gc7000l", 1600.0, 267.0}, /* NXP: 1.6 Gpixel/s and 267 Mtri/s at 800 MHz */
    };
    CHECK(jd_frame_cost_largest_program(table, "lima") == 69 && jd_frame_cost_largest_program(table, "etnaviv-gc400") == 0,
          "the largest program: lima %d, a compiler with no rows %d", jd_frame_cost_largest_program(table, "lima"),
          jd_frame_cost_largest_program(table, "etnaviv-gc400"));
    static jd_frame_count c;
    static jd_estimate e;
    jd_error err = {0};
    for (size_t i = 0; i < sizeof published / sizeof published[0]; i++) {
        const jd_board *b = jd_board_find(published[i].board);
        CHECK(b != NULL, "board %s", published[i].board);
        if (!b) continue;
        memset(&c, 0, sizeof c);
        c.num_passes = 1;
        jd_pass_count *p = &c.pass[0];
        snprintf(p->pass, sizeof p->pass, "main");
        snprintf(p->program, sizeof p->program, "fill.vert+fill.frag");
        p->width = 1920;
        p->height = 1080;
        p->fragments = 1920.0 * 1080.0;
        p->trips = 1;
        CHECK(jd_frame_cost_estimate(b, &c, table, &e, &err) == JD_OK, "%s: %s", b->name, err.msg);
        double mpix = p->fragments / e.frame_ms / 1e3;
        CHECK(fabs(mpix / published[i].mpix - 1.0) < 0.01, "%s: a one-instruction screen at %.0f Mpix/s, published %.0f",
              b->name, mpix, published[i].mpix);
        if (published[i].mtri > 0) {
            /* A grid: half a vertex per triangle, nothing drawn. */
            p->fragments = 0;
            p->triangles = 1e6;
            p->vertices = 5e5;
            CHECK(jd_frame_cost_estimate(b, &c, table, &e, &err) == JD_OK, "%s: %s", b->name, err.msg);
            double mtri = p->triangles / e.frame_ms / 1e3;
            CHECK(fabs(mtri / published[i].mtri - 1.0) < 0.01, "%s: a bare vertex program at %.1f Mtri/s, published %.0f",
                  b->name, mtri, published[i].mtri);
        }
    }
    /* A loop's trips: 13 of them cost the program as built plus 12 times
     * (one trip more at constant trips + what the loop itself adds). */
    const jd_board *b = jd_board_find("mali400-mp2");
    memset(&c, 0, sizeof c);
    c.num_passes = 1;
    snprintf(c.pass[0].program, sizeof c.pass[0].program, "loop.vert+loop.frag");
    c.pass[0].fragments = 1000;
    c.pass[0].trips = 13;
    CHECK(jd_frame_cost_estimate(b, &c, table, &e, &err) == JD_OK, "%s", err.msg);
    CHECK(fabs(e.pass[0].fs_cost - (69 + 12 * (21 + 13))) < 1e-9, "13 trips cost %g", e.pass[0].fs_cost);
    snprintf(c.pass[0].program, sizeof c.pass[0].program, "nothing.vert+nothing.frag");
    CHECK(jd_frame_cost_estimate(b, &c, table, &e, &err) == JD_ERR_ARG && strstr(err.msg, "nothing.vert+nothing.frag") &&
              strstr(err.msg, "lima"),
          "a program the table lacks is named: %s", err.msg);
    /* A vertex shader the driver reused prints no count: another row's. */
    static const char reuse[] =
        "lima           0:quad.vert+a.frag  vs    6 fs   10 spills   0 fills   0 cost vc    6 fc   10 f1   10 f2   10 - ok\n"
        "lima           1:quad.vert+b.frag  vs    - fs   57 spills   0 fills   0 cost vc    - fc   57 f1   57 f2   57 - ok\n";
    snprintf(c.pass[0].program, sizeof c.pass[0].program, "quad.vert+b.frag");
    c.pass[0].trips = 1;
    CHECK(jd_frame_cost_estimate(b, &c, reuse, &e, &err) == JD_OK && e.pass[0].vs_cost == 6 && e.pass[0].fs_cost == 57,
          "a reused vertex shader's count from another row: %g (%s)", e.pass[0].vs_cost, err.msg);
    /* The built-in table: the one CI checks. */
    CHECK(strstr(jd_frame_cost_table(), "lima ") && strstr(jd_frame_cost_table(), "mesh.vert+shade.frag[full]"),
          "the compiler table is built in");
}

int main(void)
{
    test_arena();
    test_math();
    test_mesh();
    test_orientation();
    test_proxy_thin();
    test_curvature();
    test_bounce();
    test_materials();
    test_draco_header();
    test_sh();
    test_recognise();
    test_frame_cost();
    return jd_check_summary("units");
}
