/* Preloaded into jade by tests/frame_stalls.sh: counts the calls that make a
 * tile-based GPU wait (glReadPixels, glFinish) and the frames presented
 * (eglSwapBuffers, or the headless platform's glFlush), from outside the
 * program, and prints the totals at exit. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>

typedef unsigned int GLenum, GLuint;
typedef int GLint, GLsizei;
static unsigned long readpixels, finishes;

static void report(void)
{
    const char *path = getenv("JD_GL_COUNT_OUT");
    FILE *f = path ? fopen(path, "w") : stderr;
    if (!f) return;
    fprintf(f, "glReadPixels %lu\nglFinish %lu\n", readpixels, finishes);
    if (f != stderr) fclose(f);
}

__attribute__((constructor)) static void start(void) { atexit(report); }

void glReadPixels(GLint x, GLint y, GLsizei w, GLsizei h, GLenum format, GLenum type, void *data)
{
    static void (*real)(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void *);
    if (!real) real = (void (*)(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void *))dlsym(RTLD_NEXT, "glReadPixels");
    readpixels++;
    real(x, y, w, h, format, type, data);
}

void glFinish(void)
{
    static void (*real)(void);
    if (!real) real = (void (*)(void))dlsym(RTLD_NEXT, "glFinish");
    finishes++;
    real();
}
