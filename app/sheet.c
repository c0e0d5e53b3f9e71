/* none | single | dual | full side by side with labels: what a person compares;
 * with --sheet-reference, the reference picture first. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


#include "commands.h"
#include "font5x7.h"
#include "image_in.h"
#include "image_out.h"

int jd_render_sheet(jd_session *s, jd_options *o, uint8_t *px)
{
    const int band = 28, w = o->width, h = o->height;
    uint8_t *ref = NULL;
    if (o->sheet_ref) {
        int rw, rh;
        char why[160];
        ref = jd_image_load(o->sheet_ref, &rw, &rh, 4, why, sizeof why);
        if (!ref || rw != w || rh != h) {
            fprintf(stderr, "jade render: --sheet-reference: %s: %s\n", o->sheet_ref,
                    ref ? "not the size of the sheet's pictures (--size)" : why);
            free(ref);
            return 1;
        }
    }
    const int first = ref ? 1 : 0, panels = JD_MODE_COUNT + first;
    const int sw = panels * w, sh = h + band;
    jd_error err = {0};
    uint8_t *sheet = jd_arena_alloc(&s->arena, (size_t)sw * sh * 4, 16, "the sheet image", &err);
    if (!sheet) { fprintf(stderr, "jade render: %s\n", err.msg); free(ref); return 1; }
    for (size_t i = 0; i < (size_t)sw * sh; i++) {
        sheet[4 * i] = sheet[4 * i + 1] = sheet[4 * i + 2] = 24;
        sheet[4 * i + 3] = 255;
    }
    static const char *labels[JD_MODE_COUNT] = {"NONE (DIRECT ONLY)", "SINGLE (SCCG 2006)", "DUAL FUNNEL", "FULL (DIFFUSED)"};
    const uint8_t white[3] = {235, 235, 235};
    if (ref) {
        for (int y = 0; y < h; y++) memcpy(sheet + 4 * ((size_t)(y + band) * sw), ref + 4 * (size_t)y * w, 4 * (size_t)w);
        free(ref);
        char text[96];
        snprintf(text, sizeof text, "REFERENCE (DIPOLE) - %s", o->material);
        int scale = (int)strlen(text) * 12 + 16 <= w ? 2 : 1;
        jd_font_draw(sheet, sw, sh, 8, scale == 2 ? 7 : 10, scale, text, white);
    }
    for (int m = 0; m < JD_MODE_COUNT; m++) {
        jd_scene sc = o->scene;
        sc.mode = (jd_mode)m;
        if (jd_renderer_frame(s->renderer, &sc, NULL, &err) || jd_platform_read_rgba(s->platform, px, &err)) {
            fprintf(stderr, "jade render: %s\n", err.msg);
            return 1;
        }
        for (int y = 0; y < h; y++)
            memcpy(sheet + 4 * ((size_t)(y + band) * sw + (size_t)(m + first) * w), px + 4 * (size_t)y * w, 4 * (size_t)w);
        char text[96];
        snprintf(text, sizeof text, "%s - %s", labels[m], o->material);
        int scale = (int)strlen(text) * 12 + 16 <= w ? 2 : 1;
        jd_font_draw(sheet, sw, sh, (m + first) * w + 8, scale == 2 ? 7 : 10, scale, text, white);
    }
    if (jd_png_write(o->sheet, sw, sh, sheet, &err)) {
        fprintf(stderr, "jade render: %s\n", err.msg);
        return 1;
    }
    printf("wrote %s (%dx%d: %snone | single | dual | full, %s)\n", o->sheet, sw, sh, first ? "reference | " : "", o->material);
    return 0;
}
