#include "draco_header.h"

#include <string.h>

/* Byte reader that fails instead of running past the end. */
typedef struct rd { const uint8_t *p; size_t n, at; } rd;

static int rd_u8(rd *r, uint32_t *v)
{
    if (r->at >= r->n) return 0;
    *v = r->p[r->at++];
    return 1;
}

static int rd_u32(rd *r, uint32_t *v)
{
    if (r->n - r->at < 4) return 0;
    const uint8_t *s = r->p + r->at;
    *v = (uint32_t)s[0] | (uint32_t)s[1] << 8 | (uint32_t)s[2] << 16 | (uint32_t)s[3] << 24;
    r->at += 4;
    return 1;
}

/* Draco's unsigned LEB128 varint, at most 5 bytes for 32 bits. */
static int rd_varint(rd *r, uint32_t *v)
{
    uint64_t acc = 0;
    for (int i = 0; i < 5; i++) {
        uint32_t b;
        if (!rd_u8(r, &b)) return 0;
        acc |= (uint64_t)(b & 0x7f) << (7 * i);
        if (!(b & 0x80)) {
            if (acc > 0xffffffffu) return 0;
            *v = (uint32_t)acc;
            return 1;
        }
    }
    return 0;
}

static int rd_skip(rd *r, size_t k)
{
    if (r->n - r->at < k) return 0;
    r->at += k;
    return 1;
}

/* libdraco 1.5.5 decodes metadata nested up to 1,001 levels below the
 * top (measured: 1,001 decodes, 1,002 is "Failed to decode metadata"). */
enum { MAX_SUB_LEVELS = 1001 };

/* Metadata: entries (u8 name length, name, varint size, bytes) then named
 * sub-metadata, depth first. Walked with a fixed stack of the subs left at
 * each level, not by recursion: a 3-byte level cannot exhaust the C stack.
 * libdraco loops over the declared counts even after reads fail, so a huge
 * count alone can burn seconds: every count is bounded by the bytes that
 * remain. Returns 1, 0 (corrupt) or -1 (deeper than libdraco reads). */
static int skip_metadata(rd *r)
{
    uint32_t left[MAX_SUB_LEVELS + 1];
    int depth = 0;
    for (;;) {
        uint32_t entries, subs, len;
        if (!rd_varint(r, &entries) || entries > (r->n - r->at) / 2) return 0;
        for (uint32_t i = 0; i < entries; i++)
            if (!rd_u8(r, &len) || !rd_skip(r, len) || !rd_varint(r, &len) || len == 0 || !rd_skip(r, len))
                return 0;
        if (!rd_varint(r, &subs) || subs > (r->n - r->at) / 2) return 0;
        left[depth] = subs;
        while (left[depth] == 0)
            if (depth-- == 0) return 1;
        left[depth]--;
        if (depth == MAX_SUB_LEVELS) return -1;
        depth++;
        if (!rd_u8(r, &len) || !rd_skip(r, len)) return 0; /* the sub-metadata's name */
    }
}

static int skip_geometry_metadata(rd *r)
{
    uint32_t atts, id;
    if (!rd_varint(r, &atts) || atts > (r->n - r->at) / 3) return 0;
    for (uint32_t i = 0; i < atts; i++) {
        int ok = rd_varint(r, &id) ? skip_metadata(r) : 0;
        if (ok != 1) return ok;
    }
    return skip_metadata(r);
}

jd_result jd_draco_peek(const uint8_t *buf, size_t n, const char *name, jd_draco_info *info,
                        jd_error *err)
{
    memset(info, 0, sizeof *info);
    if (n == 0)
        return jd_fail(err, JD_ERR_FORMAT, "%s: file is empty", name);
    if (n < 11 || memcmp(buf, "DRACO", 5) != 0)
        return jd_fail(err, JD_ERR_FORMAT, "%s: not a Draco file (no DRACO magic)", name);
    rd r = {buf, n, 5};
    uint32_t major = 0, minor = 0, type = 0, method = 0, flags_lo = 0, flags_hi = 0;
    rd_u8(&r, &major); rd_u8(&r, &minor); rd_u8(&r, &type); rd_u8(&r, &method);
    rd_u8(&r, &flags_lo); rd_u8(&r, &flags_hi);
    info->major = (int)major;
    info->minor = (int)minor;
    unsigned version = major << 8 | minor;
    if (type == 0)
        return jd_fail(err, JD_ERR_FORMAT, "%s: is a Draco point cloud, not a triangle mesh", name);
    if (type != 1)
        return jd_fail(err, JD_ERR_FORMAT, "%s: unknown Draco geometry type %u", name, type);
    if (major < 1 || version > 0x0202)
        return jd_fail(err, JD_ERR_FORMAT, "%s: unsupported Draco bitstream version %u.%u (libdraco 1.5.5 reads up to 2.2)",
                       name, major, minor);
    if (method > 1)
        return jd_fail(err, JD_ERR_FORMAT, "%s: unknown Draco encoding method %u", name, method);
    info->edgebreaker = method == 1;
    uint32_t flags = flags_lo | flags_hi << 8;
    info->has_metadata = (flags & 0x8000) && version >= 0x0103;
    int meta = info->has_metadata ? skip_geometry_metadata(&r) : 1;
    if (meta < 0)
        return jd_fail(err, JD_ERR_FORMAT, "%s: Draco metadata nested more than %d levels deep (libdraco's limit)",
                       name, MAX_SUB_LEVELS);
    if (!meta) return jd_fail(err, JD_ERR_FORMAT, "%s: corrupt Draco metadata block", name);

    int old = version < 0x0200;   /* fixed-width counts */
    int ok;
    uint32_t v = 0, faces = 0, verts = 0;
    if (!info->edgebreaker) {
        ok = version < 0x0202 ? rd_u32(&r, &faces) && rd_u32(&r, &verts)
                              : rd_varint(&r, &faces) && rd_varint(&r, &verts);
    } else {
        ok = rd_u8(&r, &v); /* traversal decoder type */
        if (ok && version < 0x0202)
            ok = old ? rd_u32(&r, &v) : rd_varint(&r, &v); /* new vertices */
        if (ok)
            ok = old ? rd_u32(&r, &verts) && rd_u32(&r, &faces)
                     : rd_varint(&r, &verts) && rd_varint(&r, &faces);
    }
    if (!ok)
        return jd_fail(err, JD_ERR_FORMAT, "%s: truncated Draco header (%zu bytes)", name, n);
    info->num_faces = faces;
    info->num_vertices = verts;
    return JD_OK;
}
