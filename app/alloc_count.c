#define _GNU_SOURCE
#include "alloc_count.h"

#include <stddef.h>

/* glibc's own entry points: the interposed malloc below forwards to them. */
extern void *__libc_malloc(size_t);
extern void *__libc_calloc(size_t, size_t);
extern void *__libc_realloc(void *, size_t);
extern void __libc_free(void *);

static volatile int counting;
static volatile unsigned long calls;

void jd_alloc_count_start(void) { calls = 0; counting = 1; }
unsigned long jd_alloc_count_stop(void) { counting = 0; return calls; }

#ifndef JD_NO_MALLOC_INTERPOSE /* sanitizer builds bring their own allocator */
void *malloc(size_t n) { if (counting) __atomic_add_fetch(&calls, 1, __ATOMIC_RELAXED); return __libc_malloc(n); }
void *calloc(size_t a, size_t b) { if (counting) __atomic_add_fetch(&calls, 1, __ATOMIC_RELAXED); return __libc_calloc(a, b); }
void *realloc(void *p, size_t n) { if (counting) __atomic_add_fetch(&calls, 1, __ATOMIC_RELAXED); return __libc_realloc(p, n); }
void free(void *p) { __libc_free(p); }
#endif
