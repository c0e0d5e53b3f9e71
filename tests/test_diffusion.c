/* The full mode's diffusion, on shapes made here: a flat patch keeps its
 * total diffuse reflectance (diffusion moves light, it makes none and loses
 * none), and the shadow that a thin wall casts on a floor is softened by
 * the material's reach, 1/sigma_tr (skin1's red further than its blue,
 * marble's blue further than skin1's), while the shadow's middle stays
 * dark. With an output folder, the pictures are written there as PPM. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "material.h"
#include "platform.h"
#include "renderer.h"

enum { W = 256, H = 256, MAX_V = 12000, MAX_I = 72000 };
static unsigned char mem[24 << 20];
static uint8_t img[W * H * 4];
static float pos[3 * MAX_V], nrm[3 * MAX_V];
static uint32_t idx[MAX_I];
static uint32_t nv, ni;
static jd_platform *P;
static const char *out_dir; /* argv[1]: where the pictures go, for a person to look at */
static jd_gl_caps caps;

/* A grid of nu x nv quads from o along u and v, facing n. */
static void quad(const float o[3], const float u[3], const float v[3], const float n[3], int nu, int nvv)
{
    uint32_t base = nv;
    for (int j = 0; j <= nvv; j++)
        for (int i = 0; i <= nu; i++) {
            for (int k = 0; k < 3; k++) {
                pos[3 * nv + k] = o[k] + u[k] * i / nu + v[k] * j / nvv;
                nrm[3 * nv + k] = n[k];
            }
            nv++;
        }
    for (int j = 0; j < nvv; j++)
        for (int i = 0; i < nu; i++) {
            uint32_t a = base + (uint32_t)(j * (nu + 1) + i), b = a + 1, c = a + (uint32_t)nu + 1, d = c + 1;
            uint32_t t[6] = {a, b, d, a, d, c};
            memcpy(idx + ni, t, sizeof t);
            ni += 6;
        }
}

static jd_result make_mesh(jd_arena *a, jd_mesh *m, jd_error *err)
{
    memset(m, 0, sizeof *m);
    m->num_vertices = nv;
    m->positions = pos;
    m->normals = nrm;
    jd_mesh_compute_bounds(m);
    return jd_mesh_set_indices(m, idx, ni, 0, a, err);
}

static void save(const char *name)
{
    if (!out_dir) return;
    char path[512];
    snprintf(path, sizeof path, "%s/diffusion_%s.ppm", out_dir, name);
    FILE *f = fopen(path, "wb");
    if (!f) return;
    fprintf(f, "P6 %d %d 255\n", W, H);
    for (int i = 0; i < W * H; i++) fwrite(img + 4 * i, 1, 3, f);
    fclose(f);
}

/* Renders the scene and returns linear light, the display curve undone. */
static void shot(const jd_mesh *m, const jd_scene *s, float *out, const char *name)
{
    static unsigned char arena_mem[24 << 20];
    jd_arena a;
    jd_arena_init(&a, arena_mem, sizeof arena_mem);
    jd_error err = {0};
    jd_renderer_desc d = {.mesh = m, .caps = &caps, .target_fbo = jd_platform_framebuffer(P), .width = W, .height = H};
    jd_renderer *r = NULL;
    CHECK(jd_renderer_create(&d, &a, &r, &err) == JD_OK, "%s", err.msg);
    if (!r) return;
    CHECK(jd_renderer_frame(r, s, NULL, &err) == JD_OK && jd_platform_read_rgba(P, img, &err) == JD_OK, "%s", err.msg);
    for (int i = 0; i < W * H; i++)
        for (int c = 0; c < 3; c++) {
            float y = img[4 * i + c] / 255.0f;
            y *= y;
            out[3 * i + c] = y / (1.0f - 0.15f * y) / (s->exposure > 0 ? s->exposure : 1.0f);
        }
    save(name);
    jd_renderer_destroy(r);
}

static void scene_of(jd_scene *s, const char *material, jd_mode mode)
{
    jd_scene_defaults(s, jd_material_find(material));
    s->mode = mode;
    s->mm_per_unit = 1.0f; /* the meshes are in millimetres */
    s->cam_azimuth = 0;
    s->cam_elevation = 0;
    s->specular = 0;
    s->ambient = 0;
}

static float full_pic[W * H * 3], none_pic[W * H * 3], pics[3][W * H * 3];

/* A flat 160 x 160 mm patch lit and seen head-on: in full mode the centre
 * must show Ft(wo)/c * Rd_total * I Ft(wi)/c, the reference's flat-slab
 * value, whatever the profile's shape (Ft/c as the shaders take it, the
 * true transmittance's fit: jd_fresnel_fit). */
static void flat_patch(void)
{
    nv = ni = 0;
    quad((float[]){-80, -80, 0}, (float[]){160, 0, 0}, (float[]){0, 160, 0}, (float[]){0, 0, 1}, 80, 80);
    jd_arena a;
    jd_arena_init(&a, mem, sizeof mem);
    jd_error err = {0};
    jd_mesh m;
    CHECK(make_mesh(&a, &m, &err) == JD_OK, "%s", err.msg);
    const char *mats[] = {"marble", "skin1", "wholemilk", "ketchup"};
    for (int k = 0; k < 4; k++) {
        const jd_material *mat = jd_material_find(mats[k]);
        jd_dipole dp;
        jd_dipole_init(&dp, mat->sigma_s, mat->sigma_a, mat->eta, 1.0f);
        float ft[2]; /* head-on, Ft/c is the fit's ft[0] both ways */
        jd_fresnel_fit(mat->eta, ft);
        for (int c = 0; c < 3; c++) {
            if (dp.rd_total[c] < 0.05) continue; /* ketchup's green and blue: nothing to measure in 8 bits */
            /* Each channel lit to about 0.9 on screen, where 8 bits resolve 0.2%. */
            jd_scene s;
            scene_of(&s, mats[k], JD_MODE_FULL);
            s.light_azimuth = 0;
            s.light_elevation = 0;
            s.light_intensity = (float)(0.9 / (ft[0] * ft[0] * dp.rd_total[c]));
            char name[32];
            snprintf(name, sizeof name, "patch_%s_%d", mats[k], c);
            shot(&m, &s, full_pic, name);
            double sum = 0;
            int n = 0;
            for (int y = H / 2 - 8; y < H / 2 + 8; y++)
                for (int x = W / 2 - 8; x < W / 2 + 8; x++, n++) sum += full_pic[3 * (y * W + x) + c];
            double want = ft[0] * dp.rd_total[c] * s.light_intensity * ft[0], got = sum / n;
            printf("flat patch, %s, channel %d: %.4f, Rd_total says %.4f (%+.2f%%)\n", mats[k], c, got, want,
                   100.0 * (got / want - 1.0));
            CHECK(fabs(got / want - 1.0) < 0.02, "%s channel %d keeps Rd_total within 2%%", mats[k], c);
        }
    }
}

/* The light inside the shadow within `reach` pixels of its edge, over the
 * lit floor's level, in pixels: how far the lit side's light diffuses in. */
static float penumbra(const float *pic, int c, int y, int edge, int reach, int lit)
{
    float hi = pic[3 * (y * W + lit) + c], sum = 0;
    for (int x = edge - reach; x < edge; x++) sum += pic[3 * (y * W + x) + c] / hi;
    return sum;
}

static float lum(const float *pic, int x, int y)
{
    const float *p = pic + 3 * (y * W + x);
    return (p[0] + p[1] + p[2]) / 3.0f;
}

/* A floor with a thin wall standing on it, lit from the side: the wall's
 * shadow ends in a straight edge across the floor. */
static void shadow_edge(void)
{
    nv = ni = 0;
    quad((float[]){-50, -50, 0}, (float[]){140, 0, 0}, (float[]){0, 100, 0}, (float[]){0, 0, 1}, 70, 50);
    quad((float[]){-1, 50, 0}, (float[]){0, -100, 0}, (float[]){0, 0, 30}, (float[]){-1, 0, 0}, 50, 15);
    quad((float[]){1, -50, 0}, (float[]){0, 100, 0}, (float[]){0, 0, 30}, (float[]){1, 0, 0}, 50, 15);
    quad((float[]){-1, -50, 30}, (float[]){2, 0, 0}, (float[]){0, 100, 0}, (float[]){0, 0, 1}, 1, 50);
    jd_arena a;
    jd_arena_init(&a, mem, sizeof mem);
    jd_error err = {0};
    jd_mesh m;
    CHECK(make_mesh(&a, &m, &err) == JD_OK, "%s", err.msg);
    jd_scene s;
    scene_of(&s, "marble", JD_MODE_NONE);
    s.light_azimuth = -45; /* from -x, 45 degrees up: the shadow covers x in [1, 31] mm */
    s.light_elevation = 0;
    s.light_intensity = 0.8f;
    shot(&m, &s, none_pic, "edge_none");
    int y = H / 2;
    /* Where the edge is, from the plain shadow: half-way across. */
    float hi = lum(none_pic, W - 20, y), lo = lum(none_pic, W / 2, y);
    int edge = -1;
    for (int x = W / 2; x < W - 1 && edge < 0; x++)
        if (lum(none_pic, x, y) < 0.5f * (lo + hi) && lum(none_pic, x + 1, y) >= 0.5f * (lo + hi)) edge = x;
    CHECK(edge > 0, "the wall's shadow edge is in view");
    if (edge < 0) return;
    /* Pixels per millimetre, from the shadow's width (30 mm) in none. */
    int start = -1;
    for (int x = W / 4; x < edge && start < 0; x++)
        if (lum(none_pic, x, y) < 0.5f * (lo + hi)) start = x;
    float px_mm = (float)(edge - start) / 30.0f;
    int mid = edge - (int)(12 * px_mm), lit = edge + (int)(30 * px_mm);
    if (lit > W - 2) lit = W - 2;
    printf("shadow edge at column %d, %.2f px/mm\n", edge, px_mm);

    const char *mats[] = {"marble", "skin1", "ketchup"};
    for (int k = 0; k < 3; k++) {
        scene_of(&s, mats[k], JD_MODE_FULL);
        s.light_azimuth = -45;
        s.light_elevation = 0;
        s.light_intensity = 0.8f;
        shot(&m, &s, pics[k], mats[k]);
    }
    int reach = (int)(6 * px_mm);
    float p_none = penumbra(none_pic, 0, y, edge, reach, lit) / px_mm;
    float p_marble = penumbra(pics[0], 0, y, edge, reach, lit) / px_mm;
    float p_skin_r = penumbra(pics[1], 0, y, edge, reach, lit) / px_mm, p_skin_b = penumbra(pics[1], 2, y, edge, reach, lit) / px_mm;
    printf("light within 6 mm inside the shadow, in mm of the lit floor's level: none %.2f, marble red %.2f, "
           "skin1 red %.2f, skin1 blue %.2f\n", p_none, p_marble, p_skin_r, p_skin_b);
    /* Within a few millimetres of the edge the dipole's peak dominates, so
     * the reference itself has as much of skin1's red in there as marble's
     * (0.97 and 0.85 mm in jade reference at 1.5 px/mm); the reach shows
     * where 1/sigma_tr differs most: skin1's blue (0.7 mm) against its red
     * (3.7 mm) and against marble's blue (4.0 mm). */
    float p_marble_b = penumbra(pics[0], 2, y, edge, reach, lit) / px_mm;
    printf("marble blue %.2f\n", p_marble_b);
    CHECK(p_skin_r > 2.0f * p_skin_b, "skin1's red (1/sigma_tr 3.7 mm) spreads further than its blue (0.7 mm)");
    CHECK(p_marble_b > 2.0f * p_skin_b, "marble's blue (4.0 mm) spreads further than skin1's blue (0.7 mm)");
    CHECK(p_skin_b >= p_none, "even skin1's blue is no sharper than the plain shadow");
    CHECK(p_marble > p_none + 0.4f && p_skin_r > p_none + 0.4f, "light diffuses into the shadow near its edge");
    /* The shadow's middle, 12 mm from the edge and 17 mm from the wall: dark in
     * every mode (the reference has 0.02 of the lit level there). */
    for (int k = 0; k < 3; k++) {
        float deep = pics[k][3 * (y * W + mid)], lit_full = pics[k][3 * (y * W + lit)];
        printf("%s, red: 12 mm inside the shadow %.4f of the lit level (none: %.4f)\n", mats[k], deep / lit_full,
               none_pic[3 * (y * W + mid)] / none_pic[3 * (y * W + lit)]);
        CHECK(deep < 0.1f * lit_full, "%s: the shadow's middle stays dark", mats[k]);
    }
    CHECK(none_pic[3 * (y * W + mid)] < 0.01f * none_pic[3 * (y * W + lit)], "none: the shadow is dark");
}

int main(int argc, char **argv)
{
    out_dir = argc > 1 ? argv[1] : NULL;
    jd_error err = {0};
    jd_platform_desc pd = {.kind = "headless", .width = W, .height = H};
    if (jd_platform_open(&pd, &P, &err)) { printf("%s\n", err.msg); return 1; }
    jd_gl_caps_query(&caps, &err);
    flat_patch();
    shadow_edge();
    jd_platform_close(P);
    return jd_check_summary("diffusion");
}
