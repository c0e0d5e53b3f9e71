#include "renderer_internal.h"
#include "mesh_bounce.h"
#include "mesh_carry.h"
#include "mesh_curvature.h"
#include "mesh_thickness.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "clock.h"
#include "scene.h"

/* The boards whose tier draws less than jade's full quality (the
 * frame-cost model, docs/frame-cost.md), as gl_caps recognised them or a
 * profile stands for them. NULL for any other GPU. */
static const char *tier_board(const jd_gl_caps *c) { return c->tier[0] ? c->tier : NULL; }

/* The share of the picture's size a device's tier draws at (render_scale
 * 0): on those boards full's main pass at 1920x1080 alone takes 27 ms
 * (Mali-400 MP2), and a close-up's 24 ms (VideoCore IV), 39 ms (i.MX6Q's
 * GC2000) or 29 ms (Snapdragon 410's Adreno 306), so pictures over 960x540
 * pixels are drawn at that many and enlarged. */
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
    /* The shading reads the light map (and full's shadow map, half its
     * size) over the whole texture: a size that is not a power of two would
     * leave part of the texture undrawn and put every shadow in the wrong
     * place. */
    if (d->light_map_size & (d->light_map_size - 1))
        return jd_fail(err, JD_ERR_ARG, "light map size %d must be a power of two", d->light_map_size);
    if (d->diffusion_size < 16 || d->diffusion_size > d->light_map_size)
        return jd_fail(err, JD_ERR_ARG, "diffusion size %d must be 16..%d (the light map size)", d->diffusion_size,
                       d->light_map_size);
    if (d->diffusion_size & (d->diffusion_size - 1))
        return jd_fail(err, JD_ERR_ARG, "diffusion size %d must be a power of two", d->diffusion_size);
    /* The first level gathers each of its texels' square of light-map
     * texels in a loop of at most 64 trips of four (diffuse_blur.frag, whose
     * bound GLSL ES 1.00 wants constant): past 16 a side the rest of the
     * square went unread (with a light map of 1024, full's picture against
     * the one with 128-texel levels: best gain 0.95 at 16 a side, 0.89 at
     * 32, 0.85 at 64). */
    if (d->light_map_size / d->diffusion_size > 16)
        return jd_fail(err, JD_ERR_ARG,
                       "diffusion size %d with a light map of %d: a diffusion texel gathers at most 16 x 16 light-map "
                       "texels (diffusion size at least %d)",
                       d->diffusion_size, d->light_map_size, d->light_map_size / 16);
    if (d->spread_divisor < 1 || d->spread_divisor > 16)
        return jd_fail(err, JD_ERR_ARG, "spread divisor %d must be 1..16", d->spread_divisor);

    int device_highp = d->caps->frag_highp_precision >= 23;
    if (d->precision == JD_PRECISION_HIGHP && !device_highp)
        return jd_fail(err, JD_ERR_UNSUPPORTED, "highp packing asked for, but this GPU has no fragment highp");
    r->highp = d->precision == JD_PRECISION_AUTO ? device_highp : d->precision == JD_PRECISION_HIGHP;
    /* Two vertex texture units (depth map and tail table) move A0 to the
     * vertex stage; none (Mali-400) keeps it per fragment. */
    r->vertex_thickness = !d->fragment_thickness && d->caps->max_vertex_texture_units >= 2;
    /* full's levels: the light map and the level textures per vertex, where
     * the GPU reads them there, does not pay less for the sum per fragment
     * on a mesh of this size, and keeps full's light scattered once
     * beside them (the light map read along the camera ray, mesh.vert;
     * gl_caps.h): asked for per vertex, a GPU of 8 texture units goes
     * without it beside a colour texture (render_program.c, JD_NO_SLAB). */
    _Static_assert(JD_DIFFUSION_VERTEX_UNITS == 1 + DIFF_TEXTURES, "the vertex stage's diffusion textures");
    if (d->levels < JD_LEVELS_AUTO || d->levels > JD_LEVELS_FRAGMENT)
        return jd_fail(err, JD_ERR_ARG, "levels %d must be auto, vertex or fragment", (int)d->levels);
    int vertex_units = d->caps->max_vertex_texture_units >= JD_DIFFUSION_VERTEX_UNITS;
    if (d->levels == JD_LEVELS_VERTEX && (!vertex_units || d->fragment_thickness))
        return jd_fail(err, JD_ERR_UNSUPPORTED, "full's levels per vertex asked for, but %s",
                       d->fragment_thickness ? "thickness is read per fragment (--fragment-thickness)"
                                             : "this GPU has under 6 vertex texture units");
    r->vertex_diffusion = d->levels == JD_LEVELS_VERTEX ||
                          (d->levels == JD_LEVELS_AUTO && !d->fragment_thickness &&
                           jd_gl_caps_levels_per_vertex(d->caps, d->mesh->num_vertices,
                                                        d->mesh->colors && d->mesh->texels));

    if (d->antialias < JD_AA_AUTO || d->antialias > JD_AA_POST)
        return jd_fail(err, JD_ERR_ARG, "anti-aliasing %d must be auto, off or post", (int)d->antialias);
    GLint samples = d->target_samples;
    glBindFramebuffer(GL_FRAMEBUFFER, d->target_fbo);
    if (samples <= 0) glGetIntegerv(GL_SAMPLES, &samples);
    r->target_samples = samples;
    GLint depth_bits = 0;
    glGetIntegerv(GL_DEPTH_BITS, &depth_bits);
    r->target_depth = depth_bits > 0;
    r->post_aa = d->antialias == JD_AA_POST || (d->antialias == JD_AA_AUTO && samples <= 1);
    if (d->render_scale != 0.0f && !(d->render_scale >= 0.25f && d->render_scale <= 1.0f))
        return jd_fail(err, JD_ERR_ARG, "render scale %g must be 0 (the device's tier) or 0.25..1", (double)d->render_scale);
    const char *why;
    r->may_scale = (d->render_scale > 0.0f && d->render_scale < 1.0f) ||
                   (d->render_scale == 0.0f && tier_scale(r, d->max_width, d->max_height, &why) < 1.0f);
    /* A picture drawn smaller and enlarged by the GPU: the target's samples
     * see only the enlarging pass's quad. Where that picture cannot be drawn
     * with samples of its own (no EXT_multisampled_render_to_texture, or the
     * driver refuses them: VideoCore IV in a window or under legacy KMS),
     * the pass after the frame smooths it at its own size before it is
     * enlarged, as on a target without samples (jd_renderer_resize). */
    r->aa_small = d->antialias == JD_AA_AUTO && samples > 1 && r->may_scale;
    /* Where the pass runs on every frame (a target without samples), the
     * picture's programs write each pixel's luma to the frame's alpha for
     * its edge test (shade.frag, antialias.frag): two instructions a shaded
     * pixel for seven a tested one on the Vivante GC2000. Not where it runs
     * only on a picture drawn smaller (VideoCore IV: the luma would cost
     * its shading 7 of 105 instructions at the sizes it is not drawn
     * smaller) or never (lima: 4 words of 26). */
    r->luma_alpha = r->post_aa;

    int chunked = d->mesh->index_size == 4 && !d->caps->ext_element_index_uint;
    jd_result res = jd_mesh_build_proxy(d->mesh, d->proxy_cells, a, &r->proxy, err);
    if (res) return res;
    /* The 64x64 capture needs far fewer triangles than the light map. */
    if ((res = jd_mesh_build_proxy(d->mesh, d->capture_cells, a, &r->capture_proxy, err))) return res;
    r->tail_px = jd_arena_alloc(a, TAIL_SIZE * 4, 16, "dipole tail table", err);
    if (!r->tail_px) return JD_ERR_BUDGET;
    if (!r->vertex_diffusion) {
        r->spec_px = jd_arena_alloc(a, SPEC_W * SPEC_H, 16, "highlight table", err);
        if (!r->spec_px) return JD_ERR_BUDGET;
    }

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
    r->albedo_key[0] = -1.0f;
    r->fresnel_eta = -1.0f;
    r->albedo = m->colors != NULL;
    for (uint32_t i = 0; r->albedo && m->texels && i < m->num_vertices && !r->albedo_partial; i++)
        r->albedo_partial = m->colors[4 * (size_t)i + 3] != 255;
    r->vstride = jdr_vertex_stride(m);
    while (glGetError() != GL_NO_ERROR) {}
    /* The part's thickness under each vertex of the mesh and of the light
     * map's proxy (whose vertices the Mali-400 path's levels are summed
     * at), riding in their positions' w (render_target.c): full's light
     * on thin parts (pass_light.c, update_slab). A ray a vertex on the proxy,
     * and on the mesh up to 2^17 triangles; past that (a grid of at most 64
     * cells a side holds dozens a cell, and the rays took seconds at
     * start-up: a 500,000-triangle sphere 2 s more here, one of 262,000
     * 0.8 s; the bunny's 69,451 60-100 ms) the mesh's vertices take the
     * proxy's thickness round them (jd_mesh_thickness_from, within a proxy
     * cell and a half). Where it does not fit the budget, every part counts
     * as the whole object's width: the half-space's light. */
    size_t thick_top = jd_arena_top_mark(a);
    float *thick = jd_arena_alloc_top(a, sizeof(float) * m->num_vertices, 16, "thickness", err);
    float *pthick = jd_arena_alloc_top(a, sizeof(float) * r->proxy.num_vertices, 16, "thickness", err);
    if (!thick || !pthick) { jd_arena_top_reset(a, thick_top); return JD_ERR_BUDGET; }
    float ext_max = fmaxf(ext.x, fmaxf(ext.y, ext.z));
    if (jd_mesh_thickness(&r->proxy, 2.0f * radius, a, pthick, NULL) ||
        (m->num_indices / 3 <= (1u << 17)
             ? jd_mesh_thickness(m, 2.0f * radius, a, thick, NULL)
             : jd_mesh_thickness_from(m, &r->proxy, pthick, 1.5f * ext_max / (float)d->proxy_cells, 2.0f * radius, a,
                                      thick, NULL))) { /* both or neither */
        for (uint32_t i = 0; i < m->num_vertices; i++) thick[i] = 2.0f * radius;
        for (uint32_t i = 0; i < r->proxy.num_vertices; i++) pthick[i] = 2.0f * radius;
    }
    /* The light between parts (mesh_bounce.c): made on the capture's
     * proxy, the coarsest (24 cells a side: 1,359 vertices for the default
     * asset), 32 rays a step each (64 rays, or the light map's proxy of
     * 3,510 vertices, took the knot at most 0.5% closer to Cycles);
     * smoothed there over four rings of neighbours (the rays' noise a cell
     * wide showed as mottling; that light diffuses under the surface it
     * enters anyway); carried to the vertices of the mesh and of the light
     * map's proxy (which the Mali-400 path's levels are summed at) round
     * each, within a cell and a half. All of it 0.12 s more at start-up
     * here for the default asset and the bunny, 0.04 s for the cow. Where
     * it does not fit the budget, none. */
    const jd_mesh *cp = &r->capture_proxy;
    float *bounce = jd_arena_alloc_top(a, sizeof(float) * JD_BOUNCE_TERMS * m->num_vertices, 16,
                                       "light between parts", NULL);
    float *pbounce = jd_arena_alloc_top(a, sizeof(float) * JD_BOUNCE_TERMS * r->proxy.num_vertices, 16,
                                        "light between parts", NULL);
    float *cbounce = jd_arena_alloc_top(a, sizeof(float) * JD_BOUNCE_TERMS * cp->num_vertices, 16,
                                        "light between parts", NULL);
    float reach = 1.5f * ext_max / (float)d->capture_cells;
    if (!bounce || !pbounce || !cbounce || jd_mesh_bounce(cp, 32, a, cbounce, NULL))
        bounce = pbounce = NULL;
    else {
        jd_mesh_smooth(cp, cbounce, JD_BOUNCE_TERMS, 4, a);
        if (jd_mesh_carry(m, cp, cbounce, JD_BOUNCE_TERMS, reach, 0.0f, a, bounce, NULL) ||
            jd_mesh_carry(&r->proxy, cp, cbounce, JD_BOUNCE_TERMS, reach, 0.0f, a, pbounce, NULL))
            bounce = pbounce = NULL;
    }
    /* The surface's curvature at the mesh's vertices, for full's local part
     * past the terminator (mesh_curvature.c; the proxies' programs do not
     * read it). Where it does not fit the budget, none: the terminator as
     * sharp as n.l makes it. */
    float *curve = jd_arena_alloc_top(a, sizeof(float) * m->num_vertices, 16, "curvature", NULL);
    if (curve && jd_mesh_curvature(m, a, curve, NULL)) curve = NULL;
    if ((chunked ? (res = jdr_upload_mesh_chunked(r, m, thick, curve, bounce, c, 1.0f / radius, a, err))
                 : (res = jdr_upload_mesh(m, thick, curve, bounce, c, 1.0f / radius, &r->mesh_vbo, &r->mesh_ibo, a,
                                          err))) ||
        (res = jdr_upload_mesh(&r->proxy, pthick, NULL, pbounce, c, 1.0f / radius, &r->proxy_vbo, &r->proxy_ibo, a,
                               err)) ||
        (res = jdr_upload_mesh(&r->capture_proxy, NULL, NULL, NULL, c, 1.0f / radius, &r->cap_vbo, &r->cap_ibo, a,
                               err)) ||
        (res = jdr_upload_albedo(r, m, a, err))) {
        jd_arena_top_reset(a, thick_top);
        goto fail;
    }
    jd_arena_top_reset(a, thick_top);
    r->tail_tex = jdr_new_texture(TAIL_SIZE, 1, GL_LINEAR);
    r->slab_tex = jdr_new_texture(SLAB_SIZE, 2, GL_LINEAR);
    r->target_bytes += (TAIL_SIZE + 2 * SLAB_SIZE) * 4;
    r->tail_key[0] = -1.0f; /* no table yet */
    if (r->spec_px) {
        r->spec_tex = jdr_new_table(SPEC_W, SPEC_H);
        r->target_bytes += SPEC_W * SPEC_H;
        r->spec_key = -1.0f;
    }
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
    if ((res = jdr_build_programs(r, err))) goto fail;

    int n = d->cube_size, nb = n / r->sh_block;
    int sw = (d->max_width + d->spread_divisor - 1) / d->spread_divisor;
    int shh = (d->max_height + d->spread_divisor - 1) / d->spread_divisor;
    if ((res = jdr_make_target(r, &r->light, d->light_map_size, d->light_map_size, 1, 0, "light depth", err)) ||
        (res = jdr_make_target(r, &r->atlas, 3 * n, 2 * n, 1, 0, "cube capture", err)) ||
        (res = jdr_make_target(r, &r->sh1, 6 * nb, 27 * nb, 0, 0, "SH projection", err)) ||
        (r->sh_mid > 1 &&
         (res = jdr_make_target(r, &r->sh_mid_t, 6 * nb / r->sh_mid, 27 * nb / r->sh_mid, 0, 0, "SH partial sums", err))) ||
        (res = jdr_make_target(r, &r->sh2, 6, 27, 0, 0, "SH reduction", err)) ||
        (res = jdr_make_target(r, &r->sh3, 1, 27, 0, 0, "SH result", err)) ||
        (res = jdr_make_cube_target(r, r->irr, IRR_SIZE, "irradiance map", err)) ||
        (res = jdr_make_target(r, &r->spread0, sw, shh, 1, 1, "spread A0", err)) ||
        (res = jdr_make_target(r, &r->spread_tmp, sw, shh, 0, 1, "spread blur", err)) ||
        (res = jdr_make_target(r, &r->spread1, sw, shh, 0, 1, "spread A1", err)) ||
        (res = jdr_make_target(r, &r->spread2, sw, shh, 0, 1, "spread A2", err)) ||
        (res = jdr_make_target(r, &r->diff_tmp, d->diffusion_size, d->light_map_size, 0, 0, "diffusion blur", err)) ||
        (res = jdr_make_target(r, &r->soft_tmp, d->light_map_size / 2, d->light_map_size, 0, 0, "soft shadow blur",
                               err)) ||
        (res = jdr_make_target(r, &r->soft, d->light_map_size / 2, d->light_map_size / 2, 0, 1, "soft shadow", err)))
        goto fail;
    /* These follow the picture's size: jd_renderer_resize makes their
     * storage (jdr_fit_target). */
    if (!r->vertex_diffusion && ((res = jdr_make_target(r, &r->wide, 1, 1, 1, 1, "full's levels", err)) ||
                                 (res = jdr_make_target(r, &r->wide_fill, 1, 1, 0, 1, "full's levels filled", err))))
        goto fail;
    /* A picture drawn smaller and enlarged by the GPU: the target's samples
     * would see only the enlarging pass's quad, and the edges be as drawn at
     * the smaller size. Where the GPU draws a texture with samples in its
     * tile buffer (EXT_multisampled_render_to_texture: Mesa's lima and
     * panfrost, any driver that lists it), the picture is drawn so, at the target's
     * count: the samples never leave the chip, and each tile is resolved as
     * it is written out, as the target's own are. */
    if (d->antialias == JD_AA_AUTO && samples > 1 && r->may_scale && d->get_proc &&
        d->caps->ext_multisampled_render_to_texture && d->caps->max_samples > 1) {
        r->ms.texture = (PFNGLFRAMEBUFFERTEXTURE2DMULTISAMPLEEXTPROC)d->get_proc("glFramebufferTexture2DMultisampleEXT");
        r->ms.storage = (PFNGLRENDERBUFFERSTORAGEMULTISAMPLEEXTPROC)d->get_proc("glRenderbufferStorageMultisampleEXT");
        if (r->ms.texture && r->ms.storage) r->ms.samples = samples < d->caps->max_samples ? samples : d->caps->max_samples;
    }
    if ((r->post_aa || r->may_scale) &&
        (res = jdr_make_target_ms(r, &r->scene, 1, 1, 1, 1, r->ms.samples, "frame before anti-aliasing", err)))
        goto fail;
    if ((r->post_aa || r->aa_small) && r->may_scale &&
        (res = jdr_make_target(r, &r->aa_mid, 1, 1, 0, 1, "anti-aliased frame before enlarging", err)))
        goto fail;
    for (int i = 0; i < DIFF_TEXTURES; i++)
        if ((res = jdr_make_target(r, &r->diff_lv[i], d->diffusion_size >> ((i + 1) / 2),
                                   d->diffusion_size >> ((i + 1) / 2), 0, 1,
                               "diffusion level", err)))
            goto fail;
    if ((res = jdr_build_projection_quads(r, a, err))) goto fail;
    glBindFramebuffer(GL_FRAMEBUFFER, d->target_fbo);
    /* The storage of the targets that follow the size is made here: a GPU
     * without the memory for it fails the create, its GL names released. */
    if ((res = jd_renderer_resize(r, d->width, d->height, err))) goto fail;
    *out = r;
    return JD_OK;
fail:
    jd_renderer_destroy(r);
    return res;
}

void jd_renderer_destroy(jd_renderer *r)
{
    if (!r) return;
    target *ts[] = {&r->light,   &r->atlas,   &r->sh1,      &r->sh_mid_t, &r->sh2,   &r->sh3, &r->spread0,
                    &r->spread_tmp, &r->spread1, &r->spread2, &r->diff_tmp, &r->scene, &r->aa_mid, &r->wide, &r->wide_fill,
                    &r->soft_tmp, &r->soft};
    for (size_t i = 0; i < sizeof ts / sizeof ts[0]; i++) jdr_free_target(ts[i]);
    for (int i = 0; i < DIFF_TEXTURES; i++) jdr_free_target(&r->diff_lv[i]);
    for (int i = 0; i < 6; i++) jdr_free_target(&r->irr[i]); /* the cube's texture goes with the first */
    GLuint bufs[] = {r->mesh_vbo, r->mesh_ibo, r->proxy_vbo, r->proxy_ibo, r->cap_vbo, r->cap_ibo, r->quad_vbo,
                     r->project_vbo};
    glDeleteBuffers(8, bufs);
    if (r->tail_tex) glDeleteTextures(1, &r->tail_tex);
    if (r->slab_tex) glDeleteTextures(1, &r->slab_tex);
    if (r->spec_tex) glDeleteTextures(1, &r->spec_tex);
    if (r->albedo_tex) glDeleteTextures(1, &r->albedo_tex);
    if (r->tq.ok) r->tq.del(JD_PASS_COUNT, r->tq.q);
    for (int m = 0; m < JD_MODE_COUNT; m++) glDeleteProgram(r->shade[m].id);
    glDeleteProgram(r->wide_prog.id);
    GLuint progs[] = {r->count_prog, r->up_prog, r->a0.id, r->depth_prog, r->capture_prog, r->project_prog, r->reduce_mid_prog, r->reduce_faces_prog,
                      r->reduce_final_prog, r->irr_prog, r->blur_prog, r->combine_prog, r->diff_first.id, r->diff_next.id, r->aa_prog,
                      r->aa_mark_prog, r->soft_prog, r->fill_prog};
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
    /* Storage for what this size draws through: `scene` where the frame
     * goes through the pass after it, full's levels' sum at half the
     * picture's resolution (a frame may use less of it: jd_renderer_frame). */
    jd_result res = JD_OK;
    int via = r->post_aa || width != r->d.width || height != r->d.height;
    int scaled = width != r->d.width || height != r->d.height;
    if (r->scene.fbo)
        res = jdr_fit_target(r, &r->scene, via ? width : 0, via ? height : 0, 1, "frame before anti-aliasing", err);
    /* The pass after the frame at this size: always where the target has
     * no samples; where it has, on a picture drawn smaller with one (the
     * samples it asked for refused, at start-up or at this size). */
    r->aa_now = r->post_aa || (r->aa_small && scaled && r->scene.samples <= 1);
    int mid = scaled && r->aa_now;
    if (!res && r->aa_mid.fbo)
        res = jdr_fit_target(r, &r->aa_mid, mid ? width : 0, mid ? height : 0, 1,
                             "anti-aliased frame before enlarging", err);
    if (!res && r->aa_mid.fbo) { /* the frame's depth, the same size, while aa_mid is used */
        glBindFramebuffer(GL_FRAMEBUFFER, r->aa_mid.fbo);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, mid ? r->scene.depth : 0);
        GLenum st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        if (st != GL_FRAMEBUFFER_COMPLETE)
            res = jd_fail(err, JD_ERR_GL, "anti-aliased frame before enlarging with the frame's depth: framebuffer "
                          "%dx%d incomplete (0x%x)", r->aa_mid.tw, r->aa_mid.th, st);
    }
    if (!res && r->wide.fbo) res = jdr_fit_target(r, &r->wide, (width + 1) / 2, (height + 1) / 2, 1, "full's levels", err);
    if (!res && r->wide_fill.fbo)
        res = jdr_fit_target(r, &r->wide_fill, (width + 1) / 2, (height + 1) / 2, 1, "full's levels filled", err);
    glBindFramebuffer(GL_FRAMEBUFFER, r->d.target_fbo);
    if (res) return res;
    r->scene.w = width;
    r->scene.h = height;
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
    info->texture_bytes = r->albedo_bytes;
    info->texture_width = r->albedo_w;
    info->texture_height = r->albedo_h;
    info->highp = r->highp;
    info->vertex_thickness = r->vertex_thickness;
    info->vertex_levels = r->vertex_diffusion;
    info->gpu_timer = r->tq.ok;
    info->target_samples = r->target_samples;
    info->post_antialias = r->aa_now;
    info->antialias_edges_only = jdr_aa_marks(r);
    info->picture_samples = jdr_via_scene(r) ? r->scene.samples : r->target_samples;
    info->samples_note = r->ms_note[0] ? r->ms_note : NULL;
    info->render_width = r->iw;
    info->render_height = r->ih;
    info->tier = r->tier[0] ? r->tier : NULL;
    info->proxy = &r->proxy;
}

/* The light leaving a point entered around it: the entry's colour takes the
 * texture's mean out to the profile's 60% radius (where jd_dipole_tail
 * falls to 40% of Rd_total) in the channel that reaches furthest (skin1's
 * red, whose mean free path is 3.7 mm, its blue's 0.7: on the textured
 * bunny in skin1 the red's radius came 4.7% closer to the reference than
 * green's, the same in the marble-like material), read from the mip level
 * whose texel spans it (docs/textures.md). The radius is found again only
 * when the material changes. */
static void albedo_reach(jd_renderer *r, const jd_scene *s, frame_params *f)
{
    float key[8] = {s->sigma_s[0], s->sigma_s[1], s->sigma_s[2], s->sigma_a[0], s->sigma_a[1], s->sigma_a[2], s->eta,
                    s->density};
    if (memcmp(key, r->albedo_key, sizeof key)) {
        memcpy(r->albedo_key, key, sizeof key);
        double reach = 0.0;
        for (int c = 0; c < 3; c++) {
            double a = 0.0, b = 1e4, want = 0.4 * jd_dipole_tail(&f->dipole, c, 0.0);
            for (int i = 0; i < 48; i++) {
                double mid = 0.5 * (a + b);
                if (jd_dipole_tail(&f->dipole, c, mid) > want) a = mid; else b = mid;
            }
            if (a > reach) reach = a;
        }
        r->albedo_reach_mm = (float)reach;
    }
    /* texture2D's bias is added to the level the GPU chose for the screen
     * (log2 of texels per pixel), not to level 0: the reach in texels is
     * reached by the reach in pixels where the surface faces the camera.
     * The vertex stage divides this by its own depth (gl_Position.w, the
     * depth along the view: the object's centre is at the eye's distance)
     * and takes the slant (mesh.vert). */
    f->albedo_reach = (float)(r->albedo_reach_mm / f->mm_per_world * f->px_per_world * jd_v3_len(f->eye));
}

static void frame_setup(jd_renderer *r, const jd_scene *s, frame_params *f)
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
    jd_mat4 to_map = jd_m4_identity();
    to_map.m[0] = to_map.m[5] = to_map.m[10] = 0.5f;
    to_map.m[12] = to_map.m[13] = to_map.m[14] = 0.5f;
    f->light_tex = jd_m4_mul(to_map, f->light_mvp);

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
    /* full's Fresnel factor: the fit (256 points of the true curve, a few
     * microseconds of double arithmetic, thirty times the dipole's set-up)
     * is made again only when eta changes, not every frame. */
    if (sv.eta != r->fresnel_eta) {
        r->fresnel_eta = sv.eta;
        jd_fresnel_fit(sv.eta, r->fresnel);
    }
    memcpy(f->fresnel, r->fresnel, sizeof f->fresnel);
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
    if (r->albedo)
        for (int c = 0; c < 3; c++) f->albedo_norm[c] = 1.0f / r->d.mesh->albedo_mean[c];

    /* The paper's spread width, sigma = 2 sigma_s, read as millimetres and
     * turned into pixels of the low-resolution buffer at the object's depth. */
    double world_per_px = 2.0 * dist * tan(fov * M_PI / 360.0) / (quarter ? r->iw : r->ih) *
                          r->d.spread_divisor;
    f->px_per_world = (float)(r->d.spread_divisor / world_per_px);
    f->blur_sigma_px = (float)(2.0 * mean_ss / (world_per_px * f->mm_per_world));
    if (f->blur_sigma_px < 0.25f) f->blur_sigma_px = 0.25f;
    if (f->blur_sigma_px > 24.0f) f->blur_sigma_px = 24.0f;
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

/* ---- the frame as a plan -----------------------------------------------
 * Every pass a frame may run, in the order it runs them: which modes need
 * it, what lets a still scene keep last frame's result, whether this
 * device needs it at all, and which of jd_frame_stats' passes its time
 * goes to. A new pass or tier is a row here. */
enum {
    EVERY_FRAME, /* the picture, and the tables the picture's passes read */
    LIGHT_SPACE, /* reused while the light, the material and the mode are still */
    VIEW_SPACE   /* reused while the camera is still too */
};
#define ALL_MODES ((1u << JD_MODE_COUNT) - 1u)
#define MODE(m) (1u << JD_MODE_##m)
typedef struct plan_step {
    const char *what;
    unsigned modes;
    int reuse;
    int stat; /* JD_PASS_*, or -1: CPU work outside the timings */
    int (*wanted)(const jd_renderer *r); /* NULL: always */
    void (*run)(jd_renderer *r, const jd_scene *s, const frame_params *f);
} plan_step;

static int levels_on_screen(const jd_renderer *r) { return !r->vertex_diffusion; }
static int pass_after(const jd_renderer *r) { return jdr_via_scene(r); }
static int spec_table(const jd_renderer *r) { return r->spec_tex != 0; }

static const plan_step plan[] = {
    {"the dipole's fit", MODE(FULL), EVERY_FRAME, -1, NULL, jdr_update_fit},
    {"the dipole tail table", MODE(SINGLE) | MODE(DUAL), EVERY_FRAME, -1, NULL, jdr_update_tail},
    {"the highlight's table", MODE(FULL), EVERY_FRAME, -1, spec_table, jdr_update_spec},
    {"light depth", ALL_MODES, LIGHT_SPACE, JD_PASS_LIGHT_DEPTH, NULL, jdr_pass_light_depth},
    {"full's diffusion", MODE(FULL), LIGHT_SPACE, JD_PASS_DIFFUSION, NULL, jdr_pass_diffusion},
    {"full's soft shadow", MODE(FULL), LIGHT_SPACE, JD_PASS_DIFFUSION, NULL, jdr_pass_soft_shadow},
    {"full's levels' sum", MODE(FULL), VIEW_SPACE, JD_PASS_DIFFUSION, levels_on_screen, jdr_pass_wide},
    {"the cube capture", MODE(SINGLE) | MODE(DUAL), LIGHT_SPACE, JD_PASS_CAPTURE, NULL, jdr_pass_capture},
    {"the SH projection", MODE(SINGLE) | MODE(DUAL), LIGHT_SPACE, JD_PASS_SH, NULL, jdr_pass_sh},
    {"dual's spread", MODE(DUAL), VIEW_SPACE, JD_PASS_SPREAD, NULL, jdr_pass_spread},
    {"the shading", ALL_MODES, EVERY_FRAME, JD_PASS_MAIN, NULL, jdr_pass_main},
    {"anti-aliasing or enlarging", ALL_MODES, EVERY_FRAME, JD_PASS_MAIN, pass_after, jdr_pass_final},
};
enum { PLAN_STEPS = (int)(sizeof plan / sizeof plan[0]) };

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
    if (r->albedo_tex) albedo_reach(r, s, &f);
    if (stats) memset(stats, 0, sizeof *stats);
    double t = jd_clock_ms();
    /* Packed values must reach RGBA8 bit-exact: GL enables dithering by default. */
    glDisable(GL_DITHER);
    glEnable(GL_SCISSOR_TEST);
    /* A still scene (the light, the material and the mode as last frame)
     * reuses the light-space work: light depth, diffusion, capture and SH;
     * the screen-space layers also need the camera still. */
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
    /* This frame's steps; consecutive steps timed as one pass share its
     * GPU query. */
    int run[PLAN_STEPS], n = 0;
    for (int i = 0; i < PLAN_STEPS; i++) {
        const plan_step *p = &plan[i];
        if (!(p->modes & (1u << s->mode)) || (p->wanted && !p->wanted(r))) continue;
        if ((p->reuse == LIGHT_SPACE && light_still) || (p->reuse == VIEW_SPACE && view_still)) continue;
        run[n++] = i;
    }
    for (int k = 0; k < n; k++) {
        const plan_step *p = &plan[run[k]];
        if (p->stat >= 0 && (k == 0 || plan[run[k - 1]].stat != p->stat)) gpu_begin(r, stats, p->stat);
        p->run(r, s, &f);
        if (p->stat >= 0 && (k + 1 == n || plan[run[k + 1]].stat != p->stat)) lap(r, stats, p->stat, &t);
    }
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
