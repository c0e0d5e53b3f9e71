#include "arena.h"

#include <stdint.h>
#include <string.h>

void jd_arena_init(jd_arena *a, void *mem, size_t size)
{
    a->base = mem;
    a->size = mem ? size : 0;
    a->bottom = a->top = a->peak = 0;
}

static void note_peak(jd_arena *a)
{
    if (a->bottom + a->top > a->peak)
        a->peak = a->bottom + a->top;
}

void *jd_arena_alloc(jd_arena *a, size_t size, size_t align, const char *what, jd_error *err)
{
    if (align == 0 || (align & (align - 1)))
        align = 16;
    uintptr_t start = (uintptr_t)a->base + a->bottom;
    size_t pad = (size_t)((align - (start & (align - 1))) & (align - 1));
    size_t avail = a->size - a->bottom - a->top;
    if (size > avail || pad > avail - size) {
        jd_fail(err, JD_ERR_BUDGET,
                "memory budget exhausted: %s needs %zu bytes, %zu of %zu left (raise --budget-mb)",
                what, size, avail, a->size);
        return NULL;
    }
    a->bottom += pad;
    void *p = a->base + a->bottom;
    a->bottom += size;
    note_peak(a);
    memset(p, 0, size);
    return p;
}

void *jd_arena_alloc_top(jd_arena *a, size_t size, size_t align, const char *what, jd_error *err)
{
    if (align == 0 || (align & (align - 1)))
        align = 16;
    size_t avail = a->size - a->bottom - a->top;
    if (size > avail) {
        jd_fail(err, JD_ERR_BUDGET,
                "memory budget exhausted: %s needs %zu bytes, %zu of %zu left (raise --budget-mb)",
                what, size, avail, a->size);
        return NULL;
    }
    uintptr_t end = (uintptr_t)a->base + a->size - a->top - size;
    size_t pad = (size_t)(end & (align - 1));
    if (pad > avail - size) {
        jd_fail(err, JD_ERR_BUDGET, "memory budget exhausted: %s (alignment)", what);
        return NULL;
    }
    a->top += size + pad;
    note_peak(a);
    void *p = (void *)(end - pad);
    memset(p, 0, size);
    return p;
}

size_t jd_arena_top_mark(const jd_arena *a) { return a->top; }
void jd_arena_top_reset(jd_arena *a, size_t mark) { if (mark <= a->top) a->top = mark; }
size_t jd_arena_mark(const jd_arena *a) { return a->bottom; }
void jd_arena_reset(jd_arena *a, size_t mark) { if (mark <= a->bottom) a->bottom = mark; }
size_t jd_arena_used(const jd_arena *a) { return a->bottom + a->top; }
size_t jd_arena_free_bytes(const jd_arena *a) { return a->size - a->bottom - a->top; }
