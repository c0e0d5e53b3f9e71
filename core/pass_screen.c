/* The picture's passes: the shading, its low-resolution layers (dual's
 * spread, full's levels' sum) and the pass after the frame (anti-aliasing,
 * or enlarging a picture the tier drew smaller). */
#include "renderer_internal.h"

#include <math.h>
#include <string.h>

static void set_shade_uniforms(const jd_renderer *r, const shade_prog *p, const frame_params *f, int w, int h)
{
    glUseProgram(p->id);
    glUniformMatrix4fv(p->mvp, 1, GL_FALSE, f->mvp.m);
    glUniform3f(p->eye, f->eye.x, f->eye.y, f->eye.z);
    glUniform3f(p->light_dir, f->light_dir.x, f->light_dir.y, f->light_dir.z);
    glUniform3fv(p->albedo, 1, f->albedo);
    glUniform3fv(p->light_color, 1, f->light_color);
    glUniform4fv(p->shading, 1, f->shading);
    if (p->light_z_scaled) {
        /* The depth row (column-major: every fourth from the third) as
         * the shadow test takes it, z c - 1/4 (mesh.vert). */
        float m[16], c = jdr_soft_c(r);
        memcpy(m, f->light_tex.m, sizeof m);
        for (int k = 0; k < 4; k++) m[2 + 4 * k] *= c;
        m[14] -= 0.25f;
        glUniformMatrix4fv(p->light_tex, 1, GL_FALSE, m);
    } else {
        glUniformMatrix4fv(p->light_tex, 1, GL_FALSE, f->light_tex.m);
    }
    glUniform4fv(p->light_map, 1, f->light_map);
    glUniform2fv(p->shadow_bias, 1, f->shadow_bias);
    if (p->f0 >= 0) glUniform1f(p->f0, f->f0);
    if (p->fresnel >= 0) glUniform2fv(p->fresnel, 1, f->fresnel);
    if (p->depth >= 0) glUniform1i(p->depth, 0);
    if (p->depth_v >= 0) glUniform1i(p->depth_v, 0);
    glActiveTexture(GL_TEXTURE0);
    /* full's programs read the exponential shadow map where the others
     * read the light map (light.glsl, jd_soft_lit). */
    glBindTexture(GL_TEXTURE_2D, p->soft_c >= 0 ? r->soft.tex : r->light.tex);
    if (p->soft_c >= 0) glUniform2f(p->soft_c, jdr_soft_c(r), jdr_soft_c(r) / 255.0f);
    if (p->local_x >= 0 || p->lw >= 0) { /* full: the local weight, the levels (either may be compiled out) */
        float lw[DIFF_LEVELS][3], ls[6] = {0}, wl[3] = {0};
        const jd_diffusion_fit *fit = &r->fit;
        for (int c = 0; c < 3; c++)
            for (int k = 0; k < DIFF_LOCAL; k++) wl[c] += fit->weight[k][c];
        /* On a lit point half of the first level's Gaussian is taken with
         * the local part, from the point's own light (half its weight added
         * here); the level's read keeps the other half there and all of it
         * where the point leaves the light (light.glsl, jd_diffused). */
        if (r->diff_levels > 0)
            for (int c = 0; c < 3; c++) wl[c] += DIFF_FIRST_SHARED * fit->weight[DIFF_LOCAL][c];
        for (int k = 0; k < DIFF_LEVELS; k++) {
            /* Times the 21/20 the levels' light was divided by, and the
             * first level's times its share: jd_diffused takes (2 - lit) of it. */
            float x = 21.0f / 20.0f * (k == 0 ? DIFF_FIRST_SHARED : 1.0f);
            for (int c = 0; c < 3; c++) lw[k][c] = k < r->diff_levels ? x * fit->weight[DIFF_LOCAL + k][c] : 0.0f;
            /* Light-depth units to the level's sigma * sqrt(2), in millimetres,
             * times sqrt(log2 e): the shaders take exp2 (light.glsl). */
            ls[k] = 1.20112241f * 2.0f * f->mm_per_world / (1.41421356f * fit->sigma_mm[DIFF_LOCAL + k]);
        }
        ls[5] = 1.0f / (float)r->d.diffusion_size; /* the spare slot: the first level's texel size */
        glUniform3fv(p->lw, DIFF_LEVELS, &lw[0][0]);
        glUniform3fv(p->ls, 2, ls);
        if (p->local_x >= 0) {
            /* The picture's constant factors, one product each: exposure,
             * light colour, Rd's local weight, the ambient's albedo, the
             * highlight's strength; the levels' sum read from the
             * half-resolution buffer comes halved (shade.frag). */
            float e = f->shading[3], wide = r->vertex_diffusion ? 1.0f : 2.0f, amb[3], loc[3], wid[3], spec[3];
            for (int c = 0; c < 3; c++) {
                amb[c] = f->albedo[c] * f->shading[0] * e;
                loc[c] = f->light_color[c] * wl[c] * e;
                wid[c] = f->light_color[c] * wide * e;
                spec[c] = f->light_color[c] * f->shading[1] * e;
            }
            glUniform3fv(p->amb_x, 1, amb);
            glUniform3fv(p->local_x, 1, loc);
            glUniform3fv(p->wide_x, 1, wid);
            glUniform3fv(p->spec_x, 1, spec);
        }
        if (p->keep >= 0) {
            /* The levels' half-resolution sum takes a lit face's share
             * halved, as it stores its sum (shade.frag): 1/2 - lit a/2
             * 2^(-b t), with a/2 here, not a multiply per vertex (lima's
             * vertex stage 51 -> 48 words). */
            float kp[2][3];
            for (int c = 0; c < 3; c++) {
                kp[0][c] = p == &r->wide_prog ? 0.5f * r->keep[0][c] : r->keep[0][c];
                kp[1][c] = r->keep[1][c];
            }
            glUniform3fv(p->keep, 2, &kp[0][0]);
        }
        if (p->wrap >= 0) {
            /* The local part's width where it meets the terminator: the
             * RMS width of its Gaussians (green's weights, and the half
             * of the first level's it takes on lit points), as an angle
             * at the surface's radius 1 / k (mesh_curvature.h). Its n.l
             * ramp smoothed over that angle by a box of the same variance,
             * half-width e = sqrt(3) sigma k (mesh.vert): u_wrap is e / k
             * in world units and 1 / 4e times k. */
            float sw = 0.0f, s2 = 0.0f;
            for (int k = 0; k <= DIFF_LOCAL; k++) {
                float wk = fit->weight[k][1];
                if (k == DIFF_LOCAL) wk *= r->diff_levels > 0 ? DIFF_FIRST_SHARED : 0.0f;
                sw += wk;
                s2 += wk * fit->sigma_mm[k] * fit->sigma_mm[k];
            }
            float ew = sw > 0.0f ? 1.7320508f * sqrtf(s2 / sw) / f->mm_per_world : 0.0f;
            glUniform2f(p->wrap, ew, ew > 0.0f ? 0.25f / ew : 1e4f);
        }
        if (p->bounce_rd >= 0) {
            /* The light between parts leaves the surface it came from and
             * enters this one: an albedo each. The levels' half-resolution
             * sum takes it halved, as it stores its sum (shade.frag). */
            float rd2[3], k = p == &r->wide_prog ? 0.5f : 1.0f;
            for (int c = 0; c < 3; c++) rd2[c] = k * f->albedo[c] * f->albedo[c];
            glUniform3fv(p->bounce_rd, 1, rd2);
        }
        glUniform4fv(p->light_map_v, 1, f->light_map);
        glUniform3f(p->light_dir_v, f->light_dir.x, f->light_dir.y, f->light_dir.z);
        if (p->slab >= 0) { /* unit 6: the wide buffer's, which these programs do not read */
            glUniform1i(p->slab, 6);
            glUniform1f(p->slab_scale, 2.0f * f->mm_per_world / r->slab_range_mm);
            glActiveTexture(GL_TEXTURE6);
            glBindTexture(GL_TEXTURE_2D, r->slab_tex);
        }
        if (p->light_depth_v >= 0) { /* unit 6 too: the levels summed per vertex read no slab table */
            float st[3], ss[3], st_min = 1e30f;
            for (int c = 0; c < 3; c++) {
                st[c] = (float)f->dipole.sigma_t[c];
                /* sigma_s / 4, and the light's way in at the boundary: the
                 * Fresnel transmittance at normal incidence (the face the
                 * light entered by is not known here). */
                ss[c] = (float)(f->dipole.alpha[c] * f->dipole.sigma_t[c]) * 0.25f * (1.0f - f->f0);
                if (st[c] > 0.0f && st[c] < st_min) st_min = st[c];
            }
            /* The march's reach: five mean free paths of the clearest
             * channel; its start under a lit point: two light-map texels,
             * finer than which the map's depths say nothing. */
            float texel_mm = 2.0f * f->mm_per_world / f->light_map[0];
            glUniform1i(p->light_depth_v, 6);
            glUniform3fv(p->march_st, 1, st);
            glUniform3fv(p->march_ss, 1, ss);
            glUniform4f(p->march, f->mm_per_world, 2.0f * f->mm_per_world, st_min < 1e30f ? 5.0f / st_min : 0.0f,
                        2.0f * texel_mm);
            glActiveTexture(GL_TEXTURE6);
            glBindTexture(GL_TEXTURE_2D, r->light.tex);
        }
        for (int i = 0; i < DIFF_TEXTURES; i++) {
            glUniform1i(p->lv[i] >= 0 ? p->lv[i] : p->lv_v[i], 1 + i);
            glActiveTexture(GL_TEXTURE1 + i);
            glBindTexture(GL_TEXTURE_2D, r->diff_lv[i].tex);
        }
        glActiveTexture(GL_TEXTURE0);
    }
    if (p->spec >= 0) { /* unit 1: a level's, which the programs reading this table do not read */
        glUniform1i(p->spec, 1);
        glActiveTexture(GL_TEXTURE1);
        glBindTexture(GL_TEXTURE_2D, r->spec_tex);
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
    if (p->albedo_norm >= 0) {
        /* With the texture, the fragment stage's entry mean (t0 + 2 t1) / 3,
         * written t0 / 2 + t1, takes its 2/3 from here: one multiply fewer
         * per fragment. */
        float k = p->albedo_map >= 0 ? 2.0f / 3.0f : 1.0f;
        glUniform3f(p->albedo_norm, k * f->albedo_norm[0], k * f->albedo_norm[1], k * f->albedo_norm[2]);
    }
    if (p->albedo_map >= 0) {
        glUniform1i(p->albedo_map, 7);
        glUniform1f(p->albedo_reach, f->albedo_reach);
        glActiveTexture(GL_TEXTURE7);
        glBindTexture(GL_TEXTURE_2D, r->albedo_tex);
        glActiveTexture(GL_TEXTURE0);
    }
    if (p->wide >= 0) {
        glUniform1i(p->wide, 6);
        glUniform2f(p->wide_scale, 0.5f * (float)r->wide.w / r->wide_fill.tw, 0.5f * (float)r->wide.h / r->wide_fill.th);
        glActiveTexture(GL_TEXTURE6);
        glBindTexture(GL_TEXTURE_2D, r->wide_fill.tex);
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

/* full's highlight, (n.h / |n|)^shininess of the interpolated normal n
 * and half vector h, as a table of n.n (SPEC_NN to 1, SPEC_W columns: a
 * face of a 12-triangle cube with shared corner normals reaches 0.41 in
 * its middle) and n.h (0 to 1, SPEC_H rows), read filtered (shade.frag).
 * The ratio is at most 1 (|h| <= 1). 8 bits: filtered, the steps between
 * texels are ramps, and a value under half a step (1/510) is lost where
 * the highlight adds under 0.0004 (its default strength, 0.2) to the
 * picture's linear light. Between texels the power changes by a factor of
 * at most e^(s/320) across and e^(s/255) up (s = 40: 13% and 17%); the
 * straight lines between them are within 0.3% of the curve there, 8% at
 * s = 200. Rebuilt only when the shininess changes. */
void jdr_update_spec(jd_renderer *r, const jd_scene *s, const frame_params *f)
{
    (void)s;
    float key = f->shading[2];
    if (key == r->spec_key) return;
    r->spec_key = key;
    /* As powers of 2: log2 c = log2 n.h - log2 n.n / 2, a row's and a
     * column's, so that a texel takes an exp2 only where its value is
     * between 1/512 and 1 (a band for a sharp highlight), not a pow each
     * (32,768: 0.66 ms a table on this x86 desktop, 0.07 ms so; a board's
     * CPU is several times slower, in the frame that changes it). The
     * same bytes. */
    double col[SPEC_W];
    for (int i = 0; i < SPEC_W; i++) col[i] = -0.5 * log2(SPEC_NN + (1.0 - SPEC_NN) * i / (SPEC_W - 1));
    for (int j = 0; j < SPEC_H; j++) {
        double row = j > 0 ? log2((double)j / (SPEC_H - 1)) : -INFINITY;
        for (int i = 0; i < SPEC_W; i++) {
            double e = key * (row + col[i]);
            r->spec_px[j * SPEC_W + i] = e >= 0.0 ? 255 : e < -9.0 ? 0 : (uint8_t)lrint(255.0 * exp2(e));
        }
    }
    glBindTexture(GL_TEXTURE_2D, r->spec_tex);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, SPEC_W, SPEC_H, GL_LUMINANCE, GL_UNSIGNED_BYTE, r->spec_px);
}

static void blur(jd_renderer *r, GLint step_loc, GLint inv_loc, const target *src, const target *dst, float dx,
                 float dy, float step, float inv2s2, const char *what)
{
    glBindTexture(GL_TEXTURE_2D, src->tex);
    glUniform2f(step_loc, dx * step / (float)src->tw, dy * step / (float)src->th);
    glUniform1f(inv_loc, inv2s2);
    jdr_draw_quad_into(r, dst, what, src);
}

/* A low-resolution layer drawn with a shading program: cleared to "not
 * covered" (alpha 0), depth-tested, culled as the main pass; of the light
 * map's proxy (levels: full's sum of the levels) or of the coarser capture
 * proxy (the spread's A0). */
static void draw_layer(jd_renderer *r, const target *t, const shade_prog *p, const frame_params *f, int levels,
                       const char *what)
{
    jdr_use_target(r, t, what);
    /* Two texels past the layer's region too: the picture reads the layer
     * filtered, and at its top and right edges the filter reaches the
     * texel beyond, which a frame with a larger layer (the camera farther)
     * left there (tests/test_frame_history.c); the levels' sum is filled
     * there too, from the texel beyond that (jdr_pass_wide). */
    glScissor(0, 0, t->w + 2 < t->tw ? t->w + 2 : t->tw, t->h + 2 < t->th ? t->h + 2 : t->th);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glScissor(0, 0, t->w, t->h);
    glEnable(GL_DEPTH_TEST);
    if (r->d.no_cull) glDisable(GL_CULL_FACE); else glEnable(GL_CULL_FACE);
    set_shade_uniforms(r, p, f, t->w, t->h);
    jdr_counted_read(r, &r->light, 1);
    if (levels) {
        for (int i = 0; i < r->diff_levels; i++) jdr_counted_read(r, &r->diff_lv[i], 1);
        jdr_bind_mesh(r->proxy_vbo, r->proxy_ibo);
        jdr_draw_elements(r, 1, &f->mvp, (GLsizei)r->proxy.num_indices, GL_UNSIGNED_SHORT, 0, -1);
    } else {
        jdr_counted_read(r, &r->irr[0], 6);
        jdr_bind_mesh(r->cap_vbo, r->cap_ibo);
        jdr_draw_elements(r, 2, &f->mvp, (GLsizei)r->capture_proxy.num_indices, GL_UNSIGNED_SHORT, 0, -1);
    }
}

void jdr_pass_spread(jd_renderer *r, const jd_scene *s, const frame_params *f)
{
    (void)s;
    /* A0 at low resolution from the coarse capture proxy: these layers are
     * blurred, so a finer mesh would buy nothing but vertex work. */
    draw_layer(r, &r->spread0, &r->a0, f, 0, "spread-a0");

    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    jdr_bind_quad(r);
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

/* Without vertex diffusion, full's levels are summed per fragment at a
 * lower resolution, read once (bilinear) in the main pass: the levels are
 * smooth (their finest Gaussian is a level texel wide), so two samples per
 * level texel across the picture will do, 1/2 to 1/8 of its resolution (a
 * thinner part than 8 pixels takes the levels' light of its neighbours, or
 * none where it has no covered neighbour). Drawn from the light map's
 * proxy, the surface the levels' light entered at, not the mesh: the
 * GPUs that sum the levels so (a vertex stage that cannot read the six
 * textures: Mali-400/450, Vivante GC400-GC2000, any at GLES 2.0's least)
 * shade every vertex of every draw, and the default asset's 46,080
 * vertices took Mali-400's vertex processor a third of its frame for a
 * layer of 3,762 fragments (3,510 vertices now; against the reference
 * the bunny's table as close or closer in 11 cases of 12, skin1 back-lit
 * 0.5% further; held-out meshes within 3% either way). */
static int object_box(jd_renderer *r, const jd_mat4 *mvp, int w, int h, int pad, int box[4]);

void jdr_pass_wide(jd_renderer *r, const jd_scene *s, const frame_params *f)
{
    (void)s;
    float level_px = 2.0f / (float)r->d.diffusion_size * f->px_per_world;
    int div = (int)(level_px * 0.5f);
    div = div < 2 ? 2 : div > 8 ? 8 : div;
    r->wide.w = (r->iw + div - 1) / div;
    r->wide.h = (r->ih + div - 1) / div;
    draw_layer(r, &r->wide, &r->wide_prog, f, 1, "wide");
    jdr_counted_trips(r, r->wide_unrolled ? 1 : 4); /* jd_level_at's texels */
    /* Its outline filled (wide_fill.frag) over the object's box, two texels
     * more on each side (the picture's filter reaches one past a covered
     * texel), and the texel past the region where the box reaches its edge:
     * over the whole layer it took 32,776 fragments of the default scene
     * where the box takes 9,976. The rest is never read. */
    target fill = r->wide_fill;
    fill.w = r->wide.w < fill.tw ? r->wide.w + 1 : fill.tw;
    fill.h = r->wide.h < fill.th ? r->wide.h + 1 : fill.th;
    int box[4];
    if (!object_box(r, &f->mvp, r->wide.w, r->wide.h, 2, box)) return;
    if (box[2] == r->wide.w) box[2] = fill.w;
    if (box[3] == r->wide.h) box[3] = fill.h;
    const int rect[4] = {box[0], box[1], box[2] - box[0], box[3] - box[1]};
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    jdr_bind_quad(r);
    glUseProgram(r->fill_prog);
    glUniform1i(r->fill_src, 0);
    glUniform2f(r->fill_scale, (float)fill.w / (float)r->wide.tw, (float)fill.h / (float)r->wide.th);
    glUniform2f(r->fill_texel, 0.5f / (float)r->wide.tw, 0.5f / (float)r->wide.th);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, r->wide.tex);
    jdr_draw_quad_rect(r, &fill, "wide-fill", &r->wide, rect);
}

void jdr_pass_main(jd_renderer *r, const jd_scene *s, const frame_params *f)
{
    /* Into the target, or into `scene` for the pass after: anti-aliasing,
     * or enlarging a picture drawn smaller. */
    int via_scene = jdr_via_scene(r);
    int w = r->iw, h = r->ih;
    /* "main": at the picture's resolution (the frame-cost model's name). */
    jdr_count_target(r, w == r->d.width && h == r->d.height ? "main" : "shade-scaled", w, h);
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
    /* Where the pass after reads each pixel's luma from the alpha
     * (luma_alpha: the pass runs on every frame, through `scene`), the
     * background's is cleared there too, by pack.glsl's JD_LUMA. */
    int luma = r->luma_alpha;
    glClearColor(bg[0], bg[1], bg[2], luma ? 0.299f * bg[0] + 0.587f * bg[1] + 0.114f * bg[2] : 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glScissor(0, 0, w, h);
    glEnable(GL_DEPTH_TEST);
    if (r->d.no_cull) glDisable(GL_CULL_FACE); else glEnable(GL_CULL_FACE);
    set_shade_uniforms(r, &r->shade[s->mode], f, w, h);
    jdr_counted_read(r, &r->light, 1);
    if (s->mode == JD_MODE_FULL && !r->vertex_diffusion) jdr_counted_read(r, &r->wide_fill, 1);
    if (s->mode == JD_MODE_FULL && r->vertex_diffusion) {
        for (int i = 0; i < r->diff_levels; i++) jdr_counted_read(r, &r->diff_lv[i], 1);
        /* the light map itself, along the camera rays (jd_single_march) */
        if (r->shade[s->mode].light_depth_v >= 0) jdr_counted_read(r, &r->light, 1);
    }
    if (s->mode == JD_MODE_SINGLE || s->mode == JD_MODE_DUAL) jdr_counted_read(r, &r->irr[0], 6);
    if (s->mode == JD_MODE_DUAL) jdr_counted_read(r, &r->spread2, 1);
    /* The shading's alpha is not the picture's: shade.frag writes the luma
     * for the pass after (above), or else what saved lima two instruction
     * words, and the clear's 1 stays. The pass writes 1. */
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, luma ? GL_TRUE : GL_FALSE);
    jdr_draw_mesh(r, &f->mvp);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

/* The object's extent on screen in NDC: the proxy's vertices projected,
 * and as far again as the mesh may lie from its proxy (proxy_error, at the
 * nearest vertex's depth). The bunny's box corners took 2.6 times the
 * pixels at 1080p, each one a fragment of the pass after the frame. Found
 * again only when the transform changes (a still camera keeps it). 0: a
 * vertex behind the camera, filter everything. */
static int object_extent(jd_renderer *r, const jd_mat4 *mvp, float *x0, float *y0, float *x1, float *y1)
{
    const float *m = mvp->m;
    if (!r->extent_valid || memcmp(r->extent_mvp, m, sizeof r->extent_mvp)) {
        float e0 = 1, f0 = 1, e1 = -1, f1 = -1, w_min = 1e30f;
        int inside = 1;
        for (uint32_t i = 0; i < r->proxy.num_vertices && inside; i++) {
            const float *q = r->proxy.positions + 3 * i;
            jd_vec3 p = jd_v3_scale(jd_v3_sub(jd_v3(q[0], q[1], q[2]), r->place_c), r->place_inv_r);
            float cx = m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12], cy = m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13];
            float cw = m[3] * p.x + m[7] * p.y + m[11] * p.z + m[15];
            if (cw <= 1e-4f) { inside = 0; break; }
            e0 = fminf(e0, cx / cw); e1 = fmaxf(e1, cx / cw);
            f0 = fminf(f0, cy / cw); f1 = fmaxf(f1, cy / cw);
            w_min = fminf(w_min, cw);
        }
        if (inside) { /* world units to NDC at the nearest depth: the transform's scale over w */
            float sx = sqrtf(m[0] * m[0] + m[4] * m[4] + m[8] * m[8]), sy = sqrtf(m[1] * m[1] + m[5] * m[5] + m[9] * m[9]);
            float e = r->proxy_error * fmaxf(sx, sy) / w_min;
            e0 -= e; e1 += e; f0 -= e; f1 += e;
        }
        float ext[4] = {e0, f0, e1, f1};
        memcpy(r->extent, ext, sizeof ext);
        memcpy(r->extent_mvp, m, sizeof r->extent_mvp);
        r->extent_inside = inside;
        r->extent_valid = 1;
    }
    *x0 = r->extent[0]; *y0 = r->extent[1]; *x1 = r->extent[2]; *y1 = r->extent[3];
    return r->extent_inside;
}

/* The object's box on screen in a w x h target's pixels, `pad` more on
 * each side and clamped to it: 0 where nothing of it is on screen. The
 * whole target where a vertex lies behind the camera. */
static int object_box(jd_renderer *r, const jd_mat4 *mvp, int w, int h, int pad, int box[4])
{
    float x0, y0, x1, y1;
    box[0] = box[1] = 0;
    box[2] = w;
    box[3] = h;
    if (!object_extent(r, mvp, &x0, &y0, &x1, &y1)) return 1;
    int px0 = (int)floorf((x0 * 0.5f + 0.5f) * w) - pad, px1 = (int)ceilf((x1 * 0.5f + 0.5f) * w) + pad;
    int py0 = (int)floorf((y0 * 0.5f + 0.5f) * h) - pad, py1 = (int)ceilf((y1 * 0.5f + 0.5f) * h) + pad;
    box[0] = px0 < 0 ? 0 : px0;
    box[1] = py0 < 0 ? 0 : py0;
    box[2] = px1 > w ? w : px1;
    box[3] = py1 > h ? h : py1;
    return box[2] > box[0] && box[3] > box[1];
}

/* One full-target quad of `prog` reading `src` (its used part) into the
 * bound framebuffer, inside the scissor box `box`, counted as `fragments`
 * (< 0: its area). */
static void filter_quad(jd_renderer *r, GLuint prog, GLint src_loc, GLint scale_loc, GLint texel_loc, const target *src,
                        const int box[4], double fragments)
{
    glScissor(box[0], box[1], box[2] - box[0], box[3] - box[1]);
    glUseProgram(prog);
    glUniform1i(src_loc, 0);
    glUniform2f(scale_loc, (float)src->w / (float)src->tw, (float)src->h / (float)src->th);
    if (texel_loc >= 0) glUniform2f(texel_loc, 1.0f / (float)src->tw, 1.0f / (float)src->th);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, src->tex);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    double n = fragments >= 0 ? fragments : (double)(box[2] - box[0]) * (box[3] - box[1]);
    jdr_counted_quad(r, n, 4, 2);
    jd_pass_count *p = jdr_counted(r);
    if (p) p->bytes_read += n * 4.0 * ((double)src->w / p->width) * ((double)src->h / p->height);
}

/* The pass after the frame over `box` of the bound framebuffer, reading
 * `src`. Where that framebuffer has a depth buffer (jdr_aa_marks: cleared
 * to 1 with the colour), the pass's own test runs first and alone
 * (antialias.frag with JD_AA_MARK: 17 of the whole pass's 63 instructions
 * on the Vivante GC2000, 60 of 154 on the Adreno 306, by the compiler
 * table, each pixel's luma read from the frame's alpha): it copies a flat
 * pixel and writes its depth, and discards an edge pixel. The whole pass then runs under the depth test, which the GPU
 * makes before the fragment shader (early Z: Mesa's etnaviv and freedreno
 * a3xx allow it for a program that neither discards nor writes its depth),
 * so it shades the edges only: at the close-up of the frame-cost table,
 * 17,243 of the box's 491,130 pixels at 960x540. The picture is the one
 * pass's, pixel for pixel: a pixel the mark copies is one the whole pass
 * leaves as it was (tests/test_antialias.c). */
static void smooth_box(jd_renderer *r, const target *src, const int box[4])
{
    if (!jdr_aa_marks(r)) {
        filter_quad(r, r->aa_prog, r->aa_src, r->aa_scale, r->aa_texel, src, box, -1);
        return;
    }
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    filter_quad(r, r->aa_mark_prog, r->aa_mark_src, r->aa_mark_scale, r->aa_mark_texel, src, box, -1);
    glDepthFunc(GL_LESS); /* the quad's depth (0.5) passes where the clear's 1 is left */
    glDepthMask(GL_FALSE);
    filter_quad(r, r->aa_prog, r->aa_src, r->aa_scale, r->aa_texel, src, box, r->count ? r->count_edges : -1);
    glDepthMask(GL_TRUE);
    glDisable(GL_DEPTH_TEST);
}

/* The frame from `scene` into the platform's target, its edges smoothed,
 * enlarged where it was drawn smaller. Only the object's box on screen (its
 * corners projected, two pixels more) is filtered; the rest is background,
 * cleared. Drawn smaller and smoothed too (a target without samples, or a
 * multisampled one whose samples the smaller picture could not be drawn
 * with), it is smoothed at its own size first, into `aa_mid`, and that enlarged: the
 * pass after the frame costs its instructions per pixel it filters, and at
 * 960x540 for 1920x1080 that is a quarter of the pixels (Vivante GC2000,
 * 62 instructions: 15.2 ms of the 1080p frame against 3.8, before the pass
 * shaded only its edges). */
void jdr_pass_final(jd_renderer *r, const jd_scene *s, const frame_params *f)
{
    int scaled = r->iw != r->d.width || r->ih != r->d.height, box[4];
    float bg[3];
    for (int c = 0; c < 3; c++) bg[c] = sqrtf(fmaxf(s->background[c], 0.0f));
    glClearColor(bg[0], bg[1], bg[2], 1);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    jdr_bind_quad(r);
    const target *src = &r->scene;
    if (r->aa_now && scaled) {
        /* The enlarging below reads its box's texels and their bilinear
         * neighbours: its box (two pixels round the object, a texel here)
         * and a texel more lie inside this one's three. */
        jdr_count_target(r, "antialias-scaled", r->iw, r->ih);
        glBindFramebuffer(GL_FRAMEBUFFER, r->aa_mid.fbo);
        glViewport(0, 0, r->iw, r->ih);
        /* Cleared whole, as a tiler wants a target it draws (else it
         * loads the last frame's tiles), and for the mark in the depth. */
        glScissor(0, 0, r->iw, r->ih);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        if (object_box(r, &f->mvp, r->iw, r->ih, 3, box)) smooth_box(r, &r->scene, box);
        src = &r->aa_mid;
    }
    int smooth_here = r->aa_now && !scaled;
    jdr_count_target(r, smooth_here ? "main-antialias" : "main-upscale", r->d.width, r->d.height);
    glBindFramebuffer(GL_FRAMEBUFFER, r->d.target_fbo);
    glViewport(0, 0, r->d.width, r->d.height);
    glScissor(0, 0, r->d.width, r->d.height);
    glClear(GL_COLOR_BUFFER_BIT | (r->target_depth ? GL_DEPTH_BUFFER_BIT : 0));
    if (!object_box(r, &f->mvp, r->d.width, r->d.height, 2, box)) return;
    /* The quad spans the target; its texture coordinates the used part of
     * the source, whatever its size: drawn smaller, it is enlarged here. */
    if (smooth_here)
        smooth_box(r, src, box);
    else
        filter_quad(r, r->up_prog, r->up_src, r->up_scale, -1, src, box, -1);
}
