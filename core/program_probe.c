/* Some drivers link a program they then cannot run, and skip its draws
 * without a GL error: Mesa's vc4 when register allocation fails says
 * "shader compile failed, skipping draw call" in a debug build only. A
 * pass that silently draws nothing would leave a frame without its
 * translucency and nobody the wiser, so the renderer asks every program
 * once, at start-up: each draws its own pixel of a small target, twice,
 * over two different clear colours. A pixel that holds its clear colour
 * both times was never drawn (a program cannot write both colours, whatever
 * its uniforms make of it). Two read-backs of a few pixels, at start-up
 * only: in a frame they would stall a tile-based GPU. */
#include "program_probe.h"

#include <string.h>

/* Every sampler on a unit of its own: a 2D and a cube sampler on one unit
 * (both 0 unless set) make the draw an INVALID_OPERATION. Nothing is bound
 * there, so they read (0, 0, 0, 1). */
static void set_up(GLuint prog)
{
    GLint n = 0, unit = 0;
    glGetProgramiv(prog, GL_ACTIVE_UNIFORMS, &n);
    for (GLint i = 0; i < n; i++) {
        char name[64];
        GLint size = 0;
        GLenum type = 0;
        glGetActiveUniform(prog, (GLuint)i, sizeof name, NULL, &size, &type, name);
        if (type != GL_SAMPLER_2D && type != GL_SAMPLER_CUBE) continue;
        GLint loc = glGetUniformLocation(prog, name);
        if (loc >= 0) glUniform1i(loc, unit); /* jade has no sampler arrays */
        unit += size;
    }
}

int jd_program_probe(const GLuint *progs, int n, GLuint fbo, GLuint quad_vbo, int *drawn)
{
    if (n < 1 || n > JD_PROBE_MAX) return 0;
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    int ok = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    if (ok) {
        static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
        static const GLubyte clear[2][4] = {{37, 201, 89, 143}, {211, 17, 163, 59}};
        GLubyte px[2][JD_PROBE_MAX * 4];
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        glDisable(GL_BLEND);
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_DITHER); /* or a clear colour may not come back bit-exact */
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glBindBuffer(GL_ARRAY_BUFFER, quad_vbo);
        GLint attribs = 8;
        glGetIntegerv(GL_MAX_VERTEX_ATTRIBS, &attribs);
        for (GLint a = 1; a < attribs; a++) glDisableVertexAttribArray((GLuint)a);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 8, (const void *)0);
        for (int pass = 0; pass < 2; pass++) {
            glViewport(0, 0, n, 1);
            glClearColor(clear[pass][0] / 255.0f, clear[pass][1] / 255.0f, clear[pass][2] / 255.0f,
                         clear[pass][3] / 255.0f);
            glClear(GL_COLOR_BUFFER_BIT);
            for (int i = 0; i < n; i++) {
                if (!progs[i]) continue;
                glViewport(i, 0, 1, 1);
                glUseProgram(progs[i]);
                set_up(progs[i]);
                GLint m = glGetUniformLocation(progs[i], "u_mvp");
                if (m >= 0) glUniformMatrix4fv(m, 1, GL_FALSE, identity);
                if ((m = glGetUniformLocation(progs[i], "u_light_mvp")) >= 0) glUniformMatrix4fv(m, 1, GL_FALSE, identity);
                if ((m = glGetUniformLocation(progs[i], "u_light_tex")) >= 0) glUniformMatrix4fv(m, 1, GL_FALSE, identity);
                glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
            }
            glReadPixels(0, 0, n, 1, GL_RGBA, GL_UNSIGNED_BYTE, px[pass]);
        }
        for (int i = 0; i < n; i++)
            drawn[i] = !progs[i] || memcmp(px[0] + 4 * i, clear[0], 4) != 0 || memcmp(px[1] + 4 * i, clear[1], 4) != 0;
        glUseProgram(0);
        glEnable(GL_DITHER);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return ok;
}
