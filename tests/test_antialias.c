/* Anti-aliasing: without multisampling, the pass after the frame must soften
 * the silhouette's staircase (fewer hard steps between neighbours) and leave
 * every pixel away from an edge as it was. The default asset, in the tree. */
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "gl_fixture.h"
#include "mesh_load.h"
#include "platform.h"
#include "renderer.h"

enum { W = 256, H = 256 };
static unsigned char mem[32 << 20];
static uint8_t pic[2][W * H * 4];

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "assets/default.drc";
    jd_error err = {0};
    jd_platform *P;
    /* Single-sampled, so both pictures come from the same kind of target:
     * where the headless target has EXT_multisampled_render_to_texture
     * (NVIDIA), "off" would otherwise be the multisampled picture. */
    jd_platform_desc pd = {.kind = "headless", .width = W, .height = H, .single_sample = 1};
    if (jd_platform_open(&pd, &P, &err)) { printf("%s\n", err.msg); return 1; }
    jd_gl_caps caps;
    jd_arena a;
    jd_mesh mesh;
    if (jd_test_fixture(path, mem, sizeof mem, &caps, &a, &mesh)) return 1;
    size_t mark = jd_arena_mark(&a);
    const jd_antialias modes[2] = {JD_AA_OFF, JD_AA_POST};
    for (int k = 0; k < 2; k++) {
        jd_arena_reset(&a, mark);
        jd_renderer_desc d = {.mesh = &mesh, .caps = &caps, .target_fbo = jd_platform_framebuffer(P), .width = W,
                              .height = H, .antialias = modes[k]};
        jd_renderer *r = NULL;
        jd_scene s;
        jd_scene_defaults(&s, NULL);
        CHECK(jd_renderer_create(&d, &a, &r, &err) == JD_OK, "%s", err.msg);
        if (!r) return 1;
        jd_renderer_info info;
        jd_renderer_get_info(r, &info);
        CHECK(info.post_antialias == (k == 1), "the pass runs only when asked for");
        CHECK(jd_renderer_frame(r, &s, NULL, &err) == JD_OK && jd_platform_read_rgba(P, pic[k], &err) == JD_OK, "%s",
              err.msg);
        jd_renderer_destroy(r);
    }
    /* Hard steps: neighbours (right, below) whose luma differs by 64 or more. */
    int steps[2] = {0, 0}, flat = 0, flat_changed = 0;
    for (int y = 1; y < H - 1; y++)
        for (int x = 1; x < W - 1; x++) {
            int i = y * W + x;
            for (int k = 0; k < 2; k++) {
                int c = jd_test_luma(pic[k] + 4 * i);
                steps[k] += abs(c - jd_test_luma(pic[k] + 4 * (i + 1))) >= 64;
                steps[k] += abs(c - jd_test_luma(pic[k] + 4 * (i + W))) >= 64;
            }
            /* Away from edges: the 3x3 neighbourhood within 8 levels. */
            int lo = 255, hi = 0;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int c = jd_test_luma(pic[0] + 4 * (i + dy * W + dx));
                    lo = c < lo ? c : lo;
                    hi = c > hi ? c : hi;
                }
            if (hi - lo <= 8) {
                flat++;
                int changed = 0;
                for (int ch = 0; ch < 3; ch++) changed |= abs(pic[0][4 * i + ch] - pic[1][4 * i + ch]) > 1;
                if (changed && flat_changed < 4)
                    printf("flat pixel (%d, %d) changed: %d %d %d -> %d %d %d\n", x, y, pic[0][4 * i], pic[0][4 * i + 1],
                           pic[0][4 * i + 2], pic[1][4 * i], pic[1][4 * i + 1], pic[1][4 * i + 2]);
                flat_changed += changed;
            }
        }
    printf("hard steps: %d without, %d with the pass; flat pixels %d, changed by more than 1: %d\n", steps[0], steps[1],
           flat, flat_changed);
    CHECK(steps[0] > 50, "the picture has a silhouette");
    CHECK(steps[1] < 0.6 * steps[0], "the pass removes most hard steps");
    CHECK(flat > W * H / 2 && flat_changed == 0, "pixels away from edges stay as they were");
    jd_platform_close(P);
    return jd_check_summary("antialias");
}
