#include "gltf_read.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "draco_shim.h"
#include "file_beside.h"
#include "mesh_format.h"
#include "texture_decode.h"

enum { MAX_DEPTH = 64, MAX_INSTANCES = 65536 };

/* cJSON keeps arrays as linked lists: every array jade indexes into is
 * turned into a table once, so a file with a million accessors is read in
 * linear time. */
typedef struct table {
    cJSON **item;
    int count;
} table;

typedef struct blob {
    const uint8_t *data;
    size_t size;
    uint8_t *owned;
} blob;

typedef struct gltf {
    const char *path;
    const jd_gltf_limits *lim;
    char *err;
    size_t errlen;
    table buffers, views, accessors, meshes, nodes, materials, textures, images;
    blob *buf;
    const uint8_t *bin; /* the GLB's binary chunk */
    size_t bin_size;
    size_t loaded_bytes;
    jd_mesh_arrays *out;
    size_t cap_v, cap_f; /* room in out's arrays */
    int no_nrm, no_uv;   /* some primitive lacks them: drop them all */
    int skipped;         /* primitives that are points or lines */
    /* The colour of the primitive being read (its material's
     * baseColorFactor, whether its baseColorTexture is the one jade shows),
     * the texture jade shows (-1: none yet) and whether any primitive had a
     * colour of its own. */
    double cur_factor[3];
    int cur_textured, texture, coloured, other_textures;
    /* The shown texture's KHR_texture_transform for the primitive being
     * read, as u' = x[0] u + x[1] v + x[2], v' = x[3] u + x[4] v + x[5]. */
    double cur_uvxf[6];
} gltf;

static int numbers(const cJSON *a, int n, double *out);

static int fail(gltf *g, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    if (g->err && g->errlen) vsnprintf(g->err, g->errlen, fmt, ap);
    va_end(ap);
    return -1;
}

static int make_table(gltf *g, const cJSON *root, const char *key, table *t)
{
    const cJSON *a = cJSON_GetObjectItemCaseSensitive(root, key);
    t->item = NULL;
    t->count = 0;
    if (!a) return 0;
    if (!cJSON_IsArray(a)) return fail(g, "glTF '%s' is not an array", key);
    int n = cJSON_GetArraySize(a);
    t->item = calloc((size_t)n + 1, sizeof *t->item);
    if (!t->item) return fail(g, "out of memory");
    cJSON *e;
    cJSON_ArrayForEach(e, a) t->item[t->count++] = e;
    return 0;
}

static const cJSON *at(const table *t, const cJSON *index)
{
    if (!cJSON_IsNumber(index)) return NULL;
    double v = index->valuedouble;
    if (!(v >= 0 && v < t->count) || v != floor(v)) return NULL;
    return t->item[(int)v];
}

static const cJSON *get(const cJSON *o, const char *key) { return cJSON_GetObjectItemCaseSensitive(o, key); }

/* A non-negative integer field, or def when absent; -1 when malformed. */
static double count_field(const cJSON *o, const char *key, double def)
{
    const cJSON *v = get(o, key);
    if (!v) return def;
    if (!cJSON_IsNumber(v) || !(v->valuedouble >= 0 && v->valuedouble <= 4.0e15) || v->valuedouble != floor(v->valuedouble))
        return -1;
    return v->valuedouble;
}

static int b64(int c)
{
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+' || c == '-') return 62;
    if (c == '/' || c == '_') return 63;
    return -1;
}

static int load_data_uri(gltf *g, int i, const char *uri, blob *b)
{
    const char *comma = strstr(uri, ";base64,");
    if (!comma) return fail(g, "glTF buffer %d: a data: URI that is not base64", i);
    const char *s = comma + 8;
    size_t len = strlen(s), cap = len / 4 * 3 + 3;
    if (g->loaded_bytes + cap > g->lim->max_buffer_bytes)
        return fail(g, "glTF buffers add up to more than %zu bytes", g->lim->max_buffer_bytes);
    b->owned = malloc(cap ? cap : 1);
    if (!b->owned) return fail(g, "out of memory");
    size_t n = 0;
    unsigned acc = 0;
    int bits = 0;
    for (size_t k = 0; k < len && s[k] != '='; k++) {
        int v = b64((unsigned char)s[k]);
        if (v < 0) return fail(g, "glTF buffer %d: byte %zu of its base64 data is not base64", i, k);
        acc = acc << 6 | (unsigned)v;
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            b->owned[n++] = (uint8_t)(acc >> bits);
        }
    }
    g->loaded_bytes += n;
    b->data = b->owned;
    b->size = n;
    return 0;
}

/* A buffer (at least `need` bytes) or, with need SIZE_MAX, an image file
 * beside the glTF (file_beside.h). */
static int load_file_uri(gltf *g, int i, const char *uri, size_t need, blob *b)
{
    const char *kind = need == SIZE_MAX ? "image" : "buffer";
    if (!g->path)
        return fail(g, "glTF %s %d: uri '%.200s' names a file, but the glTF came from memory; embed the "
                       "%s (GLB, or a data: URI)", kind, i, uri, kind);
    size_t room = g->lim->max_buffer_bytes - g->loaded_bytes, len = 0;
    if (need != SIZE_MAX && need > room)
        return fail(g, "glTF buffers add up to more than %zu bytes", g->lim->max_buffer_bytes);
    char why[400];
    b->owned = jd_file_beside(g->path, uri, room, &len, why, sizeof why);
    if (!b->owned) return fail(g, "glTF %s %d: %s", kind, i, why);
    if (need != SIZE_MAX && len < need)
        return fail(g, "glTF %s %d: '%.200s' has %zu bytes, the file declares %zu", kind, i, uri, len, need);
    b->size = need == SIZE_MAX ? len : need;
    g->loaded_bytes += b->size;
    b->data = b->owned;
    return 0;
}

static int load_buffers(gltf *g)
{
    g->buf = calloc((size_t)g->buffers.count + 1, sizeof *g->buf);
    if (!g->buf) return fail(g, "out of memory");
    for (int i = 0; i < g->buffers.count; i++) {
        const cJSON *b = g->buffers.item[i];
        double len = count_field(b, "byteLength", -1);
        if (len < 0) return fail(g, "glTF buffer %d has no valid byteLength", i);
        const cJSON *uri = get(b, "uri");
        if (!uri) {
            if (i != 0 || !g->bin) return fail(g, "glTF buffer %d has no uri and there is no GLB binary chunk", i);
            if (len > (double)g->bin_size)
                return fail(g, "glTF buffer 0 declares %.0f bytes; the GLB binary chunk holds %zu", len, g->bin_size);
            g->buf[i].data = g->bin;
            g->buf[i].size = (size_t)len;
        } else if (!cJSON_IsString(uri)) {
            return fail(g, "glTF buffer %d: uri is not a string", i);
        } else if (!strncmp(uri->valuestring, "data:", 5)) {
            if (load_data_uri(g, i, uri->valuestring, &g->buf[i])) return -1;
            if (g->buf[i].size < len) return fail(g, "glTF buffer %d declares %.0f bytes; its data holds %zu", i, len, g->buf[i].size);
        } else {
            if (len > (double)g->lim->max_buffer_bytes)
                return fail(g, "glTF buffer %d declares %.0f bytes, over the limit of %zu", i, len, g->lim->max_buffer_bytes);
            if (load_file_uri(g, i, uri->valuestring, (size_t)len, &g->buf[i])) return -1;
        }
    }
    return 0;
}

/* The bytes of a buffer view, checked against its buffer. */
static int view_bytes(gltf *g, const cJSON *index, const uint8_t **data, size_t *size, size_t *stride)
{
    const cJSON *v = at(&g->views, index);
    if (!v) return fail(g, "glTF refers to a bufferView that does not exist");
    const cJSON *bi = get(v, "buffer");
    const cJSON *b = at(&g->buffers, bi);
    double off = count_field(v, "byteOffset", 0), len = count_field(v, "byteLength", -1),
           st = count_field(v, "byteStride", 0);
    if (!b || off < 0 || len < 0 || st < 0 || (st && (st < 4 || st > 252)))
        return fail(g, "glTF bufferView has a missing buffer or an invalid offset, length or stride");
    const blob *bl = &g->buf[(int)bi->valuedouble];
    if (off + len > (double)bl->size)
        return fail(g, "glTF bufferView reaches byte %.0f of a buffer of %zu bytes", off + len, bl->size);
    *data = bl->data + (size_t)off;
    *size = (size_t)len;
    if (stride) *stride = (size_t)st;
    return 0;
}

static int type_comps(const char *t)
{
    static const struct { const char *name; int n; } types[] = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}};
    for (size_t i = 0; i < sizeof types / sizeof types[0]; i++)
        if (t && !strcmp(t, types[i].name)) return types[i].n;
    return 0;
}

static int comp_size(int type)
{
    switch (type) {
    case 5120: case 5121: return 1;
    case 5122: case 5123: return 2;
    case 5125: case 5126: return 4;
    default: return 0;
    }
}

static double read_comp(const uint8_t *p, int type, int normalized)
{
    switch (type) {
    case 5120: { int8_t v; memcpy(&v, p, 1); return normalized ? fmax(v / 127.0, -1.0) : v; }
    case 5121: return normalized ? p[0] / 255.0 : p[0];
    case 5122: { int16_t v; memcpy(&v, p, 2); return normalized ? fmax(v / 32767.0, -1.0) : v; }
    case 5123: { uint16_t v; memcpy(&v, p, 2); return normalized ? v / 65535.0 : v; }
    case 5125: { uint32_t v; memcpy(&v, p, 4); return v; }
    default: { float v; memcpy(&v, p, 4); return v; }
    }
}

/* An accessor as `comps` doubles per element (or, for indices, integers in
 * doubles), its element count in *count; the caller frees *out. */
static int read_accessor(gltf *g, const cJSON *index, const char *what, int comps, int indices, double **out,
                         size_t *count)
{
    const cJSON *a = at(&g->accessors, index);
    *out = NULL;
    if (!a) return fail(g, "glTF %s refers to an accessor that does not exist", what);
    if (get(a, "sparse")) return fail(g, "glTF %s accessor is sparse; jade does not read sparse accessors", what);
    const cJSON *ty = get(a, "type");
    int n = type_comps(cJSON_IsString(ty) ? ty->valuestring : NULL);
    double ct = count_field(a, "componentType", -1), cnt = count_field(a, "count", -1), off = count_field(a, "byteOffset", 0);
    int cs = ct >= 0 && ct < 1e6 ? comp_size((int)ct) : 0;
    if (n != comps || !cs || cnt < 1 || off < 0)
        return fail(g, "glTF %s accessor is not %d component(s) of a known type with a count", what, comps);
    if (indices ? !(ct == 5121 || ct == 5123 || ct == 5125) : ct == 5125)
        return fail(g, "glTF %s accessor has component type %.0f, not allowed there", what, ct);
    int normalized = cJSON_IsTrue(get(a, "normalized"));
    if (cnt > (indices ? 3.0 * g->lim->max_faces + 2 : (double)g->lim->max_vertices))
        return fail(g, "glTF %s accessor has %.0f elements, over the limit", what, cnt);
    size_t elems = (size_t)cnt, elem = (size_t)cs * (size_t)n;
    double *v = calloc(elems * (size_t)n, sizeof *v);
    if (!v) return fail(g, "out of memory");
    const cJSON *bv = get(a, "bufferView");
    if (bv) { /* without one, every element is zero */
        const uint8_t *data;
        size_t size, stride;
        if (view_bytes(g, bv, &data, &size, &stride)) { free(v); return -1; }
        if (!stride) stride = elem;
        /* Elements closer than their own size would overlap: the spec
         * forbids it, and reading them would mix one into the next. */
        if (stride < elem) {
            free(v);
            return fail(g, "glTF %s accessor's bufferView has a byteStride of %zu, smaller than its %zu-byte elements",
                        what, stride, elem);
        }
        if (off + (double)stride * (double)(elems - 1) + (double)elem > (double)size) {
            free(v);
            return fail(g, "glTF %s accessor reaches past the end of its bufferView", what);
        }
        for (size_t e = 0; e < elems; e++)
            for (int c = 0; c < n; c++)
                v[e * (size_t)n + (size_t)c] = read_comp(data + (size_t)off + e * stride + (size_t)c * (size_t)cs, (int)ct, normalized);
    }
    *out = v;
    *count = elems;
    return 0;
}

/* Room for nv more vertices and nf more faces in the merged mesh. */
static int grow(gltf *g, size_t nv, size_t nf)
{
    jd_mesh_arrays *m = g->out;
    if (m->nv + nv > g->lim->max_vertices || m->nf + nf > g->lim->max_faces)
        return fail(g, "the scene has more than %u vertices or %u faces, over the limit", g->lim->max_vertices,
                    g->lim->max_faces);
    if (m->nv + nv > g->cap_v) {
        size_t cap = (m->nv + nv) * 2;
        if (cap > g->lim->max_vertices) cap = g->lim->max_vertices;
        float *p = realloc(m->pos, cap * 3 * sizeof *p), *q = realloc(m->nrm, cap * 3 * sizeof *q);
        if (p) m->pos = p;
        if (q) m->nrm = q;
        float *u = realloc(m->uv, cap * 2 * sizeof *u);
        if (u) m->uv = u;
        uint8_t *k = realloc(m->col, cap * 4);
        if (k) m->col = k;
        if (!p || !q || !u || !k) return fail(g, "out of memory");
        g->cap_v = cap;
    }
    if (m->nf + nf > g->cap_f) {
        size_t cap = (m->nf + nf) * 2;
        if (cap > g->lim->max_faces) cap = g->lim->max_faces;
        uint32_t *i = realloc(m->idx, cap * 3 * sizeof *i);
        if (!i) return fail(g, "out of memory");
        m->idx = i;
        g->cap_f = cap;
    }
    return 0;
}

/* Appends a primitive's vertices placed by `xf` (column-major 4x4) and its
 * triangles (turned round where the transform mirrors). */
static int append(gltf *g, const double *xf, size_t nv, const double *pos, const double *nrm, const double *uv,
                  const double *color, int color_comps, const uint32_t *tri, size_t nf)
{
    if (grow(g, nv, nf)) return -1;
    jd_mesh_arrays *m = g->out;
    /* Normals go through the inverse transpose: the cofactor matrix. */
    double c[9];
    c[0] = xf[5] * xf[10] - xf[6] * xf[9];
    c[1] = xf[6] * xf[8] - xf[4] * xf[10];
    c[2] = xf[4] * xf[9] - xf[5] * xf[8];
    c[3] = xf[2] * xf[9] - xf[1] * xf[10];
    c[4] = xf[0] * xf[10] - xf[2] * xf[8];
    c[5] = xf[1] * xf[8] - xf[0] * xf[9];
    c[6] = xf[1] * xf[6] - xf[2] * xf[5];
    c[7] = xf[2] * xf[4] - xf[0] * xf[6];
    c[8] = xf[0] * xf[5] - xf[1] * xf[4];
    double det = xf[0] * c[0] + xf[4] * c[3] + xf[8] * c[6];
    for (size_t i = 0; i < nv; i++) {
        const double *p = pos + 3 * i;
        float *o = m->pos + 3 * (m->nv + i);
        for (int k = 0; k < 3; k++) o[k] = (float)(xf[k] * p[0] + xf[4 + k] * p[1] + xf[8 + k] * p[2] + xf[12 + k]);
        if (nrm) {
            const double *q = nrm + 3 * i;
            double t[3];
            for (int k = 0; k < 3; k++) t[k] = c[3 * k] * q[0] + c[3 * k + 1] * q[1] + c[3 * k + 2] * q[2];
            double l = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
            for (int k = 0; k < 3; k++) m->nrm[3 * (m->nv + i) + (size_t)k] = l > 0 ? (float)(t[k] / l) : 0.0f;
        }
        const double *x = g->cur_uvxf, u = uv ? uv[2 * i] : 0.0, w = uv ? uv[2 * i + 1] : 0.0;
        m->uv[2 * (m->nv + i)] = (float)(x[0] * u + x[1] * w + x[2]);
        m->uv[2 * (m->nv + i) + 1] = (float)(x[3] * u + x[4] * w + x[5]);
        /* The vertex's colour: factor times COLOR_0 (linear in glTF), and
         * whether the texture applies (not without coordinates). */
        uint8_t *oc = m->col + 4 * (m->nv + i);
        for (int k = 0; k < 3; k++) {
            double cv = color ? color[(size_t)color_comps * i + (size_t)k] : 1.0;
            oc[k] = jd_sqrt_encode((float)(g->cur_factor[k] * (cv > 0 ? cv : 0)));
        }
        oc[3] = g->cur_textured && uv ? 255 : 0;
    }
    if (color) g->coloured = 1;
    for (size_t f = 0; f < nf; f++) {
        uint32_t a = tri[3 * f], b = tri[3 * f + 1], d = tri[3 * f + 2];
        if (det < 0) { uint32_t s = b; b = d; d = s; }
        uint32_t *o = m->idx + 3 * (m->nf + f);
        o[0] = m->nv + a;
        o[1] = m->nv + b;
        o[2] = m->nv + d;
    }
    if (!nrm) g->no_nrm = 1;
    if (!uv) g->no_uv = 1;
    m->nv += (uint32_t)nv;
    m->nf += (uint32_t)nf;
    return 0;
}

/* A number field, or def where it is absent or not a finite number. */
static double num_or(const cJSON *o, const char *key, double def)
{
    const cJSON *v = get(o, key);
    return cJSON_IsNumber(v) && isfinite(v->valuedouble) ? v->valuedouble : def;
}

/* An RGB array field clamped to [lo, hi], or def where it is not three numbers. */
static void rgb_or(const cJSON *o, const char *key, double lo, double hi, double def, double out[3])
{
    const cJSON *a = get(o, key);
    int ok = cJSON_IsArray(a) && cJSON_GetArraySize(a) == 3;
    for (int c = 0; c < 3; c++) {
        const cJSON *v = ok ? cJSON_GetArrayItem(a, c) : NULL;
        double x = v && cJSON_IsNumber(v) && isfinite(v->valuedouble) ? v->valuedouble : def;
        out[c] = x < lo ? lo : x > hi ? hi : x;
    }
}

/* Adds `what` to a list, once: the sources joined by ", ", what jade
 * cannot show by "; " (its items may hold commas). */
static void note(char *buf, size_t cap, const char *sep, const char *what)
{
    size_t n = strlen(buf);
    if (!strstr(buf, what)) snprintf(buf + n, cap - n, "%s%s", n ? sep : "", what);
}

/* The single-scattering albedo whose multiple-scattering albedo (what the
 * eye sees of a thick slab) is m: the inversion the KHR_materials_volume_
 * scatter draft gives (after Kulla and Conty 2017, "Revisiting Physically
 * Based Shading at Imageworks"). */
static double single_albedo(double m)
{
    double r = 4.09712 + 4.20863 * m - sqrt(9.59217 + 41.6808 * m + 17.7126 * m * m);
    return 1.0 - r * r;
}

/* glTF's translucency extensions into jade's medium (docs/usage.md has the
 * table). KHR_materials_volume gives the attenuation: sigma_t =
 * -ln(attenuationColor) / attenuationDistance, per metre; _volume_scatter
 * splits it by the single-scattering albedo of its multiscatterColor and
 * reduces the scattering by scatterAnisotropy (sigma_s' = sigma_s (1 - g),
 * the similarity relation the dipole runs on); _ior gives eta. A volume
 * without scatter is a clear absorbing glass: nothing for jade's model to
 * scatter, so only said. The first material with a scattering medium wins. */
static void take_medium(gltf *g, const cJSON *mat)
{
    jd_file_medium *md = &g->out->medium;
    const cJSON *ext = get(mat, "extensions");
    if (!ext || (md->flags & JD_MEDIUM_SIGMA)) return;
    const cJSON *vol = get(ext, "KHR_materials_volume"), *sc = get(ext, "KHR_materials_volume_scatter");
    const cJSON *ior = get(ext, "KHR_materials_ior"), *dt = get(ext, "KHR_materials_diffuse_transmission");
    if (cJSON_IsObject(ior)) {
        double eta = num_or(ior, "ior", 1.5);
        if (eta >= 1.0 && eta <= 3.0) {
            md->eta = (float)eta;
            md->flags |= JD_MEDIUM_ETA;
            note(md->source, sizeof md->source, ", ", "KHR_materials_ior");
        } else {
            note(md->ignored, sizeof md->ignored, "; ", "an ior outside 1..3");
        }
    }
    if (cJSON_IsObject(vol) && cJSON_IsObject(sc)) {
        double dist = num_or(vol, "attenuationDistance", INFINITY), att[3], multi[3];
        rgb_or(vol, "attenuationColor", 1e-6, 1.0, 1.0, att);
        rgb_or(sc, "multiscatterColor", 0.0, 1.0, 0.0, multi);
        double aniso = num_or(sc, "scatterAnisotropy", 0.0);
        if (aniso < -0.99) aniso = -0.99;
        if (aniso > 0.99) aniso = 0.99;
        if (dist > 0 && isfinite(dist)) {
            for (int c = 0; c < 3; c++) {
                double sigma_t = -log(att[c]) / dist / 1000.0; /* per mm of the file's unit (metres) */
                double rho = single_albedo(multi[c]);
                if (rho < 0.0) rho = 0.0;
                if (rho > 1.0) rho = 1.0;
                md->sigma_s[c] = (float)(rho * sigma_t * (1.0 - aniso));
                md->sigma_a[c] = (float)((1.0 - rho) * sigma_t);
            }
            md->flags |= JD_MEDIUM_SIGMA;
            md->mm_per_unit = 1000.0f;
            note(md->source, sizeof md->source, ", ", "KHR_materials_volume_scatter");
        } else {
            note(md->ignored, sizeof md->ignored, "; ", "a scattering volume with no attenuationDistance");
        }
        if (get(vol, "thicknessTexture")) note(md->ignored, sizeof md->ignored, "; ", "the thickness texture");
    } else if (cJSON_IsObject(vol)) {
        note(md->ignored, sizeof md->ignored, "; ",
             "KHR_materials_volume without KHR_materials_volume_scatter (a clear absorbing medium: nothing scatters)");
    }
    if (cJSON_IsObject(dt) && !(md->flags & JD_MEDIUM_SIGMA))
        note(md->ignored, sizeof md->ignored, "; ",
             "KHR_materials_diffuse_transmission alone (a thin surface, no medium)");
    if (get(ext, "KHR_materials_dispersion")) note(md->ignored, sizeof md->ignored, "; ", "dispersion");
    if (md->ignored[0]) md->flags |= JD_MEDIUM_NOTE;
}

/* KHR_texture_transform into the primitive's coordinate transform:
 * T(offset) R(rotation) S(scale), as the extension's GLSL has it (rotation
 * counter-clockwise). gltfpack and glTF-Transform write it to undo their
 * quantized coordinates (KHR_mesh_quantization). Values that are not
 * finite, or past 1e6, leave the coordinates as they are and are said. */
static void take_texture_transform(gltf *g, const cJSON *tt)
{
    double off[2] = {0, 0}, sc[2] = {1, 1}, rot = 0;
    const cJSON *o = get(tt, "offset"), *sv = get(tt, "scale"), *r = get(tt, "rotation");
    int ok = (!o || numbers(o, 2, off)) && (!sv || numbers(sv, 2, sc)) && (!r || cJSON_IsNumber(r));
    if (r && ok) rot = r->valuedouble;
    for (int k = 0; k < 2; k++) ok = ok && fabs(off[k]) <= 1e6 && fabs(sc[k]) <= 1e6;
    if (!ok || !(fabs(rot) <= 1e6)) {
        note(g->out->medium.ignored, sizeof g->out->medium.ignored, "; ", "a KHR_texture_transform out of range");
        return;
    }
    double c = cos(rot), s = sin(rot);
    double x[6] = {c * sc[0], -s * sc[1], off[0], s * sc[0], c * sc[1], off[1]};
    memcpy(g->cur_uvxf, x, sizeof x);
}

/* The material's colour (glTF's metallic-roughness base colour, read as the
 * diffuse reflectance): its factor, and its texture where it is the one jade
 * shows (the first the scene uses; a model with several gets the others'
 * factors only, and is told so). */
static void take_colour(gltf *g, const cJSON *mat)
{
    const cJSON *pbr = get(mat, "pbrMetallicRoughness");
    double f4[4] = {1, 1, 1, 1};
    const cJSON *bf = get(pbr, "baseColorFactor");
    if (bf && numbers(bf, 4, f4))
        for (int k = 0; k < 3; k++) {
            g->cur_factor[k] = f4[k] < 0 ? 0 : f4[k] > 1 ? 1 : f4[k];
            if (g->cur_factor[k] != 1.0) g->coloured = 1;
        }
    const cJSON *bt = get(pbr, "baseColorTexture");
    if (!bt) return;
    double tex = count_field(bt, "index", -1);
    if (tex < 0 || tex >= g->textures.count) return; /* checked when decoded: a missing one is ignored */
    /* A second coordinate set, named by the textureInfo or by its
     * transform, is not read. */
    const cJSON *tt = get(get(bt, "extensions"), "KHR_texture_transform");
    if (count_field(bt, "texCoord", 0) != 0 || count_field(tt, "texCoord", 0) != 0) {
        note(g->out->medium.ignored, sizeof g->out->medium.ignored, "; ", "a colour texture on a second set of texture coordinates");
        return;
    }
    if (g->texture < 0) g->texture = (int)tex;
    if (g->texture == (int)tex) {
        g->cur_textured = 1;
        g->coloured = 1;
        if (tt) take_texture_transform(g, tt);
    } else {
        g->other_textures++;
    }
}

static void take_material(gltf *g, const cJSON *prim)
{
    const cJSON *mat = at(&g->materials, get(prim, "material"));
    for (int k = 0; k < 3; k++) g->cur_factor[k] = 1.0;
    g->cur_textured = 0;
    static const double identity[6] = {1, 0, 0, 0, 1, 0};
    memcpy(g->cur_uvxf, identity, sizeof identity);
    take_colour(g, mat);
    take_medium(g, mat);
    const cJSON *name = get(get(mat, "extras"), "jade_material");
    if (g->out->material[0] || !cJSON_IsString(name)) return;
    const char *s = name->valuestring;
    size_t n = strlen(s);
    if (n == 0 || n >= sizeof g->out->material) return;
    for (size_t i = 0; i < n; i++)
        if (!((s[i] >= 'a' && s[i] <= 'z') || (s[i] >= '0' && s[i] <= '9') || s[i] == '_' || s[i] == '-')) return;
    memcpy(g->out->material, s, n + 1);
}

/* Triangles from a primitive's indices (or 0..count-1) in its mode. */
static int triangles(gltf *g, int mode, const double *ind, size_t nind, size_t nv, uint32_t **tri, size_t *nf)
{
    size_t t = mode == 4 ? nind / 3 : nind >= 3 ? nind - 2 : 0;
    *tri = malloc(sizeof(uint32_t) * 3 * (t ? t : 1));
    if (!*tri) return fail(g, "out of memory");
    size_t k = 0;
    for (size_t i = 0; i < t; i++) {
        size_t a, b, c;
        if (mode == 4) { a = 3 * i; b = a + 1; c = a + 2; }
        else if (mode == 5) { a = i; b = i % 2 ? i + 2 : i + 1; c = i % 2 ? i + 1 : i + 2; }
        else { a = 0; b = i + 1; c = i + 2; }
        double va = ind ? ind[a] : (double)a, vb = ind ? ind[b] : (double)b, vc = ind ? ind[c] : (double)c;
        if (va >= nv || vb >= nv || vc >= nv) {
            free(*tri);
            *tri = NULL;
            return fail(g, "glTF primitive index %.0f is past its %zu vertices", fmax(va, fmax(vb, vc)), nv);
        }
        if (va == vb || vb == vc || va == vc) continue; /* strips' degenerate joins */
        (*tri)[3 * k] = (uint32_t)va;
        (*tri)[3 * k + 1] = (uint32_t)vb;
        (*tri)[3 * k + 2] = (uint32_t)vc;
        k++;
    }
    *nf = k;
    return 0;
}

static int draco_primitive(gltf *g, const double *xf, const cJSON *ext)
{
    const uint8_t *data;
    size_t size;
    if (view_bytes(g, get(ext, "bufferView"), &data, &size, NULL)) return -1;
    const cJSON *attrs = get(ext, "attributes");
    const char *names[3] = {"POSITION", "NORMAL", "TEXCOORD_0"};
    int ids[3];
    for (int k = 0; k < 3; k++) {
        double v = count_field(attrs, names[k], -1);
        ids[k] = v >= 0 && v < 1e6 ? (int)v : -1;
    }
    if (ids[0] < 0) return fail(g, "glTF Draco primitive has no POSITION attribute id");
    jd_mesh_arrays d = {0};
    char msg[256] = "";
    if (jd_draco_read_ids(data, size, ids, g->lim->max_vertices, g->lim->max_faces, &d, msg, sizeof msg))
        return fail(g, "glTF Draco primitive: %s", msg);
    for (size_t i = 0; i < 3 * (size_t)d.nf; i++)
        if (d.idx[i] >= d.nv) {
            jd_mesh_arrays_free(&d);
            return fail(g, "glTF Draco primitive refers to a vertex past its %u", d.nv);
        }
    size_t nv = d.nv;
    double *p = malloc(sizeof(double) * 3 * nv), *n = d.nrm ? malloc(sizeof(double) * 3 * nv) : NULL,
           *u = d.uv ? malloc(sizeof(double) * 2 * nv) : NULL;
    int rc = -1;
    if (p && (!d.nrm || n) && (!d.uv || u)) {
        for (size_t i = 0; i < 3 * nv; i++) p[i] = d.pos[i];
        for (size_t i = 0; n && i < 3 * nv; i++) n[i] = d.nrm[i];
        for (size_t i = 0; u && i < 2 * nv; i++) u[i] = d.uv[i];
        rc = append(g, xf, nv, p, n, u, NULL, 0, d.idx, d.nf);
    } else {
        fail(g, "out of memory");
    }
    free(p);
    free(n);
    free(u);
    jd_mesh_arrays_free(&d);
    return rc;
}

static int primitive(gltf *g, const double *xf, const cJSON *prim)
{
    double mode = count_field(prim, "mode", 4);
    if (mode < 4 || mode > 6) {
        g->skipped++;
        return 0;
    }
    take_material(g, prim);
    const cJSON *ext = get(get(prim, "extensions"), "KHR_draco_mesh_compression");
    if (ext) return draco_primitive(g, xf, ext);
    const cJSON *attrs = get(prim, "attributes");
    const cJSON *pi = get(attrs, "POSITION"), *ni = get(attrs, "NORMAL"), *ui = get(attrs, "TEXCOORD_0"),
                *ii = get(prim, "indices");
    if (!pi) return fail(g, "glTF primitive has no POSITION attribute");
    double *pos = NULL, *nrm = NULL, *uv = NULL, *ind = NULL, *col = NULL;
    uint32_t *tri = NULL;
    size_t nv = 0, nn = 0, nu = 0, ni_count = 0, nf = 0, nc = 0;
    const cJSON *ci = get(attrs, "COLOR_0");
    const cJSON *ct = get(at(&g->accessors, ci), "type");
    int col_comps = cJSON_IsString(ct) && !strcmp(ct->valuestring, "VEC4") ? 4 : 3;
    int rc = read_accessor(g, pi, "POSITION", 3, 0, &pos, &nv);
    if (!rc && ci) rc = read_accessor(g, ci, "COLOR_0", col_comps, 0, &col, &nc);
    if (!rc && ni) rc = read_accessor(g, ni, "NORMAL", 3, 0, &nrm, &nn);
    if (!rc && ui) rc = read_accessor(g, ui, "TEXCOORD_0", 2, 0, &uv, &nu);
    if (!rc && ii) rc = read_accessor(g, ii, "indices", 1, 1, &ind, &ni_count);
    if (!rc && ((nrm && nn != nv) || (uv && nu != nv) || (col && nc != nv)))
        rc = fail(g, "glTF primitive's attributes have different counts (%zu positions)", nv);
    if (!rc && nv > g->lim->max_vertices) rc = fail(g, "glTF primitive has %zu vertices, over the limit", nv);
    if (!rc) rc = triangles(g, (int)mode, ind, ii ? ni_count : nv, nv, &tri, &nf);
    if (!rc) rc = append(g, xf, nv, pos, nrm, uv, col, col_comps, tri, nf);
    free(col);
    free(pos);
    free(nrm);
    free(uv);
    free(ind);
    free(tri);
    return rc;
}

static void mat_mul(const double *a, const double *b, double *out)
{
    double r[16];
    for (int c = 0; c < 4; c++)
        for (int k = 0; k < 4; k++)
            r[4 * c + k] = a[k] * b[4 * c] + a[4 + k] * b[4 * c + 1] + a[8 + k] * b[4 * c + 2] + a[12 + k] * b[4 * c + 3];
    memcpy(out, r, sizeof r);
}

static int numbers(const cJSON *a, int n, double *out)
{
    if (!cJSON_IsArray(a) || cJSON_GetArraySize(a) != n) return 0;
    const cJSON *e;
    int i = 0;
    cJSON_ArrayForEach(e, a) {
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble)) return 0;
        out[i++] = e->valuedouble;
    }
    return 1;
}

/* The node's local matrix: `matrix`, or translation * rotation * scale. */
static int local_matrix(gltf *g, const cJSON *node, double *m)
{
    static const double id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    memcpy(m, id, sizeof id);
    const cJSON *mx = get(node, "matrix");
    if (mx) return numbers(mx, 16, m) ? 0 : fail(g, "glTF node matrix is not 16 finite numbers");
    double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
    if ((get(node, "translation") && !numbers(get(node, "translation"), 3, t)) ||
        (get(node, "rotation") && !numbers(get(node, "rotation"), 4, q)) ||
        (get(node, "scale") && !numbers(get(node, "scale"), 3, s)))
        return fail(g, "glTF node translation, rotation or scale is not finite numbers");
    double x = q[0], y = q[1], z = q[2], w = q[3];
    double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
                   2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                   2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < 3; k++) m[4 * c + k] = r[3 * c + k] * s[c];
    m[12] = t[0];
    m[13] = t[1];
    m[14] = t[2];
    return 0;
}

/* Walks the node tree from the scene's roots with an explicit stack: a
 * cyclic or very deep hierarchy is refused, not recursed into. */
static int walk(gltf *g, const cJSON *roots)
{
    struct frame {
        const cJSON *node;
        double xf[16];
        int depth;
    } *stack = malloc(sizeof *stack * (MAX_DEPTH * 64 + 64));
    if (!stack) return fail(g, "out of memory");
    static const double id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    int sp = 0, visits = 0, rc = 0;
    const cJSON *r;
    cJSON_ArrayForEach(r, roots) {
        const cJSON *node = at(&g->nodes, r);
        if (!node) { rc = fail(g, "glTF scene refers to a node that does not exist"); break; }
        stack[0].node = node;
        memcpy(stack[0].xf, id, sizeof id);
        stack[0].depth = 0;
        sp = 1;
        while (sp && !rc) {
            struct frame f = stack[--sp];
            if (++visits > MAX_INSTANCES) { rc = fail(g, "glTF scene places more than %d nodes (cyclic?)", MAX_INSTANCES); break; }
            double local[16];
            if ((rc = local_matrix(g, f.node, local))) break;
            mat_mul(f.xf, local, f.xf);
            const cJSON *mesh = get(f.node, "mesh");
            if (mesh) {
                const cJSON *m = at(&g->meshes, mesh);
                if (!m) { rc = fail(g, "glTF node refers to a mesh that does not exist"); break; }
                const cJSON *prims = get(m, "primitives"), *p;
                cJSON_ArrayForEach(p, prims) if ((rc = primitive(g, f.xf, p))) break;
                if (rc) break;
            }
            const cJSON *kids = get(f.node, "children"), *k;
            cJSON_ArrayForEach(k, kids) {
                const cJSON *child = at(&g->nodes, k);
                if (!child) { rc = fail(g, "glTF node refers to a child that does not exist"); break; }
                if (f.depth + 1 >= MAX_DEPTH || sp >= MAX_DEPTH * 64 + 63) {
                    rc = fail(g, "glTF node tree is deeper or wider than jade walks (%d levels); cyclic?", MAX_DEPTH);
                    break;
                }
                stack[sp].node = child;
                memcpy(stack[sp].xf, f.xf, sizeof f.xf);
                stack[sp].depth = f.depth + 1;
                sp++;
            }
        }
        if (rc) break;
    }
    free(stack);
    return rc;
}

/* The colour texture jade shows, decoded (texture_decode.h): its image
 * from a data: URI, a file beside the glTF or a bufferView. */
static int load_texture(gltf *g)
{
    int ti = g->texture;
    const cJSON *img = at(&g->images, get(g->textures.item[ti], "source"));
    if (!img) { /* KHR_texture_basisu, EXT_texture_webp: no core source */
        note(g->out->medium.ignored, sizeof g->out->medium.ignored, "; ", "a colour texture in a format jade does not read");
        g->texture = -1;
        return 0;
    }
    blob b = {0};
    const cJSON *uri = get(img, "uri");
    int ii = (int)get(g->textures.item[ti], "source")->valuedouble;
    /* A reader that fails may have allocated already (a data: URI bad
     * half-way): the image's bytes are this function's to free. */
    if (cJSON_IsString(uri) && !strncmp(uri->valuestring, "data:", 5)) {
        if (load_data_uri(g, ii, uri->valuestring, &b)) { free(b.owned); return -1; }
    } else if (cJSON_IsString(uri)) {
        if (load_file_uri(g, ii, uri->valuestring, SIZE_MAX, &b)) { free(b.owned); return -1; }
    } else if (get(img, "bufferView")) {
        size_t size;
        if (view_bytes(g, get(img, "bufferView"), &b.data, &size, NULL)) return -1;
        b.size = size;
    } else {
        return fail(g, "glTF image %d has neither a uri nor a bufferView", ii);
    }
    char what[48], msg[256];
    snprintf(what, sizeof what, "glTF image %d", ii);
    static const float one[3] = {1, 1, 1};
    int rc = jd_texture_decode(b.data, b.size, one, g->lim->max_texture_side, what, &g->out->tex, msg, sizeof msg);
    free(b.owned);
    return rc ? fail(g, "%s", msg) : 0;
}

static uint32_t le32(const uint8_t *p) { return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24; }

int jd_gltf_read(const uint8_t *buf, size_t n, const char *path, const jd_gltf_limits *lim, jd_mesh_arrays *out,
                 char *err, size_t errlen)
{
    gltf g = {.path = path, .lim = lim, .err = err, .errlen = errlen, .out = out, .texture = -1};
    memset(out, 0, sizeof *out);
    const char *json = (const char *)buf;
    size_t json_len = n;
    if (n >= 12 && !memcmp(buf, "glTF", 4)) {
        /* GLB: header, a JSON chunk, then an optional binary chunk. */
        if (le32(buf + 4) != 2) return fail(&g, "GLB version %u; jade reads version 2", le32(buf + 4));
        if (le32(buf + 8) > n || le32(buf + 8) < 20 || n < 20)
            return fail(&g, "GLB declares %u bytes; the file has %zu (a GLB holds at least 20)", le32(buf + 8), n);
        size_t total = le32(buf + 8), len0 = le32(buf + 12);
        if (le32(buf + 16) != 0x4E4F534Au || len0 > total - 20)
            return fail(&g, "GLB's first chunk is not JSON or runs past the file");
        json = (const char *)buf + 20;
        json_len = len0;
        size_t at1 = 20 + len0;
        if (at1 + 8 <= total && le32(buf + at1 + 4) == 0x004E4942u) {
            size_t len1 = le32(buf + at1);
            if (len1 > total - at1 - 8) return fail(&g, "GLB's binary chunk runs past the file");
            g.bin = buf + at1 + 8;
            g.bin_size = len1;
        }
    }
    /* cJSON 1.7.15 compares keywords ("true", "null") with strncmp and
     * reads past a buffer that is not NUL-terminated (found by fuzzing):
     * it gets a terminated copy. */
    char *text = malloc(json_len + 1);
    if (!text) return fail(&g, "out of memory");
    memcpy(text, json, json_len);
    text[json_len] = 0;
    cJSON *root = cJSON_ParseWithLength(text, json_len + 1);
    if (!root) {
        const char *e = cJSON_GetErrorPtr();
        ptrdiff_t at = e && e >= text && e <= text + json_len ? e - text : -1;
        free(text);
        return fail(&g, "glTF JSON does not parse (at byte %td)", at);
    }
    free(text);
    int rc = -1;
    const cJSON *ver = get(get(root, "asset"), "version");
    if (!cJSON_IsString(ver) || strncmp(ver->valuestring, "2.", 2)) {
        fail(&g, "glTF asset.version is not 2.x");
        goto done;
    }
    const cJSON *req = get(root, "extensionsRequired"), *e;
    /* KHR_mesh_quantization only widens the component types attributes may
     * have, which read_accessor reads whatever the attribute;
     * KHR_texture_transform is applied to the colour texture's coordinates
     * (take_colour). */
    cJSON_ArrayForEach(e, req) if (!cJSON_IsString(e) || (strcmp(e->valuestring, "KHR_draco_mesh_compression") &&
                                                          strcmp(e->valuestring, "KHR_mesh_quantization") &&
                                                          strcmp(e->valuestring, "KHR_texture_transform"))) {
        fail(&g, "glTF requires extension %s, which jade does not read", cJSON_IsString(e) ? e->valuestring : "(not a name)");
        goto done;
    }
    if (make_table(&g, root, "buffers", &g.buffers) || make_table(&g, root, "bufferViews", &g.views) ||
        make_table(&g, root, "accessors", &g.accessors) || make_table(&g, root, "meshes", &g.meshes) ||
        make_table(&g, root, "nodes", &g.nodes) || make_table(&g, root, "materials", &g.materials) ||
        make_table(&g, root, "textures", &g.textures) || make_table(&g, root, "images", &g.images) || load_buffers(&g))
        goto done;
    table scenes;
    if (make_table(&g, root, "scenes", &scenes)) goto done;
    const cJSON *scene = NULL;
    if (scenes.count) scene = get(root, "scene") ? at(&scenes, get(root, "scene")) : scenes.item[0];
    if (scenes.count && !scene) {
        free(scenes.item);
        fail(&g, "glTF's default scene does not exist");
        goto done;
    }
    free(scenes.item);
    if (scene) {
        rc = walk(&g, get(scene, "nodes"));
    } else {
        /* No scene: every mesh once, where it stands. */
        static const double id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
        rc = 0;
        for (int i = 0; i < g.meshes.count && !rc; i++) {
            const cJSON *p;
            cJSON_ArrayForEach(p, get(g.meshes.item[i], "primitives")) if ((rc = primitive(&g, id, p))) break;
        }
    }
    if (!rc && (out->nv == 0 || out->nf == 0))
        rc = fail(&g, "glTF's scene has no triangles%s", g.skipped ? " (only points or lines)" : "");
    if (!rc && g.texture >= 0) rc = load_texture(&g);
    if (!rc) {
        if (g.no_nrm) { free(out->nrm); out->nrm = NULL; }
        /* A primitive without coordinates has the texture's weight 0. */
        if (g.no_uv && !out->tex.texels) { free(out->uv); out->uv = NULL; }
        if (!g.coloured && !out->tex.texels) { free(out->col); out->col = NULL; }
        if (g.other_textures) {
            char what[96];
            snprintf(what, sizeof what, "%d more colour texture%s (jade shows one a model: their materials get their factor)",
                     g.other_textures, g.other_textures == 1 ? "" : "s");
            note(out->medium.ignored, sizeof out->medium.ignored, "; ", what);
        }
        if (out->medium.ignored[0]) out->medium.flags |= JD_MEDIUM_NOTE;
    }
done:
    cJSON_Delete(root);
    for (int i = 0; g.buf && i < g.buffers.count; i++) free(g.buf[i].owned);
    free(g.buf);
    free(g.buffers.item);
    free(g.views.item);
    free(g.accessors.item);
    free(g.meshes.item);
    free(g.nodes.item);
    free(g.materials.item);
    free(g.textures.item);
    free(g.images.item);
    if (rc) jd_mesh_arrays_free(out);
    return rc;
}
