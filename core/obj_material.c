#include "obj_material.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "file_beside.h"
#include "texture_decode.h"

static void note(jd_mesh_arrays *m, const char *what)
{
    char *buf = m->medium.ignored;
    size_t cap = sizeof m->medium.ignored, k = strlen(buf);
    if (!strstr(buf, what)) snprintf(buf + k, cap - k, "%s%s", k ? "; " : "", what);
    m->medium.flags |= JD_MEDIUM_NOTE;
}

/* The next line of text[*at..n) with its keyword and the rest (trimmed). */
static int next_line(const char *t, size_t n, size_t *at, char *key, size_t kcap, char *rest, size_t rcap)
{
    if (*at >= n) return 0;
    size_t e = *at;
    while (e < n && t[e] != '\n' && t[e] != '\r') e++;
    size_t i = *at, k = 0, r = 0;
    while (i < e && (t[i] == ' ' || t[i] == '\t')) i++;
    while (i < e && t[i] != ' ' && t[i] != '\t') {
        if (k + 1 < kcap) key[k++] = t[i];
        i++;
    }
    while (i < e && (t[i] == ' ' || t[i] == '\t')) i++;
    while (i < e && t[i] != '#') {
        if (r + 1 < rcap) rest[r++] = t[i];
        i++;
    }
    while (r && (rest[r - 1] == ' ' || rest[r - 1] == '\t')) r--;
    key[k] = 0;
    rest[r] = 0;
    *at = e + 1;
    return 1;
}

int jd_obj_material(const uint8_t *obj, size_t n, const char *obj_path, uint32_t max_side, size_t max_bytes,
                    jd_mesh_arrays *m, char *err, size_t errlen)
{
    char key[32], rest[1024], lib[1024] = "", use[256] = "";
    int materials = 0;
    size_t at = 0;
    while (next_line((const char *)obj, n, &at, key, sizeof key, rest, sizeof rest)) {
        if (!strcmp(key, "mtllib") && !lib[0]) snprintf(lib, sizeof lib, "%s", rest);
        if (!strcmp(key, "usemtl") && strcmp(rest, use)) {
            if (!use[0]) snprintf(use, sizeof use, "%.255s", rest);
            materials++;
        }
    }
    if (!lib[0]) return 0;
    if (!obj_path) {
        note(m, "the OBJ's material library (the OBJ came from memory)");
        return 0;
    }
    char why[300];
    size_t len = 0;
    uint8_t *mtl = jd_file_beside(obj_path, lib, 1u << 20, &len, why, sizeof why);
    if (!mtl) {
        char what[400];
        snprintf(what, sizeof what, "its material library (%s)", why);
        note(m, what);
        return 0;
    }
    if (materials > 1) note(m, "more than one OBJ material (jade shows the first one's colour on the whole model)");
    /* The material's Kd and map_Kd (its file name: the last word; the
     * options before it are not read). */
    float kd[3] = {1, 1, 1};
    char map[1024] = "";
    int in = 0, found = 0;
    at = 0;
    while (next_line((const char *)mtl, len, &at, key, sizeof key, rest, sizeof rest)) {
        if (!strcmp(key, "newmtl")) {
            if (found) break;
            in = !use[0] || !strcmp(rest, use);
            found |= in;
        } else if (in && !strcmp(key, "Kd")) {
            float r, g, b;
            if (sscanf(rest, "%f %f %f", &r, &g, &b) == 3) {
                kd[0] = r; kd[1] = g; kd[2] = b;
            }
        } else if (in && !strcmp(key, "map_Kd")) {
            const char *sp = strrchr(rest, ' ');
            snprintf(map, sizeof map, "%s", sp ? sp + 1 : rest);
        }
    }
    free(mtl);
    if (!found) return 0;
    int textured = map[0] && m->uv;
    if (map[0] && !m->uv) note(m, "map_Kd (the mesh has no texture coordinates)");
    if (textured) {
        uint8_t *img = jd_file_beside(obj_path, map, max_bytes, &len, why, sizeof why);
        if (!img) {
            snprintf(err, errlen, "the material's map_Kd: %s", why);
            return -1;
        }
        static const float one[3] = {1, 1, 1};
        int rc = jd_texture_decode(img, len, one, max_side, "the material's map_Kd", &m->tex, err, errlen);
        free(img);
        if (rc) return -1;
        /* OBJ counts v from the bottom of the picture, glTF and jade's
         * texture rows from the top. */
        for (uint32_t i = 0; i < m->nv; i++) m->uv[2 * (size_t)i + 1] = 1.0f - m->uv[2 * (size_t)i + 1];
        /* map_Kd stands for the colour, as the exporters that write both
         * (Blender's Kd 0.8) mean it. */
        kd[0] = kd[1] = kd[2] = 1.0f;
    }
    m->col = malloc(4 * (size_t)m->nv);
    if (!m->col) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    for (uint32_t i = 0; i < m->nv; i++) {
        for (int k = 0; k < 3; k++) m->col[4 * (size_t)i + (size_t)k] = jd_sqrt_encode(kd[k] < 0 ? 0 : kd[k]);
        m->col[4 * (size_t)i + 3] = textured ? 255 : 0;
    }
    return 0;
}
