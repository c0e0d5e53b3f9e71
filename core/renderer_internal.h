/* The renderer's insides, shared by its files and installed nowhere:
 * renderer.c (creation, the frame as a plan of passes), render_target.c
 * (targets and uploads), render_program.c (the program groups),
 * render_draw.c (binding and drawing, counted), pass_light.c (light depth,
 * full's diffusion), pass_sh.c (capture and SH), pass_screen.c (the
 * picture's passes), frame_count.c (jd_renderer_count). Names carry jdr_. */
#ifndef JD_RENDERER_INTERNAL_H
#define JD_RENDERER_INTERNAL_H

#include <stdint.h>

#include "diffusion_fit.h"
#include "frame_cost.h"
#include "gl.h"
#include "material.h"
#include "renderer.h"
#include "vmath.h"


#define SH_BLOCK 8
#define SH_BLOCK_SMALL 2 /* VideoCore IV, Mali-400: see jd_renderer_create */
/* The irradiance cube map's texels per face side: the SH irradiance is
 * smooth (order 2), and 16 x 16 per face, bilinearly filtered, carry it. */
#define IRR_SIZE 16
#define BLUR_TAPS 4
/* The full mode's light-space levels: Gaussians of 1, 2, 4, 8 and 16 texels
 * of the first level, one RGBA8 texture each, every second one half the
 * size (a wider Gaussian needs fewer texels): a pyramid. Each blur step has
 * 2 * DIFF_TAPS + 1 taps. */
#define DIFF_LEVELS 5
#define DIFF_TEXTURES DIFF_LEVELS
#define DIFF_TAPS 6
/* Rd's Gaussians finer than a level texel are applied at the shaded point. */
#define DIFF_LOCAL 3
/* On a lit point this share of the first level's weight is taken with the
 * local part, the rest from the level (light.glsl, jd_diffused, which gets
 * the level's weight times the share and takes 1 / share - lit of it: its
 * 2.0 is this share's reciprocal). */
#define DIFF_FIRST_SHARED 0.5f

/* Render targets are power-of-two textures (some ES 2.0 drivers cannot
 * render to NPOT ones); w x h is the region in use, set by the viewport. */
typedef struct target {
    GLuint tex, fbo, depth;
    int w, h;   /* used */
    int tw, th; /* allocated, powers of two */
    int samples; /* > 1: drawn with that many samples, resolved into tex (EXT_multisampled_render_to_texture) */
} target;

static inline int pot(int n)
{
    int p = 1;
    while (p < n) p <<= 1;
    return p;
}

typedef struct shade_prog {
    GLuint id;
    GLint mvp, light_tex, eye, irr, box_min, box_max, inv_eta, inset;
    GLint light_dir, albedo, light_color, shading, depth, tail, depth_v, tail_v, f0, fresnel, a0_scale;
    GLint spread, inv_viewport, w0, wide_scale;
    GLint light_map, shadow_bias, lv[DIFF_TEXTURES], lw, ls;
    GLint amb_x, local_x, wide_x, spec_x; /* full's constant factors (shade.frag) */
    GLint light_map_v, light_dir_v, lv_v[DIFF_TEXTURES], wide;
    GLint albedo_norm, albedo_map, albedo_reach;
    GLint slab, slab_scale, keep, bounce_rd, wrap;
    GLint light_depth_v, march_st, march_ss, march; /* full per vertex: the light scattered once (mesh.vert, jd_single_march) */
    GLint soft_c; /* full: the exponential shadow map's exponent (light.glsl, jd_soft_lit) */
    GLint spec;   /* full, the levels read from the half-resolution pass: the highlight's table */
    int light_z_scaled; /* u_light_tex's depth row scaled and offset to the shadow test's exponent (mesh.vert) */
} shade_prog;

/* A step of the full mode's light-space diffusion (diffuse_blur.frag). */
typedef struct diff_prog {
    GLuint id;
    GLint src, ref, ref_scale, step, taps, w, uv_scale, near;
    int trips; /* built with this constant trip count (JD_TRIPS), or 0: the loop's count is a uniform */
} diff_prog;

#define TAIL_SIZE 256
#define SLAB_SIZE 256
/* The highlight's table (pass_screen.c, jdr_update_spec): n.n of the
 * interpolated normal over [SPEC_NN, 1] across, n.h over [0, 1] up, the
 * ends at the end texels' centres. SPEC_NN (0.206) makes the coordinates'
 * constants exact in fp16, as lima holds them: 1.25 n.n - 65/256 and
 * 255/256 n.h + 1/512. */
#define SPEC_W 128
#define SPEC_H 256
#define SPEC_NN (1.0 - (SPEC_W - 1) / (1.25 * SPEC_W))
enum { PROJECT_FLOATS = 17 }; /* per vertex of the SH projection's rectangles (pass_sh.c) */

/* GL_EXT_disjoint_timer_query, resolved at start-up when present. */
typedef struct timer_query {
    PFNGLGENQUERIESEXTPROC gen;
    PFNGLDELETEQUERIESEXTPROC del;
    PFNGLBEGINQUERYEXTPROC begin;
    PFNGLENDQUERYEXTPROC end;
    PFNGLGETQUERYOBJECTUI64VEXTPROC result64;
    GLuint q[JD_PASS_COUNT];
    int ok, used[JD_PASS_COUNT];
} timer_query;

/* GL_EXT_multisampled_render_to_texture, resolved at start-up where the
 * frame drawn smaller takes the target's samples. */
typedef struct ms_render {
    PFNGLFRAMEBUFFERTEXTURE2DMULTISAMPLEEXTPROC texture;
    PFNGLRENDERBUFFERSTORAGEMULTISAMPLEEXTPROC storage;
    int samples; /* asked of `scene`: the target's, at most the extension's GL_MAX_SAMPLES_EXT; 0: none */
} ms_render;

struct jd_renderer {
    jd_renderer_desc d;
    int highp;
    int timing; /* jd_renderer_set_timing */
    int vertex_thickness; /* thickness read in the vertex stage */
    int vertex_diffusion; /* the full mode's levels summed in the vertex stage */
    int target_samples;   /* samples of the target: desc.target_samples, or GL_SAMPLES */
    int post_aa;          /* frames go to `scene`, then through the anti-aliasing pass */
    int aa_small;         /* the target has samples; a picture drawn smaller with none gets the pass at its size */
    int luma_alpha;       /* post_aa at start-up (0 with the pass unbuilt): the frame's alpha holds its luma for it */
    int aa_now;           /* the pass runs at this size: post_aa, or aa_small on a picture drawn smaller with one sample */
    int target_depth;     /* the target has a depth buffer: the pass after the frame can mark its flat pixels there */
    int may_scale;        /* render_scale may be under 1 at some size: `scene` and the upscale pass exist */
    int iw, ih;           /* the picture's passes' size: width x height, or less (render_scale) */
    char tier[200];       /* what the tier draws at, for jd_renderer_info */
    int sh_block;         /* capture texels per SH projection pixel, per side (8, or 2 on small register files) */
    int sh_mid;           /* > 1: an intermediate reduction by sh_mid x sh_mid, so no pass sums over 64 texels */
    jd_mode shown[JD_MODE_COUNT]; /* what a frame asking for each mode draws (build_programs) */
    char fallback[1024];  /* what this device could not run, and what it gets instead; "" */
    jd_mesh proxy, capture_proxy;
    GLuint mesh_vbo, mesh_ibo, proxy_vbo, proxy_ibo, cap_vbo, cap_ibo, quad_vbo;
    GLuint project_vbo;   /* the SH projection's 6 x 27 rectangles, with their constants */
    GLuint tail_tex;
    GLuint slab_tex;      /* full: the light a slab lets through, by thickness (pass_light.c) */
    float slab_range_mm;  /* the thickness at the table's end */
    float keep[2][3];     /* full: a lit face's levels kept by a part t mm thick, 1 - a 2^(-b t) (pass_light.c) */
    /* The model's own colours (mesh->colors): the vertex layout, and its
     * texture (0: none) with its size on the GPU and its texels per world
     * unit of the surface (for the entry's mip level). */
    int albedo, vstride;
    int albedo_partial;   /* some vertices' texture weight is 0 (partly untextured materials) */
    GLuint albedo_tex;
    int albedo_w, albedo_h;
    size_t albedo_bytes;
    float albedo_key[8], albedo_reach_mm; /* the material the entry's radius was found for, and it */
    float fresnel_eta, fresnel[2]; /* the eta full's Fresnel factor was fitted at, and the fit */
    timer_query tq;
    ms_render ms;
    char ms_note[160];    /* "", or why `scene` was made with one sample where samples were asked */
    uint8_t *tail_px;     /* TAIL_SIZE RGBA texels, rebuilt when the material changes */
    float tail_key[9];
    GLuint spec_tex;      /* full without vertex diffusion: the highlight by (n.n, n.h), SPEC_W x SPEC_H luminance */
    uint8_t *spec_px;     /* its texels, rebuilt when the shininess changes */
    float spec_key;
    float fit_key[10];
    jd_diffusion_fit fit;
    int diff_levels;      /* levels whose weights are not all zero */
    float proxy_error;    /* world units: how far the proxy may stray from the mesh */
    GLenum mesh_index_type;
    /* GPUs without 32-bit indices draw a mesh over 65,536 vertices as chunks
     * that each fit 16 bits, their vertices copied (so shared edges are
     * bit-identical: no seam). None: one draw of the whole mesh. */
    struct mesh_chunk { size_t index_offset, vertex_offset; uint32_t count, vertices; } *chunks;
    int num_chunks;
    shade_prog shade[JD_MODE_COUNT], a0, wide_prog; /* wide_prog: full's levels at half resolution */
    int wide_unrolled;    /* wide_prog built with its texel loops unrolled (JD_TRIPS) */
    GLuint depth_prog, capture_prog, project_prog, reduce_mid_prog, reduce_faces_prog, reduce_final_prog, blur_prog,
        combine_prog;
    diff_prog diff_first, diff_next; /* level 1 from the light map; the others */
    GLuint soft_prog;
    GLint soft_src, soft_step, soft_c, soft_scale;
    GLuint fill_prog;     /* the levels' sum with its outline filled (wide_fill.frag) */
    GLint fill_src, fill_texel, fill_scale;
    GLuint aa_prog, up_prog;
    GLint aa_src, aa_texel, aa_scale, up_src, up_scale;
    GLuint aa_mark_prog; /* the pass after the frame's test alone (JD_AA_MARK): flat pixels copied, edges left */
    GLint aa_mark_src, aa_mark_texel, aa_mark_scale;
    double count_edges;  /* jd_renderer_count: the pixels the full pass after the frame runs on (< 0: its whole box) */
    GLint depth_mvp, depth_light_dir, depth_fresnel;
    GLint cap_mvp, cap_light_tex, cap_light_dir, cap_bias, cap_depth, cap_light_color;
    GLint proj_atlas, proj_texel, rm_src, rm_texel, rf_src, rf_texel, rl_src, rl_texel;
    GLuint irr_prog; /* the SH result to the irradiance map */
    GLint irr_src, irr_size, irr_face;
    GLint blur_src, blur_step, blur_inv, blur_scale;
    GLint comb_src, comb_step, comb_inv, comb_a1, comb_w1, comb_w2, comb_scale;
    target light, atlas, sh1, sh_mid_t, sh2, sh3, irr[6], spread0, spread_tmp, spread1, spread2;
    target diff_tmp, diff_lv[DIFF_TEXTURES];
    /* full's exponential shadow map (soft_shadow.frag): its first pass's
     * result, and the map the shading reads in place of the light map. */
    target soft_tmp, soft;
    target scene;         /* the frame before anti-aliasing or enlarging (post_aa, or drawn smaller) */
    /* aa_now with the picture drawn smaller: `scene` anti-aliased at its
     * own size, which the enlarging then reads (one texel where unused).
     * Its depth is `scene`'s renderbuffer, attached while it is used: the
     * frame is drawn by then, and the pass marks its flat pixels there. */
    target aa_mid;
    target wide;          /* full's levels summed at a lower resolution (without vertex diffusion) */
    target wide_fill;     /* the same with its outline filled, which the picture reads */
    /* The object's extent on screen in NDC (x0, y0, x1, y1) for the pass
     * after the frame, and the transform it was found for. */
    float extent[4], extent_mvp[16];
    int extent_inside, extent_valid;
    size_t target_bytes;
    float box_half;
    jd_vec3 place_c;      /* the mesh's coordinates to the renderer's: (p - place_c) * place_inv_r */
    float place_inv_r;
    /* What a tiler would pay this frame: render-target switches (each one
     * writes the tile memory out), pixels shaded (by target area), bytes
     * written to render targets, read-backs. */
    int n_switches, n_readbacks;
    double n_fragments, n_bytes;
    /* The inputs of the light-space passes and of the screen-space spread
     * at the last frame, so a still scene reuses their results. */
    float light_key[16], view_key[24];
    int light_key_valid, view_key_valid;
    /* Programs by id with the compiler table's label for them, for the
     * frame-cost count. */
    struct { GLuint id; char label[96]; } labels[40];
    int num_labels;
    /* jd_renderer_count's frame: its record (NULL in every other frame),
     * the counting program, the vertices each mesh's draw shades under the
     * vertex reuse asked for (whole mesh, proxy, capture proxy), and
     * whether the open pass drew meshes (its fragments are read back). */
    jd_frame_count *count;
    GLuint count_prog;
    GLint count_mvp;
    double count_vertices[3];
    int count_read, count_cleared;
};

/* ---- per frame ---------------------------------------------------------- */

/* Everything a frame derives from the scene on the CPU, once. */
typedef struct frame_params {
    jd_mat4 mvp, light_mvp;
    /* light_mvp with its clip space taken to light-map coordinates ([-1, 1]
     * to [0, 1] in x, y and depth): what the shading and capture passes read. */
    jd_mat4 light_tex;
    jd_vec3 eye, light_dir;
    float light_color[3], albedo[3];
    float a0_scale[3], f0, fresnel[2];
    float shading[4];
    float range_mm;
    jd_dipole dipole;
    float w0[3], w1[3], w2[3];
    float inv_eta, inset;
    float mm_per_world, blur_sigma_px;
    float albedo_norm[3]; /* 1 / the colours' mean (JD_ALBEDO) */
    float albedo_reach;   /* the entry's radius in pixels times the depth it is seen at (JD_ALBEDO_MAP) */
    float px_per_world;   /* the picture's passes' pixels per world unit at the object's centre */
    float light_map[4], shadow_bias[2];
} frame_params;

/* render_target.c */
/* Bytes per uploaded vertex: position with the part's thickness as its
 * fourth float, and the unit normal; with colours, texture coordinates and
 * the colour's 4 bytes too; then the surface's curvature (two floats, k
 * and 1 / k, mesh_curvature.h); last, the light between parts' transfer (4
 * floats, mesh_bounce.h). */
#define JDR_STRIDE_PLAIN 52
#define JDR_STRIDE_COLOUR 64
#define JDR_BOUNCE_BYTES 16
#define JDR_CURVE_AT(stride) ((stride) - JDR_BOUNCE_BYTES - 8)
int jdr_vertex_stride(const jd_mesh *m);
jd_result jdr_upload_albedo(jd_renderer *r, const jd_mesh *m, jd_arena *a, jd_error *err);
GLuint jdr_new_texture(int w, int h, GLint filter);
GLuint jdr_new_table(int w, int h);
jd_result jdr_make_target(jd_renderer *r, target *t, int w, int h, int with_depth, int linear,
                             const char *what, jd_error *err);
jd_result jdr_make_target_ms(jd_renderer *r, target *t, int w, int h, int with_depth, int linear, int samples,
                             const char *what, jd_error *err);
jd_result jdr_make_cube_target(jd_renderer *r, target *faces, int size, const char *what, jd_error *err);
void jdr_free_target(target *t);
jd_result jdr_fit_target(jd_renderer *r, target *t, int w, int h, int linear, const char *what, jd_error *err);
jd_result jdr_upload_mesh(const jd_mesh *m, const float *thick, const float *curve, const float *bounce, jd_vec3 c,
                          float inv_r, GLuint *vbo, GLuint *ibo, jd_arena *a, jd_error *err);
jd_result jdr_upload_mesh_chunked(jd_renderer *r, const jd_mesh *m, const float *thick, const float *curve,
                                  const float *bounce, jd_vec3 c, float inv_r, jd_arena *a, jd_error *err);

/* render_draw.c */
void jdr_bind_mesh(GLuint vbo, GLuint ibo);
/* The vertex attributes of the whole mesh from byte `at` of its buffer
 * (a chunk's first vertex): position, normal, curvature, the transfer and,
 * with colours, 2 and 3. */
void jdr_mesh_attributes(const jd_renderer *r, size_t at);
void jdr_bind_quad(const jd_renderer *r);
void jdr_count_target(jd_renderer *r, const char *what, int w, int h);
void jdr_use_target(jd_renderer *r, const target *t, const char *what);
void jdr_draw_quad_into(jd_renderer *r, const target *t, const char *what, const target *src);
/* The same over the rectangle x, y, w, h of t only (the scissor keeps the rest). */
void jdr_draw_quad_rect(jd_renderer *r, const target *t, const char *what, const target *src, const int rect[4]);
void jdr_draw_elements(jd_renderer *r, int mesh, const jd_mat4 *mvp, GLsizei count, GLenum type, const void *at,
                          double vertices);
void jdr_draw_mesh(jd_renderer *r, const jd_mat4 *mvp);

/* render_program.c */
jd_result jdr_build_programs(jd_renderer *r, jd_error *err);

/* pass_light.c */
void jdr_update_fit(jd_renderer *r, const jd_scene *s, const frame_params *f);
void jdr_pass_light_depth(jd_renderer *r, const jd_scene *s, const frame_params *f);
void jdr_pass_diffusion(jd_renderer *r, const jd_scene *s, const frame_params *f);
void jdr_pass_soft_shadow(jd_renderer *r, const jd_scene *s, const frame_params *f);
float jdr_soft_c(const jd_renderer *r);

/* pass_sh.c */
void jdr_update_tail(jd_renderer *r, const jd_scene *s, const frame_params *f);
void jdr_pass_capture(jd_renderer *r, const jd_scene *s, const frame_params *f);
jd_result jdr_build_projection_quads(jd_renderer *r, jd_arena *a, jd_error *err);
void jdr_pass_sh(jd_renderer *r, const jd_scene *s, const frame_params *f);

/* pass_screen.c */
void jdr_pass_spread(jd_renderer *r, const jd_scene *s, const frame_params *f);
void jdr_pass_wide(jd_renderer *r, const jd_scene *s, const frame_params *f);
void jdr_update_spec(jd_renderer *r, const jd_scene *s, const frame_params *f);
void jdr_pass_main(jd_renderer *r, const jd_scene *s, const frame_params *f);
void jdr_pass_final(jd_renderer *r, const jd_scene *s, const frame_params *f);

/* frame_count.c */
jd_pass_count *jdr_counted(jd_renderer *r);
jd_pass_count *jdr_counted_draw(jd_renderer *r);
void jdr_counted_quad(jd_renderer *r, double fragments, double vertices, double triangles);
void jdr_counted_read(jd_renderer *r, const target *t, double layers);
void jdr_counted_trips(jd_renderer *r, double trips);
int jdr_diffusion_taps(const jd_renderer *r, int k, float *step, float *st);
void jdr_counted_open(jd_renderer *r, const char *what, int w, int h);

/* The frame goes to `scene` first, then through the pass after it:
 * anti-aliasing, or enlarging a picture drawn smaller. */
static inline int jdr_via_scene(const jd_renderer *r)
{
    return r->post_aa || r->iw != r->d.width || r->ih != r->d.height;
}

/* At this size the pass after the frame marks its flat pixels in a depth
 * buffer first and shades the edges only: the frame's depth where it is
 * drawn smaller (attached to `aa_mid`), else the target's, if it has one. */
static inline int jdr_aa_marks(const jd_renderer *r)
{
    return r->aa_now && r->aa_mark_prog && (r->iw != r->d.width || r->ih != r->d.height || r->target_depth);
}

#endif
