#include "gl_debug.h"

#include "gl.h"
#include "gl_caps.h"

#ifndef GL_DEBUG_OUTPUT_KHR
#define GL_DEBUG_OUTPUT_KHR 0x92E0
#define GL_DEBUG_OUTPUT_SYNCHRONOUS_KHR 0x8242
#endif

typedef void (*debug_proc)(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                           const GLchar *message, const void *user);
typedef void (*set_callback_fn)(debug_proc callback, const void *user);

static jd_gl_log_fn log_fn;
static void *log_user;

static const char *kind_of(GLenum source, GLenum type, GLenum severity)
{
    if (source == 0x8248) return "shader compiler"; /* GL_DEBUG_SOURCE_SHADER_COMPILER */
    switch (type) {
    case 0x824C: return "error";              /* GL_DEBUG_TYPE_ERROR */
    case 0x824D: return "deprecated";         /* DEPRECATED_BEHAVIOR */
    case 0x824E: return "undefined behaviour"; /* UNDEFINED_BEHAVIOR */
    case 0x824F: return "portability";
    case 0x8250: return "performance";
    default: break;
    }
    return severity == 0x9146 ? "warning" : "info"; /* GL_DEBUG_SEVERITY_HIGH */
}

static void on_message(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                       const GLchar *message, const void *user)
{
    (void)id;
    (void)length;
    (void)user;
    if (log_fn) log_fn(log_user, kind_of(source, type, severity), message);
}

int jd_gl_debug_enable(void *(*get_proc)(const char *name), jd_gl_log_fn fn, void *user)
{
    if (!get_proc || !jd_gl_has_extension("GL_KHR_debug")) return 0;
    set_callback_fn set = (set_callback_fn)get_proc("glDebugMessageCallbackKHR");
    if (!set) return 0;
    log_fn = fn;
    log_user = user;
    set(on_message, NULL);
    glEnable(GL_DEBUG_OUTPUT_KHR);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS_KHR);
    glGetError(); /* a driver without the enables would say INVALID_ENUM: not the caller's error */
    return 1;
}
