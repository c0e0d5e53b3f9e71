/* Wires the pieces in the one direction data flows: the platform gives a
 * context, the core renders frames, the program decides what to do with them. */
#ifndef JD_SESSION_H
#define JD_SESSION_H

#include "clock.h" /* jd_clock_ms: the one clock */
#include "gl_caps.h"
#include "options.h"
#include "platform.h"
#include "profile.h"

typedef struct jd_session {
    void *memory;
    jd_arena arena;
    jd_mesh mesh;
    jd_load_stats load;
    char mesh_path[4096];
    int stopped; /* a signal came while --wait-display waited: not a failure */
    jd_platform *platform;
    jd_gl_caps caps;
    jd_renderer *renderer;
    double t_start_ms;
} jd_session;

/* Returns 0 after printing a one-line error. */
int jd_session_open(jd_session *s, jd_options *o, const char *cmd);
/* Only the mesh, for commands without a display (the reference). */
int jd_session_open_mesh(jd_session *s, jd_options *o, const char *cmd);
/* Loads o->mesh (or the default asset) in place of the session's mesh and
 * makes a new renderer: 1 done, 0 the new mesh failed (said) and the old
 * one is back, -1 neither works (said). */
int jd_session_reload_mesh(jd_session *s, jd_options *o, const char *cmd);
void jd_session_close(jd_session *s);
/* "N triangles", and ", split to M where coarse" where the loader split
 * them (core/mesh_subdivide.c), into buf. */
const char *jd_session_triangles(const jd_session *s, char *buf, size_t cap);
/* One line: how the edges are anti-aliased. */
const char *jd_antialias_describe(const jd_renderer *r);
/* The default asset beside the program (build tree) or installed. */
int jd_default_asset(char *out, size_t cap);

#endif
