/* jade inside a program of one's own: the program makes its own GLES 2.0
 * context (here an EGL one without a window, drawing into a framebuffer
 * object) and hands jade the mesh's bytes from its own asset system.
 * Builds as C and as C++:  cc embed.c $(pkg-config --cflags --libs jade egl glesv2)
 * Run:  ./a.out /usr/share/jade/default.drc */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES2/gl2.h>
#include <jade/jade.h>

static int fail(const char *what, const char *why) { fprintf(stderr, "embed: %s: %s\n", what, why); return 1; }

int main(int argc, char **argv)
{
    /* The mesh's bytes, as an asset system would hand them over. */
    static unsigned char file[8 << 20];
    FILE *f = argc > 1 ? fopen(argv[1], "rb") : NULL;
    if (!f) return fail("usage", "embed MESH (.drc, .glb, .obj, .ply or .stl)");
    size_t size = fread(file, 1, sizeof file, f);
    fclose(f);
    /* jade's whole budget, taken once; the mesh is decoded before any GL
     * context exists (the decoder runs in a forked, sandboxed child). */
    static unsigned char memory[16 << 20];
    jd_arena arena;
    jd_arena_init(&arena, memory, sizeof memory);
    jd_error err = {JD_OK, {0}};
    jd_load_desc load;
    memset(&load, 0, sizeof load); /* zero fields: the defaults */
    load.path = argv[1]; /* only its name, for messages */
    load.data = file;
    load.size = size;
    jd_mesh mesh;
    if (jd_mesh_load_draco(&load, &arena, &mesh, NULL, &err)) return fail("load", err.msg);

    /* The program's own context: EGL on Mesa's surfaceless platform. */
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    EGLDisplay dpy = get_display ? get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL) : EGL_NO_DISPLAY;
    const EGLint cfg_attr[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES2_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
    const EGLint ctx_attr[] = {EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE};
    EGLConfig cfg;
    EGLint n = 0;
    if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, NULL, NULL) || !eglBindAPI(EGL_OPENGL_ES_API) || !eglChooseConfig(dpy, cfg_attr, &cfg, 1, &n) || !n)
        return fail("EGL", "no surfaceless display with a GLES 2.0 config");
    EGLContext ctx = eglCreateContext(dpy, cfg, EGL_NO_CONTEXT, ctx_attr);
    if (ctx == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx))
        return fail("EGL", "cannot make a GLES 2.0 context current");
    GLuint tex, depth, fbo;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 256, 256, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glGenRenderbuffers(1, &depth);
    glBindRenderbuffer(GL_RENDERBUFFER, depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT16, 256, 256);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);

    /* jade draws one frame into it. */
    jd_gl_caps caps;
    jd_renderer_desc desc;
    memset(&desc, 0, sizeof desc);
    jd_renderer *r;
    jd_scene scene;
    desc.mesh = &mesh;
    desc.caps = &caps;
    desc.target_fbo = fbo;
    desc.width = desc.height = 256;
    jd_scene_defaults(&scene, jd_material_find("skin1"));
    if (jd_gl_caps_query(&caps, &err) || jd_renderer_create(&desc, &arena, &r, &err) ||
        jd_renderer_frame(r, &scene, NULL, &err))
        return fail("render", err.msg);
    unsigned char px[4];
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glReadPixels(128, 128, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    printf("embed: %u triangles, centre pixel %d %d %d, arena peak %zu bytes\n", mesh.num_indices / 3, px[0], px[1],
           px[2], arena.peak);
    jd_renderer_destroy(r);
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, ctx);
    eglTerminate(dpy);
    return 0;
}
