/* Whether programs that linked also draw. */
#ifndef JD_PROGRAM_PROBE_H
#define JD_PROGRAM_PROBE_H

#include "gl.h"

enum { JD_PROBE_MAX = 32 };

/* Draws each of the n programs (0 ids are skipped) over one pixel of fbo
 * (RGBA8, at least n x 1) and sets drawn[i] to whether the draw landed.
 * Attribute 0 is the quad_vbo's corners (x, y), the others constant; a
 * u_mvp or u_light_mvp uniform is set to the identity, so every vertex
 * stage jade has covers its pixel. Changes the bound program, buffer,
 * viewport and the depth, cull, blend, scissor and dither switches; the
 * framebuffer left bound is 0. Returns 0 (drawn untouched) where the probe
 * cannot run: more than JD_PROBE_MAX programs or an incomplete fbo. */
int jd_program_probe(const GLuint *progs, int n, GLuint fbo, GLuint quad_vbo, int *drawn);

#endif
