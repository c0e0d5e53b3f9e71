/* jade convert IN OUT.drc: any mesh jade reads (glTF, OBJ, PLY, STL, Draco)
 * as a Draco file, for devices that should not parse text formats. The
 * input is read as `render --mesh` reads it (sandboxed, bounded, checked,
 * the winding made outward); the file's own normals and texture coordinates
 * are kept, computed normals are left for the loader to compute again. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "draco_shim.h"
#include "image_out.h"
#include "mesh_format.h"
#include "options.h"

typedef struct grow_buf {
    unsigned char *p;
    size_t n, cap;
} grow_buf;

static int collect(void *user, const void *data, size_t n)
{
    grow_buf *b = user;
    if (b->n + n > b->cap) {
        size_t cap = (b->n + n) * 2;
        unsigned char *p = realloc(b->p, cap);
        if (!p) return -1;
        b->p = p;
        b->cap = cap;
    }
    memcpy(b->p + b->n, data, n);
    b->n += n;
    return 0;
}

static int ends_with_drc(const char *path)
{
    size_t n = strlen(path);
    return n > 4 && (!strcmp(path + n - 4, ".drc") || !strcmp(path + n - 4, ".DRC"));
}

int jd_cmd_convert(int argc, char **argv)
{
    jd_options o;
    jd_options_defaults(&o);
    int rc = jd_options_command(&o, JD_OPT_CONVERT, "convert",
                                "Reads a mesh as render --mesh does (Draco, glTF/GLB, OBJ, PLY or STL, by content) and\n"
                                "writes it as a Draco file (positions at 14 bits, normals at 10, texture coordinates at 12).",
                                argc, argv);
    if (rc >= 0) return rc;
    if (o.num_positional != 2) {
        fprintf(stderr, "jade convert: expected an input mesh and an output OUT.drc, got %d name(s)\n", o.num_positional);
        return 2;
    }
    const char *in = o.positional[0], *out = o.positional[1];
    jd_error err = {0};
    if (!ends_with_drc(out)) {
        fprintf(stderr, "jade convert: %s: the output is a Draco file and must be named .drc\n", out);
        return 2;
    }
    jd_output_protect(in);
    if (jd_output_check(out, &err)) {
        fprintf(stderr, "jade convert: %s\n", err.msg);
        return 1;
    }
    o.mesh = in;
    o.load.keep_face_order = 1; /* Draco's edgebreaker orders the faces its own way */
    o.load.keep_uvs = 1;        /* a conversion keeps what the renderer would not use */
    jd_session s;
    if (!jd_session_open_mesh(&s, &o, "convert")) {
        jd_session_close(&s);
        return 1;
    }
    const jd_mesh *m = &s.mesh;
    jd_mesh_arrays a = {.nv = m->num_vertices, .nf = m->num_indices / 3, .pos = m->positions,
                        .nrm = m->normals_computed ? NULL : m->normals, .uv = m->uvs};
    a.idx = malloc(sizeof(uint32_t) * (m->num_indices ? m->num_indices : 1));
    grow_buf b = {0};
    char msg[256] = "";
    rc = 1;
    if (!a.idx) {
        fprintf(stderr, "jade convert: out of memory for %u indices\n", m->num_indices);
    } else {
        for (uint32_t i = 0; i < m->num_indices; i++) a.idx[i] = jd_mesh_index(m, i);
        if (jd_draco_encode(&a, collect, &b, msg, sizeof msg))
            fprintf(stderr, "jade convert: %s: %s\n", in, msg);
        else if (jd_bytes_write(out, "the Draco file", b.p, b.n, &err))
            fprintf(stderr, "jade convert: %s\n", err.msg);
        else {
            printf("wrote %s (%zu bytes: %u vertices, %u triangles%s%s) from %s %s (%zu bytes)\n", out, b.n, a.nv, a.nf,
                   a.nrm ? ", normals" : "", a.uv ? ", texture coordinates" : "",
                   jd_mesh_format_name((jd_mesh_format)s.load.format), in, s.load.file_bytes);
            rc = 0;
        }
    }
    free(a.idx);
    free(b.p);
    jd_session_close(&s);
    return rc;
}
