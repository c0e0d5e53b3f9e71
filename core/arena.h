/* The one memory budget of the core.
 *
 * A double-ended stack over caller memory: long-lived data grows from the
 * bottom, short-lived scratch (a file being parsed) from the top, so scratch
 * can be released without fragmenting what stays. Nothing here calls the heap.
 */
#ifndef JD_ARENA_H
#define JD_ARENA_H

#include <stddef.h>
#include "jd_result.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct jd_arena {
    unsigned char *base;
    size_t size;
    size_t bottom; /* bytes used from the start */
    size_t top;    /* bytes used from the end */
    size_t peak;   /* largest bottom + top seen */
} jd_arena;

void jd_arena_init(jd_arena *a, void *mem, size_t size);

/* Zeroed, aligned (align a power of two) block, or NULL and a JD_ERR_BUDGET
 * message naming what was being allocated. */
void *jd_arena_alloc(jd_arena *a, size_t size, size_t align, const char *what, jd_error *err);
void *jd_arena_alloc_top(jd_arena *a, size_t size, size_t align, const char *what, jd_error *err);

/* Scratch marks: take one, allocate, then return to it. */
size_t jd_arena_top_mark(const jd_arena *a);
void jd_arena_top_reset(jd_arena *a, size_t mark);
size_t jd_arena_mark(const jd_arena *a);
void jd_arena_reset(jd_arena *a, size_t mark);

size_t jd_arena_used(const jd_arena *a);
size_t jd_arena_free_bytes(const jd_arena *a);

#ifdef __cplusplus
}
#endif

#endif
