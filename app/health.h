/* A running jade's vital signs for operators and soak tests: resident
 * memory, open file descriptors and the GL names a new object would get.
 * Read straight from /proc with stack buffers: sampling allocates nothing,
 * so it may run inside a frame loop that must not touch the heap. */
#ifndef JD_HEALTH_H
#define JD_HEALTH_H
#include <stdio.h>

#include "gl_caps.h"

typedef struct jd_health {
    double rss_mib; /* resident set, from /proc/self/statm */
    int fds;        /* entries in /proc/self/fd */
    /* GL names taken since the first sample by anything but the probe
     * itself (Mesa does not reuse a deleted name, so each probe moves the
     * next name on by one): 0 while no GL object is created. */
    unsigned gl_new[4];
} jd_health;

void jd_health_sample(jd_health *h);
/* ", rss 117.3 MiB, fds 9, new GL objects 0/0/0/0" */
void jd_health_print(FILE *f, const jd_health *h);

#endif
