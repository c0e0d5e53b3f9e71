#include "obj_check.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A face corner's index: a signed decimal, relative (negative) to the
 * count so far, else counted in the whole file (some writers put faces
 * before their vertices, and libdraco reads them); 1 with *out when it
 * names an existing element. */
static int index_ok(const char **p, const char *end, long so_far, long total, long *out)
{
    const char *s = *p;
    int neg = s < end && *s == '-';
    if (neg) s++;
    long v = 0;
    const char *digits = s;
    while (s < end && *s >= '0' && *s <= '9' && v < 1000000000L) v = v * 10 + (*s++ - '0');
    if (s == digits) return 0;
    *p = s;
    *out = neg ? so_far - v + 1 : v;
    return *out >= 1 && *out <= total;
}

/* Which element a line defines: 0 v, 1 vt, 2 vn, -1 none. */
static int defines(const char *s, const char *end)
{
    while (s < end && (*s == ' ' || *s == '\t')) s++;
    if (end - s >= 2 && s[0] == 'v' && (s[1] == ' ' || s[1] == '\t')) return 0;
    if (end - s >= 3 && s[0] == 'v' && s[1] == 't' && (s[2] == ' ' || s[2] == '\t')) return 1;
    if (end - s >= 3 && s[0] == 'v' && s[1] == 'n' && (s[2] == ' ' || s[2] == '\t')) return 2;
    return -1;
}

static int bad_corner(char *err, size_t errlen, long line, const char *corner, const char *end)
{
    const char *e = corner;
    while (e < end && *e != ' ' && *e != '\t' && *e != '\r') e++;
    snprintf(err, errlen, "OBJ line %ld: face corner '%.*s' is not v, v/vt, v//vn or v/vt/vn", line,
             (int)(e - corner) > 40 ? 40 : (int)(e - corner), corner);
    return -1;
}

int jd_obj_check(const char *data, size_t n, char *err, size_t errlen)
{
    long counts[3] = {0, 0, 0}, totals[3] = {0, 0, 0}; /* v, vt, vn: so far, in the file */
    static const char *const what[3] = {"vertex", "texture coordinate", "normal"};
    for (size_t at = 0; at < n;) {
        const char *s = data + at, *end = memchr(s, '\n', n - at);
        if (!end) end = data + n;
        at = (size_t)(end - data) + 1;
        int k = defines(s, end);
        if (k >= 0) totals[k]++;
    }
    long line = 0;
    for (size_t at = 0; at < n;) {
        const char *s = data + at, *end = memchr(s, '\n', n - at);
        if (!end) end = data + n;
        at = (size_t)(end - data) + 1;
        line++;
        int def = defines(s, end);
        if (def >= 0) counts[def]++;
        while (s < end && (*s == ' ' || *s == '\t')) s++;
        if (!(end - s >= 2 && s[0] == 'f' && (s[1] == ' ' || s[1] == '\t'))) continue;
        s += 2;
        for (;;) {
            while (s < end && (*s == ' ' || *s == '\t' || *s == '\r')) s++;
            /* A comment after the corners, or a line-continuation mark
             * (which libdraco, like jade, takes for the face's end). */
            if (s >= end || *s == '#' || *s == '\\') break;
            const char *corner = s;
            for (int k = 0; k < 3; k++) {
                long v = 0;
                /* v, v/vt, v//vn or v/vt/vn: an empty vt between slashes is allowed. */
                if (k == 1 && s < end && *s == '/') goto next;
                if (!index_ok(&s, end, counts[k], totals[k], &v)) {
                    /* A number was read (s is past its digits): it names nothing. */
                    if (s > corner && s[-1] >= '0' && s[-1] <= '9') {
                        snprintf(err, errlen, "OBJ line %ld: a face refers to %s %ld, but the file has %ld", line,
                                 what[k], v, totals[k]);
                        return -1;
                    }
                    return bad_corner(err, errlen, line, corner, end);
                }
            next:
                if (k < 2 && s < end && *s == '/') {
                    s++;
                    continue;
                }
                break;
            }
            if (s < end && *s != ' ' && *s != '\t' && *s != '\r' && *s != '#' && *s != '\\')
                return bad_corner(err, errlen, line, corner, end);
        }
    }
    return 0;
}

/* A line whose first word is "mtllib". */
static int is_mtllib(const char *s, const char *end)
{
    while (s < end && (*s == ' ' || *s == '\t')) s++;
    return end - s >= 7 && !memcmp(s, "mtllib", 6) && (s[6] == ' ' || s[6] == '\t');
}

int jd_obj_for_draco(const char *data, size_t n, char **out, size_t *out_n)
{
    *out = NULL;
    *out_n = 0;
    /* Only comments after something on their line: libdraco skips whole
     * comment lines itself. */
    int any = 0;
    for (size_t at = 0; at < n && !any;) {
        const char *s = data + at, *end = memchr(s, '\n', n - at);
        if (!end) end = data + n;
        at = (size_t)(end - data) + 1;
        if (is_mtllib(s, end)) any = 1;
        while (s < end && (*s == ' ' || *s == '\t')) s++;
        if (s < end && *s != '#' && memchr(s, '#', (size_t)(end - s))) any = 1;
    }
    if (!any) return 0;
    char *o = malloc(n ? n : 1);
    if (!o) return -1;
    size_t k = 0;
    for (size_t at = 0; at < n;) {
        const char *s = data + at, *end = memchr(s, '\n', n - at);
        int has_nl = end != NULL;
        if (!end) end = data + n;
        at = (size_t)(end - data) + 1;
        const char *hash = memchr(s, '#', (size_t)(end - s));
        const char *stop = is_mtllib(s, end) ? s : hash ? hash : end;
        memcpy(o + k, s, (size_t)(stop - s));
        k += (size_t)(stop - s);
        if (has_nl) o[k++] = '\n';
    }
    *out = o;
    *out_n = k;
    return 1;
}
