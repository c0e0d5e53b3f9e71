/* A frame's picture depends on its scene alone, not on the frames drawn
 * before it: a viewer whose camera comes closer, or whose light or material
 * changes, must draw what a renderer made for that scene would. One
 * renderer draws scene B (A from elsewhere, or in another material,
 * exposure and highlight), then scene A; a fresh one draws A; the two
 * pictures of A must be the same to the bit. The object (a sphere made
 * here) overfills the picture close up, so that every layer's texels at the
 * picture's edges are read; under the generic caps and the mali400 profile
 * (full's levels summed in a half-resolution layer), in full and dual. (The
 * kiosk keeps its camera's distance; jade view zooms.) */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "material.h"
#include "platform.h"
#include "profile.h"
#include "renderer.h"

enum { W = 480, H = 320, SEG = 48, MAX_V = (SEG + 1) * (SEG + 1), MAX_I = 6 * SEG * SEG };
static unsigned char mesh_mem[4 << 20], arena_mem[24 << 20];
static uint8_t fresh[W * H * 4], after[W * H * 4];
static float pos[3 * MAX_V], nrm[3 * MAX_V];
static uint32_t idx[MAX_I];
static jd_platform *P;

static void sphere(uint32_t *nv, uint32_t *ni)
{
    *nv = *ni = 0;
    for (int j = 0; j <= SEG; j++)
        for (int i = 0; i <= SEG; i++) {
            float th = 3.14159265f * (float)j / SEG, ph = 6.2831853f * (float)i / SEG;
            float n[3] = {sinf(th) * cosf(ph), cosf(th), sinf(th) * sinf(ph)};
            for (int k = 0; k < 3; k++) {
                nrm[3 * *nv + k] = n[k];
                pos[3 * *nv + k] = 40.0f * n[k];
            }
            (*nv)++;
        }
    for (int j = 0; j < SEG; j++)
        for (int i = 0; i < SEG; i++) {
            uint32_t a = (uint32_t)(j * (SEG + 1) + i), b = a + 1, c = a + SEG + 1, d = c + 1;
            uint32_t t[6] = {a, b, c, b, d, c}; /* counter-clockwise seen from outside, as the normals */
            memcpy(idx + *ni, t, sizeof t);
            *ni += 6;
        }
}

/* Draws each scene of `seq` in turn with one renderer; the last one's
 * picture into `out`. */
static int draw(const jd_mesh *m, const jd_gl_caps *caps, const jd_scene *seq, int n, uint8_t *out)
{
    jd_arena a;
    jd_arena_init(&a, arena_mem, sizeof arena_mem);
    jd_error err = {0};
    jd_renderer_desc d = {.mesh = m, .caps = caps, .target_fbo = jd_platform_framebuffer(P), .width = W, .height = H};
    jd_renderer *r = NULL;
    int ok = jd_renderer_create(&d, &a, &r, &err) == JD_OK;
    for (int i = 0; ok && i < n; i++) ok = jd_renderer_frame(r, &seq[i], NULL, &err) == JD_OK;
    ok = ok && jd_platform_read_rgba(P, out, &err) == JD_OK;
    CHECK(ok, "%s", err.msg);
    if (r) jd_renderer_destroy(r);
    return ok;
}

int main(void)
{
    jd_error err = {0};
    jd_platform_desc pd = {.kind = "headless", .width = W, .height = H};
    if (jd_platform_open(&pd, &P, &err)) {
        printf("%s\n", err.msg);
        return 1;
    }
    jd_gl_caps generic;
    jd_gl_caps_query(&generic, &err);
    uint32_t nv, ni;
    sphere(&nv, &ni);
    jd_arena ma;
    jd_arena_init(&ma, mesh_mem, sizeof mesh_mem);
    jd_mesh m;
    memset(&m, 0, sizeof m);
    m.num_vertices = nv;
    m.positions = pos;
    m.normals = nrm;
    jd_mesh_compute_bounds(&m);
    CHECK(jd_mesh_set_indices(&m, idx, ni, 0, &ma, &err) == JD_OK, "%s", err.msg);
    const char *profiles[] = {NULL, "mali400"};
    const jd_mode modes[] = {JD_MODE_FULL, JD_MODE_DUAL};
    /* Scene A close up (the sphere past the picture's edges) after B from
     * farther (a larger half-resolution layer) or nearer, with the light
     * elsewhere or the same. */
    const float before[][2] = {{1.3f, 0.0f}, {1.6f, 0.0f}, {2.0f, 40.0f}, {2.5f, 0.0f}, {3.2f, 0.0f}, {0.9f, 0.0f},
                               {1.15f, 0.0f}};
    const int nb = (int)(sizeof before / sizeof before[0]);
    for (int p = 0; p < 2; p++) {
        jd_gl_caps caps = generic;
        if (profiles[p]) jd_profile_apply(jd_profile_find(profiles[p]), &caps);
        for (int k = 0; k < 2; k++)
            for (int b = 0; b < nb; b++) {
                jd_scene seq[2];
                jd_scene_defaults(&seq[1], jd_material_find("marble"));
                seq[1].mode = modes[k];
                seq[1].cam_distance = 1.15f;
                seq[1].light_azimuth = 170.0f;
                seq[0] = seq[1];
                seq[0].cam_distance = before[b][0];
                seq[0].light_azimuth += before[b][1];
                if (b == nb - 1) { /* the frame before in another material, exposed twice as long, its
                                    * highlight broader (full's highlight table, rebuilt); lit
                                    * from the camera, the highlight in the picture's middle */
                    seq[1].light_azimuth = seq[1].cam_azimuth;
                    jd_scene_defaults(&seq[0], jd_material_find("skin1"));
                    seq[0].mode = modes[k];
                    seq[0].cam_distance = seq[1].cam_distance;
                    seq[0].light_azimuth = seq[1].light_azimuth;
                    seq[0].exposure = 2.0f * seq[1].exposure;
                    seq[0].shininess = 0.25f * seq[1].shininess;
                }
                if (!draw(&m, &caps, &seq[1], 1, fresh) || !draw(&m, &caps, seq, 2, after)) continue;
                int differ = 0, most = 0;
                for (int i = 0; i < W * H * 4; i++)
                    if (i % 4 != 3 && fresh[i] != after[i]) {
                        differ++;
                        int dd = fresh[i] > after[i] ? fresh[i] - after[i] : after[i] - fresh[i];
                        most = dd > most ? dd : most;
                    }
                printf("%s, %s, after a frame %s %.2f, light %+g degrees: %d channels differ (at most %d)\n",
                       profiles[p] ? profiles[p] : "generic", modes[k] == JD_MODE_FULL ? "full" : "dual",
                       b == nb - 1 ? "in skin1, exposure x 2, shininess / 4, at distance" : "at distance", before[b][0], before[b][1],
                       differ, most);
                CHECK(differ == 0, "the picture of a scene does not depend on the frame before");
            }
    }
    jd_platform_close(P);
    return jd_check_summary("frame_history");
}
