/* jd_renderer_count: one frame of a scene counted pass by pass for the
 * frame-cost model (core/frame_cost.h). */
#include "renderer_internal.h"

#include <stdio.h>
#include <string.h>

#include "gl_program.h"

/* ---- the frame-cost count (jd_renderer_count) ----------------------------
 * A counting frame runs the frame's passes as they are, but every mesh draw
 * is made by the counting program with the same positions and transform
 * (no jade shader discards, so a pass shades exactly the fragments its
 * geometry passes the depth test with), adding 1/255 per fragment into
 * the pass's target; the target is read back when the pass ends. Quads
 * cover their viewport (or scissor box) once and are counted by area. */

jd_pass_count *jdr_counted(jd_renderer *r)
{
    jd_frame_count *c = r->count;
    return c && c->num_passes > 0 ? &c->pass[c->num_passes - 1] : NULL;
}

/* The open pass's program: the current one, by its label. A second program
 * into the same target opens a record of its own. */
jd_pass_count *jdr_counted_draw(jd_renderer *r)
{
    jd_pass_count *p = jdr_counted(r);
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
void jdr_counted_quad(jd_renderer *r, double fragments, double vertices, double triangles)
{
    jd_pass_count *p = jdr_counted_draw(r);
    if (!p) return;
    p->fragments += fragments;
    p->vertices += vertices;
    p->triangles += triangles;
}

/* Textures a pass samples: their used regions, each texel once. */
void jdr_counted_read(jd_renderer *r, const target *t, double layers)
{
    jd_pass_count *p = jdr_counted(r);
    if (p) p->bytes_read += (double)t->w * t->h * 4.0 * layers;
}

/* The open pass's loops run `trips` times (its program's dynamic loops). */
void jdr_counted_trips(jd_renderer *r, double trips)
{
    jd_pass_count *p = jdr_counted(r);
    if (p) p->trips = trips;
}

/* Ends the open pass: fragments of mesh draws read back from its target,
 * which is still bound (the counting adds to red, one per fragment). Mesh
 * passes draw with one program each. */
static void counted_close(jd_renderer *r)
{
    jd_pass_count *p = jdr_counted(r);
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
void jdr_counted_open(jd_renderer *r, const char *what, int w, int h)
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

/* The pixels the full pass after the frame runs on where its test marks
 * the rest first (pass_screen.c, smooth_box): antialias.frag's test, made
 * here on the frame's picture, in `scene` after a frame drawn for it (a
 * counting frame's targets hold counts, not the picture). Rows are read
 * in strips with a row above and below, and a neighbour past the picture's
 * edge is taken as its edge pixel. */
static float luma_at(const uint8_t *p) { return (0.299f * p[0] + 0.587f * p[1] + 0.114f * p[2]) / 255.0f; }

static double edge_pixels(jd_renderer *r)
{
    enum { CAP = 16384 }; /* pixels a strip */
    uint8_t rows[4 * CAP];
    int w = r->scene.w, h = r->scene.h, per = CAP / (w > 0 ? w : 1);
    if (w < 1 || h < 1 || per < 3) return -1;
    glBindFramebuffer(GL_FRAMEBUFFER, r->scene.fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    double n = 0;
    for (int y0 = 0; y0 < h; y0 += per - 2) {
        int top = y0 > 0 ? y0 - 1 : 0, end = y0 + per - 1 < h ? y0 + per - 1 : h; /* rows [top, end) read */
        glReadPixels(0, top, w, end - top, GL_RGBA, GL_UNSIGNED_BYTE, rows);
        int last = y0 + per - 2 < h ? y0 + per - 2 : h;
        for (int y = y0; y < last; y++) {
            int up = (y + 1 < h ? y + 1 : y) - top, here = y - top, down = (y > 0 ? y - 1 : y) - top;
            for (int x = 0; x < w; x++) {
                int l = x > 0 ? x - 1 : x, rr = x + 1 < w ? x + 1 : x;
                const uint8_t *row = rows + 4 * (size_t)here * w, *ru = rows + 4 * (size_t)up * w,
                              *rd = rows + 4 * (size_t)down * w;
                float v[5] = {luma_at(row + 4 * x), luma_at(ru + 4 * l), luma_at(ru + 4 * rr), luma_at(rd + 4 * l),
                              luma_at(rd + 4 * rr)};
                float lo = v[0], hi = v[0];
                for (int k = 1; k < 5; k++) {
                    lo = v[k] < lo ? v[k] : lo;
                    hi = v[k] > hi ? v[k] : hi;
                }
                n += !(hi - lo < 0.05f);
            }
        }
        if (last >= h) break;
    }
    return n;
}

jd_result jd_renderer_count(jd_renderer *r, const jd_scene *s, int vertex_cache, jd_frame_count *out, jd_error *err)
{
    memset(out, 0, sizeof *out);
    /* The pass after the frame shades its edges only where it marks the
     * rest first: they are counted on the frame's own picture. */
    r->count_edges = -1;
    if (jdr_aa_marks(r)) {
        jd_result res = jd_renderer_frame(r, s, NULL, err);
        if (res) return res;
        r->count_edges = edge_pixels(r);
    }
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
    r->count_edges = -1;
    /* The targets hold counts: the next frame draws every pass again. */
    r->light_key_valid = r->view_key_valid = 0;
    glBindFramebuffer(GL_FRAMEBUFFER, r->d.target_fbo);
    if (res == JD_OK && out->overflow)
        return jd_fail(err, JD_ERR_BUDGET, "the frame has more than %d passes to count", JD_COUNT_PASSES);
    return res;
}
