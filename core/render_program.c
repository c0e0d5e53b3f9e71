/* The programs, built at start-up in groups by what needs them; a group
 * the device cannot run takes away its mode, not the renderer. */
#include "renderer_internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "gl_program.h"
#include "program_probe.h"

static const char *const mesh_attribs[] = {"a_position", "a_normal", "a_uv", "a_color", "a_bounce", "a_curve", NULL};
static const char *const quad_attribs[] = {"a_corner", NULL};
static const char *const project_attribs[] = {"a_corner", "a_poly0", "a_poly1", "a_channel", "a_texel", NULL};

/* The device's (or the profile's) limits hold for every program: uniform
 * vectors (GLSL ES packing: a matN takes N) and samplers. Checked here so a
 * desktop with a board's profile fails where the board would. */
static jd_result check_limits(const jd_gl_caps *c, GLuint prog, const char *vs, const char *fs, jd_error *err)
{
    GLint n = 0;
    glGetProgramiv(prog, GL_ACTIVE_UNIFORMS, &n);
    int vectors = 0, samplers = 0;
    for (GLint i = 0; i < n; i++) {
        char name[64];
        GLint size = 0;
        GLenum type = 0;
        glGetActiveUniform(prog, (GLuint)i, sizeof name, NULL, &size, &type, name);
        if (type == GL_SAMPLER_2D || type == GL_SAMPLER_CUBE) samplers += size;
        else vectors += size * (type == GL_FLOAT_MAT4 ? 4 : type == GL_FLOAT_MAT3 ? 3 : type == GL_FLOAT_MAT2 ? 2 : 1);
    }
    if (vectors > c->max_vertex_uniform_vectors)
        return jd_fail(err, JD_ERR_UNSUPPORTED, "%s + %s: %d uniform vectors, over this device's %d", vs, fs, vectors,
                       c->max_vertex_uniform_vectors);
    if (samplers > c->max_texture_units)
        return jd_fail(err, JD_ERR_UNSUPPORTED, "%s + %s: %d samplers, over this device's %d texture units", vs, fs,
                       samplers, c->max_texture_units);
    return JD_OK;
}

/* ES 2.0 cannot be asked how many varying vectors a program uses, so each
 * build states it (vec2..vec4 and float each take one under the packing
 * rules for jade's shaders) and it is checked against the device's. */
static jd_result build(jd_renderer *r, int varyings, const char *vs, const char *fs, const char *defines,
                       const char *const *attribs, GLuint *out, jd_error *err)
{
    if (varyings > r->d.caps->max_varying_vectors)
        return jd_fail(err, JD_ERR_UNSUPPORTED, "%s + %s: %d varying vectors, over this device's %d", vs, fs, varyings,
                       r->d.caps->max_varying_vectors);
    jd_result res = jd_program_build(vs, fs, defines, attribs, out, err);
    if (res == JD_OK) res = check_limits(r->d.caps, *out, vs, fs, err);
    if (res == JD_OK) { /* a rebuilt program may take a freed id: the newest label wins */
        int i = 0;
        while (i < r->num_labels && r->labels[i].id != *out) i++;
        if (i < (int)(sizeof r->labels / sizeof r->labels[0])) {
            r->labels[i].id = *out;
            jd_program_label(vs, fs, defines, r->labels[i].label, sizeof r->labels[i].label);
            if (i == r->num_labels) r->num_labels++;
        }
    }
    return res;
}

static void shade_locations(shade_prog *p)
{
    GLuint id = p->id;
    p->mvp = glGetUniformLocation(id, "u_mvp");
    p->light_tex = glGetUniformLocation(id, "u_light_tex");
    p->eye = glGetUniformLocation(id, "u_eye");
    p->irr = glGetUniformLocation(id, "u_irr");
    p->box_min = glGetUniformLocation(id, "u_box_min");
    p->box_max = glGetUniformLocation(id, "u_box_max");
    p->inv_eta = glGetUniformLocation(id, "u_inv_eta");
    p->inset = glGetUniformLocation(id, "u_inset");
    p->light_dir = glGetUniformLocation(id, "u_light_dir");
    p->albedo = glGetUniformLocation(id, "u_albedo");
    p->light_color = glGetUniformLocation(id, "u_light_color");
    p->shading = glGetUniformLocation(id, "u_shading");
    p->depth = glGetUniformLocation(id, "u_depth");
    p->tail = glGetUniformLocation(id, "u_tail");
    p->depth_v = glGetUniformLocation(id, "u_depth_v");
    p->tail_v = glGetUniformLocation(id, "u_tail_v");
    p->f0 = glGetUniformLocation(id, "u_f0");
    p->fresnel = glGetUniformLocation(id, "u_fresnel");
    p->a0_scale = glGetUniformLocation(id, "u_a0_scale");
    p->spread = glGetUniformLocation(id, "u_spread");
    p->inv_viewport = glGetUniformLocation(id, "u_inv_viewport");
    p->wide_scale = glGetUniformLocation(id, "u_wide_scale");
    p->w0 = glGetUniformLocation(id, "u_w0");
    p->light_map = glGetUniformLocation(id, "u_light_map");
    p->soft_c = glGetUniformLocation(id, "u_soft_c");
    p->shadow_bias = glGetUniformLocation(id, "u_shadow_bias");
    for (int i = 0; i < DIFF_TEXTURES; i++) {
        char name[16];
        snprintf(name, sizeof name, "u_lv%d", i);
        p->lv[i] = glGetUniformLocation(id, name);
        snprintf(name, sizeof name, "u_lv%d_v", i);
        p->lv_v[i] = glGetUniformLocation(id, name);
    }
    p->light_map_v = glGetUniformLocation(id, "u_light_map_v");
    p->light_dir_v = glGetUniformLocation(id, "u_light_dir_v");
    p->wide = glGetUniformLocation(id, "u_wide");
    p->lw = glGetUniformLocation(id, "u_lw");
    p->albedo_norm = glGetUniformLocation(id, "u_albedo_norm");
    p->albedo_map = glGetUniformLocation(id, "u_albedo_map");
    p->albedo_reach = glGetUniformLocation(id, "u_albedo_reach");
    p->ls = glGetUniformLocation(id, "u_ls");
    p->amb_x = glGetUniformLocation(id, "u_amb_x");
    p->local_x = glGetUniformLocation(id, "u_local_x");
    p->wide_x = glGetUniformLocation(id, "u_wide_x");
    p->spec_x = glGetUniformLocation(id, "u_spec_x");
    p->slab = glGetUniformLocation(id, "u_slab");
    p->slab_scale = glGetUniformLocation(id, "u_slab_scale");
    p->light_depth_v = glGetUniformLocation(id, "u_light_depth_v");
    p->march_st = glGetUniformLocation(id, "u_march_st");
    p->march_ss = glGetUniformLocation(id, "u_march_ss");
    p->march = glGetUniformLocation(id, "u_march");
    p->keep = glGetUniformLocation(id, "u_keep");
    p->wrap = glGetUniformLocation(id, "u_wrap");
    p->bounce_rd = glGetUniformLocation(id, "u_bounce_rd");
    p->spec = glGetUniformLocation(id, "u_spec");
}

/* The constant trip count the diffusion program is built with, or 0 for
 * its loop's count as a uniform. Every GPU jade's compiler table covers
 * runs these few trips shorter unrolled (VideoCore IV in two threads where
 * the loop held it to one: the blur at 5 trips 372 instructions a fragment
 * where the loop cost 1719 cycles; Adreno 3xx 455 -> 257; Midgard 152 -> 70
 * bundles; Vivante 210 -> 121) but Utgard, whose six registers spill the
 * blur unrolled (lima 118 words and 9:29 spills:fills at 5 trips, where the
 * loop costs 150 words with none; since the blur takes its taps in pairs, a
 * trip each, unrolled 100 words and 3:12, the loop 120 and none). The
 * blur's trips are its pairs: the centre tap comes before the loop.
 * Utgard's squares are unrolled: their
 * loop spilled too (7:23, nearly all inside it: some 100 spill accesses a
 * fragment at 4 trips) and cost 310 words; unrolled 211 words, 32:81, and
 * 175 and 16:37 since their texels' coordinates come from the vertex
 * stage (JD_BOX_COORDS, below).
 * The squares (4 trips at the default sizes) stay a loop on Vivante
 * GC400-GC2000 too: unrolled at 8 trips (two texels a trip) they passed
 * its 256-instruction limit, and at 4 (GC3000's build: 198) would leave
 * little of it for a larger box. More
 * than 8 trips (other light-map and diffusion sizes) stay a loop. */
static int diffusion_trips(const jd_renderer *r, int first)
{
    const jd_gl_caps *c = r->d.caps;
    if (c->utgard && !first) return 0;
    int trips;
    if (first) {
        int box = r->d.light_map_size / r->d.diffusion_size;
        if (c->max_program_instructions) return 0;
        trips = box > 1 ? box * box / 4 : 1;
    } else {
        float step, st;
        int taps = jdr_diffusion_taps(r, 0, &step, &st);
        for (int k = 1; k < DIFF_TEXTURES; k++)
            if (jdr_diffusion_taps(r, k, &step, &st) != taps) return 0; /* one program serves every level */
        trips = taps;
    }
    return trips <= 8 ? trips : 0;
}

static jd_result build_diffusion(jd_renderer *r, int first, diff_prog *p, jd_error *err)
{
    char def[200];
    p->trips = diffusion_trips(r, first);
    /* The first step gathers light-map texels in squares (JD_BOX). */
    snprintf(def, sizeof def,
             "#define JD_PACK_HIGHP %d\n#define JD_TAPS %d\n#define JD_FIRST %d\n#define JD_BOX %d\n#define JD_BOX_SIDE %d\n",
             r->highp, DIFF_TAPS, first, first, r->d.light_map_size / r->d.diffusion_size);
    /* The first step's squares unrolled, four at most: their texels'
     * coordinates come from the vertex stage, two a varying (eight, every
     * ES 2.0 GPU's least), where lima spilled those it made (quad.vert). */
    int coords = first && p->trips && p->trips <= 4;
    if (p->trips) {
        size_t n = strlen(def);
        snprintf(def + n, sizeof def - n, "#define JD_TRIPS %d\n%s", p->trips, coords ? "#define JD_BOX_COORDS 1\n" : "");
    }
    jd_result res = build(r, coords ? 2 * p->trips : 1, "shaders_es2/quad.vert", "shaders_es2/diffuse_blur.frag", def,
                          quad_attribs, &p->id, err);
    if (res) return res;
    p->src = glGetUniformLocation(p->id, "u_src");
    p->ref = glGetUniformLocation(p->id, "u_ref");
    p->ref_scale = glGetUniformLocation(p->id, "u_ref_scale");
    p->step = glGetUniformLocation(p->id, "u_step");
    p->taps = glGetUniformLocation(p->id, "u_taps");
    p->w = glGetUniformLocation(p->id, "u_w");
    p->uv_scale = glGetUniformLocation(p->id, "u_uv_scale");
    p->near = glGetUniformLocation(p->id, "u_near");
    return JD_OK;
}

static jd_result build_shade(jd_renderer *r, int m, jd_error *err)
{
    char def[800];
    int translucent = m == JD_MODE_SINGLE || m == JD_MODE_DUAL, map = r->albedo_tex != 0;
    /* full's highlight from its table (pass_screen.c, jdr_update_spec):
     * the table's coordinates from n.n and n.h, each end at its texel's
     * centre. */
    char spec[200] = "";
    if (m == JD_MODE_FULL && r->spec_tex)
        snprintf(spec, sizeof spec,
                 "#define JD_SPEC_TABLE 1\n#define JD_SPEC_SCALE vec2(%.9g, %.9g)\n#define JD_SPEC_OFFSET vec2(%.9g, %.9g)\n",
                 (SPEC_W - 1) / (SPEC_W * (1.0 - SPEC_NN)), (double)(SPEC_H - 1) / SPEC_H,
                 (0.5 - SPEC_NN * (SPEC_W - 1) / (1.0 - SPEC_NN)) / SPEC_W, 0.5 / SPEC_H);
    /* full's picture pass with the levels from their buffer takes the
     * light matrix's depth row already scaled to the shadow test's
     * exponent (mesh.vert, JD_LIGHT_Z_SCALED): a multiply-add fewer a
     * vertex, and 1-7 instructions fewer on every compiler of the table
     * that it changes. */
    int z_scaled = m == JD_MODE_FULL && !r->vertex_diffusion;
    /* The model's own colours (JD_ALBEDO: per vertex; _MAP: its texture too)
     * only in the programs that draw the picture: the light-space and
     * low-resolution passes carry light, and the picture's pass multiplies
     * it by the surface's colour. */
    snprintf(def, sizeof def,
             "#define JD_PACK_HIGHP %d\n#define JD_TRANSLUCENT %d\n#define JD_SPREAD %d\n#define JD_A0_ONLY 0\n"
             "#define JD_VERTEX_THICKNESS %d\n#define JD_FULL %d\n#define JD_VERTEX_DIFFUSION %d\n"
             "#define JD_WIDE_BUFFER %d\n#define JD_WIDE_ONLY 0\n#define JD_ALBEDO %d\n#define JD_ALBEDO_MAP %d\n"
             "#define JD_ALBEDO_PARTIAL %d\n#define JD_TWO_SIDED %d\n#define JD_UTGARD %d\n%s%s%s%s",
             r->highp, translucent, m == JD_MODE_DUAL, r->vertex_thickness, m == JD_MODE_FULL,
             m == JD_MODE_FULL && r->vertex_diffusion,
             m == JD_MODE_FULL && !r->vertex_diffusion, r->albedo, r->albedo && map, r->albedo && map && r->albedo_partial,
             r->d.no_cull, r->d.caps->utgard != 0, z_scaled ? "#define JD_LIGHT_Z_SCALED 1\n" : "", spec,
             /* Full summed per vertex reads the shadow map and five levels
              * there, the shadow map and the colour texture per fragment:
              * the light map itself, which the light scattered once reads
              * along the camera ray (mesh.vert, jd_single_march), is one
              * sampler more, which a GPU of 8 units (VideoCore IV) has no
              * room for with a colour texture; there full goes without it.
              * Only when the sum per vertex is asked for: the renderer's own
              * choice sums them per fragment there (renderer.c). */
             m == JD_MODE_FULL && r->vertex_diffusion &&
                     JD_FULL_VERTEX_LEVELS_UNITS + (r->albedo && map) > r->d.caps->max_texture_units
                 ? "#define JD_NO_SLAB 1\n" : "",
             /* The frame's alpha: its luma, for the pass after it (renderer.c). */
             r->luma_alpha ? "#define JD_LUMA_ALPHA 1\n" : "");
    /* v_view v_normal v_shadow [v_light] [v_trans v_dir] [v_fresnel v_half] [v_wide or v_screen] [v_col] [v_uv] */
    int varyings = translucent ? (r->vertex_thickness ? 5 : 6) : 3 + 3 * (m == JD_MODE_FULL);
    varyings += r->albedo + (r->albedo && map);
    jd_result res = build(r, varyings, "shaders_es2/mesh.vert", "shaders_es2/shade.frag", def, mesh_attribs,
                          &r->shade[m].id, err);
    if (res == JD_OK) shade_locations(&r->shade[m]);
    r->shade[m].light_z_scaled = z_scaled;
    return res;
}

/* What every mode needs: the light depth and the plain shading. */
static jd_result build_base(jd_renderer *r, jd_error *err)
{
    char def[64];
    jd_result res = build_shade(r, JD_MODE_NONE, err);
    if (res) return res;
    snprintf(def, sizeof def, "#define JD_PACK_HIGHP %d\n", r->highp);
    if ((res = build(r, 2, "shaders_es2/depth.vert", "shaders_es2/depth.frag", def, mesh_attribs, &r->depth_prog, err)))
        return res;
    r->depth_mvp = glGetUniformLocation(r->depth_prog, "u_light_mvp");
    r->depth_light_dir = glGetUniformLocation(r->depth_prog, "u_light_dir");
    r->depth_fresnel = glGetUniformLocation(r->depth_prog, "u_fresnel");
    return JD_OK;
}

/* One SH reduction program: rx x ry blocks summed into one. */
static jd_result build_reduce(jd_renderer *r, int rx, int ry, GLuint *prog, GLint *src, GLint *texel, jd_error *err)
{
    char def[96];
    snprintf(def, sizeof def, "#define JD_PACK_HIGHP %d\n#define JD_RX %d\n#define JD_RY %d\n", r->highp, rx, ry);
    jd_result res = build(r, 1, "shaders_es2/quad.vert", "shaders_es2/sh_reduce.frag", def, quad_attribs, prog, err);
    if (res) return res;
    *src = glGetUniformLocation(*prog, "u_src");
    *texel = glGetUniformLocation(*prog, "u_src_texel");
    return JD_OK;
}

/* single (and dual): the capture, its SH reduction, the irradiance map. */
static jd_result build_sh(jd_renderer *r, jd_error *err)
{
    char def[256];
    int n = r->d.cube_size, nb = n / r->sh_block;
    jd_result res = build_shade(r, JD_MODE_SINGLE, err);
    if (res) return res;
    snprintf(def, sizeof def, "#define JD_PACK_HIGHP %d\n", r->highp);
    if ((res = build(r, 2, "shaders_es2/capture.vert", "shaders_es2/capture.frag", def, mesh_attribs, &r->capture_prog, err)))
        return res;
    r->cap_mvp = glGetUniformLocation(r->capture_prog, "u_mvp");
    r->cap_light_tex = glGetUniformLocation(r->capture_prog, "u_light_tex");
    r->cap_light_dir = glGetUniformLocation(r->capture_prog, "u_light_dir");
    r->cap_bias = glGetUniformLocation(r->capture_prog, "u_bias");
    r->cap_depth = glGetUniformLocation(r->capture_prog, "u_depth");
    r->cap_light_color = glGetUniformLocation(r->capture_prog, "u_light_color");

    snprintf(def, sizeof def, "#define JD_PACK_HIGHP %d\n#define JD_N %d\n#define JD_B %d\n#define JD_NB %d\n",
             r->highp, n, r->sh_block, nb);
    if ((res = build(r, 4, "shaders_es2/sh_project.vert", "shaders_es2/sh_project.frag", def, project_attribs,
                     &r->project_prog, err)))
        return res;
    r->proj_atlas = glGetUniformLocation(r->project_prog, "u_atlas");
    r->proj_texel = glGetUniformLocation(r->project_prog, "u_atlas_texel");
    if (r->sh_mid > 1) {
        if ((res = build_reduce(r, r->sh_mid, r->sh_mid, &r->reduce_mid_prog, &r->rm_src, &r->rm_texel, err)))
            return res;
        nb /= r->sh_mid;
    }
    if ((res = build_reduce(r, nb, nb, &r->reduce_faces_prog, &r->rf_src, &r->rf_texel, err)) ||
        (res = build_reduce(r, 6, 1, &r->reduce_final_prog, &r->rl_src, &r->rl_texel, err)))
        return res;
    snprintf(def, sizeof def, "#define JD_PACK_HIGHP %d\n#define JD_SRC_W %d.0\n#define JD_SRC_H %d.0\n", r->highp, pot(1),
             pot(27));
    if ((res = build(r, 1, "shaders_es2/quad.vert", "shaders_es2/irradiance.frag", def, quad_attribs, &r->irr_prog, err)))
        return res;
    r->irr_src = glGetUniformLocation(r->irr_prog, "u_src");
    r->irr_size = glGetUniformLocation(r->irr_prog, "u_size");
    r->irr_face = glGetUniformLocation(r->irr_prog, "u_face");
    return JD_OK;
}

/* dual: A0 at low resolution and its two blurs. */
static jd_result build_spread(jd_renderer *r, jd_error *err)
{
    char def[512];
    jd_result res = build_shade(r, JD_MODE_DUAL, err);
    if (res) return res;
    snprintf(def, sizeof def,
             "#define JD_PACK_HIGHP %d\n#define JD_TRANSLUCENT 1\n#define JD_SPREAD 0\n#define JD_A0_ONLY 1\n"
             "#define JD_VERTEX_THICKNESS %d\n#define JD_FULL 0\n#define JD_VERTEX_DIFFUSION 0\n"
             "#define JD_WIDE_BUFFER 0\n#define JD_WIDE_ONLY 0\n#define JD_ALBEDO 0\n#define JD_ALBEDO_MAP 0\n#define JD_ALBEDO_PARTIAL 0\n",
             r->highp, r->vertex_thickness);
    if ((res = build(r, r->vertex_thickness ? 5 : 6, "shaders_es2/mesh.vert", "shaders_es2/shade.frag", def,
                     mesh_attribs, &r->a0.id, err)))
        return res;
    shade_locations(&r->a0);
    snprintf(def, sizeof def, "#define JD_PACK_HIGHP 0\n#define JD_TAPS %d\n#define JD_COMBINE 0\n", BLUR_TAPS);
    if ((res = build(r, 1, "shaders_es2/quad.vert", "shaders_es2/blur.frag", def, quad_attribs, &r->blur_prog, err))) return res;
    r->blur_src = glGetUniformLocation(r->blur_prog, "u_src");
    r->blur_step = glGetUniformLocation(r->blur_prog, "u_step");
    r->blur_inv = glGetUniformLocation(r->blur_prog, "u_inv_2s2");
    r->blur_scale = glGetUniformLocation(r->blur_prog, "u_uv_scale");
    snprintf(def, sizeof def, "#define JD_PACK_HIGHP 0\n#define JD_TAPS %d\n#define JD_COMBINE 1\n", BLUR_TAPS);
    if ((res = build(r, 1, "shaders_es2/quad.vert", "shaders_es2/blur.frag", def, quad_attribs, &r->combine_prog, err)))
        return res;
    r->comb_src = glGetUniformLocation(r->combine_prog, "u_src");
    r->comb_step = glGetUniformLocation(r->combine_prog, "u_step");
    r->comb_inv = glGetUniformLocation(r->combine_prog, "u_inv_2s2");
    r->comb_a1 = glGetUniformLocation(r->combine_prog, "u_a1");
    r->comb_w1 = glGetUniformLocation(r->combine_prog, "u_w1");
    r->comb_w2 = glGetUniformLocation(r->combine_prog, "u_w2");
    r->comb_scale = glGetUniformLocation(r->combine_prog, "u_uv_scale");
    return JD_OK;
}

/* full: the light-space diffusion and, without vertex textures, the
 * half-resolution sum of its levels. */
static jd_result build_full(jd_renderer *r, jd_error *err)
{
    char def[512];
    jd_result res = build_shade(r, JD_MODE_FULL, err);
    if (res) return res;
    if (!r->vertex_diffusion) {
        /* The two narrowest levels' 2 x 2 texels (light.glsl, jd_level_at)
         * as straight code where the GPU can hold it: each trip of the two
         * loops cost lima 75 words, 32 of them the loops' own tests and
         * branches, so 4 trips took 408 words a fragment where the code
         * unrolled takes 273 (3:7 spills); Midgard 264 -> 126 bundles.
         * Vivante GC400-GC2000 keep the loop: unrolled it does not fit
         * their 256 instructions. */
        r->wide_unrolled = !r->d.caps->max_program_instructions;
        snprintf(def, sizeof def,
                 "#define JD_PACK_HIGHP %d\n#define JD_TRANSLUCENT 0\n#define JD_SPREAD 0\n#define JD_A0_ONLY 0\n"
                 "#define JD_VERTEX_THICKNESS 0\n#define JD_FULL 1\n#define JD_VERTEX_DIFFUSION 0\n"
                 "#define JD_WIDE_BUFFER 0\n#define JD_WIDE_ONLY 1\n#define JD_ALBEDO 0\n#define JD_ALBEDO_MAP 0\n#define JD_ALBEDO_PARTIAL 0\n"
                 "%s",
                 r->highp, r->wide_unrolled ? "#define JD_TRIPS 4\n" : "");
        /* v_pos v_keep v_bounce v_shadow v_exit */
        if ((res = build(r, 5, "shaders_es2/mesh.vert", "shaders_es2/shade.frag", def, mesh_attribs, &r->wide_prog.id,
                         err)))
            return res;
        shade_locations(&r->wide_prog);
        if ((res = build(r, 3, "shaders_es2/quad.vert", "shaders_es2/wide_fill.frag",
                         "#define JD_PACK_HIGHP 0\n#define JD_DIAGONALS 1\n", quad_attribs, &r->fill_prog, err)))
            return res;
        r->fill_src = glGetUniformLocation(r->fill_prog, "u_src");
        r->fill_texel = glGetUniformLocation(r->fill_prog, "u_texel");
        r->fill_scale = glGetUniformLocation(r->fill_prog, "u_uv_scale");
    }
    if ((res = build_diffusion(r, 1, &r->diff_first, err)) || (res = build_diffusion(r, 0, &r->diff_next, err)))
        return res;
    snprintf(def, sizeof def, "#define JD_PACK_HIGHP %d\n", r->highp);
    if ((res = build(r, 3, "shaders_es2/soft_shadow.vert", "shaders_es2/soft_shadow.frag", def, quad_attribs,
                     &r->soft_prog, err)))
        return res;
    r->soft_src = glGetUniformLocation(r->soft_prog, "u_src");
    r->soft_step = glGetUniformLocation(r->soft_prog, "u_step");
    r->soft_c = glGetUniformLocation(r->soft_prog, "u_c");
    r->soft_scale = glGetUniformLocation(r->soft_prog, "u_uv_scale");
    return JD_OK;
}

static jd_result build_antialias(jd_renderer *r, jd_error *err)
{
    if (r->may_scale) {
        jd_result res = build(r, 1, "shaders_es2/quad.vert", "shaders_es2/upscale.frag", "#define JD_PACK_HIGHP 0\n",
                              quad_attribs, &r->up_prog, err);
        if (res) return res;
        r->up_src = glGetUniformLocation(r->up_prog, "u_src");
        r->up_scale = glGetUniformLocation(r->up_prog, "u_uv_scale");
    }
    if (!r->post_aa && !r->aa_small) return JD_OK;
    /* Its luma from the frame's alpha where the picture's programs write it there (renderer.c). */
    const char *luma = r->luma_alpha ? "#define JD_LUMA_ALPHA 1\n" : "";
    char def[128];
    snprintf(def, sizeof def, "#define JD_PACK_HIGHP 0\n#define JD_DIAGONALS 1\n%s", luma);
    jd_result res = build(r, 3, "shaders_es2/quad.vert", "shaders_es2/antialias.frag", def, quad_attribs, &r->aa_prog, err);
    if (res) return res;
    r->aa_src = glGetUniformLocation(r->aa_prog, "u_src");
    r->aa_texel = glGetUniformLocation(r->aa_prog, "u_texel");
    r->aa_scale = glGetUniformLocation(r->aa_prog, "u_uv_scale");
    /* Its test alone, which marks the flat pixels in the depth buffer so
     * that the pass runs on the edges only (jdr_pass_final): where a frame
     * goes through `aa_mid` (its depth is the frame's) or the target has
     * a depth buffer of its own. */
    if (!r->may_scale && !r->target_depth) return JD_OK;
    snprintf(def, sizeof def, "#define JD_PACK_HIGHP 0\n#define JD_DIAGONALS 1\n#define JD_AA_MARK 1\n%s", luma);
    res = build(r, 3, "shaders_es2/quad.vert", "shaders_es2/antialias.frag", def, quad_attribs, &r->aa_mark_prog, err);
    if (res) return res;
    r->aa_mark_src = glGetUniformLocation(r->aa_mark_prog, "u_src");
    r->aa_mark_texel = glGetUniformLocation(r->aa_mark_prog, "u_texel");
    r->aa_mark_scale = glGetUniformLocation(r->aa_mark_prog, "u_uv_scale");
    return JD_OK;
}

/* The programs by what needs them. A group that does not build, or builds
 * and then draws nothing, takes away what needs it (a mode, the
 * anti-aliasing pass), never the renderer; only the base is essential. */
enum { GROUP_BASE, GROUP_SH, GROUP_SPREAD, GROUP_FULL, GROUP_AA, GROUP_COUNT };
static const char *const group_what[GROUP_COUNT] = {"the shading every mode needs", "single and dual's SH",
                                                     "dual's spread", "full's diffusion", "the anti-aliasing pass"};
static jd_result (*const group_build[GROUP_COUNT])(jd_renderer *, jd_error *) = {
    build_base, build_sh, build_spread, build_full, build_antialias};

/* A group's program ids (0 where not built); returns how many. */
static int group_programs(jd_renderer *r, int g, GLuint **out)
{
    int n = 0;
    switch (g) {
    case GROUP_BASE: out[n++] = &r->shade[JD_MODE_NONE].id; out[n++] = &r->depth_prog; break;
    case GROUP_SH:
        out[n++] = &r->shade[JD_MODE_SINGLE].id; out[n++] = &r->capture_prog; out[n++] = &r->project_prog;
        out[n++] = &r->reduce_mid_prog; out[n++] = &r->reduce_faces_prog; out[n++] = &r->reduce_final_prog;
        out[n++] = &r->irr_prog;
        break;
    case GROUP_SPREAD:
        out[n++] = &r->shade[JD_MODE_DUAL].id; out[n++] = &r->a0.id; out[n++] = &r->blur_prog; out[n++] = &r->combine_prog;
        break;
    case GROUP_FULL:
        out[n++] = &r->shade[JD_MODE_FULL].id; out[n++] = &r->wide_prog.id; out[n++] = &r->diff_first.id;
        out[n++] = &r->diff_next.id; out[n++] = &r->soft_prog; out[n++] = &r->fill_prog;
        break;
    default: out[n++] = &r->aa_prog; out[n++] = &r->up_prog; out[n++] = &r->aa_mark_prog; break;
    }
    return n;
}

static void drop_group(jd_renderer *r, int g)
{
    GLuint *ids[8];
    int n = group_programs(r, g, ids);
    for (int i = 0; i < n; i++) {
        if (*ids[i]) glDeleteProgram(*ids[i]);
        *ids[i] = 0;
    }
}

/* Appends to what start-up says of the fallbacks taken. */
static void say(jd_renderer *r, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static void say(jd_renderer *r, const char *fmt, ...)
{
    size_t n = strlen(r->fallback);
    if (n + 3 >= sizeof r->fallback) return;
    if (n) { memcpy(r->fallback + n, "; ", 3); n += 2; }
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(r->fallback + n, sizeof r->fallback - n, fmt, ap);
    va_end(ap);
}

/* Builds every group. A device whose compiler rejects a highp program gets
 * the mediump packing for all of them (precision auto only); a group
 * still failing is dropped and said. The probe then drops the groups with
 * a program that draws nothing. Each mode is shown as itself or as the
 * nearest cheaper mode whose groups are there: full as dual, dual as
 * single, single as none. */
static int build_groups(jd_renderer *r, int *ok, jd_error *gerr)
{
    int failed = 0;
    for (int g = 0; g < GROUP_COUNT; g++) {
        memset(&gerr[g], 0, sizeof gerr[g]);
        ok[g] = group_build[g](r, &gerr[g]) == JD_OK;
        failed += !ok[g];
    }
    return failed;
}

static void drop_groups(jd_renderer *r)
{
    for (int g = 0; g < GROUP_COUNT; g++) drop_group(r, g);
}

jd_result jdr_build_programs(jd_renderer *r, jd_error *err)
{
    jd_error gerr[GROUP_COUNT];
    int ok[GROUP_COUNT];
    int failed = build_groups(r, ok, gerr);
    if (failed && r->highp && r->d.precision == JD_PRECISION_AUTO) {
        char first[sizeof gerr[0].msg] = "";
        for (int g = 0; g < GROUP_COUNT && !first[0]; g++)
            if (!ok[g]) memcpy(first, gerr[g].msg, sizeof first);
        drop_groups(r);
        r->highp = 0;
        if (build_groups(r, ok, gerr) < failed) {
            say(r, "highp packing: %s; mediump packing instead", first);
        } else { /* no better: the packing the device is best at, and the same losses */
            drop_groups(r);
            r->highp = 1;
            build_groups(r, ok, gerr);
        }
    }
    if (!ok[GROUP_BASE]) return jd_fail(err, JD_ERR_UNSUPPORTED, "%s", gerr[GROUP_BASE].msg);
    const char *gl = r->d.caps->renderer;
    int software = strstr(gl, "llvmpipe") || strstr(gl, "softpipe") || strstr(gl, "swrast");
    if (r->d.program_probe == JD_PROBE_ON || (r->d.program_probe == JD_PROBE_AUTO && !software)) {
        GLuint ids[JD_PROBE_MAX], *slot[JD_PROBE_MAX];
        int owner[JD_PROBE_MAX], drawn[JD_PROBE_MAX], n = 0;
        for (int g = 0; g < GROUP_COUNT; g++) {
            if (!ok[g]) continue;
            GLuint *p[8];
            int k = group_programs(r, g, p);
            for (int i = 0; i < k && n < JD_PROBE_MAX; i++, n++) {
                slot[n] = p[i];
                ids[n] = *p[i];
                owner[n] = g;
            }
        }
        target probe = {0};
        size_t bytes = r->target_bytes;
        int probed = jdr_make_target(r, &probe, JD_PROBE_MAX, 1, 0, 0, "program probe", NULL) == JD_OK &&
                     jd_program_probe(ids, n, probe.fbo, r->quad_vbo, drawn);
        jdr_free_target(&probe);
        r->target_bytes = bytes; /* gone again */
        if (probed)
            for (int i = 0; i < n; i++)
                if (!drawn[i] && ok[owner[i]]) {
                    ok[owner[i]] = 0;
                    jd_fail(&gerr[owner[i]], JD_ERR_UNSUPPORTED,
                            "program %u (%s) links but the driver draws nothing with it", *slot[i],
                            group_what[owner[i]]);
                }
        if (!ok[GROUP_BASE]) return jd_fail(err, JD_ERR_UNSUPPORTED, "%s", gerr[GROUP_BASE].msg);
    }
    for (int g = 1; g < GROUP_COUNT; g++)
        if (!ok[g]) {
            drop_group(r, g);
            say(r, "%s unavailable: %s", group_what[g], gerr[g].msg);
        }
    /* Frames at the full resolution, edges as they come, and the frame's
     * alpha left alone (the picture's programs may write a luma there that
     * no pass reads: pass_screen.c masks it). */
    if (!ok[GROUP_AA]) r->post_aa = r->aa_small = r->may_scale = r->luma_alpha = 0;
    int have[JD_MODE_COUNT] = {1, ok[GROUP_SH], ok[GROUP_SH] && ok[GROUP_SPREAD], ok[GROUP_FULL]};
    for (int m = 0; m < JD_MODE_COUNT; m++) {
        int shown = m;
        while (!have[shown]) shown = shown == JD_MODE_FULL ? JD_MODE_DUAL : shown - 1;
        r->shown[m] = (jd_mode)shown;
        if (shown != m) say(r, "%s frames are drawn as %s", jd_mode_name((jd_mode)m), jd_mode_name((jd_mode)shown));
    }
    return JD_OK;
}
