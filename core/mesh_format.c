#include "mesh_format.h"

#include <string.h>
#include <strings.h>

#include "draco_header.h"

const char *jd_mesh_format_name(jd_mesh_format f)
{
    static const char *names[] = {"unknown", "Draco", "OBJ", "PLY", "STL", "glTF"};
    return f >= 0 && f <= JD_FORMAT_GLTF ? names[f] : "unknown";
}

/* A line starting at p (within n), as a bounded C string in out. */
static size_t line_at(const uint8_t *buf, size_t n, size_t at, char *out, size_t cap)
{
    size_t k = 0;
    while (at + k < n && buf[at + k] != '\n' && k + 1 < cap) {
        out[k] = (char)buf[at + k];
        k++;
    }
    out[k] = 0;
    if (k && out[k - 1] == '\r') out[k - 1] = 0;
    return k;
}

static int parse_count(const char *s, uint32_t *v)
{
    unsigned long long x = 0;
    if (*s < '0' || *s > '9') return 0;
    for (; *s >= '0' && *s <= '9'; s++) {
        x = x * 10 + (unsigned long long)(*s - '0');
        if (x > 0xffffffffull) return 0;
    }
    *v = (uint32_t)x;
    return 1;
}

/* PLY: "ply", "format ...", "element vertex N", "element face N", ...,
 * "end_header", all within the first 64 KiB. */
static jd_result peek_ply(const uint8_t *buf, size_t n, const char *name, uint32_t *faces, uint32_t *vertices,
                          jd_error *err)
{
    char line[256];
    size_t at = 0, limit = n < (64u << 10) ? n : (64u << 10);
    int has_faces = 0, has_strips = 0;
    while (at < limit) {
        size_t k = line_at(buf, n, at, line, sizeof line);
        at += k + 1;
        /* libdraco 1.5.5 crashed on mangled format lines in fuzzing, and
         * reads no big-endian PLY at all: said here, in words. */
        if (!strncmp(line, "format ", 7)) {
            if (!strcmp(line, "format binary_big_endian 1.0"))
                return jd_fail(err, JD_ERR_UNSUPPORTED,
                               "%s: PLY is binary big-endian, which jade's reader (libdraco) does not read; save it "
                               "as ASCII or little-endian", name);
            if (strcmp(line, "format ascii 1.0") && strcmp(line, "format binary_little_endian 1.0")) {
                char shown[41];
                size_t i = 0;
                for (; i < 40 && line[7 + i]; i++) shown[i] = line[7 + i] >= 32 && line[7 + i] < 127 ? line[7 + i] : '?';
                shown[i] = 0;
                return jd_fail(err, JD_ERR_FORMAT, "%s: PLY format line '%s' is not ascii, binary_little_endian or "
                               "binary_big_endian 1.0", name, shown);
            }
        }
        if (!strncmp(line, "element face ", 13)) has_faces = 1;
        if (!strncmp(line, "element tristrips ", 18)) has_strips = 1;
        if (!strcmp(line, "end_header")) {
            /* Said here, in words, rather than by the decoder's internals. */
            /* Strips are turned into faces in the decoder (ply_strips.c):
             * their count is known once they are read. */
            if (!has_faces && !has_strips)
                return jd_fail(err, JD_ERR_FORMAT, "%s: PLY has vertices but no faces (a point cloud): jade draws "
                               "surfaces", name);
            return JD_OK;
        }
        if (!strncmp(line, "element vertex ", 15) && !parse_count(line + 15, vertices))
            return jd_fail(err, JD_ERR_FORMAT, "%s: PLY vertex count '%s' is not a count", name, line + 15);
        if (!strncmp(line, "element face ", 13) && !parse_count(line + 13, faces))
            return jd_fail(err, JD_ERR_FORMAT, "%s: PLY face count '%s' is not a count", name, line + 13);
    }
    return jd_fail(err, JD_ERR_FORMAT, "%s: PLY header has no end_header in its first 64 KiB", name);
}

/* OBJ: text with vertex lines ("v x y z") near the start. */
static int looks_like_obj(const uint8_t *buf, size_t n)
{
    size_t limit = n < (64u << 10) ? n : (64u << 10);
    for (size_t i = 0; i < limit; i++)
        if (buf[i] == 0) return 0; /* binary */
    for (size_t i = 0; i + 2 < limit; i++)
        if ((i == 0 || buf[i - 1] == '\n') && buf[i] == 'v' && (buf[i + 1] == ' ' || buf[i + 1] == '\t')) return 1;
    return 0;
}

jd_result jd_mesh_peek(const uint8_t *buf, size_t n, const char *name, jd_mesh_format *format, uint32_t *faces,
                       uint32_t *vertices, jd_error *err)
{
    *format = JD_FORMAT_UNKNOWN;
    *faces = *vertices = 0;
    if (n == 0) return jd_fail(err, JD_ERR_FORMAT, "%s: file is empty", name);
    if (n >= 5 && !memcmp(buf, "DRACO", 5)) {
        jd_draco_info info;
        jd_result r = jd_draco_peek(buf, n, name, &info, err);
        if (r) return r;
        *format = JD_FORMAT_DRACO;
        *faces = info.num_faces;
        *vertices = info.num_vertices;
        return JD_OK;
    }
    if (n >= 12 && !memcmp(buf, "glTF", 4)) {
        *format = JD_FORMAT_GLTF;
        return JD_OK;
    }
    if (n >= 4 && !memcmp(buf, "ply", 3) && (buf[3] == '\n' || buf[3] == '\r')) {
        *format = JD_FORMAT_PLY;
        return peek_ply(buf, n, name, faces, vertices, err);
    }
    /* Binary STL: an 80-byte header (which may well say "solid"), a count,
     * then exactly 50 bytes per triangle. */
    if (n >= 84) {
        uint32_t count = (uint32_t)buf[80] | (uint32_t)buf[81] << 8 | (uint32_t)buf[82] << 16 | (uint32_t)buf[83] << 24;
        if ((uint64_t)count * 50 + 84 == n) {
            *format = JD_FORMAT_STL;
            *faces = count;
            *vertices = count > 0xffffffffu / 3 ? 0xffffffffu : 3 * count;
            return JD_OK;
        }
    }
    size_t s = 0;
    while (s < n && (buf[s] == ' ' || buf[s] == '\t' || buf[s] == '\r' || buf[s] == '\n')) s++;
    if (n - s >= 5 && !memcmp(buf + s, "solid", 5) && memmem(buf, n < 4096 ? n : 4096, "facet", 5)) {
        *format = JD_FORMAT_STL;
        return JD_OK;
    }
    /* glTF text: a JSON object with an "asset" member near its start. */
    if (s < n && buf[s] == '{' && memmem(buf, n < (64u << 10) ? n : (64u << 10), "\"asset\"", 7)) {
        *format = JD_FORMAT_GLTF;
        return JD_OK;
    }
    if (looks_like_obj(buf, n)) {
        *format = JD_FORMAT_OBJ;
        return JD_OK;
    }
    /* A binary STL whose count does not fit its size: whole 50-byte
     * triangles after the header, or the name says STL. */
    size_t len = strlen(name);
    if (n >= 84 && ((n - 84) % 50 == 0 || (len > 4 && !strcasecmp(name + len - 4, ".stl")))) {
        uint32_t count = (uint32_t)buf[80] | (uint32_t)buf[81] << 8 | (uint32_t)buf[82] << 16 | (uint32_t)buf[83] << 24;
        return jd_fail(err, JD_ERR_FORMAT,
                       "%s: a binary STL with a wrong triangle count: its header says %u, its %zu bytes hold %zu%s",
                       name, count, n, (n - 84) / 50, (n - 84) % 50 ? " and a part of one" : "");
    }
    return jd_fail(err, JD_ERR_FORMAT,
                   "%s: not a mesh jade reads: no Draco, glTF, PLY or STL header and no OBJ vertex lines", name);
}
