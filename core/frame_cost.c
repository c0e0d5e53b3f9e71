#include "frame_cost.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

extern const char jd_device_table_text[]; /* generated from tests/device-shaders.expected */

const char *jd_frame_cost_table(void) { return jd_device_table_text; }

/* A program's row of the compiler table. */
typedef struct table_row {
    double vs, fs;     /* instructions as the compiler counts them */
    double vc, fc;     /* cost per vertex and fragment as built */
    double f1, f2;     /* fragment cost with the dynamic loops at 1 and 2 trips */
} table_row;

static double number(const char *s)
{
    if (!s || !strcmp(s, "-")) return -1.0;
    char *end;
    double v = strtod(s, &end);
    return end == s ? -1.0 : v;
}

/* Splits one line into whitespace-separated words, in place of a copy. */
static int split(const char *line, size_t len, char words[][100], int max)
{
    int n = 0;
    size_t i = 0;
    while (i < len && n < max) {
        while (i < len && (line[i] == ' ' || line[i] == '\t')) i++;
        size_t start = i;
        while (i < len && line[i] != ' ' && line[i] != '\t') i++;
        if (i == start) break;
        size_t w = i - start < 99 ? i - start : 99;
        memcpy(words[n], line + start, w);
        words[n][w] = 0;
        n++;
    }
    return n;
}

/* The compiler's next row from *at on: its words w (n of them) and the
 * program's name without its number. 0 at the table's end. */
static int next_row(const char **at, const char *compiler, char w[][100], int *n, const char **name)
{
    while (**at) {
        const char *p = *at, *nl = strchr(p, '\n');
        size_t len = nl ? (size_t)(nl - p) : strlen(p);
        *at = p + len + (nl ? 1 : 0);
        *n = split(p, len, w, 24);
        if (*n < 6 || strcmp(w[0], compiler) || strcmp(w[2], "vs") || strcmp(w[4], "fs")) continue;
        const char *c = strchr(w[1], ':');
        *name = c ? c + 1 : w[1];
        return 1;
    }
    return 0;
}

int jd_frame_cost_largest_program(const char *table, const char *compiler)
{
    char w[24][100];
    const char *name;
    int n;
    double most = 0;
    for (const char *at = table ? table : jd_device_table_text; next_row(&at, compiler, w, &n, &name);)
        most = fmax(most, fmax(number(w[3]), number(w[5])));
    return (int)most;
}

static int find_row(const char *table, const char *compiler, const char *program, table_row *row)
{
    char w[24][100];
    const char *name;
    int n;
    for (const char *at = table; next_row(&at, compiler, w, &n, &name);) {
        if (strcmp(name, program)) continue;
        row->vs = number(w[3]);
        row->fs = number(w[5]);
        row->vc = row->vs;
        row->fc = row->f1 = row->f2 = row->fs;
        for (int i = 0; i + 1 < n; i++) {
            if (!strcmp(w[i], "vc")) row->vc = number(w[i + 1]);
            if (!strcmp(w[i], "fc")) row->fc = number(w[i + 1]);
            if (!strcmp(w[i], "f1")) row->f1 = number(w[i + 1]);
            if (!strcmp(w[i], "f2")) row->f2 = number(w[i + 1]);
        }
        if (row->f1 < 0 || row->f2 < 0) row->f1 = row->f2 = row->fc;
        return 1;
    }
    return 0;
}

/* The vertex cost of vertex shader `vs` in any row of the compiler's. */
static double vertex_cost_of(const char *table, const char *compiler, const char *vs)
{
    char w[24][100];
    const char *name;
    int n;
    size_t len = strlen(vs);
    for (const char *at = table; next_row(&at, compiler, w, &n, &name);) {
        if (strncmp(name, vs, len) || name[len] != '+') continue;
        for (int i = 0; i + 1 < n; i++)
            if (!strcmp(w[i], "vc") && number(w[i + 1]) >= 0) return number(w[i + 1]);
    }
    return -1.0;
}

/* The fragment cost at t trips of the program's dynamic loops: as built it
 * runs the loop once (fc: outside + body + the loop's own overhead); built
 * with one and two constant trips (loop gone) it costs f1 = outside + body
 * and f2 = outside + 2 body. Each trip more: body + overhead. */
static double fragment_cost(const table_row *r, double trips)
{
    if (trips <= 1.0) return r->fc;
    double body = fmax(r->f2 - r->f1, 0.0), overhead = fmax(r->fc - r->f1, 0.0);
    return r->fc + (trips - 1.0) * (body + overhead);
}

jd_result jd_frame_cost_estimate(const jd_board *b, const jd_frame_count *c, const char *table, jd_estimate *out,
                                 jd_error *err)
{
    if (!table) table = jd_device_table_text;
    memset(out, 0, sizeof *out);
    out->board = b;
    const double hz = b->clock_mhz * 1e6;
    double pixel_ms = 0.0, vertex_ms = 0.0, shared_ms = 0.0;
    for (int i = 0; i < c->num_passes && i < JD_COUNT_PASSES; i++) {
        const jd_pass_count *p = &c->pass[i];
        jd_pass_estimate *e = &out->pass[i];
        table_row row;
        if (!find_row(table, b->compiler, p->program, &row))
            return jd_fail(err, JD_ERR_ARG,
                           "the compiler table has no row for %s on %s (pass %s): run tools/device-shaders.sh --update",
                           p->program, b->compiler, p->pass);
        if (row.vc < 0) { /* a driver that reused a compiled vertex shader printed no count: another row's */
            char vs[64];
            const char *plus = strchr(p->program, '+');
            size_t n = plus ? (size_t)(plus - p->program) : 0;
            if (n && n < sizeof vs - 1) {
                memcpy(vs, p->program, n);
                vs[n] = 0;
                row.vc = row.vs = vertex_cost_of(table, b->compiler, vs);
            }
        }
        if (row.vc < 0 || row.fc < 0)
            return jd_fail(err, JD_ERR_ARG, "the compiler table's row for %s on %s has no instruction count",
                           p->program, b->compiler);
        e->vs_instructions = row.vs;
        e->fs_instructions = row.fs;
        e->vs_cost = row.vc;
        e->fs_cost = fragment_cost(&row, p->trips);
        /* cost units / (units per clock x items per unit) = clocks */
        e->vertex_ms = p->vertices * e->vs_cost / (b->vertex_rate * b->vertex_lanes) / hz * 1e3;
        e->triangle_ms = p->triangles * b->triangle_clocks / hz * 1e3;
        e->fragment_ms = p->fragments * e->fs_cost / (b->fragment_rate * b->fragment_lanes) / hz * 1e3;
        e->fill_ms = p->fragments / b->fill_rate / hz * 1e3;
        e->memory_ms = (p->bytes_written + p->bytes_read) / (b->dram_gbs * 1e9) * 1e3;
        double pixels = fmax(fmax(e->fragment_ms, e->fill_ms), e->memory_ms);
        double vertices = fmax(e->vertex_ms, e->triangle_ms);
        if (b->units == JD_UNITS_SHARED) {
            /* One pool of cores: vertex and fragment programs take turns;
             * fill and memory run beside them. */
            e->ms = fmax(fmax(e->vertex_ms + e->fragment_ms, e->fill_ms), fmax(e->memory_ms, e->triangle_ms));
            shared_ms += e->ms;
        } else {
            e->ms = fmax(pixels, vertices);
        }
        pixel_ms += pixels;
        vertex_ms += vertices;
    }
    out->num_passes = c->num_passes < JD_COUNT_PASSES ? c->num_passes : JD_COUNT_PASSES;
    out->vertex_ms = vertex_ms;
    out->fragment_ms = pixel_ms;
    /* Utgard's vertex processor works on the next pass (and frame) while
     * the pixel processors shade this one: the frame takes the longer. */
    out->frame_ms = b->units == JD_UNITS_SHARED ? shared_ms : fmax(pixel_ms, vertex_ms);
    return JD_OK;
}
