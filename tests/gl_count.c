/* Preloaded into jade by tests/frame_stalls.sh: counts the calls that make a
 * tile-based GPU wait (glReadPixels, glFinish), from outside the program,
 * apart for start-up (before the first frame is presented: eglSwapBuffers,
 * or the headless platform's glFlush) and for the frames after it, and
 * prints the totals at exit. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>

typedef unsigned int GLenum, GLuint;
typedef int GLint, GLsizei;
static unsigned long readpixels[2], finishes[2], presents; /* [0] start-up, [1] frames */

static void report(void)
{
    const char *path = getenv("JD_GL_COUNT_OUT");
    FILE *f = path ? fopen(path, "w") : stderr;
    if (!f) return;
    fprintf(f, "glReadPixels %lu\nglFinish %lu\nstart-up glReadPixels %lu\nstart-up glFinish %lu\npresents %lu\n",
            readpixels[1], finishes[1], readpixels[0], finishes[0], presents);
    if (f != stderr) fclose(f);
}

__attribute__((constructor)) static void start(void) { atexit(report); }

void glReadPixels(GLint x, GLint y, GLsizei w, GLsizei h, GLenum format, GLenum type, void *data)
{
    static void (*real)(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void *);
    if (!real) real = (void (*)(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void *))dlsym(RTLD_NEXT, "glReadPixels");
    readpixels[presents > 0]++;
    real(x, y, w, h, format, type, data);
}

void glFinish(void)
{
    static void (*real)(void);
    if (!real) real = (void (*)(void))dlsym(RTLD_NEXT, "glFinish");
    finishes[presents > 0]++;
    real();
}

void glFlush(void)
{
    static void (*real)(void);
    if (!real) real = (void (*)(void))dlsym(RTLD_NEXT, "glFlush");
    presents++;
    real();
}

unsigned eglSwapBuffers(void *dpy, void *surface)
{
    static unsigned (*real)(void *, void *);
    if (!real) real = (unsigned (*)(void *, void *))dlsym(RTLD_NEXT, "eglSwapBuffers");
    presents++;
    return real(dpy, surface);
}
