/* A program of an integrator's, built against the installed jade: budget,
 * load, context, renderer, one frame, one pixel read back. Written to be
 * both C11 and C++20, and built as both: the installed headers must serve
 * a C++ program. */
#include <stdio.h>
#include <stdlib.h>

#include <jade/jade.h>
#include <jade/platform.h>

int main(int argc, char **argv)
{
    if (argc < 2) { fprintf(stderr, "usage: consumer MESH.drc\n"); return 2; }
    size_t budget = 8u << 20;
    unsigned char *mem = (unsigned char *)malloc(budget);
    jd_arena arena;
    jd_arena_init(&arena, mem, budget);
    jd_error err = {JD_OK, {0}};
    jd_mesh mesh;
    jd_load_desc ld = {.path = argv[1]};
    jd_platform *p = NULL;
    jd_platform_desc pd = {.kind = "headless", .width = 64, .height = 64};
    jd_gl_caps caps;
    jd_renderer *r = NULL;
    if (jd_mesh_load_draco(&ld, &arena, &mesh, NULL, &err) || jd_platform_open(&pd, &p, &err) ||
        jd_gl_caps_query(&caps, &err)) {
        fprintf(stderr, "consumer: %s\n", err.msg);
        return 1;
    }
    jd_renderer_desc rd = {.mesh = &mesh, .caps = &caps, .target_fbo = jd_platform_framebuffer(p), .width = 64, .height = 64};
    jd_scene scene;
    jd_scene_defaults(&scene, jd_material_find("skin1"));
    static unsigned char px[64 * 64 * 4];
    if (jd_renderer_create(&rd, &arena, &r, &err) || jd_renderer_frame(r, &scene, NULL, &err) ||
        jd_platform_read_rgba(p, px, &err)) {
        fprintf(stderr, "consumer: %s\n", err.msg);
        return 1;
    }
    /* Pixels that are not the background (the corner's colour). */
    unsigned lit = 0;
    for (int i = 0; i < 64 * 64; i++) lit += abs(px[4 * i] - px[0]) + abs(px[4 * i + 1] - px[1]) > 6;
    printf("consumer: rendered %u triangles, %u of 4096 pixels show the object, arena peak %zu bytes\n",
           mesh.num_indices / 3, lit, arena.peak);
    jd_renderer_destroy(r);
    jd_platform_close(p);
    free(mem);
    return lit > 100 ? 0 : 1;
}
