/* What the GL device can do, queried once, possibly clamped by a profile. */
#ifndef JD_GL_CAPS_H
#define JD_GL_CAPS_H

#include "jd_result.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct jd_gl_caps {
    char vendor[64], renderer[128], version[128], glsl[96];
    int max_texture_size, max_renderbuffer_size, max_cube_map_size;
    int max_vertex_attribs, max_vertex_uniform_vectors, max_fragment_uniform_vectors;
    int max_varying_vectors, max_texture_units, max_vertex_texture_units;
    int max_viewport_w, max_viewport_h;
    /* glGetShaderPrecisionFormat(FRAGMENT, HIGH_FLOAT): precision bits 0 = no highp */
    int frag_highp_precision, frag_highp_range;
    int frag_mediump_precision, frag_mediump_range;
    int ext_element_index_uint, ext_disjoint_timer_query, ext_depth_texture,
        ext_texture_float, ext_packed_depth_stencil, ext_rgb8_rgba8, ext_texture_npot,
        ext_standard_derivatives;
    /* EXT_multisampled_render_to_texture: a texture drawn into with samples
     * that live in a tiler's tile buffer and are resolved as each tile is
     * written out (Mesa's lima and panfrost have it); max_samples is its
     * GL_MAX_SAMPLES_EXT (0 without it). */
    int ext_multisampled_render_to_texture, max_samples;
    int num_extensions;
    int utgard; /* Mali-400/450 and kin by renderer string: fp16 fragments whatever the query says */
    int small_register_file; /* VideoCore IV, Mali-400/450 (by name or profile): shaders kept small */
    int vivante;             /* Vivante GC model by renderer string (2000 for "Vivante GC2000 rev 5108" or "GC2000 core"), or 0 */
    int adreno;              /* Adreno model by renderer string ("FD307" from Mesa: 307; "Adreno (TM) 306": 306), or 0 */
    /* The mesh's vertex count from which full's levels are summed per
     * fragment, into a buffer at a lower resolution, even though the vertex
     * stage could read them; 0: never (Adreno 3xx, VideoCore IV and Vivante
     * GC3000-GC7000, by name or profile, set it). Their vertex and fragment
     * programs share one set of ALUs: the per-vertex sum (ir3's 477
     * instructions, vc4's 176, GC7000Lite's 313) on
     * every vertex costs more than the buffer's few thousand fragments on
     * large meshes and less on small ones, by the frame-cost model
     * (docs/frame-cost.md). */
    int levels_per_fragment_from;
    /* Instructions a program may have per stage, 0: no limit known. Vivante
     * cores before GC3000 hold their programs in a 256-instruction memory
     * (no instruction cache): a longer one fails when it is drawn. */
    int max_program_instructions;
    /* The boards' tier (docs/frame-cost.md): pictures over 960x540 shaded
     * at that count; the board's name, or "" for any other GPU. */
    char tier[32];
    char profile[16]; /* the device profile applied, or empty */
} jd_gl_caps;

/* proc returns GL entry points by name (from the platform); may be NULL. */
jd_result jd_gl_caps_query(jd_gl_caps *caps, jd_error *err);
/* What jade knows of a GPU by its GL_VENDOR and GL_RENDERER strings (set
 * in caps): Mali-400/450's fp16 fragments, the small register files of
 * those and VideoCore IV, the Vivante and Adreno models and the Vivante
 * program limit. jd_gl_caps_query calls it; a test can too, with no GL. */
void jd_gl_caps_recognise(jd_gl_caps *caps);
/* Vertex texture units full's levels' sum per vertex reads: the light map
 * and the five levels. */
#define JD_DIFFUSION_VERTEX_UNITS 6
/* Texture units full takes in all when it sums them per vertex, the light
 * map that its light scattered once reads (mesh.vert, jd_single_march)
 * among them, before a colour texture: one more than a GPU of 8
 * (VideoCore IV) has beside one (render_program.c). */
#define JD_FULL_VERTEX_LEVELS_UNITS 8
/* levels_per_fragment_from where a GPU sets it: the vertex count at which
 * the two paths cost the same by the frame-cost model at 1080p, taken from
 * the close-up, where the frame costs most (tools/frame-cost.sh's boards;
 * docs/frame-cost.md has the meshes measured). Halved and more since the
 * sum per vertex marches the light scattered once through the light map
 * (mesh.vert, jd_single_march): 3,000, 16,000 and 3,000 before. */
#define JD_ADRENO3XX_LEVELS_PER_FRAGMENT_FROM 1100
#define JD_VC4_LEVELS_PER_FRAGMENT_FROM 8000
#define JD_VIVANTE_LEVELS_PER_FRAGMENT_FROM 1350
/* Whether full's levels are summed in the vertex stage on this GPU for a
 * mesh of `vertices`, with a colour texture or not: where it reads all their
 * textures, has a unit left for the light map its light scattered once
 * reads (JD_FULL_VERTEX_LEVELS_UNITS, and one for the colour), and does not
 * pay less for the sum per fragment at a lower resolution from that size on
 * (levels_per_fragment_from). The renderer's choice where it is not told
 * (jd_renderer_desc.levels), and jade info's lines. */
int jd_gl_caps_levels_per_vertex(const jd_gl_caps *caps, unsigned vertices, int colour_texture);
int jd_gl_has_extension(const char *name);
/* Whether a space-separated extension list (GL's, or EGL's from
 * eglQueryString) names `name` as a whole word; list may be NULL. The one
 * extension search of jade and its platforms. */
int jd_extension_listed(const char *list, const char *name);

/* Whether mediump fragment arithmetic really runs at 16 bits here, by a
 * canary shader that no compiler can fold: 1 yes, 0 no (32 bits: e.g.
 * llvmpipe on a CPU without F16C), -1 could not tell. Draws into a 4x4
 * target and reads one pixel back: for start-up and tests, never a frame. */
int jd_gl_mediump_is_fp16(void);
/* The same, with the canary pixel's bytes (RGBA; red 191 at 32 bits, 64,
 * 0 or 255 at 16 as the driver rounds). */
int jd_gl_mediump_canary(unsigned char rgba[4]);

/* How many textures, buffers, framebuffers and renderbuffers the current
 * context holds: every name below the one a new object would get, asked
 * with glIsTexture and the like (drivers need not reuse freed names, so
 * the next name alone climbs without a leak). Flat over a long run unless
 * GL objects leak: a leak detector that needs no driver support. Costs a
 * few thousand glIs* calls; call it rarely (health lines), never in a frame. */
typedef struct jd_gl_names { unsigned texture, buffer, framebuffer, renderbuffer; } jd_gl_names;
void jd_gl_probe_names(jd_gl_names *out);

#ifdef __cplusplus
}
#endif

#endif
