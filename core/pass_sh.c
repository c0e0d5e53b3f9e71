/* single and dual: the lit object captured into a cube atlas, projected
 * onto SH as a fragment-shader reduction, and the irradiance cube map the
 * shading reads; the dipole tail table. */
#include "renderer_internal.h"

#include <math.h>
#include <string.h>

#include "sh.h"

/* M(t) over t in [0, range]: the bracket of the dipole tail (without
 * alpha'/2, which is in the A0 scale), halved into [0,1] and stored as its
 * square root so thin-light values keep precision in 8 bits. Rebuilt only
 * when the material or the scale changes. */
void jdr_update_tail(jd_renderer *r, const jd_scene *s, const frame_params *f)
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

void jdr_pass_capture(jd_renderer *r, const jd_scene *s, const frame_params *f)
{
    (void)s;
    int n = r->d.cube_size;
    float h = r->box_half;
    jdr_use_target(r, &r->atlas, "capture");
    jdr_counted_read(r, &r->light, 1);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    if (r->d.no_cull) glDisable(GL_CULL_FACE); else glEnable(GL_CULL_FACE);
    glUseProgram(r->capture_prog);
    glUniformMatrix4fv(r->cap_light_tex, 1, GL_FALSE, f->light_tex.m);
    glUniform3f(r->cap_light_dir, f->light_dir.x, f->light_dir.y, f->light_dir.z);
    glUniform3fv(r->cap_light_color, 1, f->light_color);
    glUniform1f(r->cap_bias, 1.5f / (float)r->d.proxy_cells);
    glUniform1i(r->cap_depth, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, r->light.tex);
    jdr_bind_mesh(r->cap_vbo, r->cap_ibo);
    jd_mat4 ortho = jd_m4_ortho(-h, h, -h, h, 3.0f - h - 0.01f, 3.0f + h + 0.01f);
    for (int face = 0; face < 6; face++) {
        float a[3], u[3], v[3];
        jd_cube_face_frame(face, a, u, v);
        jd_mat4 view = jd_m4_look_at(jd_v3(3 * a[0], 3 * a[1], 3 * a[2]), jd_v3(0, 0, 0), jd_v3(v[0], v[1], v[2]));
        jd_mat4 mvp = jd_m4_mul(ortho, view);
        glViewport((face % 3) * n, (face / 3) * n, n, n);
        glUniformMatrix4fv(r->cap_mvp, 1, GL_FALSE, mvp.m);
        jdr_draw_elements(r, 2, &mvp, (GLsizei)r->capture_proxy.num_indices, GL_UNSIGNED_SHORT, 0, -1);
    }
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
jd_result jdr_build_projection_quads(jd_renderer *r, jd_arena *a, jd_error *err)
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
    glDisableVertexAttribArray(5); /* the mesh's curvature: not this buffer's */
    jdr_use_target(r, &r->sh1, "sh-project");
    jdr_counted_read(r, &r->atlas, 1);
    glDrawArrays(GL_TRIANGLES, 0, 6 * 6 * 27);
    jdr_counted_quad(r, (double)r->sh1.w * r->sh1.h, 6 * 6 * 27, 2 * 6 * 27); /* the rectangles tile it */
    for (GLuint i = 2; i < 5; i++) glDisableVertexAttribArray(i);
    jdr_bind_quad(r);
}

void jdr_pass_sh(jd_renderer *r, const jd_scene *s, const frame_params *f)
{
    (void)s;
    (void)f;
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    jdr_bind_quad(r);
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
        jdr_draw_quad_into(r, &r->sh_mid_t, "sh-reduce-mid", &r->sh1);
        src = &r->sh_mid_t;
    }
    glUseProgram(r->reduce_faces_prog);
    glUniform1i(r->rf_src, 0);
    glUniform2f(r->rf_texel, 1.0f / src->tw, 1.0f / src->th);
    glBindTexture(GL_TEXTURE_2D, src->tex);
    jdr_draw_quad_into(r, &r->sh2, "sh-reduce-faces", src);
    glUseProgram(r->reduce_final_prog);
    glUniform1i(r->rl_src, 0);
    glUniform2f(r->rl_texel, 1.0f / r->sh2.tw, 1.0f / r->sh2.th);
    glBindTexture(GL_TEXTURE_2D, r->sh2.tex);
    jdr_draw_quad_into(r, &r->sh3, "sh-reduce", &r->sh2);
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
        jdr_draw_quad_into(r, &r->irr[f], "irradiance", &r->sh3);
    }
}
