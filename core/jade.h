/* jade's public interface: #include <jade/jade.h> (the platforms, from the
 * jade-platform library: <jade/platform.h>).
 *
 * Typical use: give the core one memory budget (jd_arena_init), load a Draco
 * mesh before any GL context exists (jd_mesh_load_draco forks a sandboxed
 * decoder), make a GLES 2.0 context current (your own, or platform.h's),
 * query its capabilities (jd_gl_caps_query), create a renderer
 * (jd_renderer_create) and call jd_renderer_frame once per frame. */
#ifndef JADE_H
#define JADE_H

#ifdef __cplusplus
extern "C" {
#endif

#include "jd_result.h"
#include "arena.h"
#include "vmath.h"
#include "mesh.h"
#include "mesh_load.h"
#include "material.h"
#include "gl_caps.h"
#include "profile.h"
#include "board.h"
#include "frame_cost.h"
#include "renderer.h"

#ifdef __cplusplus
}
#endif
#endif
