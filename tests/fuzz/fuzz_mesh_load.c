/* libFuzzer: the whole sandboxed load, as `jade render --mesh` runs it:
 * the header check, libdraco in a child process under its limits, and the
 * parent's checks of everything that comes back (records, indices, finite
 * attributes, the winding and normals that follow). A crash of libdraco
 * itself is the child's, reported as an error; any crash here is jade's. */
/* mkstemps is not in C11: ask glibc for it. */
#define _DEFAULT_SOURCE
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "arena.h"
#include "mesh_load.h"

static char path[4096];
static void *memory;
enum { BUDGET = 64 << 20 };

/* The loader takes a path, so each input goes through one file. It is made
 * with mkstemps (no name another user could have placed a link at first)
 * and removed when libFuzzer exits: every CI run used to leave one behind. */
static void remove_input(void)
{
    unlink(path);
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    const char *dir = getenv("TMPDIR");
    if (!dir || !*dir) dir = "/tmp";
    int n = snprintf(path, sizeof path, "%s/jade-fuzz-mesh-XXXXXX.drc", dir);
    if (n < 0 || (size_t)n >= sizeof path) return 1;
    int fd = mkstemps(path, 4);
    if (fd < 0) return 1;
    close(fd);
    atexit(remove_input);
    memory = malloc(BUDGET);
    return memory ? 0 : 1;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f) abort();
    if (size && fwrite(data, 1, size, f) != size) abort();
    fclose(f);
    jd_arena arena;
    jd_arena_init(&arena, memory, BUDGET);
    jd_load_desc d = {.path = path, .timeout_ms = 1000, .allow_32bit_indices = 1};
    jd_mesh mesh;
    jd_error err;
    jd_mesh_load_draco(&d, &arena, &mesh, NULL, &err);
    return 0;
}
