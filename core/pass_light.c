/* The light's passes: the light-depth map every mode shadows with, and
 * full's diffusion of the light that entered, level by level in light space. */
#include "renderer_internal.h"
#include "slab.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Least squares of log2(1 - k) on a line in d, over the samples where
 * 0.01 < 1 - k < 1: k(d) = 1 - a 2^(-b d), which the vertex stages
 * evaluate with no texture read. b comes out per mm; a = 0 where the
 * samples give no decay (nothing is lost: k = 1). */
static void fit_keep(const double *d, const double *k, int n, double *a, double *b)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0, sn = 0;
    for (int i = 0; i < n; i++) {
        double lose = 1.0 - k[i];
        if (lose > 0.01 && lose < 1.0) {
            double y = log2(lose);
            sx += d[i], sy += y, sxx += d[i] * d[i], sxy += d[i] * y, sn += 1.0;
        }
    }
    double den = sn * sxx - sx * sx;
    *b = den > 0.0 ? -(sn * sxy - sx * sy) / den : 0.0;
    double la = sn > 0.0 ? (sy + *b * sx) / sn : -30.0;
    *a = sn >= 2.0 && *b > 0.0 ? fmin(exp2(la), 1.0) : 0.0;
    if (*a == 0.0) *b = 0.0;
}

/* The light a part d mm thick lets through to its far face, which the
 * levels' Gaussians of the depth gap do not give: a slab lit on one face
 * sends T(d) of the light out of the other (the multipole, slab.h; the
 * reference carries the same across its thin parts), where the levels
 * give sum_k w_k G_k(d) for a point d below a uniformly lit face. The
 * table's rows hold the two per channel (times 21/20, the light map's
 * scale), over d from 0 to 4 sigma of the widest level: the shading adds
 * T at the part's thickness less the levels at the depth gap, times the
 * light that entered above (light.glsl, jd_slab_light), at points that
 * face away from the light. Added, not multiplied: the levels also bring
 * light from beside the point, which a factor on their sum would scale
 * with the thickness below. Two rows, not their difference: a light
 * slanted across a part crosses it longer than the part is thick, and the
 * reference carries the light along the normal. */
static void update_slab(jd_renderer *r, const frame_params *f)
{
    const jd_diffusion_fit *fit = &r->fit;
    float range = 4.0f * fit->sigma_mm[DIFF_LOCAL + (r->diff_levels > 0 ? r->diff_levels - 1 : 0)];
    double slack = 2.0 * f->mm_per_world * f->light_map[3]; /* depth units to mm */
    /* On a lit face of a part d mm thick, the share of the half-space's
     * light that makes the face return the slab's R(d) (the light that
     * went deep leaves through the far side): the reference's profile on
     * a slab loses at every radius, so the local part (the Gaussians finer
     * than a level texel) loses with the levels (with the levels alone
     * taking the loss, a thin part's shadow edge came out 0.82 of the
     * reference's width). The local part's share rides in full's Fresnel
     * term, one number a vertex: green's R(d) / Rd, for all channels;
     * green's levels keep the same, red's and blue's make up their
     * channel's R(d) Rd with the local part at green's share. Each fitted
     * as 1 - a 2^(-b d) (fit_keep; VideoCore IV's vertex program went from
     * 161 to 615 instructions with a table read for it instead). d: the
     * part's thickness along the normal (mesh_thickness.c), as the
     * reference takes it. */
    unsigned char px[SLAB_SIZE * 8];
    double dd[SLAB_SIZE], refl[3][SLAB_SIZE];
    for (int i = 0; i < SLAB_SIZE; i++) {
        double d = (i + 0.5) / SLAB_SIZE * range, q = fmax(d - slack, 0.0);
        dd[i] = d;
        for (int c = 0; c < 3; c++) {
            double trans, levels = 0.0, rd = f->dipole.rd_total[c];
            jd_slab_totals(&f->dipole, c, d, &refl[c][i], &trans);
            for (int k = 0; k < r->diff_levels; k++) {
                double u = q / fit->sigma_mm[DIFF_LOCAL + k];
                levels += fit->weight[DIFF_LOCAL + k][c] * exp(-0.5 * u * u);
            }
            /* Both rows as square roots, as the levels keep their light:
             * the shading takes their difference, which on a far face is
             * a few parts in a hundred, and in 8 bits a step of 1/255
             * there came out as patches with stepped edges where it
             * crossed zero (the fandisk back-lit in skin1, green and blue:
             * docs/quality.md, "The light through thin parts where it does
             * not come through"). */
            px[4 * i + c] = (unsigned char)lrint(255.0 * sqrt(fmin(21.0 / 20.0 * trans * rd, 1.0)));
            px[4 * (SLAB_SIZE + i) + c] = (unsigned char)lrint(255.0 * sqrt(fmin(21.0 / 20.0 * levels, 1.0)));
        }
        px[4 * i + 3] = 255, px[4 * (SLAB_SIZE + i) + 3] = 255;
    }
    double kg[SLAB_SIZE], kc[SLAB_SIZE];
    for (int n = 0; n < 3; n++) {
        int c = (n + 1) % 3;
        /* On a lit face half of the first level's weight rides with the
         * local part (jd_diffused), so the levels' light holds the other half. */
        double a, b, rd = f->dipole.rd_total[c], wide = r->diff_levels > 0 ? DIFF_FIRST_SHARED * fit->weight[DIFF_LOCAL][c] : 0.0;
        for (int k = 1; k < r->diff_levels; k++) wide += fit->weight[DIFF_LOCAL + k][c];
        for (int i = 0; i < SLAB_SIZE; i++)
            kc[i] = c == 1 ? refl[c][i] : wide > 0.0 ? (refl[c][i] * rd - (rd - wide) * kg[i]) / wide : 1.0;
        fit_keep(dd, kc, SLAB_SIZE, &a, &b);
        if (c == 1)
            for (int i = 0; i < SLAB_SIZE; i++) kg[i] = 1.0 - a * exp2(-b * dd[i]);
        /* per world unit: the shaders take the thickness in the sphere's units */
        r->keep[0][c] = (float)a, r->keep[1][c] = (float)(b * f->mm_per_world);
    }
    r->slab_range_mm = range;
    glBindTexture(GL_TEXTURE_2D, r->slab_tex);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, SLAB_SIZE, 2, GL_RGBA, GL_UNSIGNED_BYTE, px);
}

/* The full mode's sum of Gaussians: the finest below a level texel (applied
 * at the shaded point), then one per light-space level, and the light
 * through thin parts that they miss. Refitted only when the material, the
 * scale or the light map's depth slack changes. */
void jdr_update_fit(jd_renderer *r, const jd_scene *s, const frame_params *f)
{
    float key[10] = {s->sigma_s[0], s->sigma_s[1], s->sigma_s[2], s->sigma_a[0], s->sigma_a[1],
                     s->sigma_a[2], s->eta, s->density, f->mm_per_world, f->light_map[3]};
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
    update_slab(r, f);
}

void jdr_pass_light_depth(jd_renderer *r, const jd_scene *s, const frame_params *f)
{
    (void)s;
    jdr_use_target(r, &r->light, "light-depth");
    glClearColor(1, 0, 0, 0); /* packed 1.0: nothing in front; no light */
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    /* Only surfaces facing the light can be the nearest to it. */
    if (r->d.no_cull) glDisable(GL_CULL_FACE); else glEnable(GL_CULL_FACE);
    glUseProgram(r->depth_prog);
    glUniformMatrix4fv(r->depth_mvp, 1, GL_FALSE, f->light_mvp.m);
    glUniform3f(r->depth_light_dir, f->light_dir.x, f->light_dir.y, f->light_dir.z);
    glUniform2fv(r->depth_fresnel, 1, f->fresnel);
    jdr_bind_mesh(r->proxy_vbo, r->proxy_ibo);
    jdr_draw_elements(r, 1, &f->light_mvp, (GLsizei)r->proxy.num_indices, GL_UNSIGNED_SHORT, 0, -1);
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
    glUniform2f(p->ref_scale, (float)from->tw / (float)from->w, (float)from->th / (float)from->h);
    glUniform2f(p->uv_scale, (float)from->w / from->tw, (float)from->h / from->th);
    glUniform2f(p->step, sx, sy);
    if (box) /* a square of 2 x 2 taps a trip; the side is the program's JD_BOX_SIDE */
        glUniform1i(p->taps, box > 1 ? box * box / 4 : 1);
    else {
        float w[DIFF_TAPS + 1];
        for (int i = 0; i <= taps; i++) w[i] = expf(-(float)(i * i) / (2.0f * st * st));
        glUniform1i(p->taps, taps);
        glUniform1fv(p->w, taps + 1, w);
    }
    glUniform1f(p->near, near);
    glBindTexture(GL_TEXTURE_2D, from->tex);
    jdr_draw_quad_into(r, to, what, from);
    jdr_counted_read(r, &r->light, 1); /* the reference depths */
    /* Built with its trips unrolled, the program's own count holds them all. */
    jdr_counted_trips(r, p->trips ? 1 : box ? (box > 1 ? box * box / 4 : 1) : taps);
}

/* Level k's blur (both directions): its taps a side, their spacing in
 * source texels and their Gaussian's sigma in taps. Level k is level k-1
 * blurred by the Gaussian whose variance brings it to sigma_k = 2^k
 * first-level texels (variances add); level 1 blurs the squares, whose
 * own variance is a box's. The same for every frame of a renderer: the
 * programs are built for its trip count (render_program.c). */
int jdr_diffusion_taps(const jd_renderer *r, int k, float *step, float *st)
{
    int box = r->d.light_map_size / r->d.diffusion_size;
    /* The square's variance in level texels (a box of n: (n^2 - 1) / 12 n^2). */
    float prev = k == 0 ? sqrtf((float)(box * box - 1) / (12.0f * (float)(box * box))) : (float)(1 << (k - 1));
    float sigma = (float)(1 << k), inc = sqrtf(sigma * sigma - prev * prev);
    /* First-level texels per source texel: texture k has 2^((k+1)/2) of
     * them per texel (1, 2, 2, 4, 4); level 1 reads the squares. */
    float per_src = k == 0 ? 1.0f : (float)(1 << (k / 2));
    float sig = inc / per_src; /* in source texels, also tmp's rows */
    /* The first level's blur reads the squares, sharp at their texels:
     * taps half a sigma (at least a texel) apart. Later levels read a
     * level already blurred by sigma_(k-1), at least 1/sqrt(3) of this
     * step's increment: taps a sigma apart (3 a side, not 6) sample it
     * without a ripple (the Gaussian's alias at that spacing is
     * exp(-2 pi^2 / 3), 0.1%), at half the cost. */
    float spacing = k == 0 ? sig * 3.0f / DIFF_TAPS : sig;
    *step = fmaxf(spacing, 1.0f);
    *st = sig / *step;
    /* Taps out to 2 sigma, no more: out to 3 (7 taps, 2 loop trips more
     * a pass, a quarter more of the diffusion's cost) the pictures were
     * further from the reference, not closer, and showed more blotches:
     * a tap far out that alone finds lit texels beside an unlit stretch
     * gets the whole of the normalised convolution's weight there (the
     * fandisk back-lit, docs/frame-cost.md). The five weights' variance is
     * 6-8% under sigma^2; widened to match it they blotched as the seven
     * did. */
    return (int)fminf(ceilf(2.0f * *st), (float)DIFF_TAPS);
}

/* The full mode's light-space levels: level k is level k-1 blurred by the
 * Gaussian whose variance brings it to sigma_k (variances add), so every
 * step is short. Level 1 comes from the light-depth map: its texels
 * gathered in squares of one level texel (a box's variance), then blurred
 * by the rest of its Gaussian. A horizontal pass into diff_tmp (the
 * destination's width, the source's height), a vertical one into the
 * level's texture. Sigmas are counted in texels of the first level;
 * texture k has 2^((k+1)/2) of those per texel (1, 2, 2, 4, 4): every
 * level's Gaussian is at least one of its own texels wide. */
void jdr_pass_diffusion(jd_renderer *r, const jd_scene *s, const frame_params *f)
{
    (void)s;
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    jdr_bind_quad(r);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, r->light.tex);
    glActiveTexture(GL_TEXTURE0);
    /* Light-depth units per first-level texel: the map spans 2 world units
     * across and 2 in depth, so units of width and depth are alike. */
    float texel = 1.0f / (float)r->d.diffusion_size, map_texel = 1.0f / (float)r->d.light_map_size;
    int box = r->d.light_map_size / r->d.diffusion_size;
    for (int k = 0; k < r->diff_levels; k++) {
        float sigma = (float)(1 << k);
        target *dst = &r->diff_lv[k], *tmp = &r->diff_tmp;
        /* Light within 3 sigma (and two map texels) of a texel's own
         * surface in depth is that surface's; the rest came from elsewhere.
         * At 1.5 sigma a surface slanted past 56 degrees to the light split
         * in two within a texel, and its deeper half was weighed against the
         * point's depth as if another surface's. 3 sigma put full closer to
         * Cycles in all eight of tests/cycles_truth.sh's cases and to the
         * reference with light between parts in all eight of the bunny's,
         * with 5% less high-pass error and 3% less flicker (docs/quality.md,
         * "The levels' depth window"). */
        float near = 3.0f * sigma * texel + 2.0f * map_texel + f->light_map[3];
        if (k == 0) /* the squares, into the level itself: the blur reads them from there */
            diffuse_step(r, &r->diff_first, &r->light, dst, 1.0f / (float)r->light.tw, 1.0f / (float)r->light.th, 0,
                         0.0f, box, near, "diffusion-1box");
        const target *src = k == 0 ? dst : &r->diff_lv[k - 1];
        float step, st;
        int taps = jdr_diffusion_taps(r, k, &step, &st);
        tmp->w = dst->w;
        tmp->h = src->h;
        /* The vertical pass's taps reach a few rows past those the
         * horizontal one writes, and tmp is as tall as the light map: there
         * lay a wider level's rows from earlier in the frame (light from the
         * middle of the map, at its edge) or, never written, whatever the
         * memory held (a new texture's contents are undefined, and a driver
         * that reuses freed buffers hands over another target's data). A
         * band of no light there (depth 1, S 0: the normalised convolution
         * leaves it out), as past the light map's edge. */
        int band = (int)ceilf((float)taps * step) + 1;
        if (band > tmp->th - tmp->h) band = tmp->th - tmp->h;
        if (band > 0) {
            glBindFramebuffer(GL_FRAMEBUFFER, tmp->fbo);
            glScissor(0, tmp->h, tmp->w, band);
            glClearColor(0.0f, 1.0f, 0.0f, 1.0f);
            glClear(GL_COLOR_BUFFER_BIT);
        }
        char what[24];
        snprintf(what, sizeof what, "diffusion-%dh", k + 1);
        diffuse_step(r, &r->diff_next, src, tmp, step / (float)src->tw, 0.0f, taps, st, 0, near, what);
        snprintf(what, sizeof what, "diffusion-%dv", k + 1);
        diffuse_step(r, &r->diff_next, tmp, dst, 0.0f, step / (float)tmp->th, taps, st, 0, near, what);
    }
}

/* full's exponential shadow map's exponent per light-depth unit: 0.25 per
 * texel of depth (light.glsl, jd_soft_lit, whose slack of a texel, the
 * - 0.25 in mesh.vert, is this exponent times a texel: change them
 * together). */
float jdr_soft_c(const jd_renderer *r)
{
    return 0.25f * (float)r->d.light_map_size;
}

/* The texels of a light-space target of n x n that the light map's proxy
 * covers, and `margin` more each way: x, y, w, h. Its vertices taken
 * through the light's matrix on the CPU, once for each light (a few
 * thousand): their box is half to two thirds of the one the bounding box's
 * corners make, and the passes that use it cost that much less. */
static void object_rect(const jd_renderer *r, const frame_params *f, int n, int margin, int rect[4])
{
    /* light map xy = M ((p - c) inv_r): the map's rows of M folded with the placement */
    const float *m = f->light_tex.m, k = r->place_inv_r;
    float ax = m[0] * k, bx = m[4] * k, cx = m[8] * k, ay = m[1] * k, by = m[5] * k, cy = m[9] * k;
    float dx = m[12] - ax * r->place_c.x - bx * r->place_c.y - cx * r->place_c.z;
    float dy = m[13] - ay * r->place_c.x - by * r->place_c.y - cy * r->place_c.z;
    float lo[2] = {1.0f, 1.0f}, hi[2] = {0.0f, 0.0f};
    const float *p = r->proxy.positions;
    for (uint32_t i = 0; i < r->proxy.num_vertices; i++, p += 3) {
        float x = ax * p[0] + bx * p[1] + cx * p[2] + dx, y = ay * p[0] + by * p[1] + cy * p[2] + dy;
        lo[0] = fminf(lo[0], x), hi[0] = fmaxf(hi[0], x);
        lo[1] = fminf(lo[1], y), hi[1] = fmaxf(hi[1], y);
    }
    int x0 = (int)floorf(lo[0] * (float)n) - margin, y0 = (int)floorf(lo[1] * (float)n) - margin;
    int x1 = (int)ceilf(hi[0] * (float)n) + margin, y1 = (int)ceilf(hi[1] * (float)n) + margin;
    x0 = x0 < 0 ? 0 : x0, y0 = y0 < 0 ? 0 : y0;
    x1 = x1 > n ? n : x1, y1 = y1 > n ? n : y1;
    rect[0] = x0, rect[1] = y0;
    rect[2] = x1 > x0 ? x1 - x0 : 0, rect[3] = y1 > y0 ? y1 - y0 : 0;
}

/* full's shadow test, made once for the light: the light map's depths as
 * an exponential shadow map blurred by a Gaussian of 1.2 texels
 * (soft_shadow.frag), across into soft_tmp, then down into soft, each pass
 * halving the resolution in its direction. The shading reads it
 * bilinearly where the other modes read the light map. */
void jdr_pass_soft_shadow(jd_renderer *r, const jd_scene *s, const frame_params *f)
{
    (void)s;
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    jdr_bind_quad(r);
    glUseProgram(r->soft_prog);
    glUniform1i(r->soft_src, 0);
    glUniform2f(r->soft_c, jdr_soft_c(r), 1.0f / jdr_soft_c(r));
    glUniform2f(r->soft_scale, (float)r->light.w / (float)r->light.tw, (float)r->light.h / (float)r->light.th);
    glActiveTexture(GL_TEXTURE0);
    glUniform2f(r->soft_step, 1.0f / (float)r->light.tw, 0.0f);
    glBindTexture(GL_TEXTURE_2D, r->light.tex);
    /* Only around the object: the shading reads the map where the object
     * is (rect, in the map's texels, with 3 to spare each way beyond the
     * proxy, whose vertices may lie inside the mesh's outline by its
     * error; the map spans 2 world units), and the
     * second pass reads the first's rows up to 2.5 light-map texels beyond
     * its own. */
    int rect[4];
    object_rect(r, f, r->soft.w, 3 + (int)ceilf(r->proxy_error * 0.5f * (float)r->soft.w), rect);
    int row0 = 2 * rect[1] - 3, row1 = 2 * (rect[1] + rect[3]) + 3;
    row0 = row0 < 0 ? 0 : row0;
    row1 = row1 > r->soft_tmp.h ? r->soft_tmp.h : row1;
    const int tmp_rect[4] = {rect[0], row0, rect[2], row1 - row0};
    jdr_draw_quad_rect(r, &r->soft_tmp, "soft-shadow-h", &r->light, tmp_rect);
    glUniform2f(r->soft_scale, (float)r->soft_tmp.w / (float)r->soft_tmp.tw, (float)r->soft_tmp.h / (float)r->soft_tmp.th);
    glUniform2f(r->soft_step, 0.0f, 1.0f / (float)r->soft_tmp.th);
    glBindTexture(GL_TEXTURE_2D, r->soft_tmp.tex);
    jdr_draw_quad_rect(r, &r->soft, "soft-shadow-v", &r->soft_tmp, rect);
}
