#include "profile.h"

#include <stdio.h>
#include <string.h>

const jd_profile jd_profiles[] = {
    {"generic", "any GLES 2.0 device: the specification's minimums, no extensions", 2048, 2048, 2048, 2048, 128, 16, 8,
     8, 0, 0, 0, "OpenGL ES 2.0.25, tables 6.18-6.20 (sizes raised to 2048, the smallest jade renders with)",
     "the pass after the frame (ES 2.0 guarantees no multisampled config)", 0, 0, NULL, 0},
    {"vc4", "Raspberry Pi 0-3 (VideoCore IV, Mesa vc4)", 2048, 2048, 2048, 2048, 256, 256, 8, 8, 8, 1, 0,
     "Mesa vc4_screen.c: 2D textures 2048, 8 varyings, samplers in both stages, fp32 (highp) shaders, "
     "8- and 16-bit index buffers only",
     "4x multisampling in the EGL config (resolved in VideoCore IV's tile buffer); a picture the tier draws smaller "
     "and the GPU enlarges has one sample (no EXT_multisampled_render_to_texture): the pass after the frame smooths "
     "it at its own size", 1, 0, "VideoCore IV", JD_VC4_LEVELS_PER_FRAGMENT_FROM},
    {"mali400", "Mali-400/450 (Utgard: ARM driver, Mesa lima)", 4096, 4096, 4096, 1024, 256, 256, 8, 8, 0, 0, 0,
     "ARM gles_config_m200.h / gles2_config_m200.h: 256 uniform vectors per stage, no vertex texture units, "
     "renderbuffers and viewports 4096, cube maps 1024; fragment shaders fp16 only; Mesa lima_screen.c: "
     "8 varyings (the hardware's limit)",
     "4x multisampling in the EGL config (free on Mali-400's tile buffer)", 1, 0, "Mali-400/450", 0},
    {"vivante", "Vivante GC2000 class (NXP i.MX6 Quad/Dual; STM32MP1's GC400 and i.MX6 DualLite's GC880 below it)",
     8192, 8192, 8192, 8192, 168, 64, 8, 8, 4, 1, 1,
     "Mesa etnaviv_screen.c on GC2000 rev 5108 (drm-shim): 168 vertex and 64 fragment uniform vectors (Vivante's "
     "gcmCONFIGUREUNIFORMS), 4 vertex samplers, 8K textures, fp32 shaders; the cores' own varying count (11 on "
     "GC2000, 8 on GC400; Mesa reports 16); programs of at most 256 instructions per stage (no instruction cache "
     "before GC3000). GC400 has no vertex samplers: jade reads its caps and draws thickness per fragment there",
     "4x multisampling in the EGL config where the driver offers one (resolved by GC2000's resolve engine: "
     "Vivante draws in immediate mode, the samples cost memory traffic; Mesa's etnaviv offers one only with "
     "ETNA_MESA_DEBUG=msaa); otherwise the pass after the frame", 0, 256,
     "Vivante GC400-GC2000", 0},
    {"adreno3xx", "Adreno 306/320 (Snapdragon 410/600: Qualcomm's driver, Mesa freedreno)", 8192, 8192, 8192, 8192,
     4096, 4096, 16, 16, 16, 1, 1,
     "Mesa freedreno_screen.c for a3xx as FD307 (Adreno 306) and FD320 report under the drm-shim: 16 varyings, 16 "
     "samplers in both stages, 8K textures, fp32 shaders (ir3 lowers mediump to 16-bit registers only from a5xx)",
     "4x multisampling in the EGL config where the driver offers one (resolved in Adreno's on-chip GMEM; Mesa's "
     "freedreno offers none on a3xx); otherwise the pass after the frame", 0, 0, "Adreno 3xx",
     JD_ADRENO3XX_LEVELS_PER_FRAGMENT_FROM},
    {"gc7000l", "Vivante GC7000Lite (NXP i.MX8M Quad; GC3000 in i.MX6 QuadPlus alike)", 8192, 8192, 8192, 8192,
     1024, 1024, 16, 16, 16, 1, 1,
     "Mesa etnaviv_screen.c on GC7000 rev 6214 (drm-shim): 1024 uniform vectors per stage, 16 varyings, 16 samplers "
     "in both stages, 8K textures, fp32 shaders, 32-bit indices; an instruction cache (no program size limit)",
     "4x multisampling in the EGL config where the driver offers one (Mesa's etnaviv offers one only with "
     "ETNA_MESA_DEBUG=msaa); otherwise the pass after the frame", 0, 0, "Vivante GC3000-GC7000",
     JD_VIVANTE_LEVELS_PER_FRAGMENT_FROM},
};
const int jd_profile_count = (int)(sizeof jd_profiles / sizeof jd_profiles[0]);

const jd_profile *jd_profile_find(const char *name)
{
    for (int i = 0; i < jd_profile_count; i++)
        if (strcmp(jd_profiles[i].name, name) == 0) return &jd_profiles[i];
    return NULL;
}

static void lower(int *v, int limit)
{
    if (*v > limit) *v = limit;
}

void jd_profile_apply(const jd_profile *p, jd_gl_caps *c)
{
    lower(&c->max_texture_size, p->max_texture_size);
    lower(&c->max_renderbuffer_size, p->max_renderbuffer_size);
    lower(&c->max_cube_map_size, p->max_cube_map_size);
    lower(&c->max_viewport_w, p->max_viewport);
    lower(&c->max_viewport_h, p->max_viewport);
    lower(&c->max_vertex_uniform_vectors, p->max_vertex_uniform_vectors);
    lower(&c->max_fragment_uniform_vectors, p->max_fragment_uniform_vectors);
    lower(&c->max_varying_vectors, p->max_varying_vectors);
    lower(&c->max_texture_units, p->max_texture_units);
    lower(&c->max_vertex_texture_units, p->max_vertex_texture_units);
    if (!p->frag_highp) {
        c->frag_highp_precision = 0;
        c->frag_highp_range = 0;
    }
    if (!p->ext_element_index_uint) c->ext_element_index_uint = 0;
    /* Optional extensions the profiles do not promise. */
    c->ext_disjoint_timer_query = 0;
    c->ext_depth_texture = 0;
    c->ext_texture_float = 0;
    c->ext_packed_depth_stencil = 0;
    c->ext_standard_derivatives = 0;
    /* Mali-400/450 under Mesa's lima (lima_screen.c:
     * PIPE_CAP_SURFACE_SAMPLE_COUNT, 4 samples) draws a texture with 4x
     * samples in the tile buffer (ARM's own driver: where it lists the
     * extension; not looked at here); the other profiles' GPUs promise no
     * such thing (Mesa's vc4, etnaviv and freedreno before a6xx lack it). */
    if (strcmp(p->name, "mali400") || c->max_samples < 4) {
        c->ext_multisampled_render_to_texture = 0;
        c->max_samples = 0;
    } else {
        c->max_samples = 4;
    }
    /* The board's GPU itself: what recognising it by name would set. */
    if (p->small_register_file) c->small_register_file = 1;
    if (!strcmp(p->name, "mali400")) c->utgard = 1; /* as the renderer string "Mali-400" would */
    if (p->levels_per_fragment_from) c->levels_per_fragment_from = p->levels_per_fragment_from;
    if (p->max_program_instructions &&
        (!c->max_program_instructions || c->max_program_instructions > p->max_program_instructions))
        c->max_program_instructions = p->max_program_instructions;
    if (p->tier) snprintf(c->tier, sizeof c->tier, "%s", p->tier);
    snprintf(c->profile, sizeof c->profile, "%s", p->name);
}
