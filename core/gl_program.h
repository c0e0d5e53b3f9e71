/* Shader programs built from the GLSL ES 1.00 files embedded at build time. */
#ifndef JD_GL_PROGRAM_H
#define JD_GL_PROGRAM_H

#include <stddef.h>

#include "gl.h"
#include "jd_result.h"

typedef struct jd_shader_source {
    const char *name; /* path in the source tree, e.g. shaders_es2/shade.frag */
    const char *text;
} jd_shader_source;

extern const jd_shader_source jd_shader_sources[];
extern const int jd_shader_source_count;

const char *jd_shader_text(const char *name);

/* Builds vs+fs with `defines` ("#define X 1\n" lines) inserted after #version.
 * Attributes are bound in order of the NULL-terminated `attribs`. A failure
 * names the file and line and carries the driver's log. */
jd_result jd_program_build(const char *vs_name, const char *fs_name, const char *defines,
                           const char *const *attribs, GLuint *out, jd_error *err);

/* Told about every program as it is built: once before compiling
 * (result < 0) and once after linking (JD_OK or the error, whose message
 * is in `msg`). For `jade info --compile` and device-compiler runs: a
 * driver's own messages printed in between belong to this program. */
typedef void (*jd_program_observer)(void *user, const char *vs, const char *fs, const char *defines, int result,
                                    const char *msg);
void jd_program_observe(jd_program_observer fn, void *user);

/* The label the compiler table (tests/device-shaders.expected) and the
 * frame-cost model know a program by: "mesh.vert+shade.frag[full]". */
void jd_program_label(const char *vs, const char *fs, const char *defines, char *out, size_t cap);

/* Defines added to every program built from now on ("" or NULL: none):
 * tools/device-shaders.sh builds every program again with JD_UNROLL 1 and
 * 2 (dynamic loops at that constant trip count) to learn what one more
 * trip costs on each compiler. */
void jd_program_extra_defines(const char *defines);

/* Tests: write every assembled shader source to dir (NULL: stop), named
 * NNN_<file>, exactly as the driver receives it. */
void jd_program_dump_to(const char *dir);

#endif
