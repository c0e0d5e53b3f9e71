#include "renderer.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "clock.h"
#include "diffusion_fit.h"
#include "frame_cost.h"
#include "gl.h"
#include "gl_program.h"
#include "program_probe.h"
#include "scene.h"
#include "sh.h"
#include "vmath.h"

#define SH_BLOCK 8
#define SH_BLOCK_SMALL 2 /* VideoCore IV, Mali-400: see jd_renderer_create */
/* The irradiance cube map's texels per face side: the SH irradiance is
 * smooth (order 2), and 16 x 16 per face, bilinearly filtered, carry it. */
#define IRR_SIZE 16
#define BLUR_TAPS 4
/* The full mode's light-space levels: Gaussians of 1, 2, 4, 8 and 16 texels
 * of the first level, one RGBA8 texture each, every second one half the
 * size (a wider Gaussian needs fewer texels): a pyramid. Each blur step has
 * 2 * DIFF_TAPS + 1 taps. */
#define DIFF_LEVELS 5
#define DIFF_TEXTURES DIFF_LEVELS
#define DIFF_TAPS 6
/* Rd's Gaussians finer than a level texel are applied at the shaded point. */
#define DIFF_LOCAL 3

/* Render targets are power-of-two textures (some ES 2.0 drivers cannot
 * render to NPOT ones); w x h is the region in use, set by the viewport. */
typedef struct target {
    GLuint tex, fbo, depth;
    int w, h;   /* used */
    int tw, th; /* allocated, powers of two */
} target;

static int pot(int n)
{
    int p = 1;
    while (p < n) p <<= 1;
    return p;
}

typedef struct shade_prog {
    GLuint id;
    GLint mvp, light_mvp, eye, irr, box_min, box_max, inv_eta, inset;
    GLint light_dir, albedo, light_color, shading, depth, tail, depth_v, tail_v, f0, a0_scale;
    GLint spread, inv_viewport, w0;
    GLint light_map, shadow_bias, lv[DIFF_TEXTURES], lw, ls, wl;
    GLint light_map_v, light_dir_v, lv_v[DIFF_TEXTURES], wide;
} shade_prog;

/* A step of the full mode's light-space diffusion (diffuse_blur.frag). */
typedef struct diff_prog {
    GLuint id;
    GLint src, ref, ref_scale, step, taps, w, uv_scale, near, box;
} diff_prog;

#define TAIL_SIZE 256

/* GL_EXT_disjoint_timer_query, resolved at start-up when present. */
typedef struct timer_query {
    PFNGLGENQUERIESEXTPROC gen;
    PFNGLDELETEQUERIESEXTPROC del;
    PFNGLBEGINQUERYEXTPROC begin;
    PFNGLENDQUERYEXTPROC end;
    PFNGLGETQUERYOBJECTUI64VEXTPROC result64;
    GLuint q[JD_PASS_COUNT];
    int ok, used[JD_PASS_COUNT];
} timer_query;

struct jd_renderer {
    jd_renderer_desc d;
    int highp;
    int timing; /* jd_renderer_set_timing */
    int vertex_thickness; /* thickness read in the vertex stage */
    int vertex_diffusion; /* the full mode's levels summed in the vertex stage */
    int target_samples;   /* GL_SAMPLES of the platform's target */
    int post_aa;          /* frames go to `scene`, then through the anti-aliasing pass */
    int may_scale;        /* render_scale may be under 1 at some size: `scene` and the upscale pass exist */
    int iw, ih;           /* the picture's passes' size: width x height, or less (render_scale) */
    char tier[200];       /* what the tier draws at, for jd_renderer_info */
    int sh_block;         /* capture texels per SH projection pixel, per side (8, or 2 on small register files) */
    int sh_mid;           /* > 1: an intermediate reduction by sh_mid x sh_mid, so no pass sums over 64 texels */
    jd_mode shown[JD_MODE_COUNT]; /* what a frame asking for each mode draws (build_programs) */
    char fallback[1024];  /* what this device could not run, and what it gets instead; "" */
    jd_mesh proxy, capture_proxy;
    GLuint mesh_vbo, mesh_ibo, proxy_vbo, proxy_ibo, cap_vbo, cap_ibo, quad_vbo;
    GLuint project_vbo;   /* the SH projection's 6 x 27 rectangles, with their constants */
    GLuint tail_tex;
    timer_query tq;
    uint8_t *tail_px;     /* TAIL_SIZE RGBA texels, rebuilt when the material changes */
    float tail_key[9];
    float fit_key[9];
    jd_diffusion_fit fit;
    int diff_levels;      /* levels whose weights are not all zero */
    float proxy_error;    /* world units: how far the proxy may stray from the mesh */
    GLenum mesh_index_type;
    /* GPUs without 32-bit indices draw a mesh over 65,536 vertices as chunks
     * that each fit 16 bits, their vertices copied (so shared edges are
     * bit-identical: no seam). None: one draw of the whole mesh. */
    struct mesh_chunk { size_t index_offset, vertex_offset; uint32_t count, vertices; } *chunks;
    int num_chunks;
    shade_prog shade[JD_MODE_COUNT], a0, wide_prog; /* wide_prog: full's levels at half resolution */
    GLuint depth_prog, capture_prog, project_prog, reduce_mid_prog, reduce_faces_prog, reduce_final_prog, blur_prog,
        combine_prog;
    diff_prog diff_first, diff_next; /* level 1 from the light map; the others */
    GLuint aa_prog, up_prog;
    GLint aa_src, aa_texel, aa_scale, up_src, up_scale;
    GLint depth_mvp, depth_light_dir, depth_f0;
    GLint cap_mvp, cap_light_mvp, cap_light_dir, cap_bias, cap_depth, cap_light_color;
    GLint proj_atlas, proj_texel, rm_src, rm_texel, rf_src, rf_texel, rl_src, rl_texel;
    GLuint irr_prog; /* the SH result to the irradiance map */
    GLint irr_src, irr_size, irr_face;
    GLint blur_src, blur_step, blur_inv, blur_scale;
    GLint comb_src, comb_step, comb_inv, comb_a1, comb_w1, comb_w2, comb_scale;
    target light, atlas, sh1, sh_mid_t, sh2, sh3, irr[6], spread0, spread_tmp, spread1, spread2;
    target diff_tmp, diff_lv[DIFF_TEXTURES];
    target scene;         /* the frame before anti-aliasing or enlarging (post_aa, or drawn smaller) */
    target wide;          /* full's levels summed at 1/wide_div resolution (without vertex diffusion) */
    int wide_div;
    size_t target_bytes;
    float box_half;
    jd_vec3 place_c;      /* the mesh's coordinates to the renderer's: (p - place_c) * place_inv_r */
    float place_inv_r;
    /* What a tiler would pay this frame: render-target switches (each one
     * writes the tile memory out), pixels shaded (by target area), bytes
     * written to render targets, read-backs. */
    int n_switches, n_readbacks;
    double n_fragments, n_bytes;
    /* The inputs of the light-space passes and of the screen-space spread
     * at the last frame, so a still scene reuses their results. */
    float light_key[16], view_key[24];
    int light_key_valid, view_key_valid;
    /* Programs by id with the compiler table's label for them, for the
     * frame-cost count. */
    struct { GLuint id; char label[96]; } labels[40];
    int num_labels;
    /* jd_renderer_count's frame: its record (NULL in every other frame),
     * the counting program, the vertices each mesh's draw shades under the
     * vertex reuse asked for (whole mesh, proxy, capture proxy), and
     * whether the open pass drew meshes (its fragments are read back). */
    jd_frame_count *count;
    GLuint count_prog;
    GLint count_mvp;
    double count_vertices[3];
    int count_read, count_cleared;
};

/* ---- start-up ---------------------------------------------------------- */

/* A new texture bound to `kind`, clamped and without mipmaps: NPOT-safe
 * in core ES 2.0. */
static GLuint new_sampled(GLenum kind, GLint filter)
{
    GLuint tex;
    glGenTextures(1, &tex);
    glBindTexture(kind, tex);
    glTexParameteri(kind, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(kind, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(kind, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(kind, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return tex;
}

/* An RGBA8 2D texture. */
static GLuint new_texture(int w, int h, GLint filter)
{
    GLuint tex = new_sampled(GL_TEXTURE_2D, filter);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    return tex;
}

static jd_result make_target(jd_renderer *r, target *t, int w, int h, int with_depth, int linear,
                             const char *what, jd_error *err)
{
    const jd_gl_caps *c = r->d.caps;
    t->w = w;
    t->h = h;
    t->tw = pot(w);
    t->th = pot(h);
    if (t->tw > c->max_texture_size || t->th > c->max_texture_size)
        return jd_fail(err, JD_ERR_UNSUPPORTED, "%s target %dx%d exceeds the max texture size %d", what, t->tw,
                       t->th, c->max_texture_size);
    t->tex = new_texture(t->tw, t->th, linear ? GL_LINEAR : GL_NEAREST);
    glGenFramebuffers(1, &t->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t->tex, 0);
    r->target_bytes += (size_t)t->tw * t->th * 4;
    if (with_depth) {
        glGenRenderbuffers(1, &t->depth);
        glBindRenderbuffer(GL_RENDERBUFFER, t->depth);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT16, t->tw, t->th);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t->depth);
        r->target_bytes += (size_t)t->tw * t->th * 2;
    }
    GLenum st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE)
        return jd_fail(err, JD_ERR_GL, "%s framebuffer %dx%d is incomplete (0x%x)", what, w, h, st);
    return JD_OK;
}

/* A cube map of RGBA8 faces, each its own framebuffer: six targets sharing
 * one texture (held by the first). Linear filtering, clamped at the edges. */
static jd_result make_cube_target(jd_renderer *r, target *faces, int size, const char *what, jd_error *err)
{
    GLuint tex = new_sampled(GL_TEXTURE_CUBE_MAP, GL_LINEAR);
    for (int f = 0; f < 6; f++)
        glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f, 0, GL_RGBA, size, size, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    faces[0].tex = tex;
    for (int f = 0; f < 6; f++) {
        target *t = &faces[f];
        t->w = t->h = t->tw = t->th = size;
        glGenFramebuffers(1, &t->fbo);
        glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_CUBE_MAP_POSITIVE_X + f, tex, 0);
        GLenum st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        if (st != GL_FRAMEBUFFER_COMPLETE)
            return jd_fail(err, JD_ERR_GL, "%s face %d (%dx%d) is incomplete (0x%x)", what, f, size, size, st);
    }
    r->target_bytes += (size_t)6 * size * size * 4;
    return JD_OK;
}

static void free_target(target *t)
{
    if (t->fbo) glDeleteFramebuffers(1, &t->fbo);
    if (t->tex) glDeleteTextures(1, &t->tex);
    if (t->depth) glDeleteRenderbuffers(1, &t->depth);
    memset(t, 0, sizeof *t);
}

/* Positions normalised to the bounding sphere (centre 0, radius 1) keep
 * coordinates small for fp16 varyings; interleaved with normals. */
/* One vertex as uploaded: the position centred and scaled to the unit
 * sphere, then the normal. */
static void pack_vertex(float *o, const jd_mesh *m, uint32_t i, jd_vec3 c, float inv_r)
{
    const float *p = m->positions + 3 * (size_t)i, *n = m->normals + 3 * (size_t)i;
    o[0] = (p[0] - c.x) * inv_r;
    o[1] = (p[1] - c.y) * inv_r;
    o[2] = (p[2] - c.z) * inv_r;
    o[3] = n[0];
    o[4] = n[1];
    o[5] = n[2];
}

static jd_result upload_mesh(const jd_mesh *m, jd_vec3 c, float inv_r, GLuint *vbo, GLuint *ibo,
                             jd_arena *a, jd_error *err)
{
    size_t top = jd_arena_top_mark(a);
    float *v = jd_arena_alloc_top(a, sizeof(float) * 6 * m->num_vertices, 16, "vertex upload scratch", err);
    if (!v) return JD_ERR_BUDGET;
    for (uint32_t i = 0; i < m->num_vertices; i++) pack_vertex(v + 6 * (size_t)i, m, i, c, inv_r);
    glGenBuffers(1, vbo);
    glBindBuffer(GL_ARRAY_BUFFER, *vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * 6 * m->num_vertices), v, GL_STATIC_DRAW);
    glGenBuffers(1, ibo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, *ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)((size_t)m->index_size * m->num_indices), m->indices,
                 GL_STATIC_DRAW);
    jd_arena_top_reset(a, top);
    return glGetError() == GL_NO_ERROR ? JD_OK : jd_fail(err, JD_ERR_GL, "mesh upload failed (out of GPU memory?)");
}

/* The mesh as chunks of at most 65,535 distinct vertices each, in triangle
 * order (which meshoptimizer made local: few vertices repeat across
 * chunks). Vertex and index data for every chunk go into one buffer each. */
static jd_result upload_mesh_chunked(jd_renderer *r, const jd_mesh *m, jd_vec3 c, float inv_r, jd_arena *a,
                                     jd_error *err)
{
    const uint32_t limit = 65535;
    size_t top = jd_arena_top_mark(a);
    /* Worst case every triangle brings three new vertices. */
    size_t max_chunks = (size_t)m->num_indices / 3 / (limit / 3) + 2;
    int32_t *local = jd_arena_alloc_top(a, sizeof(int32_t) * m->num_vertices, 16, "chunk vertex map", err);
    uint32_t *used = jd_arena_alloc_top(a, sizeof(uint32_t) * limit, 16, "chunk vertex list", err);
    /* Copies: at most one per index, and in practice far fewer than twice
     * the vertices (a chunk repeats only its border). */
    size_t v_cap = m->num_indices < (size_t)m->num_vertices * 2 ? m->num_indices : (size_t)m->num_vertices * 2;
    float *v = jd_arena_alloc_top(a, sizeof(float) * 6 * v_cap, 16, "chunked vertex upload", err);
    uint16_t *ix = jd_arena_alloc_top(a, sizeof(uint16_t) * m->num_indices, 16, "chunked index upload", err);
    r->chunks = jd_arena_alloc(a, sizeof *r->chunks * max_chunks, 16, "mesh chunks", err);
    if (!local || !used || !v || !ix || !r->chunks) { jd_arena_top_reset(a, top); return JD_ERR_BUDGET; }
    for (uint32_t i = 0; i < m->num_vertices; i++) local[i] = -1;
    size_t nv = 0, ni = 0;
    uint32_t n_used = 0;
    r->num_chunks = 0;
    struct mesh_chunk *ch = NULL;
    for (uint32_t t = 0; t < m->num_indices; t += 3) {
        uint32_t tri[3] = {jd_mesh_index(m, t), jd_mesh_index(m, t + 1), jd_mesh_index(m, t + 2)};
        int fresh = 0;
        for (int k = 0; k < 3; k++) fresh += local[tri[k]] < 0;
        if (!ch || n_used + (uint32_t)fresh > limit) { /* a new chunk */
            for (uint32_t k = 0; k < n_used; k++) local[used[k]] = -1;
            n_used = 0;
            if ((size_t)r->num_chunks == max_chunks) { jd_arena_top_reset(a, top); return jd_fail(err, JD_ERR_BUDGET, "too many mesh chunks"); }
            ch = &r->chunks[r->num_chunks++];
            ch->index_offset = ni * sizeof(uint16_t);
            ch->vertex_offset = nv * 6 * sizeof(float);
            ch->count = 0;
            ch->vertices = 0;
        }
        for (int k = 0; k < 3; k++) {
            if (local[tri[k]] < 0) {
                if (nv == v_cap) { jd_arena_top_reset(a, top); return jd_fail(err, JD_ERR_BUDGET, "mesh chunks: vertex copies over the scratch"); }
                pack_vertex(v + 6 * nv++, m, tri[k], c, inv_r);
                ch->vertices++;
                local[tri[k]] = (int32_t)n_used;
                used[n_used++] = tri[k];
            }
            ix[ni++] = (uint16_t)local[tri[k]];
        }
        ch->count += 3;
    }
    glGenBuffers(1, &r->mesh_vbo);
    glBindBuffer(GL_ARRAY_BUFFER, r->mesh_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * 6 * nv), v, GL_STATIC_DRAW);
    glGenBuffers(1, &r->mesh_ibo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->mesh_ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(sizeof(uint16_t) * ni), ix, GL_STATIC_DRAW);
    jd_arena_top_reset(a, top);
    return glGetError() == GL_NO_ERROR ? JD_OK : jd_fail(err, JD_ERR_GL, "mesh upload failed (out of GPU memory?)");
}

static const char *const mesh_attribs[] = {"a_position", "a_normal", NULL};
static const char *const quad_attribs[] = {"a_corner", NULL};
static const char *const project_attribs[] = {"a_corner", "a_poly0", "a_poly1", "a_channel", "a_texel", NULL};
enum { PROJECT_FLOATS = 17 }; /* per vertex of the projection's rectangles */

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
    p->light_mvp = glGetUniformLocation(id, "u_light_mvp");
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
    p->a0_scale = glGetUniformLocation(id, "u_a0_scale");
    p->spread = glGetUniformLocation(id, "u_spread");
    p->inv_viewport = glGetUniformLocation(id, "u_inv_viewport");
    p->w0 = glGetUniformLocation(id, "u_w0");
    p->light_map = glGetUniformLocation(id, "u_light_map");
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
    p->ls = glGetUniformLocation(id, "u_ls");
    p->wl = glGetUniformLocation(id, "u_wl");
}

static jd_result build_diffusion(jd_renderer *r, int first, diff_prog *p, jd_error *err)
{
    char def[128];
    /* The first step gathers light-map texels in squares (JD_BOX). */
    snprintf(def, sizeof def, "#define JD_PACK_HIGHP %d\n#define JD_TAPS %d\n#define JD_FIRST %d\n#define JD_BOX %d\n",
             r->highp, DIFF_TAPS, first, first);
    jd_result res = build(r, 1, "shaders_es2/quad.vert", "shaders_es2/diffuse_blur.frag", def, quad_attribs, &p->id, err);
    if (res) return res;
    p->src = glGetUniformLocation(p->id, "u_src");
    p->ref = glGetUniformLocation(p->id, "u_ref");
    p->ref_scale = glGetUniformLocation(p->id, "u_ref_scale");
    p->step = glGetUniformLocation(p->id, "u_step");
    p->taps = glGetUniformLocation(p->id, "u_taps");
    p->w = glGetUniformLocation(p->id, "u_w");
    p->uv_scale = glGetUniformLocation(p->id, "u_uv_scale");
    p->near = glGetUniformLocation(p->id, "u_near");
    p->box = glGetUniformLocation(p->id, "u_box");
    return JD_OK;
}

static jd_result build_shade(jd_renderer *r, int m, jd_error *err)
{
    char def[512];
    int translucent = m == JD_MODE_SINGLE || m == JD_MODE_DUAL;
    snprintf(def, sizeof def,
             "#define JD_PACK_HIGHP %d\n#define JD_TRANSLUCENT %d\n#define JD_SPREAD %d\n#define JD_A0_ONLY 0\n"
             "#define JD_VERTEX_THICKNESS %d\n#define JD_FULL %d\n#define JD_VERTEX_DIFFUSION %d\n"
             "#define JD_WIDE_BUFFER %d\n#define JD_WIDE_ONLY 0\n",
             r->highp, translucent, m == JD_MODE_DUAL, r->vertex_thickness, m == JD_MODE_FULL, r->vertex_diffusion,
             m == JD_MODE_FULL && !r->vertex_diffusion);
    /* v_pos v_normal v_shadow [v_light] [v_trans v_dir] [v_fresnel] [v_wide] */
    int varyings = translucent ? (r->vertex_thickness ? 5 : 6)
                               : 3 + (m == JD_MODE_FULL) + (m == JD_MODE_FULL && r->vertex_diffusion);
    jd_result res = build(r, varyings, "shaders_es2/mesh.vert", "shaders_es2/shade.frag", def, mesh_attribs,
                          &r->shade[m].id, err);
    if (res == JD_OK) shade_locations(&r->shade[m]);
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
    r->depth_f0 = glGetUniformLocation(r->depth_prog, "u_f0");
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
    r->cap_light_mvp = glGetUniformLocation(r->capture_prog, "u_light_mvp");
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
        snprintf(def, sizeof def, "#define JD_PACK_HIGHP %d\n#define JD_RX %d\n#define JD_RY %d\n", r->highp, r->sh_mid,
                 r->sh_mid);
        if ((res = build(r, 1, "shaders_es2/quad.vert", "shaders_es2/sh_reduce.frag", def, quad_attribs,
                         &r->reduce_mid_prog, err)))
            return res;
        r->rm_src = glGetUniformLocation(r->reduce_mid_prog, "u_src");
        r->rm_texel = glGetUniformLocation(r->reduce_mid_prog, "u_src_texel");
        nb /= r->sh_mid;
    }
    snprintf(def, sizeof def, "#define JD_PACK_HIGHP %d\n#define JD_RX %d\n#define JD_RY %d\n", r->highp, nb, nb);
    if ((res = build(r, 1, "shaders_es2/quad.vert", "shaders_es2/sh_reduce.frag", def, quad_attribs, &r->reduce_faces_prog, err)))
        return res;
    r->rf_src = glGetUniformLocation(r->reduce_faces_prog, "u_src");
    r->rf_texel = glGetUniformLocation(r->reduce_faces_prog, "u_src_texel");
    snprintf(def, sizeof def, "#define JD_PACK_HIGHP %d\n#define JD_RX 6\n#define JD_RY 1\n", r->highp);
    if ((res = build(r, 1, "shaders_es2/quad.vert", "shaders_es2/sh_reduce.frag", def, quad_attribs, &r->reduce_final_prog, err)))
        return res;
    r->rl_src = glGetUniformLocation(r->reduce_final_prog, "u_src");
    r->rl_texel = glGetUniformLocation(r->reduce_final_prog, "u_src_texel");
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
             "#define JD_WIDE_BUFFER 0\n#define JD_WIDE_ONLY 0\n",
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
        snprintf(def, sizeof def,
                 "#define JD_PACK_HIGHP %d\n#define JD_TRANSLUCENT 0\n#define JD_SPREAD 0\n#define JD_A0_ONLY 0\n"
                 "#define JD_VERTEX_THICKNESS 0\n#define JD_FULL 1\n#define JD_VERTEX_DIFFUSION 0\n"
                 "#define JD_WIDE_BUFFER 0\n#define JD_WIDE_ONLY 1\n",
                 r->highp);
        if ((res = build(r, 3, "shaders_es2/mesh.vert", "shaders_es2/shade.frag", def, mesh_attribs, &r->wide_prog.id,
                         err)))
            return res;
        shade_locations(&r->wide_prog);
    }
    if ((res = build_diffusion(r, 1, &r->diff_first, err))) return res;
    return build_diffusion(r, 0, &r->diff_next, err);
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
    if (!r->post_aa) return JD_OK;
    jd_result res = build(r, 1, "shaders_es2/quad.vert", "shaders_es2/antialias.frag", "#define JD_PACK_HIGHP 0\n",
                          quad_attribs, &r->aa_prog, err);
    if (res) return res;
    r->aa_src = glGetUniformLocation(r->aa_prog, "u_src");
    r->aa_texel = glGetUniformLocation(r->aa_prog, "u_texel");
    r->aa_scale = glGetUniformLocation(r->aa_prog, "u_uv_scale");
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
        out[n++] = &r->diff_next.id;
        break;
    default: out[n++] = &r->aa_prog; out[n++] = &r->up_prog; break;
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

static jd_result build_programs(jd_renderer *r, jd_error *err)
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
        int probed = make_target(r, &probe, JD_PROBE_MAX, 1, 0, 0, "program probe", NULL) == JD_OK &&
                     jd_program_probe(ids, n, probe.fbo, r->quad_vbo, drawn);
        free_target(&probe);
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
    if (!ok[GROUP_AA]) r->post_aa = r->may_scale = 0; /* frames at the full resolution, edges as they come */
    int have[JD_MODE_COUNT] = {1, ok[GROUP_SH], ok[GROUP_SH] && ok[GROUP_SPREAD], ok[GROUP_FULL]};
    for (int m = 0; m < JD_MODE_COUNT; m++) {
        int shown = m;
        while (!have[shown]) shown = shown == JD_MODE_FULL ? JD_MODE_DUAL : shown - 1;
        r->shown[m] = (jd_mode)shown;
        if (shown != m) say(r, "%s frames are drawn as %s", jd_mode_name((jd_mode)m), jd_mode_name((jd_mode)shown));
    }
    return JD_OK;
}

static jd_result build_projection_quads(jd_renderer *r, jd_arena *a, jd_error *err);

/* The boards whose tier draws less than jade's full quality (the
 * frame-cost model, docs/frame-cost.md): Mali-400/450 and VideoCore IV, by
 * renderer string or profile. NULL for any other GPU. */
static const char *tier_board(const jd_gl_caps *c)
{
    if (c->utgard || !strcmp(c->profile, "mali400")) return "Mali-400/450";
    if (!strcmp(c->profile, "vc4") || strstr(c->renderer, "VC4") || strstr(c->renderer, "VideoCore")) return "VideoCore IV";
    return NULL;
}

/* The share of the picture's size a device's tier draws at (render_scale
 * 0): on those boards full's main pass at 1920x1080 alone takes 27 ms
 * (Mali-400 MP2) and a close-up's 24 ms (VideoCore IV), so pictures over
 * 960x540 pixels are drawn at that many and enlarged. */
static float tier_scale(const jd_renderer *r, int w, int h, const char **why)
{
    *why = tier_board(r->d.caps);
    double budget = 960.0 * 540.0;
    if (!*why || (double)w * h <= budget * 1.05) return 1.0f;
    return (float)sqrt(budget / ((double)w * h));
}

void jd_renderer_desc_defaults(jd_renderer_desc *d)
{
    if (d->width <= 0) d->width = 512;
    if (d->height <= 0) d->height = 512;
    if (d->max_width < d->width) d->max_width = d->width;
    if (d->max_height < d->height) d->max_height = d->height;
    if (!d->cube_size) d->cube_size = 64;
    if (!d->light_map_size) d->light_map_size = 256;
    if (!d->proxy_cells) d->proxy_cells = 40;
    if (!d->capture_cells) d->capture_cells = 24;
    if (!d->spread_divisor) d->spread_divisor = 8;
    if (!d->diffusion_size) d->diffusion_size = d->light_map_size / 4;
}

static jd_result create(const jd_renderer_desc *desc, jd_arena *a, jd_renderer **out, jd_error *err);

jd_result jd_renderer_create(const jd_renderer_desc *desc, jd_arena *a, jd_renderer **out, jd_error *err)
{
    /* A failed create gives the arena back as it found it. */
    size_t bottom = jd_arena_mark(a), top = jd_arena_top_mark(a);
    jd_result r = create(desc, a, out, err);
    if (r) {
        jd_arena_reset(a, bottom);
        jd_arena_top_reset(a, top);
    }
    return r;
}

static jd_result create(const jd_renderer_desc *desc, jd_arena *a, jd_renderer **out, jd_error *err)
{
    if (!desc->mesh || !desc->caps) return jd_fail(err, JD_ERR_ARG, "renderer needs a mesh and the GL caps");
    jd_renderer *r = jd_arena_alloc(a, sizeof *r, 16, "renderer", err);
    if (!r) return JD_ERR_BUDGET;
    r->d = *desc;
    jd_renderer_desc *d = &r->d;
    jd_renderer_desc_defaults(d);
    if (d->rotation != 0 && d->rotation != 90 && d->rotation != 180 && d->rotation != 270)
        return jd_fail(err, JD_ERR_ARG, "rotation %d must be 0, 90, 180 or 270", d->rotation);
    /* The SH projection sums a block of capture texels per pixel; 8x8 is
     * more than the register files of VideoCore IV (vc4 cannot allocate it)
     * and Mali-400 (lima spills 33 values) hold, so those take 2x2 blocks
     * and one more reduction pass (tools/device-shaders.sh measures it). */
    r->sh_block = d->caps->small_register_file ? SH_BLOCK_SMALL : SH_BLOCK;
    if (d->cube_size < 8 || d->cube_size > 256 || d->cube_size % SH_BLOCK)
        return jd_fail(err, JD_ERR_ARG, "cube size %d must be a multiple of %d from 8 to 256", d->cube_size, SH_BLOCK);
    /* More than 8x8 blocks per face: a first reduction down to 8x8. */
    int blocks = d->cube_size / r->sh_block;
    r->sh_mid = blocks > 8 && blocks % 8 == 0 ? blocks / 8 : 1;
    if (d->light_map_size < 16 || d->light_map_size > 2048)
        return jd_fail(err, JD_ERR_ARG, "light map size %d must be 16..2048", d->light_map_size);
    if (d->diffusion_size < 16 || d->diffusion_size > d->light_map_size)
        return jd_fail(err, JD_ERR_ARG, "diffusion size %d must be 16..%d (the light map size)", d->diffusion_size,
                       d->light_map_size);
    if (d->diffusion_size & (d->diffusion_size - 1))
        return jd_fail(err, JD_ERR_ARG, "diffusion size %d must be a power of two", d->diffusion_size);
    if (d->spread_divisor < 1 || d->spread_divisor > 16)
        return jd_fail(err, JD_ERR_ARG, "spread divisor %d must be 1..16", d->spread_divisor);

    int device_highp = d->caps->frag_highp_precision >= 23;
    if (d->precision == JD_PRECISION_HIGHP && !device_highp)
        return jd_fail(err, JD_ERR_UNSUPPORTED, "highp packing asked for, but this GPU has no fragment highp");
    r->highp = d->precision == JD_PRECISION_AUTO ? device_highp : d->precision == JD_PRECISION_HIGHP;
    /* Two vertex texture units (depth map and tail table) move A0 to the
     * vertex stage; none (Mali-400) keeps it per fragment. */
    r->vertex_thickness = !d->fragment_thickness && d->caps->max_vertex_texture_units >= 2;
    /* The light map and the level textures. */
    r->vertex_diffusion = !d->fragment_thickness && d->caps->max_vertex_texture_units >= 1 + DIFF_TEXTURES;

    if (d->antialias < JD_AA_AUTO || d->antialias > JD_AA_POST)
        return jd_fail(err, JD_ERR_ARG, "anti-aliasing %d must be auto, off or post", (int)d->antialias);
    GLint samples = 0;
    glBindFramebuffer(GL_FRAMEBUFFER, d->target_fbo);
    glGetIntegerv(GL_SAMPLES, &samples);
    r->target_samples = samples;
    r->post_aa = d->antialias == JD_AA_POST || (d->antialias == JD_AA_AUTO && samples <= 1);
    if (d->render_scale != 0.0f && !(d->render_scale >= 0.25f && d->render_scale <= 1.0f))
        return jd_fail(err, JD_ERR_ARG, "render scale %g must be 0 (the device's tier) or 0.25..1", (double)d->render_scale);
    const char *why;
    r->may_scale = (d->render_scale > 0.0f && d->render_scale < 1.0f) ||
                   (d->render_scale == 0.0f && tier_scale(r, d->max_width, d->max_height, &why) < 1.0f);

    int chunked = d->mesh->index_size == 4 && !d->caps->ext_element_index_uint;
    jd_result res = jd_mesh_build_proxy(d->mesh, d->proxy_cells, a, &r->proxy, err);
    if (res) return res;
    /* The 64x64 capture needs far fewer triangles than the light map. */
    if ((res = jd_mesh_build_proxy(d->mesh, d->capture_cells, a, &r->capture_proxy, err))) return res;
    r->tail_px = jd_arena_alloc(a, TAIL_SIZE * 4, 16, "dipole tail table", err);
    if (!r->tail_px) return JD_ERR_BUDGET;

    const jd_mesh *m = d->mesh;
    jd_vec3 c, ext = jd_v3_sub(m->bmax, m->bmin);
    float radius;
    jd_mesh_placement(m, &c, &radius);
    r->place_c = c;
    r->place_inv_r = 1.0f / radius;
    r->box_half = 0.5f * fmaxf(ext.x, fmaxf(ext.y, ext.z)) / radius * 1.01f;
    /* Vertex clustering moves a vertex by at most a cell's diagonal; the
     * surface between, by about half of that. */
    r->proxy_error = 0.87f * fmaxf(ext.x, fmaxf(ext.y, ext.z)) / radius / (float)d->proxy_cells;
    r->fit_key[0] = -1.0f;
    while (glGetError() != GL_NO_ERROR) {}
    if ((chunked ? (res = upload_mesh_chunked(r, m, c, 1.0f / radius, a, err))
                 : (res = upload_mesh(m, c, 1.0f / radius, &r->mesh_vbo, &r->mesh_ibo, a, err))) ||
        (res = upload_mesh(&r->proxy, c, 1.0f / radius, &r->proxy_vbo, &r->proxy_ibo, a, err)) ||
        (res = upload_mesh(&r->capture_proxy, c, 1.0f / radius, &r->cap_vbo, &r->cap_ibo, a, err)))
        goto fail;
    r->tail_tex = new_texture(TAIL_SIZE, 1, GL_LINEAR);
    r->target_bytes += TAIL_SIZE * 4;
    r->tail_key[0] = -1.0f; /* no table yet */
    r->mesh_index_type = m->index_size == 2 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT;
    static const float quad[] = {-1, -1, 1, -1, -1, 1, 1, 1};
    glGenBuffers(1, &r->quad_vbo);
    glBindBuffer(GL_ARRAY_BUFFER, r->quad_vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof quad, quad, GL_STATIC_DRAW);

    if (d->get_proc && d->caps->ext_disjoint_timer_query) {
        timer_query *tq = &r->tq;
        tq->gen = (PFNGLGENQUERIESEXTPROC)d->get_proc("glGenQueriesEXT");
        tq->del = (PFNGLDELETEQUERIESEXTPROC)d->get_proc("glDeleteQueriesEXT");
        tq->begin = (PFNGLBEGINQUERYEXTPROC)d->get_proc("glBeginQueryEXT");
        tq->end = (PFNGLENDQUERYEXTPROC)d->get_proc("glEndQueryEXT");
        tq->result64 = (PFNGLGETQUERYOBJECTUI64VEXTPROC)d->get_proc("glGetQueryObjectui64vEXT");
        tq->ok = tq->gen && tq->del && tq->begin && tq->end && tq->result64;
        if (tq->ok) tq->gen(JD_PASS_COUNT, tq->q);
    }
    if ((res = build_programs(r, err))) goto fail;

    int n = d->cube_size, nb = n / r->sh_block;
    int sw = (d->max_width + d->spread_divisor - 1) / d->spread_divisor;
    int shh = (d->max_height + d->spread_divisor - 1) / d->spread_divisor;
    if ((res = make_target(r, &r->light, d->light_map_size, d->light_map_size, 1, 0, "light depth", err)) ||
        (res = make_target(r, &r->atlas, 3 * n, 2 * n, 1, 0, "cube capture", err)) ||
        (res = make_target(r, &r->sh1, 6 * nb, 27 * nb, 0, 0, "SH projection", err)) ||
        (r->sh_mid > 1 &&
         (res = make_target(r, &r->sh_mid_t, 6 * nb / r->sh_mid, 27 * nb / r->sh_mid, 0, 0, "SH partial sums", err))) ||
        (res = make_target(r, &r->sh2, 6, 27, 0, 0, "SH reduction", err)) ||
        (res = make_target(r, &r->sh3, 1, 27, 0, 0, "SH result", err)) ||
        (res = make_cube_target(r, r->irr, IRR_SIZE, "irradiance map", err)) ||
        (res = make_target(r, &r->spread0, sw, shh, 1, 1, "spread A0", err)) ||
        (res = make_target(r, &r->spread_tmp, sw, shh, 0, 1, "spread blur", err)) ||
        (res = make_target(r, &r->spread1, sw, shh, 0, 1, "spread A1", err)) ||
        (res = make_target(r, &r->spread2, sw, shh, 0, 1, "spread A2", err)) ||
        (res = make_target(r, &r->diff_tmp, d->diffusion_size, d->light_map_size, 0, 0, "diffusion blur", err)))
        goto fail;
    if (!r->vertex_diffusion &&
        (res = make_target(r, &r->wide, (d->max_width + 1) / 2, (d->max_height + 1) / 2, 1, 1, "full's levels", err)))
        goto fail;
    if ((r->post_aa || r->may_scale) &&
        (res = make_target(r, &r->scene, d->max_width, d->max_height, 1, 1, "frame before anti-aliasing", err)))
        goto fail;
    for (int i = 0; i < DIFF_TEXTURES; i++)
        if ((res = make_target(r, &r->diff_lv[i], d->diffusion_size >> (i / 2), d->diffusion_size >> (i / 2), 0, 1,
                               "diffusion level", err)))
            goto fail;
    if ((res = build_projection_quads(r, a, err))) goto fail;
    glBindFramebuffer(GL_FRAMEBUFFER, d->target_fbo);
    *out = r;
    return jd_renderer_resize(r, d->width, d->height, err);
fail:
    jd_renderer_destroy(r);
    return res;
}

void jd_renderer_destroy(jd_renderer *r)
{
    if (!r) return;
    target *ts[] = {&r->light,   &r->atlas,   &r->sh1,      &r->sh_mid_t, &r->sh2,   &r->sh3, &r->spread0,
                    &r->spread_tmp, &r->spread1, &r->spread2, &r->diff_tmp, &r->scene, &r->wide};
    for (size_t i = 0; i < sizeof ts / sizeof ts[0]; i++) free_target(ts[i]);
    for (int i = 0; i < DIFF_TEXTURES; i++) free_target(&r->diff_lv[i]);
    for (int i = 0; i < 6; i++) free_target(&r->irr[i]); /* the cube's texture goes with the first */
    GLuint bufs[] = {r->mesh_vbo, r->mesh_ibo, r->proxy_vbo, r->proxy_ibo, r->cap_vbo, r->cap_ibo, r->quad_vbo,
                     r->project_vbo};
    glDeleteBuffers(8, bufs);
    if (r->tail_tex) glDeleteTextures(1, &r->tail_tex);
    if (r->tq.ok) r->tq.del(JD_PASS_COUNT, r->tq.q);
    for (int m = 0; m < JD_MODE_COUNT; m++) glDeleteProgram(r->shade[m].id);
    glDeleteProgram(r->wide_prog.id);
    GLuint progs[] = {r->count_prog, r->up_prog, r->a0.id, r->depth_prog, r->capture_prog, r->project_prog, r->reduce_mid_prog, r->reduce_faces_prog,
                      r->reduce_final_prog, r->irr_prog, r->blur_prog, r->combine_prog, r->diff_first.id, r->diff_next.id, r->aa_prog};
    for (size_t i = 0; i < sizeof progs / sizeof progs[0]; i++) glDeleteProgram(progs[i]);
    memset(r, 0, sizeof *r);
}

void jd_renderer_finish(jd_renderer *r) { (void)r; glFinish(); }
void jd_renderer_set_timing(jd_renderer *r, int on) { r->timing = on; }

jd_result jd_renderer_resize(jd_renderer *r, int width, int height, jd_error *err)
{
    if (width < 1 || height < 1 || width > r->d.max_width || height > r->d.max_height)
        return jd_fail(err, JD_ERR_ARG, "size %dx%d outside 1x1..%dx%d set at start-up", width, height, r->d.max_width,
                       r->d.max_height);
    r->d.width = width;
    r->d.height = height;
    /* The picture's passes at render_scale of the size, or the tier's. */
    const char *why = NULL;
    float scale = r->d.render_scale > 0.0f ? r->d.render_scale : tier_scale(r, width, height, &why);
    r->iw = width;
    r->ih = height;
    r->tier[0] = 0;
    if (scale < 1.0f && r->may_scale) {
        r->iw = (int)ceilf((float)width * scale);
        r->ih = (int)ceilf((float)height * scale);
        snprintf(r->tier, sizeof r->tier, "%dx%d drawn at %dx%d and enlarged (%s%s%g)", width, height, r->iw, r->ih,
                 why ? why : "", why ? "'s tier: render scale " : "render scale ", (double)scale);
    }
    width = r->iw;
    height = r->ih;
    r->scene.w = width;
    r->scene.h = height;
    /* full's levels' sum: half the picture's resolution until a frame
     * says how large a level texel is on screen (jd_renderer_frame). */
    r->wide_div = 2;
    r->wide.w = (width + 1) / 2;
    r->wide.h = (height + 1) / 2;
    int div = r->d.spread_divisor;
    target *spread[] = {&r->spread0, &r->spread_tmp, &r->spread1, &r->spread2};
    for (int i = 0; i < 4; i++) {
        spread[i]->w = (width + div - 1) / div;
        spread[i]->h = (height + div - 1) / div;
    }
    return JD_OK;
}
void jd_renderer_get_info(const jd_renderer *r, jd_renderer_info *info)
{
    for (int m = 0; m < JD_MODE_COUNT; m++) info->shown_as[m] = r->shown[m];
    info->fallback = r->fallback[0] ? r->fallback : NULL;
    info->target_bytes = r->target_bytes;
    info->highp = r->highp;
    info->vertex_thickness = r->vertex_thickness;
    info->gpu_timer = r->tq.ok;
    info->target_samples = r->target_samples;
    info->post_antialias = r->post_aa;
    info->render_width = r->iw;
    info->render_height = r->ih;
    info->tier = r->tier[0] ? r->tier : NULL;
    info->proxy = &r->proxy;
}

/* ---- per frame ---------------------------------------------------------- */

/* Everything a frame derives from the scene on the CPU, once. */
typedef struct frame_params {
    jd_mat4 mvp, light_mvp;
    jd_vec3 eye, light_dir;
    float light_color[3], albedo[3];
    float a0_scale[3], f0;
    float shading[4];
    float range_mm;
    jd_dipole dipole;
    float w0[3], w1[3], w2[3];
    float inv_eta, inset;
    float mm_per_world, blur_sigma_px;
    float px_per_world;   /* the picture's passes' pixels per world unit at the object's centre */
    float light_map[4], shadow_bias[2];
} frame_params;

static void frame_setup(const jd_renderer *r, const jd_scene *s, frame_params *f)
{
    /* A panel mounted at 90 or 270 degrees shows the picture sideways: the
     * camera sees the rotated aspect and clip space turns to meet the panel. */
    int quarter = r->d.rotation == 90 || r->d.rotation == 270;
    float aspect = quarter ? (float)r->d.height / (float)r->d.width : (float)r->d.width / (float)r->d.height;
    jd_scene_view sv;
    jd_scene_view_of(s, r->d.mesh, aspect, &sv);
    f->mm_per_world = sv.mm_per_world;
    float dist = sv.cam_distance, fov = sv.fov_deg;
    f->eye = sv.eye;
    jd_mat4 view = jd_m4_look_at(f->eye, jd_v3(0, 0, 0), jd_v3(0, 1, 0));
    jd_mat4 proj = jd_m4_perspective(fov, aspect, fmaxf(dist - 1.2f, 0.05f), dist + 1.2f);
    if (r->d.rotation) {
        float a = (float)r->d.rotation * 3.14159265f / 180.0f, c = roundf(cosf(a)), sn = roundf(sinf(a));
        jd_mat4 rot = jd_m4_identity();
        rot.m[0] = c; rot.m[1] = sn; rot.m[4] = -sn; rot.m[5] = c;
        proj = jd_m4_mul(rot, proj);
    }
    f->mvp = jd_m4_mul(proj, view);

    f->light_dir = sv.light_dir;
    jd_mat4 lview = jd_m4_look_at(jd_v3_scale(f->light_dir, 2.0f), jd_v3(0, 0, 0), jd_v3(0, 1, 0));
    f->light_mvp = jd_m4_mul(jd_m4_ortho(-1, 1, -1, 1, 1, 3), lview);

    jd_scene_optics o;
    jd_scene_optics_of(s, &sv, &o);
    f->dipole = o.dipole;
    memcpy(f->albedo, o.albedo, sizeof f->albedo);
    memcpy(f->a0_scale, o.a0_scale, sizeof f->a0_scale);
    memcpy(f->w0, o.w0, sizeof f->w0);
    memcpy(f->w1, o.w1, sizeof f->w1);
    memcpy(f->w2, o.w2, sizeof f->w2);
    for (int c = 0; c < 3; c++) f->light_color[c] = s->light_intensity;
    double mean_ss = o.mean_sigma_s;
    f->range_mm = 2.0f * f->mm_per_world;
    f->f0 = sv.f0;
    f->shading[0] = s->ambient;
    f->shading[1] = s->specular;
    f->shading[2] = sv.shininess;
    f->shading[3] = sv.exposure;
    f->inv_eta = 1.0f / sv.eta;
    f->inset = 2.0f / (float)r->d.proxy_cells;
    /* The light's ortho box is 2 world units on each side, depth included:
     * light-depth units are world units / 2, a texel is 1/size of them. The
     * shadow test moves the point towards the light by the proxy's error and
     * by the depth one and a half texels span at the surface's slope. */
    float lsz = (float)r->d.light_map_size;
    f->light_map[0] = lsz;
    f->light_map[1] = 1.0f / lsz;
    f->light_map[2] = sv.f0;
    f->light_map[3] = 0.5f * r->proxy_error;
    f->shadow_bias[0] = 1.5f / lsz;
    f->shadow_bias[1] = 0.5f * r->proxy_error;

    /* The paper's spread width, sigma = 2 sigma_s, read as millimetres and
     * turned into pixels of the low-resolution buffer at the object's depth. */
    double world_per_px = 2.0 * dist * tan(fov * M_PI / 360.0) / (quarter ? r->iw : r->ih) *
                          r->d.spread_divisor;
    f->px_per_world = (float)(r->d.spread_divisor / world_per_px);
    f->blur_sigma_px = (float)(2.0 * mean_ss / (world_per_px * f->mm_per_world));
    if (f->blur_sigma_px < 0.25f) f->blur_sigma_px = 0.25f;
    if (f->blur_sigma_px > 24.0f) f->blur_sigma_px = 24.0f;
}

/* M(t) over t in [0, range]: the bracket of the dipole tail (without
 * alpha'/2, which is in the A0 scale), halved into [0,1] and stored as its
 * square root so thin-light values keep precision in 8 bits. Rebuilt only
 * when the material or the scale changes. */
static void update_tail(jd_renderer *r, const jd_scene *s, const frame_params *f)
{
    float key[9] = {s->sigma_s[0], s->sigma_s[1], s->sigma_s[2], s->sigma_a[0], s->sigma_a[1],
                    s->sigma_a[2], s->eta, s->density, f->range_mm};
    if (!memcmp(key, r->tail_key, sizeof key)) return;
    memcpy(r->tail_key, key, sizeof key);
    const jd_dipole *d = &f->dipole;
    for (int i = 0; i < TAIL_SIZE; i++) {
        double t = (double)i / (TAIL_SIZE - 1) * f->range_mm;
        for (int c = 0; c < 3; c++) {
            double m = d->alpha[c] > 0 ? jd_dipole_tail(d, c, t) / (0.5 * d->alpha[c]) : 0.0;
            double v = sqrt(fmin(fmax(m * 0.5, 0.0), 1.0));
            r->tail_px[4 * i + c] = (uint8_t)(v * 255.0 + 0.5);
        }
        r->tail_px[4 * i + 3] = 255;
    }
    glBindTexture(GL_TEXTURE_2D, r->tail_tex);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, TAIL_SIZE, 1, GL_RGBA, GL_UNSIGNED_BYTE, r->tail_px);
}

/* The full mode's sum of Gaussians: the finest below a level texel (applied
 * at the shaded point), then one per light-space level. Refitted only when
 * the material or the scale changes. */
static void update_fit(jd_renderer *r, const jd_scene *s, const frame_params *f)
{
    float key[9] = {s->sigma_s[0], s->sigma_s[1], s->sigma_s[2], s->sigma_a[0], s->sigma_a[1],
                    s->sigma_a[2], s->eta, s->density, f->mm_per_world};
    if (!memcmp(key, r->fit_key, sizeof key)) return;
    memcpy(r->fit_key, key, sizeof key);
    float texel_mm = 2.0f * f->mm_per_world / (float)r->d.diffusion_size;
    float sigma[DIFF_LOCAL + DIFF_LEVELS] = {texel_mm / 16.0f, texel_mm / 5.0f, texel_mm / 2.0f};
    for (int k = 0; k < DIFF_LEVELS; k++) sigma[DIFF_LOCAL + k] = texel_mm * (float)(1 << k);
    jd_diffusion_fit_profile(&f->dipole, sigma, DIFF_LOCAL + DIFF_LEVELS, &r->fit);
    r->diff_levels = 0;
    for (int k = 0; k < DIFF_LEVELS; k++)
        for (int c = 0; c < 3; c++)
            if (r->fit.weight[DIFF_LOCAL + k][c] > 1e-5f) r->diff_levels = k + 1;
}

static void bind_mesh(GLuint vbo, GLuint ibo);

/* ---- the frame-cost count (jd_renderer_count) ----------------------------
 * A counting frame runs the frame's passes as they are, but every mesh draw
 * is made by the counting program with the same positions and transform
 * (no jade shader discards, so a pass shades exactly the fragments its
 * geometry passes the depth test with), adding 1/255 per fragment into
 * the pass's target; the target is read back when the pass ends. Quads
 * cover their viewport (or scissor box) once and are counted by area. */

static jd_pass_count *counted(jd_renderer *r)
{
    jd_frame_count *c = r->count;
    return c && c->num_passes > 0 ? &c->pass[c->num_passes - 1] : NULL;
}

/* The open pass's program: the current one, by its label. A second program
 * into the same target opens a record of its own. */
static jd_pass_count *counted_draw(jd_renderer *r)
{
    jd_pass_count *p = counted(r);
    if (!p) return NULL;
    GLint id = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &id);
    const char *label = "?";
    for (int i = 0; i < r->num_labels; i++)
        if ((GLint)r->labels[i].id == id) label = r->labels[i].label;
    if (p->program[0] && strcmp(p->program, label)) {
        jd_frame_count *c = r->count;
        if (c->num_passes == JD_COUNT_PASSES) { c->overflow = 1; return NULL; }
        jd_pass_count *q = &c->pass[c->num_passes++];
        *q = *p;
        q->fragments = q->vertices = q->triangles = q->bytes_written = q->bytes_read = 0;
        q->trips = 1;
        p = q;
    }
    snprintf(p->program, sizeof p->program, "%s", label);
    return p;
}

/* Quads: a viewport's (or scissor box's) area, once. */
static void counted_quad(jd_renderer *r, double fragments, double vertices, double triangles)
{
    jd_pass_count *p = counted_draw(r);
    if (!p) return;
    p->fragments += fragments;
    p->vertices += vertices;
    p->triangles += triangles;
}

/* Textures a pass samples: their used regions, each texel once. */
static void counted_read(jd_renderer *r, const target *t, double layers)
{
    jd_pass_count *p = counted(r);
    if (p) p->bytes_read += (double)t->w * t->h * 4.0 * layers;
}

/* The open pass's loops run `trips` times (its program's dynamic loops). */
static void counted_trips(jd_renderer *r, double trips)
{
    jd_pass_count *p = counted(r);
    if (p) p->trips = trips;
}

/* Ends the open pass: fragments of mesh draws read back from its target,
 * which is still bound (the counting adds to red, one per fragment). Mesh
 * passes draw with one program each. */
static void counted_close(jd_renderer *r)
{
    jd_pass_count *p = counted(r);
    if (!p || !r->count_read) return;
    r->count_read = 0;
    uint8_t rows[32768];
    int w = p->width, per = (int)(sizeof rows / 4) / (w > 0 ? w : 1);
    if (per < 1) return;
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    double sum = 0;
    for (int y = 0; y < p->height; y += per) {
        int n = p->height - y < per ? p->height - y : per;
        glReadPixels(0, y, w, n, GL_RGBA, GL_UNSIGNED_BYTE, rows);
        for (int i = 0; i < w * n; i++) sum += rows[4 * i];
    }
    p->fragments += sum;
}

/* A pass begins: `what` it is, w x h of its target. */
static void counted_open(jd_renderer *r, const char *what, int w, int h)
{
    jd_frame_count *c = r->count;
    if (!c) return;
    counted_close(r);
    c->target_switches++;
    if (c->num_passes == JD_COUNT_PASSES) { c->overflow = 1; return; }
    jd_pass_count *p = &c->pass[c->num_passes++];
    memset(p, 0, sizeof *p);
    snprintf(p->pass, sizeof p->pass, "%s", what);
    p->width = w;
    p->height = h;
    p->trips = 1;
    p->bytes_written = (double)w * h * 4.0;
    r->count_cleared = 0;
}

/* glDrawElements of one of the meshes (0 the whole mesh, 1 the proxy, 2
 * the capture proxy) under `mvp`: in a counting frame, the counting draw,
 * shading `vertices` (< 0: the mesh's whole draw). */
static void draw_elements(jd_renderer *r, int mesh, const jd_mat4 *mvp, GLsizei count, GLenum type, const void *at,
                          double vertices)
{
    jd_pass_count *p = r->count ? counted_draw(r) : NULL;
    if (!p) {
        glDrawElements(GL_TRIANGLES, count, type, at);
        return;
    }
    GLint prog = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &prog);
    if (!r->count_cleared) { /* the pass's own clear colour would be counted */
        glClearColor(0, 0, 0, 0);
        glClear(GL_COLOR_BUFFER_BIT);
        r->count_cleared = 1;
    }
    glUseProgram(r->count_prog);
    glUniformMatrix4fv(r->count_mvp, 1, GL_FALSE, mvp->m);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glDrawElements(GL_TRIANGLES, count, type, at);
    glDisable(GL_BLEND);
    glUseProgram((GLuint)prog);
    p->vertices += vertices >= 0 ? vertices : r->count_vertices[mesh];
    p->triangles += count / 3;
    r->count_read = 1;
}

/* The whole mesh: one draw, or one per 16-bit chunk. */
static void draw_mesh(jd_renderer *r, const jd_mat4 *mvp)
{
    bind_mesh(r->mesh_vbo, r->mesh_ibo);
    if (!r->num_chunks) {
        draw_elements(r, 0, mvp, (GLsizei)r->d.mesh->num_indices, r->mesh_index_type, 0, -1);
        return;
    }
    for (int i = 0; i < r->num_chunks; i++) {
        const struct mesh_chunk *ch = &r->chunks[i];
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 24, (const void *)ch->vertex_offset);
        glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 24, (const void *)(ch->vertex_offset + 12));
        /* A chunk's own vertices under the range model; under a FIFO, the
         * whole mesh's misses shared out by triangles. */
        double v = r->count_vertices[0] < 0 ? (double)ch->vertices
                                            : r->count_vertices[0] * ch->count / (double)r->d.mesh->num_indices;
        draw_elements(r, 0, mvp, (GLsizei)ch->count, GL_UNSIGNED_SHORT, (const void *)ch->index_offset, v);
    }
}

static void bind_mesh(GLuint vbo, GLuint ibo)
{
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 24, (const void *)0);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 24, (const void *)12);
}

static void bind_quad(const jd_renderer *r)
{
    glBindBuffer(GL_ARRAY_BUFFER, r->quad_vbo);
    glDisableVertexAttribArray(1);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 8, (const void *)0);
}

/* The scissor keeps clears to the used corner of a power-of-two target. */
/* Every render-target switch of a frame passes here, and is counted. */
static void count_target(jd_renderer *r, const char *what, int w, int h)
{
    counted_open(r, what, w, h);
    r->n_switches++;
    r->n_fragments += (double)w * h;
    r->n_bytes += (double)w * h * 4.0;
}

static void use_target(jd_renderer *r, const target *t, const char *what)
{
    count_target(r, what, t->w, t->h);
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glViewport(0, 0, t->w, t->h);
    glScissor(0, 0, t->w, t->h);
}

static void pass_light_depth(jd_renderer *r, const frame_params *f)
{
    use_target(r, &r->light, "light-depth");
    glClearColor(1, 0, 0, 0); /* packed 1.0: nothing in front; no light */
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    /* Only surfaces facing the light can be the nearest to it. */
    if (r->d.no_cull) glDisable(GL_CULL_FACE); else glEnable(GL_CULL_FACE);
    glUseProgram(r->depth_prog);
    glUniformMatrix4fv(r->depth_mvp, 1, GL_FALSE, f->light_mvp.m);
    glUniform3f(r->depth_light_dir, f->light_dir.x, f->light_dir.y, f->light_dir.z);
    glUniform1f(r->depth_f0, f->f0);
    bind_mesh(r->proxy_vbo, r->proxy_ibo);
    draw_elements(r, 1, &f->light_mvp, (GLsizei)r->proxy.num_indices, GL_UNSIGNED_SHORT, 0, -1);
}

static void pass_capture(jd_renderer *r, const frame_params *f)
{
    int n = r->d.cube_size;
    float h = r->box_half;
    use_target(r, &r->atlas, "capture");
    counted_read(r, &r->light, 1);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    if (r->d.no_cull) glDisable(GL_CULL_FACE); else glEnable(GL_CULL_FACE);
    glUseProgram(r->capture_prog);
    glUniformMatrix4fv(r->cap_light_mvp, 1, GL_FALSE, f->light_mvp.m);
    glUniform3f(r->cap_light_dir, f->light_dir.x, f->light_dir.y, f->light_dir.z);
    glUniform3fv(r->cap_light_color, 1, f->light_color);
    glUniform1f(r->cap_bias, 1.5f / (float)r->d.proxy_cells);
    glUniform1i(r->cap_depth, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, r->light.tex);
    bind_mesh(r->cap_vbo, r->cap_ibo);
    jd_mat4 ortho = jd_m4_ortho(-h, h, -h, h, 3.0f - h - 0.01f, 3.0f + h + 0.01f);
    for (int face = 0; face < 6; face++) {
        float a[3], u[3], v[3];
        jd_cube_face_frame(face, a, u, v);
        jd_mat4 view = jd_m4_look_at(jd_v3(3 * a[0], 3 * a[1], 3 * a[2]), jd_v3(0, 0, 0), jd_v3(v[0], v[1], v[2]));
        jd_mat4 mvp = jd_m4_mul(ortho, view);
        glViewport((face % 3) * n, (face / 3) * n, n, n);
        glUniformMatrix4fv(r->cap_mvp, 1, GL_FALSE, mvp.m);
        draw_elements(r, 2, &mvp, (GLsizei)r->capture_proxy.num_indices, GL_UNSIGNED_SHORT, 0, -1);
    }
}

/* A quad over all of t, reading `src` (NULL: nothing counted). */
static void draw_quad_into(jd_renderer *r, const target *t, const char *what, const target *src)
{
    use_target(r, t, what);
    if (src) counted_read(r, src, 1);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    counted_quad(r, (double)t->w * t->h, 4, 2);
}

/* A polynomial in (1, fx, fy, fx^2, fy^2, fx fy). */
typedef struct poly6 { float c[6]; } poly6;

static poly6 poly_linear(float c0, float c1, float c2)
{
    poly6 p = {{c0, c1, c2, 0, 0, 0}};
    return p;
}

static poly6 poly_mul(poly6 a, poly6 b) /* both linear */
{
    poly6 p = {{a.c[0] * b.c[0], a.c[0] * b.c[1] + a.c[1] * b.c[0], a.c[0] * b.c[2] + a.c[2] * b.c[0],
                a.c[1] * b.c[1], a.c[2] * b.c[2], a.c[1] * b.c[2] + a.c[2] * b.c[1]}};
    return p;
}

static poly6 poly_axpy(float s, poly6 a, float t, poly6 b)
{
    poly6 p;
    for (int i = 0; i < 6; i++) p.c[i] = s * a.c[i] + t * b.c[i];
    return p;
}

/* The real SH basis Y_k(w) on cube face `face`, w = (a + fx u + fy v) /
 * sqrt(q): a polynomial over q^(d/2). Faces as the capture lays them out. */
static poly6 sh_on_face(int face, int k, int *d)
{
    static const float frames[6][3][3] = {
        {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}}, {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},
        {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}, {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}}};
    const float(*fr)[3] = frames[face];
    poly6 x = poly_linear(fr[0][0], fr[1][0], fr[2][0]), y = poly_linear(fr[0][1], fr[1][1], fr[2][1]),
          z = poly_linear(fr[0][2], fr[1][2], fr[2][2]);
    poly6 q = {{1, 0, 0, 1, 1, 0}};
    *d = k == 0 ? 0 : k < 4 ? 1 : 2;
    switch (k) {
    case 0: return poly_linear(0.282095f, 0, 0);
    case 1: return poly_axpy(0.488603f, y, 0, y);
    case 2: return poly_axpy(0.488603f, z, 0, z);
    case 3: return poly_axpy(0.488603f, x, 0, x);
    case 4: return poly_axpy(1.092548f, poly_mul(x, y), 0, q);
    case 5: return poly_axpy(1.092548f, poly_mul(y, z), 0, q);
    case 6: return poly_axpy(0.315392f * 3.0f, poly_mul(z, z), -0.315392f, q);
    case 7: return poly_axpy(1.092548f, poly_mul(x, z), 0, q);
    default: return poly_axpy(0.546274f, poly_mul(x, x), -0.546274f, poly_mul(y, y));
    }
}

/* The projection target holds, per (face, coefficient row), an NB x NB
 * rectangle of blocks; each rectangle is two triangles carrying its
 * constants. Built once; the arena's top is scratch for the upload. */
static jd_result build_projection_quads(jd_renderer *r, jd_arena *a, jd_error *err)
{
    int n = r->d.cube_size, nb = n / r->sh_block, B = r->sh_block;
    float W = (float)(6 * nb), H = (float)(27 * nb);
    size_t top = jd_arena_top_mark(a);
    float *v = jd_arena_alloc_top(a, sizeof(float) * PROJECT_FLOATS * 6 * 6 * 27, 16, "SH projection rectangles", err);
    if (!v) return JD_ERR_BUDGET;
    float *o = v;
    for (int face = 0; face < 6; face++)
        for (int row = 0; row < 27; row++) {
            int k = row / 3, ch = row % 3, d;
            poly6 p = sh_on_face(face, k, &d);
            /* dw's 4/N^2 * 6N^2/(4 pi), the block mean, the packing's range */
            for (int i = 0; i < 6; i++) p.c[i] *= 6.0f / 3.14159265f / (float)(B * B) / 1.5f;
            float fx = (float)(face % 3 * n), fy = (float)(face / 3 * n);
            float x0 = (float)(face * nb), y0 = (float)(row * nb);
            static const int corners[6][2] = {{0, 0}, {1, 0}, {0, 1}, {0, 1}, {1, 0}, {1, 1}};
            for (int c = 0; c < 6; c++) {
                int cx = corners[c][0], cy = corners[c][1];
                float attr[PROJECT_FLOATS] = {
                    (x0 + (float)(cx * nb)) / W * 2.0f - 1.0f, (y0 + (float)(cy * nb)) / H * 2.0f - 1.0f,
                    p.c[0], p.c[1], p.c[2], p.c[3], p.c[4], p.c[5], 0.5f * (float)(3 + d), 0.0f,
                    ch == 0 ? 1.0f : 0.0f, ch == 1 ? 1.0f : 0.0f, ch == 2 ? 1.0f : 0.0f,
                    /* the block's first sample, at pixel centres: corner + 0.5 - B/2 + n across */
                    fx + 0.5f - 0.5f * (float)B + (float)(cx * n), fy + 0.5f - 0.5f * (float)B + (float)(cy * n), fx, fy};
                memcpy(o, attr, sizeof attr);
                o += PROJECT_FLOATS;
            }
        }
    glGenBuffers(1, &r->project_vbo);
    glBindBuffer(GL_ARRAY_BUFFER, r->project_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)((size_t)(o - v) * sizeof(float)), v, GL_STATIC_DRAW);
    jd_arena_top_reset(a, top);
    return glGetError() == GL_NO_ERROR ? JD_OK : jd_fail(err, JD_ERR_GL, "SH projection upload failed");
}

static void draw_projection(jd_renderer *r)
{
    glBindBuffer(GL_ARRAY_BUFFER, r->project_vbo);
    static const int sizes[5] = {2, 4, 4, 3, 4};
    size_t at = 0;
    for (GLuint i = 0; i < 5; i++) {
        glEnableVertexAttribArray(i);
        glVertexAttribPointer(i, sizes[i], GL_FLOAT, GL_FALSE, PROJECT_FLOATS * sizeof(float),
                              (const void *)(at * sizeof(float)));
        at += (size_t)sizes[i];
    }
    use_target(r, &r->sh1, "sh-project");
    counted_read(r, &r->atlas, 1);
    glDrawArrays(GL_TRIANGLES, 0, 6 * 6 * 27);
    counted_quad(r, (double)r->sh1.w * r->sh1.h, 6 * 6 * 27, 2 * 6 * 27); /* the rectangles tile it */
    for (GLuint i = 2; i < 5; i++) glDisableVertexAttribArray(i);
    bind_quad(r);
}

static void pass_sh(jd_renderer *r)
{
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    bind_quad(r);
    glActiveTexture(GL_TEXTURE0);
    glUseProgram(r->project_prog);
    glUniform1i(r->proj_atlas, 0);
    glUniform2f(r->proj_texel, 1.0f / r->atlas.tw, 1.0f / r->atlas.th);
    glBindTexture(GL_TEXTURE_2D, r->atlas.tex);
    draw_projection(r);
    const target *src = &r->sh1;
    if (r->sh_mid > 1) {
        glUseProgram(r->reduce_mid_prog);
        glUniform1i(r->rm_src, 0);
        glUniform2f(r->rm_texel, 1.0f / r->sh1.tw, 1.0f / r->sh1.th);
        glBindTexture(GL_TEXTURE_2D, r->sh1.tex);
        draw_quad_into(r, &r->sh_mid_t, "sh-reduce-mid", &r->sh1);
        src = &r->sh_mid_t;
    }
    glUseProgram(r->reduce_faces_prog);
    glUniform1i(r->rf_src, 0);
    glUniform2f(r->rf_texel, 1.0f / src->tw, 1.0f / src->th);
    glBindTexture(GL_TEXTURE_2D, src->tex);
    draw_quad_into(r, &r->sh2, "sh-reduce-faces", src);
    glUseProgram(r->reduce_final_prog);
    glUniform1i(r->rl_src, 0);
    glUniform2f(r->rl_texel, 1.0f / r->sh2.tw, 1.0f / r->sh2.th);
    glBindTexture(GL_TEXTURE_2D, r->sh2.tex);
    draw_quad_into(r, &r->sh3, "sh-reduce", &r->sh2);
    /* The coefficients stay on the GPU: they become the irradiance cube map
     * the shading pass reads (a read-back here would make a tile-based GPU
     * finish the frame so far while the CPU waits). Six tiny faces cost a
     * tiler less than finding a direction's place in a 2D map would cost
     * every fragment of the main pass: there textureCube does it. */
    glUseProgram(r->irr_prog);
    glUniform1i(r->irr_src, 0);
    glUniform2f(r->irr_size, (float)IRR_SIZE, 2.0f / IRR_SIZE);
    glBindTexture(GL_TEXTURE_2D, r->sh3.tex);
    /* Each face's direction at (sc, tc) = axis + sc s + tc t, as GLES 2.0
     * maps directions to cube faces (its table 3.21). */
    static const float frames[6][9] = {
        {1, 0, 0, 0, 0, -1, 0, -1, 0}, {-1, 0, 0, 0, 0, 1, 0, -1, 0}, {0, 1, 0, 1, 0, 0, 0, 0, 1},
        {0, -1, 0, 1, 0, 0, 0, 0, -1}, {0, 0, 1, 1, 0, 0, 0, -1, 0},  {0, 0, -1, -1, 0, 0, 0, -1, 0},
    };
    for (int f = 0; f < 6; f++) {
        glUniformMatrix3fv(r->irr_face, 1, GL_FALSE, frames[f]);
        draw_quad_into(r, &r->irr[f], "irradiance", &r->sh3);
    }
}

static void set_shade_uniforms(const jd_renderer *r, const shade_prog *p, const frame_params *f, int w, int h)
{
    glUseProgram(p->id);
    glUniformMatrix4fv(p->mvp, 1, GL_FALSE, f->mvp.m);
    glUniform3f(p->eye, f->eye.x, f->eye.y, f->eye.z);
    glUniform3f(p->light_dir, f->light_dir.x, f->light_dir.y, f->light_dir.z);
    glUniform3fv(p->albedo, 1, f->albedo);
    glUniform3fv(p->light_color, 1, f->light_color);
    glUniform4fv(p->shading, 1, f->shading);
    glUniformMatrix4fv(p->light_mvp, 1, GL_FALSE, f->light_mvp.m);
    glUniform4fv(p->light_map, 1, f->light_map);
    glUniform2fv(p->shadow_bias, 1, f->shadow_bias);
    if (p->f0 >= 0) glUniform1f(p->f0, f->f0);
    if (p->depth >= 0) glUniform1i(p->depth, 0);
    if (p->depth_v >= 0) glUniform1i(p->depth_v, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, r->light.tex);
    if (p->wl >= 0 || p->lw >= 0) { /* full: the local weight, the levels (either may be compiled out) */
        float lw[DIFF_LEVELS][3], ls[6] = {0}, wl[3] = {0};
        const jd_diffusion_fit *fit = &r->fit;
        for (int c = 0; c < 3; c++)
            for (int k = 0; k < DIFF_LOCAL; k++) wl[c] += fit->weight[k][c];
        for (int k = 0; k < DIFF_LEVELS; k++) {
            for (int c = 0; c < 3; c++) lw[k][c] = k < r->diff_levels ? fit->weight[DIFF_LOCAL + k][c] : 0.0f;
            /* Light-depth units to the level's sigma * sqrt(2), in millimetres. */
            ls[k] = 2.0f * f->mm_per_world / (1.41421356f * fit->sigma_mm[DIFF_LOCAL + k]);
        }
        ls[5] = (float)r->d.diffusion_size; /* the spare slot: the first level's texels per side */
        glUniform3fv(p->lw, DIFF_LEVELS, &lw[0][0]);
        glUniform3fv(p->ls, 2, ls);
        glUniform3fv(p->wl, 1, wl);
        glUniform4fv(p->light_map_v, 1, f->light_map);
        glUniform3f(p->light_dir_v, f->light_dir.x, f->light_dir.y, f->light_dir.z);
        for (int i = 0; i < DIFF_TEXTURES; i++) {
            glUniform1i(p->lv[i] >= 0 ? p->lv[i] : p->lv_v[i], 1 + i);
            glActiveTexture(GL_TEXTURE1 + i);
            glBindTexture(GL_TEXTURE_2D, r->diff_lv[i].tex);
        }
        glActiveTexture(GL_TEXTURE0);
    }
    if (p->irr >= 0) {
        float hb = r->box_half;
        glUniform1i(p->irr, 2);
        glActiveTexture(GL_TEXTURE2);
        glBindTexture(GL_TEXTURE_CUBE_MAP, r->irr[0].tex);
        glUniform3f(p->box_min, -hb, -hb, -hb);
        glUniform3f(p->box_max, hb, hb, hb);
        glUniform1f(p->inv_eta, f->inv_eta);
        glUniform1f(p->inset, f->inset);
        glUniform3fv(p->a0_scale, 1, f->a0_scale);
        glUniform1i(p->tail >= 0 ? p->tail : p->tail_v, 3);
        glActiveTexture(GL_TEXTURE3);
        glBindTexture(GL_TEXTURE_2D, r->tail_tex);
        glActiveTexture(GL_TEXTURE0);
    }
    if (p->wide >= 0) {
        glUniform1i(p->wide, 6);
        glUniform2f(p->inv_viewport, (float)r->wide.w / r->wide.tw / (float)w, (float)r->wide.h / r->wide.th / (float)h);
        glActiveTexture(GL_TEXTURE6);
        glBindTexture(GL_TEXTURE_2D, r->wide.tex);
        glActiveTexture(GL_TEXTURE0);
    }
    if (p->spread >= 0) {
        glUniform1i(p->spread, 1);
        /* Screen position to the used corner of the spread texture. */
        glUniform2f(p->inv_viewport, (float)r->spread2.w / r->spread2.tw / (float)w,
                    (float)r->spread2.h / r->spread2.th / (float)h);
        glUniform3fv(p->w0, 1, f->w0);
        glActiveTexture(GL_TEXTURE1);
        glBindTexture(GL_TEXTURE_2D, r->spread2.tex);
        glActiveTexture(GL_TEXTURE0);
    }
}

static void blur(jd_renderer *r, GLint step_loc, GLint inv_loc, const target *src, const target *dst, float dx,
                 float dy, float step, float inv2s2, const char *what)
{
    glBindTexture(GL_TEXTURE_2D, src->tex);
    glUniform2f(step_loc, dx * step / (float)src->tw, dy * step / (float)src->th);
    glUniform1f(inv_loc, inv2s2);
    draw_quad_into(r, dst, what, src);
}

/* A low-resolution layer drawn with a shading program: cleared to "not
 * covered" (alpha 0), depth-tested, culled as the main pass; of the whole
 * mesh (full's levels) or of the coarse capture proxy (the spread's A0). */
static void draw_layer(jd_renderer *r, const target *t, const shade_prog *p, const frame_params *f, int whole_mesh,
                       const char *what)
{
    use_target(r, t, what);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    if (r->d.no_cull) glDisable(GL_CULL_FACE); else glEnable(GL_CULL_FACE);
    set_shade_uniforms(r, p, f, t->w, t->h);
    counted_read(r, &r->light, 1);
    if (whole_mesh) {
        for (int i = 0; i < r->diff_levels; i++) counted_read(r, &r->diff_lv[i], 1);
        draw_mesh(r, &f->mvp);
    } else {
        counted_read(r, &r->irr[0], 6);
        bind_mesh(r->cap_vbo, r->cap_ibo);
        draw_elements(r, 2, &f->mvp, (GLsizei)r->capture_proxy.num_indices, GL_UNSIGNED_SHORT, 0, -1);
    }
}

static void pass_spread(jd_renderer *r, const frame_params *f)
{
    /* A0 at low resolution from the coarse capture proxy: these layers are
     * blurred, so a finer mesh would buy nothing but vertex work. */
    draw_layer(r, &r->spread0, &r->a0, f, 0, "spread-a0");

    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    bind_quad(r);
    glUseProgram(r->blur_prog);
    glUniform1i(r->blur_src, 0);
    glUniform2f(r->blur_scale, (float)r->spread0.w / r->spread0.tw, (float)r->spread0.h / r->spread0.th);
    glActiveTexture(GL_TEXTURE0);
    float sigma = f->blur_sigma_px;
    float step = sigma * 3.0f / BLUR_TAPS;
    if (step < 1.0f) step = 1.0f;
    float st = sigma / step;
    float inv2s2 = 1.0f / (2.0f * st * st);
    /* A1 = G * A0; A2 = G * A1, whose last (vertical) pass also combines. */
    blur(r, r->blur_step, r->blur_inv, &r->spread0, &r->spread_tmp, 1, 0, step, inv2s2, "spread-a1h");
    blur(r, r->blur_step, r->blur_inv, &r->spread_tmp, &r->spread1, 0, 1, step, inv2s2, "spread-a1v");
    blur(r, r->blur_step, r->blur_inv, &r->spread1, &r->spread_tmp, 1, 0, step, inv2s2, "spread-a2h");
    glUseProgram(r->combine_prog);
    glUniform1i(r->comb_src, 0);
    glUniform1i(r->comb_a1, 1);
    glUniform3fv(r->comb_w1, 1, f->w1);
    glUniform3fv(r->comb_w2, 1, f->w2);
    glUniform2f(r->comb_scale, (float)r->spread0.w / r->spread0.tw, (float)r->spread0.h / r->spread0.th);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, r->spread1.tex);
    glActiveTexture(GL_TEXTURE0);
    blur(r, r->comb_step, r->comb_inv, &r->spread_tmp, &r->spread2, 0, 1, step, inv2s2, "spread-a2v");
}

/* One step of the full mode's light-space diffusion: from `from` into `to`
 * with program p, taps `step` (uv) apart, 2 taps + 1 of them with the
 * Gaussian weights of sigma st taps (box: a square of `box` texels a side,
 * equal weights). */
static void diffuse_step(jd_renderer *r, const diff_prog *p, const target *from, const target *to, float sx, float sy,
                         int taps, float st, int box, float near, const char *what)
{
    glUseProgram(p->id);
    glUniform1i(p->src, 0);
    glUniform1i(p->ref, 1);
    glUniform2f(p->ref_scale, 1.0f / (float)to->w, 1.0f / (float)to->h);
    glUniform2f(p->uv_scale, (float)from->w / from->tw, (float)from->h / from->th);
    glUniform2f(p->step, sx, sy);
    if (box) { /* two taps a trip */
        glUniform1i(p->taps, box > 1 ? box * box / 2 : 1);
        glUniform1f(p->box, (float)box);
    } else {
        float w[2 * DIFF_TAPS + 1];
        for (int i = 0; i <= 2 * taps; i++) w[i] = expf(-(float)((i - taps) * (i - taps)) / (2.0f * st * st));
        glUniform1i(p->taps, taps);
        glUniform1fv(p->w, 2 * taps + 1, w);
    }
    glUniform1f(p->near, near);
    glBindTexture(GL_TEXTURE_2D, from->tex);
    draw_quad_into(r, to, what, from);
    counted_read(r, &r->light, 1); /* the reference depths */
    counted_trips(r, box ? (box > 1 ? box * box / 2 : 1) : 2 * taps + 1);
}

/* The full mode's light-space levels: level k is level k-1 blurred by the
 * Gaussian whose variance brings it to sigma_k (variances add), so every
 * step is short. Level 1 comes from the light-depth map: its texels
 * gathered in squares of one level texel (a box's variance), then blurred
 * by the rest of its Gaussian. A horizontal pass into diff_tmp (the
 * destination's width, the source's height), a vertical one into the
 * level's texture. Sigmas are counted in texels of the first level;
 * texture k has 2^(k/2) of those per texel. */
static void pass_diffusion(jd_renderer *r, const frame_params *f)
{
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    bind_quad(r);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, r->light.tex);
    glActiveTexture(GL_TEXTURE0);
    /* Light-depth units per first-level texel: the map spans 2 world units
     * across and 2 in depth, so units of width and depth are alike. */
    float texel = 1.0f / (float)r->d.diffusion_size, map_texel = 1.0f / (float)r->d.light_map_size;
    int box = r->d.light_map_size / r->d.diffusion_size;
    /* The square's variance in level texels (a box of n: (n^2 - 1) / 12 n^2). */
    float prev = sqrtf((float)(box * box - 1) / (12.0f * (float)(box * box)));
    for (int k = 0; k < r->diff_levels; k++) {
        float sigma = (float)(1 << k);
        float inc = sqrtf(sigma * sigma - prev * prev);
        prev = sigma;
        target *dst = &r->diff_lv[k], *tmp = &r->diff_tmp;
        /* Light within 1.5 sigma (and two map texels) of a texel's own
         * surface in depth is that surface's; the rest came from elsewhere. */
        float near = 1.5f * sigma * texel + 2.0f * map_texel + f->light_map[3];
        if (k == 0) /* the squares, into the level itself: the blur reads them from there */
            diffuse_step(r, &r->diff_first, &r->light, dst, 1.0f / (float)r->light.tw, 1.0f / (float)r->light.th, 0,
                         0.0f, box, near, "diffusion-1box");
        const target *src = k == 0 ? dst : &r->diff_lv[k - 1];
        /* First-level texels per source texel. */
        float per_src = k == 0 ? 1.0f : (float)(1 << ((k - 1) / 2));
        float sig = inc / per_src; /* in source texels, also tmp's rows */
        /* The first level's blur reads the squares, sharp at their texels:
         * taps half a sigma (at least a texel) apart. Later levels read a
         * level already blurred by sigma_(k-1), at least 1/sqrt(3) of this
         * step's increment: taps a sigma apart (3 a side, not 6) sample it
         * without a ripple (the Gaussian's alias at that spacing is
         * exp(-2 pi^2 / 3), 0.1%), at half the cost. */
        float spacing = k == 0 ? sig * 3.0f / DIFF_TAPS : sig;
        float step = fmaxf(spacing, 1.0f), st = sig / step;
        /* Taps out to 3 sigma, no more. */
        int taps = (int)fminf(ceilf(3.0f * st), (float)DIFF_TAPS);
        tmp->w = dst->w;
        tmp->h = src->h;
        char what[24];
        snprintf(what, sizeof what, "diffusion-%dh", k + 1);
        diffuse_step(r, &r->diff_next, src, tmp, step / (float)src->tw, 0.0f, taps, st, 0, near, what);
        snprintf(what, sizeof what, "diffusion-%dv", k + 1);
        diffuse_step(r, &r->diff_next, tmp, dst, 0.0f, step / (float)tmp->th, taps, st, 0, near, what);
    }
}

/* Without vertex diffusion, full's levels are summed per fragment at half
 * resolution: a quarter of the texture reads, and one bilinear read in the
 * main pass. */
static void pass_wide(jd_renderer *r, const frame_params *f)
{
    draw_layer(r, &r->wide, &r->wide_prog, f, 1, "wide");
    counted_trips(r, 4); /* jd_level_at's texels */
}

static void pass_main(jd_renderer *r, const jd_scene *s, const frame_params *f)
{
    /* Into the target, or into `scene` for the pass after: anti-aliasing,
     * or enlarging a picture drawn smaller. */
    int via_scene = r->post_aa || r->iw != r->d.width || r->ih != r->d.height;
    int w = r->iw, h = r->ih;
    /* "main": at the picture's resolution (the frame-cost model's name). */
    count_target(r, w == r->d.width && h == r->d.height ? "main" : "shade-scaled", w, h);
    glBindFramebuffer(GL_FRAMEBUFFER, via_scene ? r->scene.fbo : r->d.target_fbo);
    glViewport(0, 0, w, h);
    /* The pass after reads one texel past the frame's right and top
     * edges: where the texture is larger than the frame (power-of-two
     * sizes, a window made smaller), that texel is cleared too, or the
     * edge column takes whatever the texture held. */
    if (via_scene)
        glScissor(0, 0, w < r->scene.tw ? w + 1 : w, h < r->scene.th ? h + 1 : h);
    else
        glScissor(0, 0, w, h);
    float bg[3];
    for (int c = 0; c < 3; c++) bg[c] = sqrtf(fmaxf(s->background[c], 0.0f)); /* display gamma 2, as the shader */
    glClearColor(bg[0], bg[1], bg[2], 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glScissor(0, 0, w, h);
    glEnable(GL_DEPTH_TEST);
    if (r->d.no_cull) glDisable(GL_CULL_FACE); else glEnable(GL_CULL_FACE);
    set_shade_uniforms(r, &r->shade[s->mode], f, w, h);
    counted_read(r, &r->light, 1);
    if (s->mode == JD_MODE_FULL && !r->vertex_diffusion) counted_read(r, &r->wide, 1);
    if (s->mode == JD_MODE_FULL && r->vertex_diffusion)
        for (int i = 0; i < r->diff_levels; i++) counted_read(r, &r->diff_lv[i], 1);
    if (s->mode == JD_MODE_SINGLE || s->mode == JD_MODE_DUAL) counted_read(r, &r->irr[0], 6);
    if (s->mode == JD_MODE_DUAL) counted_read(r, &r->spread2, 1);
    draw_mesh(r, &f->mvp);
}

/* The frame from `scene` into the platform's target, its edges smoothed.
 * Only the object's box on screen (its corners projected, two pixels
 * more) is filtered; the rest is background, cleared. */
static void pass_antialias(jd_renderer *r, const jd_scene *s, const frame_params *f)
{
    count_target(r, r->post_aa ? "main-antialias" : "main-upscale", r->d.width, r->d.height);
    glBindFramebuffer(GL_FRAMEBUFFER, r->d.target_fbo);
    glViewport(0, 0, r->d.width, r->d.height);
    glScissor(0, 0, r->d.width, r->d.height);
    float bg[3];
    for (int c = 0; c < 3; c++) bg[c] = sqrtf(fmaxf(s->background[c], 0.0f));
    glClearColor(bg[0], bg[1], bg[2], 1);
    glClear(GL_COLOR_BUFFER_BIT);
    /* The object's extent on screen: the proxy's vertices projected, and
     * as far again as the mesh may lie from its proxy (proxy_error, at the
     * nearest vertex's depth). The bunny's box corners took 2.6 times the
     * pixels at 1080p, each one a fragment of this pass. */
    float x0 = 1, y0 = 1, x1 = -1, y1 = -1, w_min = 1e30f;
    int inside = 1;
    double area = (double)r->d.width * r->d.height;
    const float *m = f->mvp.m;
    for (uint32_t i = 0; i < r->proxy.num_vertices && inside; i++) {
        const float *q = r->proxy.positions + 3 * i;
        jd_vec3 p = jd_v3_scale(jd_v3_sub(jd_v3(q[0], q[1], q[2]), r->place_c), r->place_inv_r);
        float cx = m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12], cy = m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13];
        float cw = m[3] * p.x + m[7] * p.y + m[11] * p.z + m[15];
        if (cw <= 1e-4f) { inside = 0; break; } /* behind the camera: filter everything */
        x0 = fminf(x0, cx / cw); x1 = fmaxf(x1, cx / cw);
        y0 = fminf(y0, cy / cw); y1 = fmaxf(y1, cy / cw);
        w_min = fminf(w_min, cw);
    }
    if (inside) { /* world units to NDC at the nearest depth: the transform's scale over w */
        float sx = sqrtf(m[0] * m[0] + m[4] * m[4] + m[8] * m[8]), sy = sqrtf(m[1] * m[1] + m[5] * m[5] + m[9] * m[9]);
        float e = r->proxy_error * fmaxf(sx, sy) / w_min;
        x0 -= e; x1 += e; y0 -= e; y1 += e;
    }
    if (inside) {
        int px0 = (int)floorf((x0 * 0.5f + 0.5f) * r->d.width) - 2, px1 = (int)ceilf((x1 * 0.5f + 0.5f) * r->d.width) + 2;
        int py0 = (int)floorf((y0 * 0.5f + 0.5f) * r->d.height) - 2, py1 = (int)ceilf((y1 * 0.5f + 0.5f) * r->d.height) + 2;
        px0 = px0 < 0 ? 0 : px0; py0 = py0 < 0 ? 0 : py0;
        px1 = px1 > r->d.width ? r->d.width : px1; py1 = py1 > r->d.height ? r->d.height : py1;
        if (px1 <= px0 || py1 <= py0) return;
        glScissor(px0, py0, px1 - px0, py1 - py0);
        area = (double)(px1 - px0) * (py1 - py0);
    }
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    bind_quad(r);
    /* The quad spans the target; its texture coordinates the used part of
     * `scene`, whatever its size: drawn smaller, it is enlarged here. */
    if (r->post_aa) {
        glUseProgram(r->aa_prog);
        glUniform1i(r->aa_src, 0);
        glUniform2f(r->aa_texel, 1.0f / (float)r->scene.tw, 1.0f / (float)r->scene.th);
        glUniform2f(r->aa_scale, (float)r->scene.w / (float)r->scene.tw, (float)r->scene.h / (float)r->scene.th);
    } else {
        glUseProgram(r->up_prog);
        glUniform1i(r->up_src, 0);
        glUniform2f(r->up_scale, (float)r->scene.w / (float)r->scene.tw, (float)r->scene.h / (float)r->scene.th);
    }
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, r->scene.tex);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    counted_quad(r, area, 4, 2);
    jd_pass_count *p = counted(r);
    if (p) p->bytes_read += area * 4.0 * ((double)r->iw / r->d.width) * ((double)r->ih / r->d.height);
}

static void gpu_begin(jd_renderer *r, jd_frame_stats *st, int pass)
{
    if (r->timing && st && r->tq.ok) {
        r->tq.begin(GL_TIME_ELAPSED_EXT, r->tq.q[pass]);
        r->tq.used[pass] = 1;
    }
}

static void lap(jd_renderer *r, jd_frame_stats *st, int pass, double *t)
{
    if (!r->timing || !st) return;
    if (r->tq.ok && r->tq.used[pass]) r->tq.end(GL_TIME_ELAPSED_EXT);
    glFinish();
    double now = jd_clock_ms();
    st->pass_ms[pass] += now - *t;
    *t = now;
}

/* After the frame's last glFinish every query is available; a disjoint
 * event (the GPU clock was disturbed) invalidates the whole frame. */
static void gpu_collect(jd_renderer *r, jd_frame_stats *st)
{
    if (!r->timing || !st || !r->tq.ok) return;
    GLint disjoint = 0;
    glGetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint);
    st->gpu_valid = !disjoint;
    for (int p = 0; p < JD_PASS_COUNT; p++) {
        if (!r->tq.used[p]) continue;
        GLuint64 ns = 0;
        r->tq.result64(r->tq.q[p], GL_QUERY_RESULT_EXT, &ns);
        st->gpu_ms[p] = (double)ns / 1e6;
        r->tq.used[p] = 0;
    }
}

jd_result jd_renderer_frame(jd_renderer *r, const jd_scene *asked, jd_frame_stats *stats, jd_error *err)
{
    if (asked->mode < 0 || asked->mode >= JD_MODE_COUNT)
        return jd_fail(err, JD_ERR_ARG, "unknown mode %d", (int)asked->mode);
    /* A mode this device cannot run is drawn as the cheaper one start-up
     * chose and said. */
    jd_scene shown = *asked;
    shown.mode = r->shown[asked->mode];
    const jd_scene *s = &shown;
    frame_params f;
    memset(&f, 0, sizeof f);
    frame_setup(r, s, &f);
    if (stats) memset(stats, 0, sizeof *stats);
    double t = jd_clock_ms();
    /* Packed values must reach RGBA8 bit-exact: GL enables dithering by default. */
    glDisable(GL_DITHER);
    glEnable(GL_SCISSOR_TEST);
    /* A still scene (the light, the material and the mode as last frame)
     * reuses the light-space work: light depth, diffusion, capture and SH;
     * the spread is screen-space and also needs the camera still. */
    float lk[16] = {(float)s->mode, s->light_azimuth, s->light_elevation, s->light_intensity, s->sigma_s[0],
                    s->sigma_s[1], s->sigma_s[2], s->sigma_a[0], s->sigma_a[1], s->sigma_a[2], s->eta, s->density,
                    s->mm_per_unit, s->gain, s->specular, s->ambient};
    float vk[24];
    memcpy(vk, lk, sizeof lk);
    float vk_rest[8] = {s->cam_azimuth, s->cam_elevation, s->cam_distance, s->fov_deg, (float)r->d.width,
                        (float)r->d.height, s->exposure, s->fit};
    memcpy(vk + 16, vk_rest, sizeof vk_rest);
    int light_still = r->light_key_valid && !memcmp(lk, r->light_key, sizeof lk);
    int view_still = light_still && r->view_key_valid && !memcmp(vk, r->view_key, sizeof vk);
    r->light_key_valid = r->view_key_valid = 0; /* set again once this frame has succeeded */
    r->n_switches = r->n_readbacks = 0;
    r->n_fragments = r->n_bytes = 0;
    /* Every mode shadows its direct light with the light-depth map. */
    if (!light_still) {
        gpu_begin(r, stats, JD_PASS_LIGHT_DEPTH);
        pass_light_depth(r, &f);
        lap(r, stats, JD_PASS_LIGHT_DEPTH, &t);
    }
    if (s->mode == JD_MODE_FULL) {
        update_fit(r, s, &f);
        if (!light_still) {
            gpu_begin(r, stats, JD_PASS_DIFFUSION);
            pass_diffusion(r, &f);
            lap(r, stats, JD_PASS_DIFFUSION, &t);
        }
        /* The levels' sum is in screen space, at a resolution that keeps
         * two samples per level texel across (their finest Gaussian is a
         * texel wide): 1/2 to 1/4 of the picture's. */
        if (!r->vertex_diffusion && !view_still) {
            float level_px = 2.0f / (float)r->d.diffusion_size * f.px_per_world;
            r->wide_div = level_px >= 8.0f ? 4 : level_px >= 6.0f ? 3 : 2;
            r->wide.w = (r->iw + r->wide_div - 1) / r->wide_div;
            r->wide.h = (r->ih + r->wide_div - 1) / r->wide_div;
            pass_wide(r, &f);
        }
    }
    if (s->mode == JD_MODE_SINGLE || s->mode == JD_MODE_DUAL) {
        update_tail(r, s, &f);
        if (!light_still) { /* else the irradiance map is as it was */
            gpu_begin(r, stats, JD_PASS_CAPTURE);
            pass_capture(r, &f);
            lap(r, stats, JD_PASS_CAPTURE, &t);
            gpu_begin(r, stats, JD_PASS_SH);
            pass_sh(r);
            lap(r, stats, JD_PASS_SH, &t);
        }
        if (s->mode == JD_MODE_DUAL && !view_still) {
            gpu_begin(r, stats, JD_PASS_SPREAD);
            pass_spread(r, &f);
            lap(r, stats, JD_PASS_SPREAD, &t);
        }
    }
    gpu_begin(r, stats, JD_PASS_MAIN);
    pass_main(r, s, &f);
    if (r->post_aa || r->iw != r->d.width || r->ih != r->d.height) pass_antialias(r, s, &f);
    lap(r, stats, JD_PASS_MAIN, &t);
    gpu_collect(r, stats);
    if (stats) {
        stats->blur_sigma_px = f.blur_sigma_px;
        stats->target_switches = r->n_switches;
        stats->readbacks = r->n_readbacks;
        stats->fragments = r->n_fragments;
        stats->target_bytes_written = r->n_bytes;
        stats->reused = light_still + view_still;
    }
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) return jd_fail(err, JD_ERR_GL, "GL error 0x%x during the %s frame", e, jd_mode_name(s->mode));
    memcpy(r->light_key, lk, sizeof lk);
    memcpy(r->view_key, vk, sizeof vk);
    r->light_key_valid = r->view_key_valid = 1;
    return JD_OK;
}

jd_result jd_renderer_read_capture(jd_renderer *r, uint8_t *atlas, uint8_t *sh27, int *n, jd_error *err)
{
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (atlas) {
        glBindFramebuffer(GL_FRAMEBUFFER, r->atlas.fbo);
        glReadPixels(0, 0, r->atlas.w, r->atlas.h, GL_RGBA, GL_UNSIGNED_BYTE, atlas);
    }
    if (sh27) {
        glBindFramebuffer(GL_FRAMEBUFFER, r->sh3.fbo);
        glReadPixels(0, 0, 1, 27, GL_RGBA, GL_UNSIGNED_BYTE, sh27);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, r->d.target_fbo);
    if (n) *n = r->d.cube_size;
    return glGetError() == GL_NO_ERROR ? JD_OK : jd_fail(err, JD_ERR_GL, "reading the capture back failed");
}

/* Vertices a FIFO post-transform cache of n entries shades for the index
 * stream (its misses); n = 0: the draw's index range, which Utgard and
 * Midgard shade whole (Mesa lima_draw.c: max_index - min_index + 1). */
static double shaded_vertices(const jd_mesh *m, int n)
{
    if (!m->num_indices) return 0;
    if (n <= 0) {
        uint32_t lo = UINT32_MAX, hi = 0;
        for (uint32_t i = 0; i < m->num_indices; i++) {
            uint32_t v = jd_mesh_index(m, i);
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
        }
        return (double)(hi - lo) + 1.0;
    }
    uint32_t fifo[64];
    if (n > 64) n = 64;
    int head = 0, filled = 0;
    double misses = 0;
    for (uint32_t i = 0; i < m->num_indices; i++) {
        uint32_t v = jd_mesh_index(m, i);
        int hit = 0;
        for (int k = 0; k < filled && !hit; k++) hit = fifo[k] == v;
        if (hit) continue;
        misses++;
        fifo[head] = v;
        head = (head + 1) % n;
        if (filled < n) filled++;
    }
    return misses;
}

jd_result jd_renderer_count(jd_renderer *r, const jd_scene *s, int vertex_cache, jd_frame_count *out, jd_error *err)
{
    memset(out, 0, sizeof *out);
    if (!r->count_prog) {
        static const char *const attribs[] = {"a_position", NULL};
        jd_result res = jd_program_build("shaders_es2/count.vert", "shaders_es2/count.frag", "#define JD_PACK_HIGHP 0\n",
                                         attribs, &r->count_prog, err);
        if (res) return res;
        r->count_mvp = glGetUniformLocation(r->count_prog, "u_mvp");
    }
    /* Chunks under the range model: each chunk's own vertex count. */
    r->count_vertices[0] = r->num_chunks && vertex_cache <= 0 ? -1.0 : shaded_vertices(r->d.mesh, vertex_cache);
    r->count_vertices[1] = shaded_vertices(&r->proxy, vertex_cache);
    r->count_vertices[2] = shaded_vertices(&r->capture_proxy, vertex_cache);
    /* Every pass runs, as in a frame whose light moved. */
    r->light_key_valid = r->view_key_valid = 0;
    r->count = out;
    r->count_read = 0;
    jd_result res = jd_renderer_frame(r, s, NULL, err);
    counted_close(r);
    r->count = NULL;
    /* The targets hold counts: the next frame draws every pass again. */
    r->light_key_valid = r->view_key_valid = 0;
    glBindFramebuffer(GL_FRAMEBUFFER, r->d.target_fbo);
    if (res == JD_OK && out->overflow)
        return jd_fail(err, JD_ERR_BUDGET, "the frame has more than %d passes to count", JD_COUNT_PASSES);
    return res;
}
