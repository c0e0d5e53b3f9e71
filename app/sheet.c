/* none | single | dual | full side by side with labels: what a person compares;
 * with --sheet-reference, the reference picture first. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


#include "commands.h"
#include "font5x7.h"
#include "image_in.h"
#include "image_out.h"

/* The panels' labels at one size: twice the font's where every one fits its
 * panel, else the font's own; a label still too long for its panel loses
 * the material's name, then its end (a label that ran on was drawn over the
 * next one's, and a short one came out twice the size of its neighbours). */
static void draw_labels(uint8_t *sheet, int sw, int sh, int w, int first, const char *material)
{
    static const char *modes[JD_MODE_COUNT] = {"NONE (DIRECT ONLY)", "SINGLE (SCCG 2006)", "DUAL FUNNEL", "FULL (DIFFUSED)"};
    const uint8_t white[3] = {235, 235, 235};
    char text[JD_MODE_COUNT + 1][96];
    const int panels = JD_MODE_COUNT + first;
    int scale = 2;
    for (int p = 0; p < panels; p++) {
        snprintf(text[p], sizeof text[p], "%s - %s", p < first ? "REFERENCE (DIPOLE)" : modes[p - first], material);
        if ((int)strlen(text[p]) * 12 + 16 > w) scale = 1;
    }
    /* 6 pixels a character at the font's size, 8 of margin on each side. */
    int fit = (w - 16) / (6 * scale);
    for (int p = 0; p < panels; p++) {
        if (fit < 1) break;
        char *dash = strstr(text[p], " - ");
        if ((int)strlen(text[p]) > fit && dash) *dash = '\0';
        if ((int)strlen(text[p]) > fit) text[p][fit] = '\0';
        jd_font_draw(sheet, sw, sh, p * w + 8, scale == 2 ? 7 : 10, scale, text[p], white);
    }
}

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
    if (ref) {
        for (int y = 0; y < h; y++) memcpy(sheet + 4 * ((size_t)(y + band) * sw), ref + 4 * (size_t)y * w, 4 * (size_t)w);
        free(ref);
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
    }
    draw_labels(sheet, sw, sh, w, first, o->material);
    if (jd_png_write(o->sheet, sw, sh, sheet, &err)) {
        fprintf(stderr, "jade render: %s\n", err.msg);
        return 1;
    }
    printf("wrote %s (%dx%d: %snone | single | dual | full, %s)\n", o->sheet, sw, sh, first ? "reference | " : "", o->material);
    return 0;
}
