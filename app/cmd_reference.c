/* jade reference: the scene `jade render` shows, rendered on the CPU with
 * the physically based dipole, for jade metric to judge jade's modes by. */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "commands.h"
#include "display_curve.h"
#include "image_out.h"
#include "ref_render.h"
#include "session.h"

int jd_cmd_reference(int argc, char **argv)
{
    jd_options o;
    jd_options_defaults(&o);
    o.out = "reference.png";
    int rc = jd_options_command(&o, JD_OPT_REFERENCE, "reference",
                                "Renders the scene of jade render on the CPU with the Jensen et al. 2001 dipole\n"
                                "BSSRDF (hierarchical, Jensen & Buhler 2002), its albedo the transport equation's\n"
                                "for the half-space and the light's angle: the ground truth for jade metric.\n"
                                "The PNG is tone-mapped exactly as jade maps its own output.",
                                argc, argv);
    if (rc >= 0) return rc;
    if (o.volume_mm > 0) o.volume = 1; /* a cell size only means something to the volume */
    if (!o.frames) o.frames = 1;
    if (o.volume && o.frames > 1) {
        fprintf(stderr, "jade reference: --volume draws one frame (its solve is for one light), not --frames %d\n",
                o.frames);
        return 2;
    }
    jd_session s;
    if (!jd_session_open_mesh(&s, &o, "reference")) { jd_session_close(&s); return 1; }
    /* jd_ref_create refuses it too, in the library's words; said here in
     * the option's, before any work, with the eta the scene resolves to. */
    jd_scene_view view;
    jd_scene_view_of(&o.scene, &s.mesh, (float)o.width / (float)o.height, &view);
    if (o.single_scatter && view.eta != 1.0f) {
        fprintf(stderr, "jade reference: --single-scatter traces light through an index-matched boundary: it needs --eta 1, "
                        "not %g\n", (double)view.eta);
        jd_session_close(&s);
        return 2;
    }

    jd_ref_desc d = {.mesh = &s.mesh, .scene = o.scene, .width = o.width, .height = o.height,
                     .samples = (uint32_t)o.samples, .error = o.ref_error, .window_mm = o.window_mm,
                     .pixel_samples = o.pixel_samples, .bounces = o.bounces,
                     .volume = o.volume, .volume_mm = o.volume_mm, .single_scatter = o.single_scatter,
                     .threads = o.threads, .progress = !o.quiet, .seed = (uint32_t)o.seed};
    size_t n = (size_t)o.width * o.height;
    float *linear = malloc(n * 3 * sizeof(float));
    uint8_t *mask = malloc(n), *rgba = malloc(n * 4);
    jd_ref *ref = NULL;
    jd_ref_stats st;
    jd_error err = {0};
    rc = 1;
    /* With --frames N and --light-step the light turns from frame to frame
     * (jd_ref_relight: the samples placed once); an output with %d in its
     * name is written every frame under its number, one without for the
     * last. Every name is checked before the first frame. */
    const char *outs[3] = {o.out, o.pfm, o.mask_out};
    int seq[3];
    char name[PATH_MAX], first[PATH_MAX];
    for (int k = 0; k < 3; k++)
        if ((seq[k] = jd_frame_names_check(outs[k], o.frames, &err)) < 0) {
            fprintf(stderr, "jade reference: %s\n", err.msg);
            goto done;
        }
    if (!linear || !mask || !rgba) {
        fprintf(stderr, "jade reference: out of memory for a %dx%d picture\n", o.width, o.height);
        goto done;
    }
    for (int i = 0; i < o.frames; i++) {
        jd_result r = i == 0 ? jd_ref_create(&d, &ref, &st, &err)
                             : jd_ref_relight(ref, jd_options_light_at(o.scene.light_azimuth, o.light_step, i), &st,
                                              &err);
        if (r || jd_ref_render(ref, linear, mask, &st, &err)) {
            fprintf(stderr, "jade reference: %s: %s\n", s.mesh_path, err.msg);
            goto done;
        }
        int last = i == o.frames - 1;
        for (size_t j = 0; j < n; j++) {
            for (int c = 0; c < 3; c++) rgba[4 * j + c] = jd_display_encode(linear[3 * j + c]);
            rgba[4 * j + 3] = 255;
        }
        if (seq[0] || last) {
            jd_frame_name(o.out, i, name, sizeof name, &err);
            if (jd_png_write(name, o.width, o.height, rgba, &err)) goto failed;
        }
        if (o.pfm && (seq[1] || last)) {
            jd_frame_name(o.pfm, i, name, sizeof name, &err);
            if (jd_pfm_write(name, o.width, o.height, linear, &err)) goto failed;
        }
        if (o.mask_out && (seq[2] || last)) {
            for (size_t j = 0; j < n; j++) {
                rgba[4 * j] = rgba[4 * j + 1] = rgba[4 * j + 2] = mask[j];
                rgba[4 * j + 3] = 255;
            }
            jd_frame_name(o.mask_out, i, name, sizeof name, &err);
            if (jd_png_write(name, o.width, o.height, rgba, &err)) goto failed;
        }
    }
    /* The names written: the last frame's, from the first's for a sequence. */
    for (int k = 0; k < 3; k++) {
        if (!outs[k]) continue;
        jd_frame_name(outs[k], 0, first, sizeof first, &err);
        jd_frame_name(outs[k], o.frames - 1, name, sizeof name, &err);
        int range = seq[k] && o.frames > 1;
        printf("%s%s%s%s", k ? ", " : "wrote ", range ? first : "", range ? " to " : "", name);
    }
    if (o.frames > 1) printf(" (%d frames, the light turning %g degrees a frame;", o.frames, (double)o.light_step);
    else printf(" (");
    char tri[80];
    printf("%s%dx%d, reference, %s, mesh %s: %s)\n", o.frames > 1 ? " " : "", o.width, o.height, o.material,
           s.mesh_path, jd_session_triangles(&s, tri, sizeof tri));
    if (o.volume)
        printf("%u samples (%.3f mm apart over %.0f mm^2), %d threads; irradiance %.0f ms, volume %u cells of %.3g mm "
               "(%.2f%% of the light in parts thinner than one), solved in %.0f ms (%d iterations to residual %.1e), ",
               st.samples, st.spacing_mm, st.surface_mm2, st.threads, st.irradiance_ms, st.volume_cells, st.volume_mm,
               100 * st.volume_lost, st.tree_ms, st.volume_iterations, st.volume_residual);
    else
        printf("%u samples (%.3f mm apart over %.0f mm^2; %u carry light across a thin part), window %.2f mm, %d "
               "threads; irradiance %.0f ms, octree %.0f ms, ",
               st.samples, st.spacing_mm, st.surface_mm2, st.carried, st.window_mm, st.threads, st.irradiance_ms,
               st.tree_ms);
    if (o.bounces) printf("light between parts %.0f ms (%d bounce%s), ", st.bounce_ms, o.bounces, o.bounces > 1 ? "s" : "");
    if (o.volume)
        printf("pixels %.0f ms (%ld on the object)\n", st.pixels_ms, st.object_pixels);
    else
        printf("pixels %.0f ms (%ld on the object, %.0f kernel evaluations each)\n", st.pixels_ms, st.object_pixels,
               st.evals_per_pixel);
    rc = 0;
    goto done;
failed:
    fprintf(stderr, "jade reference: %s\n", err.msg);
done:
    jd_ref_destroy(ref);
    free(linear);
    free(mask);
    free(rgba);
    jd_session_close(&s);
    return rc;
}
