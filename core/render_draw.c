/* Binding and drawing: every target switch and draw of a frame passes
 * here, so that the tiler counters and jd_renderer_count see them all. */
#include "renderer_internal.h"

#include <stdio.h>
#include <string.h>

void jdr_bind_mesh(GLuint vbo, GLuint ibo)
{
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(1);
    glEnableVertexAttribArray(4);
    glEnableVertexAttribArray(5);
    /* The position's fourth float is the part's thickness (render_target.c):
     * programs that declare a vec3 position drop it. */
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, JDR_STRIDE_PLAIN, (const void *)0);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, JDR_STRIDE_PLAIN, (const void *)16);
    /* The light between parts' transfer, last in the vertex (render_target.c). */
    glVertexAttribPointer(4, 4, GL_FLOAT, GL_FALSE, JDR_STRIDE_PLAIN,
                          (const void *)(JDR_STRIDE_PLAIN - JDR_BOUNCE_BYTES));
    glVertexAttribPointer(5, 2, GL_FLOAT, GL_FALSE, JDR_STRIDE_PLAIN, (const void *)JDR_CURVE_AT(JDR_STRIDE_PLAIN));
}

void jdr_mesh_attributes(const jd_renderer *r, size_t at)
{
    GLsizei st = (GLsizei)r->vstride;
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, st, (const void *)at);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, st, (const void *)(at + 16));
    glVertexAttribPointer(4, 4, GL_FLOAT, GL_FALSE, st, (const void *)(at + (size_t)st - JDR_BOUNCE_BYTES));
    glVertexAttribPointer(5, 2, GL_FLOAT, GL_FALSE, st, (const void *)(at + (size_t)JDR_CURVE_AT(st)));
    if (!r->albedo) return;
    glEnableVertexAttribArray(2);
    glEnableVertexAttribArray(3);
    glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, st, (const void *)(at + 28));
    glVertexAttribPointer(3, 4, GL_UNSIGNED_BYTE, GL_TRUE, st, (const void *)(at + 36));
}

void jdr_bind_quad(const jd_renderer *r)
{
    glBindBuffer(GL_ARRAY_BUFFER, r->quad_vbo);
    glDisableVertexAttribArray(1);
    glDisableVertexAttribArray(4);
    glDisableVertexAttribArray(5);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 8, (const void *)0);
}

/* The scissor keeps clears to the used corner of a power-of-two target. */
/* Every render-target switch of a frame passes here, and is counted. */
void jdr_count_target(jd_renderer *r, const char *what, int w, int h)
{
    jdr_counted_open(r, what, w, h);
    r->n_switches++;
    r->n_fragments += (double)w * h;
    r->n_bytes += (double)w * h * 4.0;
}

void jdr_use_target(jd_renderer *r, const target *t, const char *what)
{
    jdr_count_target(r, what, t->w, t->h);
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glViewport(0, 0, t->w, t->h);
    glScissor(0, 0, t->w, t->h);
}

/* A quad over all of t, reading `src` (NULL: nothing counted). */
void jdr_draw_quad_into(jd_renderer *r, const target *t, const char *what, const target *src)
{
    const int all[4] = {0, 0, t->w, t->h};
    jdr_draw_quad_rect(r, t, what, src, all);
}

void jdr_draw_quad_rect(jd_renderer *r, const target *t, const char *what, const target *src, const int rect[4])
{
    jdr_count_target(r, what, rect[2], rect[3]);
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glViewport(0, 0, t->w, t->h);
    glScissor(rect[0], rect[1], rect[2], rect[3]);
    if (src) jdr_counted_read(r, src, 1);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    jdr_counted_quad(r, (double)rect[2] * rect[3], 4, 2);
}

/* glDrawElements of one of the meshes (0 the whole mesh, 1 the proxy, 2
 * the capture proxy) under `mvp`: in a counting frame, the counting draw,
 * shading `vertices` (< 0: the mesh's whole draw). */
void jdr_draw_elements(jd_renderer *r, int mesh, const jd_mat4 *mvp, GLsizei count, GLenum type, const void *at,
                          double vertices)
{
    jd_pass_count *p = r->count ? jdr_counted_draw(r) : NULL;
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
void jdr_draw_mesh(jd_renderer *r, const jd_mat4 *mvp)
{
    jdr_bind_mesh(r->mesh_vbo, r->mesh_ibo);
    jdr_mesh_attributes(r, 0);
    if (!r->num_chunks) {
        jdr_draw_elements(r, 0, mvp, (GLsizei)r->d.mesh->num_indices, r->mesh_index_type, 0, -1);
        return;
    }
    for (int i = 0; i < r->num_chunks; i++) {
        const struct mesh_chunk *ch = &r->chunks[i];
        jdr_mesh_attributes(r, ch->vertex_offset);
        /* A chunk's own vertices under the range model; under a FIFO, the
         * whole mesh's misses shared out by triangles. */
        double v = r->count_vertices[0] < 0 ? (double)ch->vertices
                                            : r->count_vertices[0] * ch->count / (double)r->d.mesh->num_indices;
        jdr_draw_elements(r, 0, mvp, (GLsizei)ch->count, GL_UNSIGNED_SHORT, (const void *)ch->index_offset, v);
    }
}
