#include "ply_strips.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A PLY's header as far as this needs it: its format, and per element its
 * name, count, the bytes of one instance where all its properties are
 * scalars (binary), and for the strips its list's count and item sizes. */
enum { ASCII, LITTLE, BIG };
typedef struct element {
    char name[32];
    uint64_t count;
    int fixed;          /* every property a scalar */
    size_t size;        /* bytes an instance, where fixed */
    int list_count, list_item, list_signed; /* the strips' one list property */
    int props;
} element;

static int type_size(const char *t, int *is_signed)
{
    static const struct { const char *name; int size, sign; } types[] = {
        {"char", 1, 1},  {"int8", 1, 1},   {"uchar", 1, 0},  {"uint8", 1, 0},   {"short", 2, 1},  {"int16", 2, 1},
        {"ushort", 2, 0}, {"uint16", 2, 0}, {"int", 4, 1},    {"int32", 4, 1},   {"uint", 4, 0},   {"uint32", 4, 0},
        {"float", 4, 1}, {"float32", 4, 1}, {"double", 8, 1}, {"float64", 8, 1}};
    for (size_t i = 0; i < sizeof types / sizeof types[0]; i++)
        if (!strcmp(t, types[i].name)) {
            if (is_signed) *is_signed = types[i].sign;
            return types[i].size;
        }
    return 0;
}

static int fail(char *err, size_t cap, const char *msg)
{
    snprintf(err, cap, "%s", msg);
    return -1;
}

/* An integer of `size` bytes at p in the file's byte order. */
static int64_t read_int(const uint8_t *p, int size, int sign, int order)
{
    uint64_t v = 0;
    for (int i = 0; i < size; i++) v |= (uint64_t)p[order == BIG ? size - 1 - i : i] << (8 * i);
    if (sign && size < 8 && (v >> (8 * size - 1)) & 1) v |= ~(uint64_t)0 << (8 * size);
    return (int64_t)v;
}

/* A decimal integer at *p, after blanks, never reading past n (the file is
 * not NUL-terminated); 0 where there is none. */
static int read_decimal(const uint8_t *d, size_t n, size_t *p, int64_t *v)
{
    size_t i = *p;
    while (i < n && (d[i] == ' ' || d[i] == '\t' || d[i] == '\r' || d[i] == '\n')) i++;
    int neg = i < n && d[i] == '-';
    if (i < n && (d[i] == '-' || d[i] == '+')) i++;
    size_t start = i;
    int64_t x = 0;
    while (i < n && d[i] >= '0' && d[i] <= '9') {
        if (x < (int64_t)1 << 40) x = x * 10 + (d[i] - '0');
        i++;
    }
    if (i == start) return 0;
    *v = neg ? -x : x;
    *p = i;
    return 1;
}

/* Output that grows as needed, up to a bound set from the input. */
typedef struct out_buf { char *p; size_t n, cap; } out_buf;

static int put(out_buf *o, const void *d, size_t n)
{
    if (o->n + n > o->cap) return -1;
    memcpy(o->p + o->n, d, n);
    o->n += n;
    return 0;
}

/* One triangle of a strip, in the strip's alternating winding. */
static int emit(out_buf *o, int order, int64_t a, int64_t b, int64_t c, uint64_t *faces)
{
    if (a == b || b == c || a == c) return 0; /* the strips' joins */
    if (order == ASCII) {
        char line[80];
        int k = snprintf(line, sizeof line, "3 %lld %lld %lld\n", (long long)a, (long long)b, (long long)c);
        if (put(o, line, (size_t)k)) return -1;
    } else {
        uint8_t rec[13] = {3};
        int64_t v[3] = {a, b, c};
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 4; k++) rec[1 + 4 * i + (order == BIG ? 3 - k : k)] = (uint8_t)((uint64_t)v[i] >> (8 * k));
        if (put(o, rec, sizeof rec)) return -1;
    }
    (*faces)++;
    return 0;
}

int jd_ply_strips_to_faces(const char *data, size_t n, char **out, size_t *out_n, char *err, size_t errlen)
{
    const uint8_t *d = (const uint8_t *)data;
    *out = NULL;
    *out_n = 0;
    /* The header: lines up to end_header, within the first 64 KiB. */
    element el[16];
    int nel = 0, format = -1, strips = -1;
    size_t at = 0, body = 0, limit = n < (64u << 10) ? n : (64u << 10);
    while (at < limit && !body) {
        size_t e = at;
        while (e < limit && d[e] != '\n') e++;
        if (e >= limit) return fail(err, errlen, "PLY header has no end_header in its first 64 KiB");
        char line[256];
        size_t len = e - at < sizeof line - 1 ? e - at : sizeof line - 1;
        memcpy(line, d + at, len);
        line[len] = 0;
        if (len && line[len - 1] == '\r') line[--len] = 0;
        at = e + 1;
        char a[32], b[32], c[32], name[32];
        unsigned long long count;
        if (!strcmp(line, "end_header")) body = at;
        else if (sscanf(line, "format %31s", a) == 1)
            format = !strcmp(a, "ascii") ? ASCII : !strcmp(a, "binary_little_endian") ? LITTLE
                     : !strcmp(a, "binary_big_endian") ? BIG : -1;
        else if (sscanf(line, "element %31s %llu", name, &count) == 2) {
            if (nel == 16) return fail(err, errlen, "PLY header has more than 16 elements");
            element *x = &el[nel++];
            memset(x, 0, sizeof *x);
            snprintf(x->name, sizeof x->name, "%s", name);
            x->count = count;
            x->fixed = 1;
            if (!strcmp(name, "tristrips")) strips = nel - 1;
        } else if (sscanf(line, "property list %31s %31s %31s", a, b, c) == 3) {
            if (!nel) return fail(err, errlen, "PLY property before any element");
            element *x = &el[nel - 1];
            x->fixed = 0;
            x->props++;
            x->list_count = type_size(a, NULL);
            x->list_item = type_size(b, &x->list_signed);
            if (!x->list_count || !x->list_item || !strcmp(b, "float") || !strcmp(b, "double"))
                return fail(err, errlen, "PLY list property of an unknown or non-integer type");
        } else if (sscanf(line, "property %31s %31s", a, b) == 2) {
            if (!nel) return fail(err, errlen, "PLY property before any element");
            int s = type_size(a, NULL);
            if (!s) return fail(err, errlen, "PLY property of an unknown type");
            el[nel - 1].size += (size_t)s;
            el[nel - 1].props++;
        }
    }
    if (strips < 0) return 0;
    uint64_t vertices = 0;
    for (int i = 0; i < nel; i++) {
        if (!strcmp(el[i].name, "face")) return 0; /* faces already: the strips are extra */
        if (!strcmp(el[i].name, "vertex")) vertices = el[i].count;
    }
    if (format < 0) return fail(err, errlen, "PLY format is not ascii, binary_little_endian or binary_big_endian");
    element *st = &el[strips];
    if (st->props != 1 || st->fixed) return fail(err, errlen, "PLY tristrips element is not one list of indices");
    /* Where the strips' data starts and ends: ASCII one line an instance;
     * binary, the elements before them must be all scalars. */
    size_t start = body;
    for (int i = 0; i < strips; i++) {
        if (format == ASCII) {
            for (uint64_t k = 0; k < el[i].count; k++) {
                while (start < n && d[start] != '\n') start++;
                if (start >= n) return fail(err, errlen, "PLY ends inside an element before its tristrips");
                start++;
            }
        } else {
            if (!el[i].fixed) return fail(err, errlen, "PLY has list properties before its tristrips");
            if (el[i].count > (n - start) / (el[i].size ? el[i].size : 1))
                return fail(err, errlen, "PLY ends inside an element before its tristrips");
            start += (size_t)el[i].count * el[i].size;
        }
    }
    /* The strips' indices, decoded into faces; the output is bounded by a
     * triangle per index of the input (13 bytes or a short line each). */
    out_buf o = {NULL, 0, 0};
    size_t most = (n - start) / (format == ASCII ? 2 : (size_t)st->list_item) + 1;
    o.cap = body + (start - body) + most * (format == ASCII ? 40 : 13) + 256;
    o.p = malloc(o.cap);
    if (!o.p) return fail(err, errlen, "out of memory for the PLY's faces");
    /* The header, its tristrips element turned into a face element. */
    o.n = 0;
    char hdr[128];
    int k;
    at = 0;
    int in_strips = 0;
    size_t face_at = 0;
    while (at < body) {
        size_t e = at;
        while (d[e] != '\n') e++;
        const char *line = data + at;
        size_t len = e + 1 - at;
        if (len >= 18 && !strncmp(line, "element tristrips", 17)) {
            in_strips = 1;
            face_at = o.n + 13; /* where the count's digits go */
            /* The face count is written once known: a fixed-width field. */
            k = snprintf(hdr, sizeof hdr, "element face %020llu\nproperty list uchar int vertex_indices\n", 0ULL);
            if (put(&o, hdr, (size_t)k)) goto full;
        } else if (len >= 8 && !strncmp(line, "element", 7)) {
            in_strips = 0;
            if (put(&o, line, len)) goto full;
        } else if (!(in_strips && !strncmp(line, "property", 8))) {
            if (put(&o, line, len)) goto full;
        }
        at = e + 1;
    }
    if (put(&o, data + body, start - body)) goto full;
    uint64_t faces = 0;
    size_t p = start;
    for (uint64_t s = 0; s < st->count; s++) {
        int64_t len;
        if (format == ASCII) {
            if (!read_decimal(d, n, &p, &len)) goto short_strips;
        } else {
            if (n - p < (size_t)st->list_count) goto short_strips;
            len = read_int(d + p, st->list_count, 0, format);
            p += (size_t)st->list_count;
        }
        if (len < 0 || (uint64_t)len > (n - p) / (format == ASCII ? 1 : (size_t)st->list_item) + 1) goto short_strips;
        int64_t a = -1, b = -1;
        int64_t parity = 0;
        for (int64_t i = 0; i < len; i++) {
            int64_t v;
            if (format == ASCII) {
                if (!read_decimal(d, n, &p, &v)) goto short_strips;
            } else {
                if (n - p < (size_t)st->list_item) goto short_strips;
                v = read_int(d + p, st->list_item, st->list_signed, format);
                p += (size_t)st->list_item;
            }
            if (v < 0) { /* -1: a new strip */
                a = b = -1;
                parity = 0;
                continue;
            }
            if ((uint64_t)v >= vertices) goto bad_index;
            if (a >= 0 && b >= 0) {
                if (emit(&o, format, parity % 2 ? b : a, parity % 2 ? a : b, v, &faces)) goto full;
                parity++;
            }
            a = b;
            b = v;
        }
        if (format == ASCII)
            while (p < n && d[p] != '\n') p++;
    }
    if (format != ASCII) {
        /* Whatever follows the strips (other elements) goes on as it was. */
        if (put(&o, data + p, n - p)) goto full;
    } else if (p < n && put(&o, data + p, n - p)) {
        goto full;
    }
    /* The face count into its fixed-width field. */
    {
        char num[24]; /* 20 digits hold any 64-bit count */
        snprintf(num, sizeof num, "%020llu", (unsigned long long)faces);
        memcpy(o.p + face_at, num, 20);
    }
    *out = o.p;
    *out_n = o.n;
    return 1;
full:
    free(o.p);
    return fail(err, errlen, "PLY tristrips: more faces than the file can hold");
short_strips:
    free(o.p);
    return fail(err, errlen, "PLY tristrips run past the end of the file");
bad_index:
    free(o.p);
    return fail(err, errlen, "PLY tristrips refer to a vertex past the vertex count");
}
