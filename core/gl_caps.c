#include "gl_caps.h"

#include <stdio.h>
#include <string.h>

#include "gl.h"

int jd_gl_has_extension(const char *name)
{
    const char *all = (const char *)glGetString(GL_EXTENSIONS);
    size_t n = strlen(name);
    for (const char *p = all; p && (p = strstr(p, name)) != NULL; p += n)
        if ((p == all || p[-1] == ' ') && (p[n] == ' ' || p[n] == 0)) return 1;
    return 0;
}

static void copy_str(char *dst, size_t cap, GLenum what)
{
    const char *s = (const char *)glGetString(what);
    snprintf(dst, cap, "%s", s ? s : "?");
}

jd_result jd_gl_caps_query(jd_gl_caps *c, jd_error *err)
{
    memset(c, 0, sizeof *c);
    if (!glGetString(GL_VERSION))
        return jd_fail(err, JD_ERR_GL, "no current GL context to query");
    copy_str(c->vendor, sizeof c->vendor, GL_VENDOR);
    copy_str(c->renderer, sizeof c->renderer, GL_RENDERER);
    copy_str(c->version, sizeof c->version, GL_VERSION);
    copy_str(c->glsl, sizeof c->glsl, GL_SHADING_LANGUAGE_VERSION);
    GLint v[2];
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &c->max_texture_size);
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &c->max_renderbuffer_size);
    glGetIntegerv(GL_MAX_CUBE_MAP_TEXTURE_SIZE, &c->max_cube_map_size);
    glGetIntegerv(GL_MAX_VERTEX_ATTRIBS, &c->max_vertex_attribs);
    glGetIntegerv(GL_MAX_VERTEX_UNIFORM_VECTORS, &c->max_vertex_uniform_vectors);
    glGetIntegerv(GL_MAX_FRAGMENT_UNIFORM_VECTORS, &c->max_fragment_uniform_vectors);
    glGetIntegerv(GL_MAX_VARYING_VECTORS, &c->max_varying_vectors);
    glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &c->max_texture_units);
    glGetIntegerv(GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS, &c->max_vertex_texture_units);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, v);
    c->max_viewport_w = v[0];
    c->max_viewport_h = v[1];
    GLint range[2] = {0, 0}, prec = 0;
    glGetShaderPrecisionFormat(GL_FRAGMENT_SHADER, GL_HIGH_FLOAT, range, &prec);
    c->frag_highp_precision = prec;
    c->frag_highp_range = range[1];
    glGetShaderPrecisionFormat(GL_FRAGMENT_SHADER, GL_MEDIUM_FLOAT, range, &prec);
    c->frag_mediump_precision = prec;
    c->frag_mediump_range = range[1];
    c->ext_element_index_uint = jd_gl_has_extension("GL_OES_element_index_uint");
    c->ext_disjoint_timer_query = jd_gl_has_extension("GL_EXT_disjoint_timer_query");
    c->ext_depth_texture = jd_gl_has_extension("GL_OES_depth_texture");
    c->ext_texture_float = jd_gl_has_extension("GL_OES_texture_float");
    c->ext_packed_depth_stencil = jd_gl_has_extension("GL_OES_packed_depth_stencil");
    c->ext_rgb8_rgba8 = jd_gl_has_extension("GL_OES_rgb8_rgba8");
    c->ext_texture_npot = jd_gl_has_extension("GL_OES_texture_npot");
    c->ext_standard_derivatives = jd_gl_has_extension("GL_OES_standard_derivatives");
    const char *all = (const char *)glGetString(GL_EXTENSIONS);
    for (const char *p = all; p && *p; p++)
        if (*p != ' ' && (p == all || p[-1] == ' ')) c->num_extensions++;
    while (glGetError() != GL_NO_ERROR) {}
    return JD_OK;
}

void jd_gl_probe_names(jd_gl_names *out)
{
    GLuint n;
    glGenTextures(1, &n);
    glDeleteTextures(1, &n);
    out->texture = n;
    glGenBuffers(1, &n);
    glDeleteBuffers(1, &n);
    out->buffer = n;
    glGenFramebuffers(1, &n);
    glDeleteFramebuffers(1, &n);
    out->framebuffer = n;
    glGenRenderbuffers(1, &n);
    glDeleteRenderbuffers(1, &n);
    out->renderbuffer = n;
}
