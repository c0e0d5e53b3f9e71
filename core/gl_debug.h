/* The driver's own messages (GL_KHR_debug) passed to the program's log:
 * on real boards they say what the GL errors do not, e.g. a shader that
 * spills or a draw the driver skipped; vc4 reports its shader costs there. */
#ifndef JD_GL_DEBUG_H
#define JD_GL_DEBUG_H

/* kind: "shader compiler" (whatever its type: shader-db counts, spills),
 * "error", "undefined behaviour", "deprecated", "portability",
 * "performance", "warning" (high severity) or "info". */
typedef void (*jd_gl_log_fn)(void *user, const char *kind, const char *msg);

/* Installs `fn` for the current context where GL_KHR_debug exists (looked
 * up through get_proc) and turns debug output on, synchronous, so that a
 * message arrives during the call that caused it. Returns 0 without it. */
int jd_gl_debug_enable(void *(*get_proc)(const char *name), jd_gl_log_fn fn, void *user);

#endif
