#include "gl_caps.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl.h"

int jd_extension_listed(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = list; p && (p = strstr(p, name)) != NULL; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == 0)) return 1;
    return 0;
}

int jd_gl_has_extension(const char *name) { return jd_extension_listed((const char *)glGetString(GL_EXTENSIONS), name); }

static void copy_str(char *dst, size_t cap, GLenum what)
{
    const char *s = (const char *)glGetString(what);
    snprintf(dst, cap, "%s", s ? s : "?");
}

/* The GPUs jade knows by name: what their queries do not say. */
void jd_gl_caps_recognise(jd_gl_caps *c)
{
    /* Mali-400/450 (Utgard) fragment processors compute in fp16 whatever
     * the precision query says: Mesa's lima reports 23 bits for mediump and
     * highp. Recognised by name, so jade packs for mediump there. */
    if (strstr(c->renderer, "Mali-4") || strstr(c->renderer, "Mali-3") || strstr(c->renderer, "Mali-2") ||
        strstr(c->renderer, "Mali400") || strstr(c->renderer, "Mali450") || !strncmp(c->renderer, "lima", 4)) {
        c->utgard = 1;
        c->small_register_file = 1;
        c->frag_highp_precision = 0;
        c->frag_highp_range = 0;
        if (c->frag_mediump_precision > 10) c->frag_mediump_precision = 10;
        if (c->frag_mediump_range > 15) c->frag_mediump_range = 15;
        snprintf(c->tier, sizeof c->tier, "Mali-400/450");
    }
    /* VideoCore IV (Mesa vc4 says "VC4 V3D 2.1"; Broadcom's blob "VideoCore IV HW"). */
    if (strstr(c->renderer, "VC4") || strstr(c->renderer, "VideoCore IV")) {
        c->small_register_file = 1;
        c->levels_per_fragment_from = JD_VC4_LEVELS_PER_FRAGMENT_FROM;
        snprintf(c->tier, sizeof c->tier, "VideoCore IV");
    }
    /* Vivante ("Vivante GC2000 rev 5108" from Mesa etnaviv, "GC2000 core"
     * with vendor "Vivante Corporation" from Vivante's driver) and Adreno
     * ("FD307" from Mesa freedreno, for the Adreno 306 of chip id 3.0.6.0;
     * "Adreno (TM) 306" from Qualcomm's): the model sets the frame-cost
     * tier and, on Vivante, the program size limit. */
    const char *gc = strstr(c->renderer, "GC");
    if (gc && (strstr(c->renderer, "Vivante") || strstr(c->vendor, "Vivante")) && gc[2] >= '1' && gc[2] <= '9')
        c->vivante = atoi(gc + 2);
    if (c->vivante > 0 && c->vivante < 3000) c->max_program_instructions = 256;
    if (!strncmp(c->renderer, "FD", 2) && c->renderer[2] >= '1' && c->renderer[2] <= '9') c->adreno = atoi(c->renderer + 2);
    const char *a = strstr(c->renderer, "Adreno (TM) ");
    if (a) c->adreno = atoi(a + strlen("Adreno (TM) "));
    if (c->vivante > 0 && c->vivante < 3000) snprintf(c->tier, sizeof c->tier, "Vivante GC400-GC2000");
    /* GC3000 (i.MX6 QuadPlus) and GC7000Lite (i.MX8M Quad): GC2000's 4
     * shader cores and 2 pixel pipes (Mesa's etnaviv drm-shim, from the
     * chips' feature registers), shared by vertices and fragments, with an
     * instruction cache and vertex texture units. Full's shading at 1080p
     * takes a close-up 23 ms on GC7000Lite at 800 MHz (the frame-cost
     * model, imx8mq-gc7000l), and the levels summed per vertex 313
     * instructions on every vertex shaded. */
    if (c->vivante >= 3000 && c->vivante < 8000) {
        snprintf(c->tier, sizeof c->tier, "Vivante GC3000-GC7000");
        c->levels_per_fragment_from = JD_VIVANTE_LEVELS_PER_FRAGMENT_FROM;
    }
    if (c->adreno >= 300 && c->adreno < 400) {
        snprintf(c->tier, sizeof c->tier, "Adreno 3xx");
        c->levels_per_fragment_from = JD_ADRENO3XX_LEVELS_PER_FRAGMENT_FROM;
    }
}

int jd_gl_caps_levels_per_vertex(const jd_gl_caps *c, unsigned vertices, int colour_texture)
{
    if (c->levels_per_fragment_from > 0 && vertices >= (unsigned)c->levels_per_fragment_from) return 0;
    return c->max_vertex_texture_units >= JD_DIFFUSION_VERTEX_UNITS &&
           JD_FULL_VERTEX_LEVELS_UNITS + (colour_texture != 0) <= c->max_texture_units;
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
    jd_gl_caps_recognise(c);
    c->ext_element_index_uint = jd_gl_has_extension("GL_OES_element_index_uint");
    c->ext_disjoint_timer_query = jd_gl_has_extension("GL_EXT_disjoint_timer_query");
    c->ext_depth_texture = jd_gl_has_extension("GL_OES_depth_texture");
    c->ext_texture_float = jd_gl_has_extension("GL_OES_texture_float");
    c->ext_packed_depth_stencil = jd_gl_has_extension("GL_OES_packed_depth_stencil");
    c->ext_rgb8_rgba8 = jd_gl_has_extension("GL_OES_rgb8_rgba8");
    c->ext_texture_npot = jd_gl_has_extension("GL_OES_texture_npot");
    c->ext_standard_derivatives = jd_gl_has_extension("GL_OES_standard_derivatives");
    c->ext_multisampled_render_to_texture = jd_gl_has_extension("GL_EXT_multisampled_render_to_texture");
    if (c->ext_multisampled_render_to_texture) glGetIntegerv(GL_MAX_SAMPLES_EXT, &c->max_samples);
    const char *all = (const char *)glGetString(GL_EXTENSIONS);
    for (const char *p = all; p && *p; p++)
        if (*p != ' ' && (p == all || p[-1] == ' ')) c->num_extensions++;
    while (glGetError() != GL_NO_ERROR) {}
    return JD_OK;
}

static unsigned count_live(void (*gen)(GLsizei, GLuint *), void (*del)(GLsizei, const GLuint *),
                           GLboolean (*is)(GLuint))
{
    GLuint next = 0;
    gen(1, &next);
    del(1, &next);
    unsigned live = 0, top = next < 65536 ? next : 65536;
    for (GLuint k = 1; k < top; k++) live += is(k) == GL_TRUE;
    return live;
}

void jd_gl_probe_names(jd_gl_names *out)
{
    out->texture = count_live(glGenTextures, glDeleteTextures, glIsTexture);
    out->buffer = count_live(glGenBuffers, glDeleteBuffers, glIsBuffer);
    out->framebuffer = count_live(glGenFramebuffers, glDeleteFramebuffers, glIsFramebuffer);
    out->renderbuffer = count_live(glGenRenderbuffers, glDeleteRenderbuffers, glIsRenderbuffer);
}

/* x = (1 + v) * k * 0.001 - 1 with v = 1e-4 from a varying and k = 1000
 * from a uniform, so no compiler can fold it: 1e-4 at fp32 (to a part in
 * 1e3); at fp16, 1 + 1e-4 and k * 0.001 each round to a multiple of 2^-11
 * or 2^-10, and x to a multiple of about 5e-4, never near 1e-4: llvmpipe
 * gives 0, an NVIDIA H100 1.5e-4 or more (red 255).
 * Written as x * 5000 + 0.25 into RGBA8: 32 bits 191, 16 bits 64 or,
 * clamped, 0 or 255. (x less 1e-4 in the shader itself read as fp32 on
 * llvmpipe's fp16: a compiler may fold (x - 1) - 1e-4 into x - 1.0001.) */
static const char canary_vs[] =
    "#version 100\nattribute vec2 a_corner;\nvarying mediump float v_v;\n"
    "void main() { v_v = 1e-4; gl_Position = vec4(a_corner, 0.0, 1.0); }\n";
static const char canary_fs[] =
    "#version 100\nprecision mediump float;\nvarying mediump float v_v;\nuniform mediump float u_k;\n"
    "void main() { float x = (1.0 + v_v) * u_k * 0.001 - 1.0; gl_FragColor = vec4(x * 5000.0 + 0.25, 0.0, 0.0, 1.0); }\n";

static GLuint canary_shader(GLenum type, const char *src)
{
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) { glDeleteShader(s); return 0; }
    return s;
}

int jd_gl_mediump_is_fp16(void)
{
    unsigned char px[4];
    return jd_gl_mediump_canary(px);
}

int jd_gl_mediump_canary(unsigned char rgba[4])
{
    memset(rgba, 0, 4);
    /* An error an earlier call left pending (jade info queries limits a
     * driver may not know) must not read as this test's. */
    for (int i = 0; i < 16 && glGetError() != GL_NO_ERROR; i++) {}
    GLuint vs = canary_shader(GL_VERTEX_SHADER, canary_vs), fs = canary_shader(GL_FRAGMENT_SHADER, canary_fs);
    if (!vs || !fs) { glDeleteShader(vs); glDeleteShader(fs); return -1; }
    GLuint p = glCreateProgram();
    glAttachShader(p, vs);
    glAttachShader(p, fs);
    glBindAttribLocation(p, 0, "a_corner");
    glLinkProgram(p);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint link_ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &link_ok);
    if (!link_ok) { glDeleteProgram(p); return -1; }
    GLuint tex, fbo;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 4, 4, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    static const float quad[] = {-1, -1, 1, -1, -1, 1, 1, 1};
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glViewport(0, 0, 4, 4);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(p);
    glUniform1f(glGetUniformLocation(p, "u_k"), 1000.0f);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, quad);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glDisableVertexAttribArray(0);
    unsigned char *px = rgba;
    glReadPixels(1, 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    glUseProgram(0);
    glDeleteProgram(p);
    int gl_ok = glGetError() == GL_NO_ERROR;
    /* A driver that draws nothing (Mesa's drm-shims read back zeros)
     * answers nothing. */
    if (!gl_ok || px[3] != 255) return -1;
    return px[0] < 175 || px[0] > 207;
}
