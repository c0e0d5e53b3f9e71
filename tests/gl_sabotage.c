/* Preloaded into jade by tests/fallback.sh: plays a driver that cannot run
 * one of jade's shaders. JD_SABOTAGE=MARKER:reject makes every shader whose
 * source contains MARKER fail to compile (a compiler that rejects it);
 * MARKER:drop makes such a fragment shader compile and link but draw
 * nothing (a driver that skips the draws of a program it could not
 * register-allocate, as Mesa's vc4 does). Counts what it did on stderr.
 * JD_POISON_TEXTURES=1 (tests/undefined_texels.sh) fills every texture made
 * without data with noise: what GLES 2.0 leaves undefined, and what a
 * driver that hands out freed buffers again (Mesa's lima keeps a cache of
 * them) really gives. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef unsigned int GLenum, GLuint;
typedef int GLint, GLsizei;
typedef char GLchar;
#define GL_SHADER_TYPE 0x8B4F
#define GL_FRAGMENT_SHADER 0x8B30

static int hits, poisoned;
static void report(void)
{
    if (getenv("JD_SABOTAGE")) fprintf(stderr, "gl_sabotage: %d shaders changed\n", hits);
    if (getenv("JD_POISON_TEXTURES")) fprintf(stderr, "gl_sabotage: %d textures poisoned\n", poisoned);
}
__attribute__((constructor)) static void start(void) { atexit(report); }

void glShaderSource(GLuint shader, GLsizei count, const GLchar *const *string, const GLint *length)
{
    static void (*real)(GLuint, GLsizei, const GLchar *const *, const GLint *);
    static void (*get)(GLuint, GLenum, GLint *);
    if (!real) {
        real = (void (*)(GLuint, GLsizei, const GLchar *const *, const GLint *))dlsym(RTLD_NEXT, "glShaderSource");
        get = (void (*)(GLuint, GLenum, GLint *))dlsym(RTLD_NEXT, "glGetShaderiv");
    }
    const char *spec = getenv("JD_SABOTAGE");
    const char *colon = spec ? strrchr(spec, ':') : NULL;
    int found = 0;
    if (colon)
        for (GLsizei i = 0; i < count && !found; i++) {
            size_t n = length && length[i] >= 0 ? (size_t)length[i] : strlen(string[i]);
            size_t m = (size_t)(colon - spec);
            for (size_t k = 0; m && k + m <= n && !found; k++) found = memcmp(string[i] + k, spec, m) == 0;
        }
    GLint type = 0;
    if (found) get(shader, GL_SHADER_TYPE, &type);
    if (found && !strcmp(colon + 1, "reject")) {
        static const GLchar *bad = "#version 100\nvoid main() { this is not GLSL }\n";
        hits++;
        real(shader, 1, &bad, NULL);
    } else if (found && !strcmp(colon + 1, "drop") && type == GL_FRAGMENT_SHADER) {
        static const GLchar *none = "#version 100\nvoid main() { discard; }\n";
        hits++;
        real(shader, 1, &none, NULL);
    } else {
        real(shader, count, string, length);
    }
}

#define GL_RGBA 0x1908
#define GL_UNSIGNED_BYTE 0x1401
void glTexImage2D(GLenum target, GLint level, GLint internal, GLsizei w, GLsizei h, GLint border, GLenum format,
                  GLenum type, const void *pixels)
{
    static void (*real)(GLenum, GLint, GLint, GLsizei, GLsizei, GLint, GLenum, GLenum, const void *);
    if (!real)
        real = (void (*)(GLenum, GLint, GLint, GLsizei, GLsizei, GLint, GLenum, GLenum, const void *))dlsym(
            RTLD_NEXT, "glTexImage2D");
    unsigned char *noise = NULL;
    if (!pixels && getenv("JD_POISON_TEXTURES") && format == GL_RGBA && type == GL_UNSIGNED_BYTE && w > 0 && h > 0 &&
        (noise = malloc((size_t)w * (size_t)h * 4))) {
        /* Bytes of every value, different in each texture and channel. */
        static unsigned int x = 12345u;
        for (size_t i = 0; i < (size_t)w * (size_t)h * 4; i++) {
            x = x * 1103515245u + 12345u;
            noise[i] = (unsigned char)(x >> 16);
        }
        poisoned++;
    }
    real(target, level, internal, w, h, border, format, type, noise ? noise : pixels);
    free(noise);
}
