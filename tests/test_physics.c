/* Physical sense, on the back-lit Stanford bunny (encoded from ../shared at
 * test time): thin parts transmit, density and absorption behave, and the
 * spread funnel softens. Measured on the rendered pictures. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "mesh_load.h"
#include "platform.h"
#include "renderer.h"

enum { W = 192, H = 192 };
static unsigned char mem[32 << 20];
static uint8_t img[W * H * 4];
static float lin[6][W * H * 3];
static jd_renderer *R;
static jd_platform *P;

/* Renders and returns linear light (the shader's display gamma is 2). */
static void shot(jd_scene *s, float *out)
{
    jd_error err = {0};
    CHECK(jd_renderer_frame(R, s, NULL, &err) == JD_OK && jd_platform_read_rgba(P, img, &err) == JD_OK, "%s", err.msg);
    for (int i = 0; i < W * H; i++)
        for (int c = 0; c < 3; c++) {
            float v = img[4 * i + c] / 255.0f;
            out[3 * i + c] = v * v;
        }
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "build/testdata/bunny.drc";
    if (access(path, R_OK) != 0) {
        printf("SKIP: %s is absent (encoded from ../shared/testdata at test time)\n", path);
        return 77;
    }
    jd_arena a;
    jd_arena_init(&a, mem, sizeof mem);
    jd_error err = {0};
    jd_mesh mesh;
    jd_load_desc ld = {.path = path, .allow_32bit_indices = 1};
    if (jd_mesh_load_draco(&ld, &a, &mesh, NULL, &err)) { printf("%s\n", err.msg); return 1; }
    jd_platform_desc pd = {.kind = "headless", .width = W, .height = H};
    if (jd_platform_open(&pd, &P, &err)) { printf("%s\n", err.msg); return 1; }
    jd_gl_caps caps;
    jd_gl_caps_query(&caps, &err);
    jd_renderer_desc d = {0};
    d.mesh = &mesh;
    d.caps = &caps;
    d.target_fbo = jd_platform_framebuffer(P);
    d.width = W;
    d.height = H;
    if (jd_renderer_create(&d, &a, &R, &err)) { printf("%s\n", err.msg); return 1; }

    /* Side view, light straight behind the bunny: the ears are thin. */
    jd_scene s;
    jd_scene_defaults(&s, jd_material_find("marble"));
    s.cam_azimuth = 90;
    s.cam_elevation = 5;
    s.light_azimuth = 270;
    s.light_elevation = 10;
    s.mode = JD_MODE_NONE;   shot(&s, lin[0]);
    s.mode = JD_MODE_SINGLE; shot(&s, lin[1]);
    s.mode = JD_MODE_DUAL;   shot(&s, lin[2]);
    s.density = 2;           shot(&s, lin[3]);
    s.density = 1;

    /* Object pixels differ from the background; the ears are the top 22%
     * of the object's rows. */
    const float bg = s.background[1];
    int y0 = H, y1 = -1;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            if (fabsf(lin[0][3 * (y * W + x) + 1] - bg) > 0.004f) { if (y < y0) y0 = y; if (y > y1) y1 = y; }
    CHECK(y1 > y0 + 40, "the bunny is in view (rows %d..%d)", y0, y1);
    int ear_end = y0 + (int)(0.22f * (y1 - y0));
    double ear[4] = {0}, body[4] = {0};
    int n_ear = 0, n_body = 0;
    for (int y = y0; y <= y1; y++)
        for (int x = 0; x < W; x++) {
            int i = y * W + x;
            if (fabsf(lin[0][3 * i + 1] - bg) <= 0.004f) continue;
            for (int k = 0; k < 4; k++) {
                double l = lin[k][3 * i] + lin[k][3 * i + 1] + lin[k][3 * i + 2];
                if (y <= ear_end) ear[k] += l; else body[k] += l;
            }
            if (y <= ear_end) n_ear++; else n_body++;
        }
    for (int k = 0; k < 4; k++) { ear[k] /= n_ear; body[k] /= n_body; }
    printf("ears (%d px): none %.4f single %.4f dual %.4f dual-density-2 %.4f\n", n_ear, ear[0], ear[1], ear[2], ear[3]);
    printf("body (%d px): none %.4f single %.4f dual %.4f\n", n_body, body[0], body[1], body[2]);
    CHECK(ear[2] > 1.15 * ear[0], "back-lit ears brighter in dual than in none (%.4f vs %.4f)", ear[2], ear[0]);
    double gain_ear = ear[2] / ear[0], gain_body = body[2] / body[0];
    CHECK(gain_ear > gain_body, "thin ears gain more than the thick body (%.2fx vs %.2fx)", gain_ear, gain_body);
    double t1 = ear[2] - ear[0], t2 = ear[3] - ear[0];
    CHECK(t2 < 0.8 * t1, "doubling density darkens the transmitted light (%.4f -> %.4f)", t1, t2);

    /* Ketchup: red passes, blue is absorbed (sigma_a 0.061 vs 1.45 per mm). */
    jd_scene k;
    jd_scene_defaults(&k, jd_material_find("ketchup"));
    k.cam_azimuth = 90; k.cam_elevation = 5; k.light_azimuth = 270; k.light_elevation = 10;
    k.mode = JD_MODE_NONE;   shot(&k, lin[4]);
    k.mode = JD_MODE_SINGLE; shot(&k, lin[5]);
    double red = 0, blue = 0;
    for (int i = 0; i < W * H; i++) {
        red += lin[5][3 * i] - lin[4][3 * i];
        blue += lin[5][3 * i + 2] - lin[4][3 * i + 2];
    }
    printf("ketchup transmitted light: red %.3f, blue %.3f\n", red, blue);
    CHECK(red > 5.0 * fmax(blue, 1e-6) && red > 0.5, "ketchup transmits red far more than blue");

    /* The translucent layer's high-frequency energy (sum of squared
     * Laplacian over the object) must drop from single to dual. */
    double hf[2] = {0};
    for (int m = 0; m < 2; m++)
        for (int y = y0 + 1; y < y1; y++)
            for (int x = 1; x < W - 1; x++) {
                int i = y * W + x;
                if (fabsf(lin[0][3 * i + 1] - bg) <= 0.004f) continue;
                double c = lin[1 + m][3 * i + 1] - lin[0][3 * i + 1];
                double lap = -4 * c;
                int nb[4] = {i - 1, i + 1, i - W, i + W};
                for (int q = 0; q < 4; q++) lap += lin[1 + m][3 * nb[q] + 1] - lin[0][3 * nb[q] + 1];
                hf[m] += lap * lap;
            }
    printf("high-frequency energy of the translucent layer: single %.5f, dual %.5f\n", hf[0], hf[1]);
    CHECK(hf[1] < hf[0], "dual is softer than single");
    jd_renderer_destroy(R);
    jd_platform_close(P);
    return jd_check_summary("physics");
}
