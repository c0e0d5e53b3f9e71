/* The translucency renderer: every GL resource is made at creation; a frame
 * allocates nothing. */
#ifndef JD_RENDERER_H
#define JD_RENDERER_H

#include "arena.h"
#include "frame_cost.h"
#include "gl_caps.h"
#include "material.h"
#include "mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* none: direct light, shadowed; single: + the SCCG 2006 translucent layer;
 * dual: + the spread funnel (the paper); full: the direct light diffused under
 * the surface with the dipole's profile (jade's own, measured against
 * jade reference). */
typedef enum jd_mode { JD_MODE_NONE = 0, JD_MODE_SINGLE, JD_MODE_DUAL, JD_MODE_FULL, JD_MODE_COUNT } jd_mode;
typedef enum jd_precision { JD_PRECISION_AUTO = 0, JD_PRECISION_HIGHP, JD_PRECISION_MEDIUMP } jd_precision;
/* Edges: AUTO leaves them to a multisampled target (GL_SAMPLES > 1: an EGL
 * config with samples, free on tile-based GPUs; a picture drawn smaller for
 * it is drawn with the target's samples where the GPU has
 * EXT_multisampled_render_to_texture, and where it has not, smoothed by
 * the pass below at its own size before it is enlarged) and otherwise
 * smooths them in a pass after the frame (one full-size render target
 * more). Where the target has
 * a depth buffer, or the picture is drawn smaller, the pass's own test
 * first marks the flat pixels in the depth buffer, and the pass then shades
 * only the edges (a few percent of the pixels), with the same picture. */
typedef enum jd_antialias { JD_AA_AUTO = 0, JD_AA_OFF, JD_AA_POST } jd_antialias;
/* The start-up check that every program draws (core/program_probe.c): two
 * small read-backs, and every program's shaders compiled at once rather
 * than when a mode first needs them. AUTO runs it on GPUs and skips it on
 * software rasterizers (llvmpipe, softpipe), which draw whatever links. */
typedef enum jd_probe { JD_PROBE_AUTO = 0, JD_PROBE_ON, JD_PROBE_OFF } jd_probe;
/* Where full sums its light-space levels: in the vertex stage (where it
 * reads six textures), or per fragment into a buffer at a lower resolution
 * that the picture reads. AUTO: by the GPU and the mesh's vertex count
 * (jd_gl_caps_levels_per_vertex), and per fragment wherever the sum per
 * vertex would leave full without its light through thin parts (a GPU of 8
 * texture units with a colour texture). The two give nearly the same
 * picture; asking for one tests it or prices it on a board. */
typedef enum jd_levels { JD_LEVELS_AUTO = 0, JD_LEVELS_VERTEX, JD_LEVELS_FRAGMENT } jd_levels;

const char *jd_mode_name(jd_mode m);
int jd_mode_parse(const char *s, jd_mode *out);

/* Zero fields take the defaults in brackets (jd_renderer_desc_defaults
 * writes them in); mesh and caps are the caller's. */
typedef struct jd_renderer_desc {
    const jd_mesh *mesh;
    const jd_gl_caps *caps;
    unsigned target_fbo;  /* where frames go: the caller's framebuffer object [0, the window] */
    int width, height;    /* [512 x 512] */
    int max_width, max_height; /* [width x height] the largest jd_renderer_resize may ask */
    int rotation;         /* 0, 90, 180 or 270 degrees: portrait panels, applied in the projection */
    int cube_size;        /* [64] texels per capture face, a multiple of 8 */
    int light_map_size;   /* [256] */
    int proxy_cells;      /* [40] vertex-clustering grid of the proxy mesh */
    int capture_cells;    /* [24] coarser proxy for the cube capture */
    int spread_divisor;   /* [8] spread layers at 1/N resolution */
    int diffusion_size;   /* [light_map_size / 4] texels per side of the full mode's first light-space level, a power of two, at least light_map_size / 16 */
    jd_precision precision; /* [from the device's fragment highp support] */
    jd_antialias antialias; /* [AUTO] */
    int no_cull;          /* draw back faces too (open meshes) */
    int fragment_thickness; /* read thickness per fragment even where the
                               vertex stage could (coarse meshes); full's
                               levels then per fragment too */
    jd_levels levels;     /* [AUTO] where full sums its levels (VERTEX needs 6 vertex texture units) */
    /* Looks up GL extension entry points (the platform's); with it and
     * GL_EXT_disjoint_timer_query, timed frames also get GPU pass times. */
    void *(*get_proc)(const char *name);
    jd_probe program_probe; /* [AUTO] (OFF: compile-only runs on drivers that cannot read back) */
    /* The picture's passes drawn at this share of width x height and
     * enlarged to it by one bilinear pass (0.25..1). [0: the device's tier:
     * 1, or where a board cannot shade the full resolution in a frame
     * (Mali-400/450, VideoCore IV) at 960 rows and more, less; the line
     * jd_renderer_info.tier says which] */
    float render_scale;
    /* Samples per pixel of target_fbo. [0: its GL_SAMPLES] A caller whose
     * framebuffer's colour is attached by EXT_multisampled_render_to_texture
     * says so here: Mesa 22.3's GL_SAMPLES reads 0 for it, and the renderer
     * would run its anti-aliasing pass over a picture already multisampled
     * (jd_platform_samples knows the headless target's). */
    int target_samples;
} jd_renderer_desc;

/* What a frame shows. jd_scene_defaults fills a sensible one. */
typedef struct jd_scene {
    jd_mode mode;
    float cam_azimuth, cam_elevation; /* degrees */
    float cam_distance;   /* in bounding radii (half the box diagonal); 0: fit */
    float fit;            /* [0.9] with cam_distance 0: the camera comes as near as
                             keeps the object's bounding box within this share
                             of the picture, across and up */
    float fov_deg;
    float light_azimuth, light_elevation;
    float light_intensity;
    float ambient, specular, shininess, exposure;
    float sigma_s[3], sigma_a[3]; /* mm^-1 */
    float eta, density;
    float mm_per_unit;    /* 0: the object is 100 mm across */
    float gain;           /* artistic K of the translucent layer */
    float background[3];
} jd_scene;

void jd_scene_defaults(jd_scene *s, const jd_material *m);

/* What a scene makes of a mesh's world, in one place so that the renderer
 * and anything that must show the same picture (jade reference) agree. */
typedef struct jd_scene_view {
    jd_vec3 centre;       /* jd_mesh_placement */
    float radius;
    float mm_per_world;   /* millimetres per world unit */
    jd_vec3 eye;          /* the camera, looking at the origin with +Y up */
    float cam_distance, fov_deg;
    jd_vec3 light_dir;    /* unit, towards the (directional) light */
    float eta, f0;        /* refractive index, Schlick's F0 */
    float shininess, exposure;
} jd_scene_view;
/* aspect: width / height of the picture as the camera sees it. */
void jd_scene_view_of(const jd_scene *s, const jd_mesh *m, float aspect, jd_scene_view *v);

enum { JD_PASS_LIGHT_DEPTH, JD_PASS_CAPTURE, JD_PASS_SH, JD_PASS_SPREAD, JD_PASS_DIFFUSION, JD_PASS_MAIN, JD_PASS_COUNT };
const char *jd_pass_name(int pass);

typedef struct jd_frame_stats {
    double pass_ms[JD_PASS_COUNT]; /* CPU wall time per pass (with jd_renderer_set_timing) */
    double gpu_ms[JD_PASS_COUNT];  /* GPU time per pass, when gpu_valid */
    int gpu_valid;
    float blur_sigma_px;           /* spread width in low-res pixels */
    /* What the frame costs a tile-based GPU, counted by the renderer:
     * render-target switches (each writes the tile memory out), read-backs
     * (each waits for everything drawn so far), pixels covered by the
     * passes (target areas) and bytes written to render targets (colour). */
    int target_switches, readbacks;
    double fragments, target_bytes_written;
    int reused; /* 0; 1: the light-space passes reused (light and material still); 2: the spread too */
} jd_frame_stats;

typedef struct jd_renderer jd_renderer;

/* Writes the default into every field of d left at zero: on a zeroed
 * descriptor, the defaults themselves (the values in brackets above). */
void jd_renderer_desc_defaults(jd_renderer_desc *d);

/* Every GL object (programs, textures, framebuffers, buffers) is made here,
 * in the context current on this thread, and every byte comes from the
 * arena. On failure nothing is left behind: the GL objects are deleted and
 * the arena is as it was. */
jd_result jd_renderer_create(const jd_renderer_desc *desc, jd_arena *a, jd_renderer **out,
                             jd_error *err);
/* One frame into desc.target_fbo. No read-back, no glFinish, no heap.
 *
 * GL state it sets and leaves so (a caller drawing more in the same context
 * sets these again for itself): the bound framebuffer (target_fbo at the
 * end), viewport and scissor box (the frame's size), the current program,
 * the array and element array buffers, vertex attribute arrays 0-4 (their
 * pointers and enables), the 2D and cube map textures bound on units 0-6
 * (unit 0 active at the end), depth test and face culling (on or off as
 * its last pass needed), the scissor test (on), dither (off) and the clear
 * colour; the target's depth buffer holds the frame's depths, or where the
 * pass after the frame runs, its marks. It expects, and does not set, the rest at GL's defaults:
 * blending off, depth function GL_LESS, colour and depth writes on, front
 * faces counter-clockwise, back faces culled, stencil test off. */
jd_result jd_renderer_frame(jd_renderer *r, const jd_scene *s, jd_frame_stats *stats,
                            jd_error *err);
/* What one frame of `s` asks of a tile-based GPU, pass by pass, for the
 * frame-cost model (jd_frame_cost_estimate): each pass's target, program,
 * fragments shaded (with overdraw, after the depth test: its mesh draws are
 * made again by a counting program and the target read back), vertices
 * shaded (vertex_cache 0: each draw's index range; N: a FIFO of N
 * entries), triangles, and bytes written and read. Not a frame to show: it
 * reads back and builds its counting program the first time, and where
 * the pass after the frame shades only its edges it draws a frame first and
 * reads its picture back to count them; bench calls it outside the timed
 * frames. */
jd_result jd_renderer_count(jd_renderer *r, const jd_scene *s, int vertex_cache, jd_frame_count *out,
                            jd_error *err);
/* Deletes the GL objects (the context must be current); the arena's bytes
 * are the caller's to reset. */
void jd_renderer_destroy(jd_renderer *r);
/* Waits for the GPU (glFinish): for timing whole frames, never inside one. */
void jd_renderer_finish(jd_renderer *r);
/* glFinish after each pass, recording CPU (and, where timer queries exist,
 * GPU) times per pass in jd_frame_stats: for bench, not for a kiosk. */
void jd_renderer_set_timing(jd_renderer *r, int on);
/* A new drawable size within desc.max_width x max_height, between frames.
 * The two targets that follow the picture's size (the frame before the
 * pass after it, full's levels' sum) get storage for it where it takes
 * other powers of two, and the frame's none where nothing goes through it:
 * JD_ERR_GL where the GPU has no memory left for them. */
jd_result jd_renderer_resize(jd_renderer *r, int width, int height, jd_error *err);

/* What a renderer chose for this device, and what it holds. */
typedef struct jd_renderer_info {
    size_t target_bytes;      /* render targets' memory on the GPU */
    size_t texture_bytes;     /* the model's colour texture on the GPU, mipmaps included (0: none) */
    int texture_width, texture_height; /* its size as uploaded (halved to the device's limit) */
    int highp;                /* SH packing: 1 three bytes (fragment highp), 0 two (mediump) */
    int vertex_thickness;     /* thickness read per vertex (vertex texture units), else per fragment */
    int vertex_levels;        /* full's levels summed per vertex, else per fragment at a lower resolution */
    int gpu_timer;            /* GL_EXT_disjoint_timer_query: per-pass GPU times with timing on */
    int target_samples;       /* samples per pixel of the target (desc.target_samples, or GL_SAMPLES) */
    int post_antialias;       /* at this size the anti-aliasing pass runs after each frame */
    /* At this size it shades only the pixels its test finds on an edge,
     * having marked the others in a depth buffer first (the target's, or
     * the frame's where it is drawn smaller): a few percent of them */
    int antialias_edges_only;
    /* Samples per pixel the picture is drawn with: the target's, or where it
     * is drawn smaller and enlarged, its own (EXT_multisampled_render_to_texture;
     * 0 or 1: one) */
    int picture_samples;
    const char *samples_note; /* NULL, or one line: samples asked for the picture and refused by the driver */
    int render_width, render_height; /* the picture's passes' size (render_scale) */
    const char *tier;         /* NULL, or one line: the resolution this device's tier draws at, and why */
    const jd_mesh *proxy;     /* the coarse mesh the light-space passes draw */
    /* What a frame asking for each mode draws: the mode itself, or where
     * this device's compiler rejected a program or its driver draws
     * nothing with one, the nearest cheaper mode (full -> dual -> single ->
     * none). */
    jd_mode shown_as[JD_MODE_COUNT];
    const char *fallback;     /* NULL, or one line: what was dropped, why, and what stands in */
} jd_renderer_info;
void jd_renderer_get_info(const jd_renderer *r, jd_renderer_info *info);
/* Reads back the last frame's capture atlas (3N x 2N RGBA8, rows bottom-up)
 * and the 27 packed SH pixels, for tests against the CPU reference. */
jd_result jd_renderer_read_capture(jd_renderer *r, uint8_t *atlas, uint8_t *sh27, int *n,
                                   jd_error *err);

#ifdef __cplusplus
}
#endif

#endif
