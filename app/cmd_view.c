/* jade view: the desktop emulator. An X11 window under the device profile
 * of choice; drag to orbit, scroll to zoom, keys for mode, material, light. */
#include <stdio.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>

#include "commands.h"
#include "image_out.h"

static const char keys_help[] =
    "keys: m mode, n material, l light orbit on/off, [ ] turn the light, + - zoom, s screenshot, q or Esc quit";

/* Zooming starts from where the fitted camera stands, not from "fit". */
static void zoom(jd_scene *sc, const jd_mesh *m, int w, int h, float by)
{
    if (sc->cam_distance <= 0) {
        jd_scene_view v;
        jd_scene_view_of(sc, m, (float)w / (float)h, &v);
        sc->cam_distance = v.cam_distance;
    }
    sc->cam_distance = fminf(fmaxf(sc->cam_distance * by, 1.3f), 20.0f);
}

int jd_cmd_view(int argc, char **argv)
{
    jd_options o;
    jd_options_defaults(&o);
    o.platform = "x11";
    char summary[400];
    snprintf(summary, sizeof summary,
             "Opens an EGL window on X11 showing the scene; with --profile, under a device's limits.\n%s", keys_help);
    int rc = jd_options_command(&o, JD_OPT_VIEW, "view", summary, argc, argv);
    if (rc >= 0) return rc;
    if (o.screenshot && !o.frames) {
        fprintf(stderr, "jade view: --screenshot needs --frames N (the last frame is written)\n");
        return 2;
    }
    jd_session s;
    if (!jd_session_open(&s, &o, "view")) { jd_session_close(&s); return 1; }
    int mw, mh;
    jd_platform_max_size(s.platform, &mw, &mh);
    /* Screenshots of any window size, allocated once before the loop. */
    uint8_t *shot = malloc((size_t)mw * mh * 4);
    if (!shot) { fprintf(stderr, "jade view: cannot reserve the screenshot buffer\n"); jd_session_close(&s); return 1; }
    printf("%s\n%s\n%s\n", jd_platform_describe(s.platform), jd_antialias_describe(s.renderer), keys_help);
    jd_scene sc = o.scene;
    int material = 0, orbit = 0, shots = 0, w = o.width, h = o.height;
    for (int i = 0; i < jd_material_count; i++)
        if (!strcmp(jd_materials[i].name, o.material)) material = i;
    jd_error err = {0};
    rc = 0;
    for (long frame = 0; !o.frames || frame < o.frames; frame++) {
        jd_event ev;
        int quit = 0, snap = 0;
        while (jd_platform_poll(s.platform, &ev)) {
            if (ev.type == JD_EVENT_QUIT) quit = 1;
            else if (ev.type == JD_EVENT_RESIZE) {
                w = ev.w;
                h = ev.h;
                if (jd_renderer_resize(s.renderer, w, h, &err)) { fprintf(stderr, "jade view: %s\n", err.msg); quit = 1; }
            } else if (ev.type == JD_EVENT_DRAG) {
                sc.cam_azimuth -= 0.4f * ev.dx;
                sc.cam_elevation += 0.4f * ev.dy;
                if (sc.cam_elevation > 85) sc.cam_elevation = 85;
                if (sc.cam_elevation < -85) sc.cam_elevation = -85;
            } else if (ev.type == JD_EVENT_SCROLL) {
                zoom(&sc, &s.mesh, w, h, ev.dy > 0 ? 0.9f : 1.1f);
            } else if (ev.type == JD_EVENT_KEY) {
                switch (ev.key) {
                case 'q': case 27: quit = 1; break;
                case 'm': sc.mode = (jd_mode)((sc.mode + 1) % JD_MODE_COUNT); printf("mode %s\n", jd_mode_name(sc.mode)); break;
                case 'n': {
                    material = (material + 1) % jd_material_count;
                    const jd_material *m = &jd_materials[material];
                    memcpy(sc.sigma_s, m->sigma_s, sizeof sc.sigma_s);
                    memcpy(sc.sigma_a, m->sigma_a, sizeof sc.sigma_a);
                    sc.eta = m->eta;
                    printf("material %s\n", m->name);
                    break;
                }
                case 'l': orbit = !orbit; break;
                case '[': sc.light_azimuth -= 15; break;
                case ']': sc.light_azimuth += 15; break;
                case '+': case '=': zoom(&sc, &s.mesh, w, h, 0.9f); break;
                case '-': zoom(&sc, &s.mesh, w, h, 1.1f); break;
                case 's': snap = 1; break;
                default: break;
                }
            }
        }
        if (quit) break;
        if (orbit) sc.light_azimuth += 3.0f;
        if (jd_renderer_frame(s.renderer, &sc, NULL, &err)) { fprintf(stderr, "jade view: %s\n", err.msg); rc = 1; break; }
        int last = o.frames && frame == o.frames - 1;
        if (snap || (last && o.screenshot)) {
            char name[64];
            const char *path = last && o.screenshot ? o.screenshot : name;
            snprintf(name, sizeof name, "jade-view-%d.png", ++shots);
            if (jd_platform_read_rgba(s.platform, shot, &err) || jd_png_write(path, w, h, shot, &err)) {
                fprintf(stderr, "jade view: %s\n", err.msg);
                rc = 1;
                break;
            }
            printf("wrote %s (%dx%d)\n", path, w, h);
        }
        if (jd_platform_present(s.platform, &err)) { fprintf(stderr, "jade view: %s\n", err.msg); rc = 1; break; }
    }
    free(shot);
    jd_session_close(&s);
    return rc;
}
