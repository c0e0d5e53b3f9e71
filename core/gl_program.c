#include "gl_program.h"

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *dump_dir;
static int dump_count;
static char extra_defines[128];
static jd_program_observer observer;
static void *observer_user;

void jd_program_observe(jd_program_observer fn, void *user)
{
    observer = fn;
    observer_user = user;
}

void jd_program_dump_to(const char *dir) { dump_dir = dir; }

void jd_program_extra_defines(const char *defines)
{
    snprintf(extra_defines, sizeof extra_defines, "%s", defines ? defines : "");
}

/* The tags a program's defines switch on, in the order the compiler table
 * has always shown them. */
static void tag(char *out, size_t cap, const char *defines, const char *name, const char *shown)
{
    const char *p = defines ? strstr(defines, name) : NULL;
    if (p && p[strlen(name)] == ' ' && p[strlen(name) + 1] != '0') {
        size_t n = strlen(out);
        snprintf(out + n, cap - n, "%s%s", out[n - 1] == '[' ? "" : ",", shown);
    }
}

void jd_program_label(const char *vs, const char *fs, const char *defines, char *out, size_t cap)
{
    const char *v = strrchr(vs, '/'), *f = strrchr(fs, '/');
    snprintf(out, cap, "%s+%s[", v ? v + 1 : vs, f ? f + 1 : fs);
    static const char *const tags[][2] = {
        {"JD_TRANSLUCENT", "translucent"}, {"JD_SPREAD", "spread"}, {"JD_FULL", "full"},
        {"JD_A0_ONLY", "a0"}, {"JD_WIDE_ONLY", "wide"}, {"JD_VERTEX_DIFFUSION", "vertex-diffusion"},
        {"JD_VERTEX_THICKNESS", "vertex-thickness"}, {"JD_FIRST", "first"}, {"JD_BOX", "box"}, {"JD_TRIPS", "unrolled"}, {"JD_COMBINE", "combine"},
        {"JD_PACK_HIGHP", "highp"}, {"JD_ALBEDO", "colour"}, {"JD_ALBEDO_MAP", "texture"},
        {"JD_ALBEDO_PARTIAL", "partial"}, {"JD_TWO_SIDED", "two-sided"}, {"JD_AA_MARK", "mark"}};
    for (size_t i = 0; i < sizeof tags / sizeof tags[0]; i++) tag(out, cap, defines, tags[i][0], tags[i][1]);
    size_t n = strlen(out);
    if (out[n - 1] == '[') out[n - 1] = 0;
    else snprintf(out + n, cap - n, "]");
}

static void dump(const char *name, const char *const *parts, int n)
{
    char path[512];
    const char *base = strrchr(name, '/');
    snprintf(path, sizeof path, "%s/%03d_%s", dump_dir, dump_count++, base ? base + 1 : name);
    int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) return;
    for (int i = 0; i < n; i++) {
        size_t len = strlen(parts[i]);
        if (write(fd, parts[i], len) != (ssize_t)len) break;
    }
    close(fd);
}

const char *jd_shader_text(const char *name)
{
    for (int i = 0; i < jd_shader_source_count; i++)
        if (strcmp(jd_shader_sources[i].name, name) == 0 ||
            strcmp(strrchr(jd_shader_sources[i].name, '/') + 1, name) == 0)
            return jd_shader_sources[i].text;
    return NULL;
}

/* Driver logs say "0:12(5): error" (Mesa), "ERROR: 0:12:" (ANGLE, Mali) or
 * "0(12) : error" (NVIDIA): the first number is the source string, the second
 * the line. */
static void log_location(const char *log, int *string, int *line)
{
    *string = 0;
    *line = 0;
    for (const char *p = log; p && *p; p++)
        if (p[0] >= '0' && p[0] <= '9' && (p[1] == ':' || p[1] == '(') && p[2] >= '0' && p[2] <= '9' &&
            (p == log || p[-1] < '0' || p[-1] > '9')) {
            *string = p[0] - '0';
            *line = atoi(p + 2);
            return;
        }
}

/* The driver's log as one line, so every error stays one line. */
static void one_line_log(GLuint obj, int is_program, char *log, int cap)
{
    log[0] = 0;
    if (is_program) glGetProgramInfoLog(obj, cap, NULL, log);
    else glGetShaderInfoLog(obj, cap, NULL, log);
    for (char *p = log; *p; p++)
        if (*p == '\n' || *p == '\r') *p = ' ';
}

static const char *skip_version(const char *text)
{
    if (strncmp(text, "#version", 8) != 0) return text;
    const char *nl = strchr(text, '\n');
    return nl ? nl + 1 : text + strlen(text);
}

/* Fragment shaders get a default precision (highp only where the packing
 * asks for it and the device has it) and JD_FRAGMENT; every shader gets the packing helpers
 * as source string 1 and the light-map helpers as string 2; the shader's own
 * file is string 0, its lines numbered as in the file. */
static jd_result compile(GLenum type, const char *name, const char *defines, GLuint *out,
                         jd_error *err)
{
    const char *text = jd_shader_text(name);
    const char *pack = jd_shader_text("shaders_es2/pack.glsl");
    const char *light = jd_shader_text("shaders_es2/light.glsl");
    if (!text || !pack || !light) return jd_fail(err, JD_ERR_ARG, "shader %s is not embedded in this build", name);
    const char *parts[10];
    int n = 0;
    parts[n++] = "#version 100\n";
    parts[n++] = defines ? defines : "";
    parts[n++] = extra_defines;
    if (type == GL_FRAGMENT_SHADER)
        parts[n++] = "#define JD_FRAGMENT 1\n#if JD_PACK_HIGHP\nprecision highp float;\nprecision highp sampler2D;\n#else\n"
                     "precision mediump float;\nprecision mediump sampler2D;\n#endif\n"
                     "#line 1 1\n";
    else
        parts[n++] = "precision highp sampler2D;\n#line 1 1\n";
    parts[n++] = pack;
    parts[n++] = "\n#line 1 2\n";
    parts[n++] = light;
    parts[n++] = "\n#line 2 0\n";
    parts[n++] = skip_version(text);
    if (dump_dir) dump(name, parts, n);
    GLuint sh = glCreateShader(type);
    glShaderSource(sh, n, parts, NULL);
    glCompileShader(sh);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024];
        one_line_log(sh, 0, log, sizeof log);
        glDeleteShader(sh);
        int string, line;
        log_location(log, &string, &line);
        return jd_fail(err, JD_ERR_GL, "%s:%d: shader does not compile: %s",
                       string == 1 ? "shaders_es2/pack.glsl" : string == 2 ? "shaders_es2/light.glsl" : name, line, log);
    }
    *out = sh;
    return JD_OK;
}

static jd_result build_program(const char *vs_name, const char *fs_name, const char *defines,
                               const char *const *attribs, GLuint *out, jd_error *err);

jd_result jd_program_build(const char *vs_name, const char *fs_name, const char *defines,
                           const char *const *attribs, GLuint *out, jd_error *err)
{
    if (observer) observer(observer_user, vs_name, fs_name, defines, -1, NULL);
    jd_result r = build_program(vs_name, fs_name, defines, attribs, out, err);
    if (observer) observer(observer_user, vs_name, fs_name, defines, (int)r, r && err ? err->msg : NULL);
    return r;
}

static jd_result build_program(const char *vs_name, const char *fs_name, const char *defines,
                               const char *const *attribs, GLuint *out, jd_error *err)
{
    GLuint vs = 0, fs = 0;
    jd_result r = compile(GL_VERTEX_SHADER, vs_name, defines, &vs, err);
    if (r) return r;
    r = compile(GL_FRAGMENT_SHADER, fs_name, defines, &fs, err);
    if (r) { glDeleteShader(vs); return r; }
    GLuint p = glCreateProgram();
    glAttachShader(p, vs);
    glAttachShader(p, fs);
    for (GLuint i = 0; attribs && attribs[i]; i++) glBindAttribLocation(p, i, attribs[i]);
    glLinkProgram(p);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[1024];
        one_line_log(p, 1, log, sizeof log);
        glDeleteProgram(p);
        return jd_fail(err, JD_ERR_GL, "%s + %s: program does not link: %s", vs_name, fs_name, log);
    }
    *out = p;
    return JD_OK;
}
