/* Reads a Draco file's header and declared counts without decoding it, so
 * absurd declarations are refused before libdraco allocates for them. */
#ifndef JD_DRACO_HEADER_H
#define JD_DRACO_HEADER_H

#include <stddef.h>
#include <stdint.h>
#include "jd_result.h"

typedef struct jd_draco_info {
    int major, minor;
    int edgebreaker;      /* else sequential */
    int has_metadata;
    uint32_t num_faces;   /* as declared */
    uint32_t num_vertices; /* as declared (edgebreaker: encoded vertices) */
} jd_draco_info;

/* name is used only in messages. */
jd_result jd_draco_peek(const uint8_t *buf, size_t n, const char *name, jd_draco_info *info,
                        jd_error *err);

#endif
