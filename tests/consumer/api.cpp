// Every function of the installed headers, from C++, linked against the
// installed package (consumer.sh builds it with pkg-config and with
// find_package(jade)). Those that need no GL context are called; the rest
// (called with a context by consumer.c and examples/embed.c) are linked by
// taking their addresses. consumer.sh fails when a public function is
// missing from this list, so it cannot fall behind the headers.
#include <jade/jade.h>
#include <jade/platform.h>

#include <cstdio>
#include <cstring>

typedef void (*any_fn)();
#define FN(f) reinterpret_cast<any_fn>(&f)

int main()
{
    static const any_fn all[] = {
        FN(jd_albedo_ratio),
        FN(jd_albedo_total),
        FN(jd_arena_alloc),
        FN(jd_arena_alloc_top),
        FN(jd_arena_free_bytes),
        FN(jd_arena_init),
        FN(jd_arena_mark),
        FN(jd_arena_reset),
        FN(jd_arena_top_mark),
        FN(jd_arena_top_reset),
        FN(jd_arena_used),
        FN(jd_dipole_fdr),
        FN(jd_dipole_init),
        FN(jd_dipole_rd),
        FN(jd_dipole_rd_total),
        FN(jd_dipole_tail),
        FN(jd_extension_listed),
        FN(jd_fail),
        FN(jd_fresnel_dielectric),
        FN(jd_fresnel_fit),
        FN(jd_fresnel_mean),
        FN(jd_gl_caps_levels_per_vertex),
        FN(jd_gl_caps_query),
        FN(jd_gl_caps_recognise),
        FN(jd_gl_has_extension),
        FN(jd_gl_mediump_canary),
        FN(jd_gl_mediump_is_fp16),
        FN(jd_gl_probe_names),
        FN(jd_m4_identity),
        FN(jd_m4_look_at),
        FN(jd_m4_mul),
        FN(jd_m4_ortho),
        FN(jd_m4_perspective),
        FN(jd_m4_point),
        FN(jd_material_find),
        FN(jd_material_from_reflectance),
        FN(jd_mesh_build_proxy),
        FN(jd_mesh_check_finite),
        FN(jd_mesh_compute_bounds),
        FN(jd_mesh_albedo_prepare),
        FN(jd_mesh_albedo_at),
        FN(jd_mesh_compute_normals),
        FN(jd_mesh_fix_normals),
        FN(jd_unit_normal),
        FN(jd_mesh_index),
        FN(jd_load_default_timeout_ms),
        FN(jd_mesh_load_draco),
        FN(jd_mesh_normals_follow_winding),
        FN(jd_mesh_orient_outward),
        FN(jd_mesh_placement),
        FN(jd_mesh_set_indices),
        FN(jd_mesh_validate),
        FN(jd_mode_name),
        FN(jd_mode_parse),
        FN(jd_pass_name),
        FN(jd_platform_capture),
        FN(jd_platform_close),
        FN(jd_platform_describe),
        FN(jd_platform_display_size),
        FN(jd_platform_framebuffer),
        FN(jd_platform_gl_proc),
        FN(jd_platform_max_size),
        FN(jd_platform_open),
        FN(jd_platform_poll),
        FN(jd_platform_present),
        FN(jd_platform_present_stats),
        FN(jd_platform_probe),
        FN(jd_platform_read_rgba),
        FN(jd_platform_samples),
        FN(jd_platform_scale_out),
        FN(jd_platform_size),
        FN(jd_platform_time_ms),
        FN(jd_profile_apply),
        FN(jd_profile_find),
        FN(jd_board_find),
        FN(jd_frame_cost_table),
        FN(jd_frame_cost_estimate),
        FN(jd_frame_cost_largest_program),
        FN(jd_renderer_count),
        FN(jd_quit_on_signals),
        FN(jd_quit_requested),
        FN(jd_reload_count),
        FN(jd_renderer_create),
        FN(jd_renderer_desc_defaults),
        FN(jd_renderer_destroy),
        FN(jd_renderer_finish),
        FN(jd_renderer_frame),
        FN(jd_renderer_get_info),
        FN(jd_renderer_read_capture),
        FN(jd_renderer_resize),
        FN(jd_renderer_set_timing),
        FN(jd_result_name),
        FN(jd_scene_defaults),
        FN(jd_scene_view_of),
        FN(jd_v3),
        FN(jd_v3_add),
        FN(jd_v3_cross),
        FN(jd_v3_dot),
        FN(jd_v3_from_angles),
        FN(jd_v3_len),
        FN(jd_v3_norm),
        FN(jd_v3_scale),
        FN(jd_v3_sub),
    };
    int linked = 0;
    for (any_fn f : all) linked += f != nullptr;
    // The calls that need no GL context.
    static unsigned char memory[1 << 16];
    jd_arena a;
    jd_arena_init(&a, memory, sizeof memory);
    jd_error err;
    std::memset(&err, 0, sizeof err);
    size_t mark = jd_arena_mark(&a), top = jd_arena_top_mark(&a);
    void *p = jd_arena_alloc(&a, 100, 16, "a test", &err), *q = jd_arena_alloc_top(&a, 100, 16, "a test", &err);
    bool ok = p && q && jd_arena_used(&a) >= 200 && jd_arena_free_bytes(&a) < sizeof memory;
    jd_arena_reset(&a, mark);
    jd_arena_top_reset(&a, top);
    ok = ok && jd_arena_used(&a) == 0;
    jd_mode m;
    ok = ok && jd_mode_parse("dual", &m) == 1 && std::strcmp(jd_mode_name(m), "dual") == 0 && jd_pass_name(0) != nullptr;
    ok = ok && jd_material_find("skin1") != nullptr && jd_profile_find("mali400") != nullptr;
    ok = ok && jd_load_default_timeout_ms(0, 0) == 1500;
    {
        static jd_frame_count fc;
        static jd_estimate est;
        fc.num_passes = 1;
        std::snprintf(fc.pass[0].program, sizeof fc.pass[0].program, "mesh.vert+shade.frag[full]");
        fc.pass[0].fragments = 1000;
        fc.pass[0].trips = 1;
        const jd_board *b = jd_board_find("mali400-mp2");
        ok = ok && b && jd_frame_cost_table() != nullptr &&
             jd_frame_cost_estimate(b, &fc, nullptr, &est, &err) == JD_OK && est.frame_ms > 0.0;
    }
    ok = ok && jd_fail(&err, JD_ERR_ARG, "x %d", 1) == JD_ERR_ARG && std::strcmp(err.msg, "x 1") == 0 &&
         jd_result_name(JD_ERR_ARG) != nullptr;
    jd_vec3 v = jd_v3_norm(jd_v3_cross(jd_v3(1, 0, 0), jd_v3(0, 1, 0)));
    ok = ok && v.z > 0.99f && jd_v3_len(jd_v3_add(v, jd_v3_scale(jd_v3_sub(v, v), 2.0f))) > 0.99f && jd_v3_dot(v, v) > 0.99f;
    jd_renderer_desc d;
    std::memset(&d, 0, sizeof d);
    jd_renderer_desc_defaults(&d);
    ok = ok && d.cube_size == 64;
    jd_scene s;
    jd_scene_defaults(&s, jd_material_find("marble"));
    ok = ok && s.mode == JD_MODE_FULL;
    ok = ok && jd_platform_time_ms() > 0.0;
    ok = ok && jd_extension_listed("GL_OES_a GL_OES_ab", "GL_OES_ab") && !jd_extension_listed("GL_OES_abc", "GL_OES_ab");
    std::printf("api: %d public functions linked from C++, the GL-free ones called: %s\n", linked, ok ? "ok" : "FAILED");
    return linked == (int)(sizeof all / sizeof all[0]) && ok ? 0 : 1;
}
