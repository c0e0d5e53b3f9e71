/* Render targets (power-of-two textures with a framebuffer, a depth
 * renderbuffer where asked) and the mesh uploads, chunked to 16-bit
 * indices where the GPU has no 32-bit ones. */
#include "renderer_internal.h"
#include "mesh_bounce.h"
#include "mesh_load.h"

#include <stdio.h>
#include <string.h>

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
GLuint jdr_new_texture(int w, int h, GLint filter)
{
    GLuint tex = new_sampled(GL_TEXTURE_2D, filter);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    return tex;
}

/* A one-byte (luminance) table, filtered: its texels come with their
 * first glTexSubImage2D, before any pass reads it. w: a multiple of 4
 * (GL's default row alignment). */
GLuint jdr_new_table(int w, int h)
{
    GLuint tex = new_sampled(GL_TEXTURE_2D, GL_LINEAR);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_LUMINANCE, w, h, 0, GL_LUMINANCE, GL_UNSIGNED_BYTE, NULL);
    return tex;
}

/* Every texel of the bound framebuffer's colour defined (0) from the
 * start: GLES leaves a new texture's contents undefined, and a driver that
 * reuses freed buffers (Mesa's lima keeps a cache of them) hands over
 * another target's data, which a pass whose taps or filtering reach past
 * the region it wrote would draw (the spread's blur at its edges;
 * tests/undefined_texels.sh fills new textures with noise). Once, at
 * set-up: no frame pays for it. */
static void clear_whole(void)
{
    GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST), mask[4];
    glGetBooleanv(GL_COLOR_WRITEMASK, mask);
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glColorMask(mask[0], mask[1], mask[2], mask[3]);
    if (scissor) glEnable(GL_SCISSOR_TEST);
}

/* A target of w x h: its framebuffer (and depth renderbuffer), the
 * storage from jdr_fit_target, as every target's is. */
jd_result jdr_make_target(jd_renderer *r, target *t, int w, int h, int with_depth, int linear,
                             const char *what, jd_error *err)
{
    return jdr_make_target_ms(r, t, w, h, with_depth, linear, 0, what, err);
}

/* The same, drawn with `samples` (> 1) that EXT_multisampled_render_to_texture
 * keeps in the tile buffer and resolves into the texture; one sample where
 * the driver will not (jdr_fit_target). */
jd_result jdr_make_target_ms(jd_renderer *r, target *t, int w, int h, int with_depth, int linear, int samples,
                             const char *what, jd_error *err)
{
    memset(t, 0, sizeof *t);
    t->samples = samples > 1 ? samples : 0;
    glGenFramebuffers(1, &t->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    if (with_depth) {
        glGenRenderbuffers(1, &t->depth);
        glBindRenderbuffer(GL_RENDERBUFFER, t->depth); /* a name becomes an object when bound */
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t->depth);
    }
    return jdr_fit_target(r, t, w, h, linear, what, err);
}

/* The texture and depth of `t` attached with t->samples: 1 where the
 * framebuffer is complete so. Otherwise it is left for one sample and
 * r->ms_note says why: a driver may list the extension and refuse a
 * format or a size with samples, and the picture is drawn all the same. */
static int attach_multisampled(jd_renderer *r, target *t, const char *what)
{
    while (glGetError() != GL_NO_ERROR) {}
    if (t->depth) {
        glBindRenderbuffer(GL_RENDERBUFFER, t->depth);
        r->ms.storage(GL_RENDERBUFFER, t->samples, GL_DEPTH_COMPONENT16, t->tw, t->th);
    }
    r->ms.texture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t->tex, 0, t->samples);
    GLenum e = glGetError(), st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (e == GL_NO_ERROR && st == GL_FRAMEBUFFER_COMPLETE) return 1;
    snprintf(r->ms_note, sizeof r->ms_note, "%s %dx%d with %d samples refused by the driver (GL error 0x%x, "
             "framebuffer 0x%x): drawn with one", what, t->tw, t->th, t->samples, e, st);
    t->samples = 0;
    while (glGetError() != GL_NO_ERROR) {}
    return 0;
}

/* A target's storage for w x h: made at start-up, and made again for the
 * targets that follow the picture's size (the frame before the pass after
 * it, full's levels' sum) at a resize where w x h takes other powers of
 * two, never in a frame. Sized for the picture, not for the largest the
 * budget allows: at 1080p on a board whose tier draws 960x540 the frame's
 * target is 1024 x 1024, not 2048 x 2048 (25 MB of GPU memory, 6 here),
 * and where nothing goes through it (the display engine enlarging the
 * picture) it keeps one texel. w or h 0: not needed. A new texture, attached afresh (some
 * drivers mishandle a texture specified again while attached). */
jd_result jdr_fit_target(jd_renderer *r, target *t, int w, int h, int linear, const char *what, jd_error *err)
{
    int tw = pot(w > 0 && h > 0 ? w : 1), th = pot(w > 0 && h > 0 ? h : 1);
    t->w = w;
    t->h = h;
    if (tw == t->tw && th == t->th) return JD_OK;
    if (tw > r->d.caps->max_texture_size || th > r->d.caps->max_texture_size)
        return jd_fail(err, JD_ERR_UNSUPPORTED, "%s target %dx%d exceeds the max texture size %d", what, tw, th,
                       r->d.caps->max_texture_size);
    /* Bytes a texel: the colour's 4 (samples live in tile memory and are
     * resolved into it) and the depth's 2 a sample. */
    size_t texel = t->depth ? 4 + 2 * (size_t)(t->samples > 1 ? t->samples : 1) : 4;
    while (glGetError() != GL_NO_ERROR) {}
    glDeleteTextures(1, &t->tex);
    r->target_bytes -= (size_t)t->tw * t->th * texel;
    t->tex = jdr_new_texture(tw, th, linear ? GL_LINEAR : GL_NEAREST);
    t->tw = tw;
    t->th = th;
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    if (!(t->samples > 1 && r->ms.texture && attach_multisampled(r, t, what))) {
        t->samples = 0;
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t->tex, 0);
        if (t->depth) {
            glBindRenderbuffer(GL_RENDERBUFFER, t->depth);
            glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT16, tw, th);
        }
    }
    texel = t->depth ? 4 + 2 * (size_t)(t->samples > 1 ? t->samples : 1) : 4;
    r->target_bytes += (size_t)tw * th * texel;
    GLenum e = glGetError(), st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (e == GL_OUT_OF_MEMORY)
        return jd_fail(err, JD_ERR_GL, "%s target %dx%d: the GPU is out of memory", what, tw, th);
    if (st != GL_FRAMEBUFFER_COMPLETE)
        return jd_fail(err, JD_ERR_GL, "%s framebuffer %dx%d is incomplete (0x%x)", what, tw, th, st);
    clear_whole();
    return JD_OK;
}

/* A cube map of RGBA8 faces, each its own framebuffer: six targets sharing
 * one texture (held by the first). Linear filtering, clamped at the edges. */
jd_result jdr_make_cube_target(jd_renderer *r, target *faces, int size, const char *what, jd_error *err)
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
        clear_whole();
    }
    r->target_bytes += (size_t)6 * size * size * 4;
    return JD_OK;
}

void jdr_free_target(target *t)
{
    if (t->fbo) glDeleteFramebuffers(1, &t->fbo);
    if (t->tex) glDeleteTextures(1, &t->tex);
    if (t->depth) glDeleteRenderbuffers(1, &t->depth);
    memset(t, 0, sizeof *t);
}

/* One vertex as uploaded: the position centred and scaled to the unit
 * sphere (coordinates small for fp16 varyings) and, as its fourth float,
 * the part's thickness t under the vertex (thick: in the mesh's units,
 * scaled with the positions, at most 2, the sphere's width; NULL: 0;
 * mesh_thickness.c); the unit normal ((0, 0, 1) for one of no length). The
 * thickness rode in the normal's length until 2026-12-05, which every
 * vertex stage then normalised: 4 bytes a vertex fewer, but lima's full
 * vertex stage took 67 words, 60 without (a square root, a reciprocal and
 * eight operations a vertex). For a mesh with colours its texture
 * coordinates and colour (4 bytes, normalised). Then the surface's
 * curvature k, scaled with the positions, and 1 / k (curve: NULL: 0;
 * mesh_curvature.h; the shader's 1 / 4e without a reciprocal there).
 * Last, the light between parts' transfer (bounce: JD_BOUNCE_TERMS a
 * vertex; NULL: none). */
_Static_assert(JDR_BOUNCE_BYTES == JD_BOUNCE_TERMS * sizeof(float), "the transfer's bytes");

static void pack_vertex(uint8_t *o, const jd_mesh *m, const float *thick, const float *curve, const float *bounce,
                        uint32_t i, jd_vec3 c, float inv_r)
{
    const float *p = m->positions + 3 * (size_t)i, *n = m->normals + 3 * (size_t)i;
    jd_vec3 u = jd_unit_normal(n);
    float t = thick ? thick[i] * inv_r : 0.0f;
    float v[9] = {(p[0] - c.x) * inv_r, (p[1] - c.y) * inv_r, (p[2] - c.z) * inv_r, t < 2.0f ? t : 2.0f, u.x, u.y, u.z,
                  0.0f, 0.0f};
    float b[JD_BOUNCE_TERMS] = {0};
    if (bounce) memcpy(b, bounce + JD_BOUNCE_TERMS * (size_t)i, sizeof b);
    memcpy(o + jdr_vertex_stride(m) - JDR_BOUNCE_BYTES, b, JDR_BOUNCE_BYTES);
    float k[2] = {curve ? curve[i] / inv_r : 0.0f, 1e4f};
    if (k[0] > 1e-4f) k[1] = 1.0f / k[0];
    memcpy(o + JDR_CURVE_AT(jdr_vertex_stride(m)), k, sizeof k);
    if (!m->colors) {
        memcpy(o, v, 28);
        return;
    }
    if (m->uvs) {
        v[7] = m->uvs[2 * (size_t)i];
        v[8] = m->uvs[2 * (size_t)i + 1];
    }
    memcpy(o, v, 36);
    memcpy(o + 36, m->colors + 4 * (size_t)i, 4);
}

int jdr_vertex_stride(const jd_mesh *m) { return m->colors ? JDR_STRIDE_COLOUR : JDR_STRIDE_PLAIN; }

jd_result jdr_upload_mesh(const jd_mesh *m, const float *thick, const float *curve, const float *bounce, jd_vec3 c,
                          float inv_r, GLuint *vbo, GLuint *ibo, jd_arena *a, jd_error *err)
{
    size_t top = jd_arena_top_mark(a);
    size_t stride = (size_t)jdr_vertex_stride(m);
    uint8_t *v = jd_arena_alloc_top(a, stride * m->num_vertices, 16, "vertex upload scratch", err);
    if (!v) return JD_ERR_BUDGET;
    for (uint32_t i = 0; i < m->num_vertices; i++) pack_vertex(v + stride * i, m, thick, curve, bounce, i, c, inv_r);
    glGenBuffers(1, vbo);
    glBindBuffer(GL_ARRAY_BUFFER, *vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(stride * m->num_vertices), v, GL_STATIC_DRAW);
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
jd_result jdr_upload_mesh_chunked(jd_renderer *r, const jd_mesh *m, const float *thick, const float *curve,
                                  const float *bounce, jd_vec3 c, float inv_r, jd_arena *a, jd_error *err)
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
    size_t stride = (size_t)jdr_vertex_stride(m);
    uint8_t *v = jd_arena_alloc_top(a, stride * v_cap, 16, "chunked vertex upload", err);
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
            ch->vertex_offset = nv * stride;
            ch->count = 0;
            ch->vertices = 0;
        }
        for (int k = 0; k < 3; k++) {
            if (local[tri[k]] < 0) {
                if (nv == v_cap) { jd_arena_top_reset(a, top); return jd_fail(err, JD_ERR_BUDGET, "mesh chunks: vertex copies over the scratch"); }
                pack_vertex(v + stride * nv++, m, thick, curve, bounce, tri[k], c, inv_r);
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
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(stride * nv), v, GL_STATIC_DRAW);
    glGenBuffers(1, &r->mesh_ibo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->mesh_ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(sizeof(uint16_t) * ni), ix, GL_STATIC_DRAW);
    jd_arena_top_reset(a, top);
    return glGetError() == GL_NO_ERROR ? JD_OK : jd_fail(err, JD_ERR_GL, "mesh upload failed (out of GPU memory?)");
}

/* The model's colour texture: halved on the CPU until the device takes it
 * (its largest texture, and at most 1024: the fragment stage is mediump
 * only, and a mediump texture coordinate in [0, 1), with 11 significant
 * bits where mediump is fp16 (Mali-400), lands within half a texel of
 * 1024), mipmapped (the entry's colour is read from a coarser level) and
 * repeating. Its bytes, mipmaps included, are counted. */
jd_result jdr_upload_albedo(jd_renderer *r, const jd_mesh *m, jd_arena *a, jd_error *err)
{
    if (!m->texels || !m->uvs) return JD_OK;
    size_t top = jd_arena_top_mark(a);
    int cap = r->d.caps->max_texture_size > 0 ? r->d.caps->max_texture_size : 64;
    if (cap > JD_TEXTURE_MEDIUMP_SIDE) cap = JD_TEXTURE_MEDIUMP_SIDE;
    int w = (int)m->texture_w, h = (int)m->texture_h;
    const uint8_t *src = m->texels;
    while (w > cap || h > cap) {
        int nw = w > 1 ? w / 2 : 1, nh = h > 1 ? h / 2 : 1;
        uint8_t *dst = jd_arena_alloc_top(a, (size_t)nw * nh * 4, 16, "colour texture reduction", err);
        if (!dst) { jd_arena_top_reset(a, top); return JD_ERR_BUDGET; }
        for (int y = 0; y < nh; y++)
            for (int x = 0; x < nw; x++)
                for (int c = 0; c < 4; c++) {
                    int sx = w > 1 ? 2 * x : x, sy = h > 1 ? 2 * y : y, dx = w > 1, dy = h > 1;
                    unsigned sum = src[4 * ((size_t)sy * w + sx) + c] + src[4 * ((size_t)sy * w + sx + dx) + c] +
                                   src[4 * ((size_t)(sy + dy) * w + sx) + c] + src[4 * ((size_t)(sy + dy) * w + sx + dx) + c];
                    dst[4 * ((size_t)y * nw + x) + c] = (uint8_t)((sum + 2) / 4);
                }
        src = dst;
        w = nw;
        h = nh;
    }
    glGenTextures(1, &r->albedo_tex);
    glBindTexture(GL_TEXTURE_2D, r->albedo_tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, src);
    glGenerateMipmap(GL_TEXTURE_2D);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glBindTexture(GL_TEXTURE_2D, 0);
    jd_arena_top_reset(a, top);
    r->albedo_w = w;
    r->albedo_h = h;
    r->albedo_bytes = (size_t)w * h * 4 * 4 / 3;
    return glGetError() == GL_NO_ERROR ? JD_OK
                                       : jd_fail(err, JD_ERR_GL, "the colour texture (%d x %d) did not upload (out of GPU memory?)", w, h);
}
