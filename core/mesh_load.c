#include "mesh_load.h"
#include "mesh_format.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "clock.h"
#include "draco_header.h"
#include "draco_shim.h"
#include "gltf_read.h"
#include "mesh_subdivide.h"
#include "obj_material.h"

#if defined(__SANITIZE_ADDRESS__)
#define JD_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define JD_ASAN 1
#endif
#endif

static int write_all(void *user, const void *data, size_t n)
{
    int fd = *(int *)user;
    const char *p = data;
    while (n) {
        ssize_t k = write(fd, p, n);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) return -1;
        p += k;
        n -= (size_t)k;
    }
    return 0;
}

#ifndef JD_ASAN
/* The address space the child already has, so its limit can add a budget on top. */
static size_t current_vm_bytes(void)
{
    char buf[64] = "";
    int fd = open("/proc/self/statm", O_RDONLY | O_CLOEXEC);
    if (fd < 0) return 0;
    ssize_t n = read(fd, buf, sizeof buf - 1);
    close(fd);
    unsigned long pages = 0;
    for (ssize_t i = 0; i < n && buf[i] >= '0' && buf[i] <= '9'; i++) pages = pages * 10 + (unsigned long)(buf[i] - '0');
    return (size_t)pages * (size_t)sysconf(_SC_PAGESIZE);
}
#endif

static void child_main(const jd_load_desc *d, const uint8_t *buf, size_t n, int data_fd,
                       int err_fd)
{
    signal(SIGPIPE, SIG_IGN);
#ifndef JD_ASAN /* a sanitizer's report in the child is wanted where it runs */
    /* What the libraries print as they fail (glibc's abort messages, which
     * it writes to the terminal unless told otherwise; a reader's own
     * chatter) is not jade's one line: the parent says what happened. */
    setenv("LIBC_FATAL_STDERR_", "1", 1);
    int null_fd = open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null_fd >= 0) {
        dup2(null_fd, 2);
        close(null_fd);
    }
#endif
    struct rlimit cpu = {(rlim_t)(d->timeout_ms / 1000 + 2), (rlim_t)(d->timeout_ms / 1000 + 3)};
    setrlimit(RLIMIT_CPU, &cpu);
    /* A wall-clock bound on the child's whole life, streaming and clean-up
     * included: a child blocked (not spinning) escapes RLIMIT_CPU, and the
     * parent waits for it once the mesh has arrived. */
    alarm((unsigned)(d->timeout_ms / 1000) + 2);
#ifndef JD_ASAN /* ASan reserves terabytes of shadow; the count caps still hold */
    size_t vm = current_vm_bytes();
    if (vm) {
        struct rlimit as = {vm + d->decode_memory_bytes, vm + d->decode_memory_bytes};
        setrlimit(RLIMIT_AS, &as);
    }
#endif
    char msg[512] = "";
    jd_mesh_arrays m;
    int rc;
    if (d->format == JD_FORMAT_GLTF) {
#ifdef JD_HAVE_CJSON
        jd_gltf_limits lim = {d->max_vertices, d->max_faces, d->max_file_bytes, (uint32_t)d->max_texture_size};
        rc = jd_gltf_read(buf, n, d->data ? NULL : d->path, &lim, &m, msg, sizeof msg);
#else
        snprintf(msg, sizeof msg, "this jade was built without libcjson, so it cannot read glTF");
        rc = -1;
#endif
    } else {
        rc = jd_draco_read(buf, n, (int)d->format, d->max_vertices, d->max_faces, &m, msg, sizeof msg);
        if (rc == 0 && d->format == JD_FORMAT_OBJ)
            rc = jd_obj_material(buf, n, d->data ? NULL : d->path, (uint32_t)d->max_texture_size, d->max_file_bytes, &m,
                                 msg, sizeof msg);
    }
    if (rc == 0) {
        /* Neither sent nor checked nor given arena memory where nothing
         * needs them (a colour texture does). */
        if (!d->keep_uvs && !m.tex.texels) jd_mesh_arrays_drop_uvs(&m);
        /* Split where coarse, then ordered; as the file has them where the
         * caller keeps the triangles' order (jade convert). */
        m.nf_read = m.nf;
        if (jd_mesh_arrays_simplify(&m, d->simplify_to, msg, sizeof msg) != 0) rc = -1;
        if (rc == 0 && !d->keep_face_order && jd_mesh_arrays_subdivide(&m, d->max_vertices, d->max_faces) != 0) {
            snprintf(msg, sizeof msg, "out of memory splitting its large triangles");
            rc = -1;
        }
        if (rc == 0 && !d->keep_face_order) jd_mesh_arrays_order(&m);
        if (rc == 0 && jd_mesh_arrays_emit(&m, write_all, &data_fd) != 0) {
            snprintf(msg, sizeof msg, "could not hand the decoded mesh back (pipe closed)");
            rc = -1;
        }
    }
    if (rc != 0) write_all(&err_fd, msg, strlen(msg));
    _exit(rc == 0 ? 0 : 1);
}

typedef struct reader {
    int fd;
    double deadline;
    const char *name;
    int timeout_ms;
} reader;

/* Reads exactly n bytes before the deadline; 0 on success. */
static jd_result read_exact(reader *r, void *dst, size_t n, int *eof, jd_error *err)
{
    char *p = dst;
    *eof = 0;
    while (n) {
        int left = (int)(r->deadline - jd_clock_ms());
        if (left <= 0)
            return jd_fail(err, JD_ERR_TIMEOUT, "%s: decoding took longer than %d ms; refused",
                           r->name, r->timeout_ms);
        struct pollfd pfd = {r->fd, POLLIN, 0};
        int k = poll(&pfd, 1, left);
        if (k < 0 && errno == EINTR) continue;
        if (k == 0) continue;
        ssize_t got = read(r->fd, p, n);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) { *eof = 1; return JD_ERR_FORMAT; }
        p += got;
        n -= (size_t)got;
    }
    return JD_OK;
}

/* The caller's bytes, into the arena where the file would have gone. */
static jd_result copy_data(const jd_load_desc *d, jd_arena *a, uint8_t **buf, size_t *n, jd_error *err)
{
    if (d->size > d->max_file_bytes)
        return jd_fail(err, JD_ERR_LIMIT, "%s: %zu bytes, over the limit of %zu", d->path, d->size, d->max_file_bytes);
    uint8_t *p = jd_arena_alloc_top(a, d->size ? d->size : 1, 16, "the mesh data", err);
    if (!p) return JD_ERR_BUDGET;
    memcpy(p, d->data, d->size);
    *buf = p;
    *n = d->size;
    return JD_OK;
}

static jd_result read_file(const jd_load_desc *d, jd_arena *a, uint8_t **buf, size_t *n,
                           jd_error *err)
{
    /* Non-blocking, so a FIFO with no writer is refused below instead of
     * hanging the open. */
    int fd = open(d->path, O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0)
        return jd_fail(err, JD_ERR_IO, "%s: cannot open: %s", d->path, strerror(errno));
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        close(fd);
        return jd_fail(err, JD_ERR_IO, "%s: not a regular file", d->path);
    }
    if ((size_t)st.st_size > d->max_file_bytes) {
        close(fd);
        return jd_fail(err, JD_ERR_LIMIT, "%s: file is %lld bytes, over the limit of %zu",
                       d->path, (long long)st.st_size, d->max_file_bytes);
    }
    size_t size = (size_t)st.st_size;
    uint8_t *p = jd_arena_alloc_top(a, size ? size : 1, 16, "the mesh file", err);
    if (!p) { close(fd); return JD_ERR_BUDGET; }
    size_t got = 0;
    while (got < size) {
        ssize_t k = read(fd, p + got, size - got);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) {
            close(fd);
            return jd_fail(err, JD_ERR_IO, "%s: read failed after %zu bytes", d->path, got);
        }
        got += (size_t)k;
    }
    close(fd);
    *buf = p;
    *n = size;
    return JD_OK;
}

static jd_result reap(pid_t pid, int kill_it, int *status)
{
    if (kill_it) kill(pid, SIGKILL);
    while (waitpid(pid, status, 0) < 0)
        if (errno != EINTR) return JD_ERR_CRASH;
    return JD_OK;
}

static jd_result child_failure(const jd_load_desc *d, int status, int err_fd, jd_error *err)
{
    char msg[512] = "";
    ssize_t k = read(err_fd, msg, sizeof msg - 1);
    if (k > 0) msg[k] = 0;
    if (WIFSIGNALED(status)) {
        int sig = WTERMSIG(status);
        if (sig == SIGXCPU || sig == SIGALRM)
            return jd_fail(err, JD_ERR_TIMEOUT, "%s: decoding used more than its CPU time; refused", d->path);
        return jd_fail(err, JD_ERR_CRASH, "%s: the %s decoder crashed (signal %d, %s); the file is corrupt",
                       d->path, jd_mesh_format_name(d->format), sig, strsignal(sig));
    }
    if (strstr(msg, "out of memory"))
        return jd_fail(err, JD_ERR_LIMIT, "%s: decoding needed more than %zu MiB; refused", d->path,
                       d->decode_memory_bytes >> 20);
    if (msg[0]) return jd_fail(err, JD_ERR_FORMAT, "%s: %s", d->path, msg);
    return jd_fail(err, JD_ERR_FORMAT, "%s: the %s decoder failed (exit %d)", d->path, jd_mesh_format_name(d->format),
                   WIFEXITED(status) ? WEXITSTATUS(status) : -1);
}

/* The decoder's medium is not trusted either: strings ended and printable,
 * coefficients finite and in the command line's ranges, or dropped. */
static void take_medium(jd_file_medium *m)
{
    m->source[sizeof m->source - 1] = 0;
    m->ignored[sizeof m->ignored - 1] = 0;
    for (char *p = m->source; *p; p++)
        if (*p < 32 || *p > 126) *p = '?';
    for (char *p = m->ignored; *p; p++)
        if (*p < 32 || *p > 126) *p = '?';
    if (m->flags & JD_MEDIUM_SIGMA)
        for (int c = 0; c < 3; c++)
            if (!(m->sigma_s[c] >= 0.0f && m->sigma_s[c] <= 1000.0f && m->sigma_a[c] >= 0.0f &&
                  m->sigma_a[c] <= 1000.0f))
                m->flags &= ~(uint32_t)JD_MEDIUM_SIGMA;
    if (!(m->mm_per_unit > 0.0f && m->mm_per_unit <= 1e9f)) m->mm_per_unit = 0.0f;
    if ((m->flags & JD_MEDIUM_ETA) && !(m->eta >= 1.0f && m->eta <= 3.0f)) m->flags &= ~(uint32_t)JD_MEDIUM_ETA;
    m->flags &= JD_MEDIUM_SIGMA | JD_MEDIUM_ETA | JD_MEDIUM_NOTE;
}

/* The decode's deadline where the caller gives none: 1.5 s, and 1 s more
 * per MiB of the file and 5 ms per thousand triangles its header declares.
 * A flat 1.5 s refused a 35 MB scan of 980,000 triangles that decodes in
 * 2.4 s here and 8-16 s under qemu-aarch64, where a board's slower cores
 * stand; the bound stays finite (about 85 s at the 64 MiB and 4,000,000
 * faces of the defaults' limits), which is what it is for: a decoder that
 * loops or stalls on a hostile file is stopped. */
int jd_load_default_timeout_ms(size_t file_bytes, uint32_t declared_faces)
{
    double ms = 1500.0 + 1000.0 * (double)file_bytes / (1024.0 * 1024.0) + 0.005 * (double)declared_faces;
    return ms < 600000.0 ? (int)ms : 600000;
}

jd_result jd_mesh_load_draco(const jd_load_desc *desc, jd_arena *a, jd_mesh *out,
                             jd_load_stats *stats, jd_error *err)
{
    jd_load_desc d = *desc;
    if (!d.path && !d.data) return jd_fail(err, JD_ERR_ARG, "no mesh path or data given");
    if (!d.path) d.path = "the mesh in memory";
    if (!d.max_file_bytes) d.max_file_bytes = 64u << 20;
    if (!d.max_vertices) d.max_vertices = 4000000;
    if (!d.max_faces) d.max_faces = 4000000;
    int default_memory = !d.decode_memory_bytes;
    if (default_memory) d.decode_memory_bytes = (size_t)192 << 20;
    if (d.max_texture_size <= 0) d.max_texture_size = JD_TEXTURE_MEDIUMP_SIDE;
    for (int p = 1; p <= d.max_texture_size; p <<= 1)
        if (p * 2 > d.max_texture_size) { d.max_texture_size = p; break; } /* a power of two */
    jd_load_stats st = {0};
    memset(out, 0, sizeof *out);

    size_t top = jd_arena_top_mark(a), bottom = jd_arena_mark(a);
    uint8_t *buf = NULL;
    size_t n = 0;
    jd_result r = d.data ? copy_data(&d, a, &buf, &n, err) : read_file(&d, a, &buf, &n, err);
    if (r) return r;
    st.file_bytes = n;

    /* The format by content; the sizes its header declares are checked
     * before any decoder sees the file. */
    jd_mesh_format format;
    uint32_t declared_faces, declared_vertices;
    r = jd_mesh_peek(buf, n, d.path, &format, &declared_faces, &declared_vertices, err);
    if (r) goto fail;
    st.declared_faces = declared_faces;
    st.format = format;
    if (declared_faces > d.max_faces || (format != JD_FORMAT_STL && declared_vertices > d.max_vertices)) {
        r = jd_fail(err, JD_ERR_LIMIT, "%s: declares %u faces and %u vertices, over the limit of %u / %u; refused",
                    d.path, declared_faces, declared_vertices, d.max_faces, d.max_vertices);
        goto fail;
    }
    d.format = format;
    if (d.timeout_ms <= 0) d.timeout_ms = jd_load_default_timeout_ms(n, declared_faces);
    /* Simplifying takes meshoptimizer's scratch beside the mesh (about 130
     * bytes a triangle: its quadrics, edges and collapses): the default's
     * room grows by that where the file may hold more than asked for (an
     * OBJ declares no count: a triangle takes at least 24 of its bytes, a
     * vertex line and a face line). */
    size_t faces_at_most = declared_faces > n / 24 ? declared_faces : n / 24;
    if (default_memory && d.simplify_to && faces_at_most > d.simplify_to)
        d.decode_memory_bytes += (size_t)160 * faces_at_most;

    int data_pipe[2], err_pipe[2];
    if (pipe2(data_pipe, O_CLOEXEC) != 0) { r = jd_fail(err, JD_ERR_IO, "pipe: %s", strerror(errno)); goto fail; }
    if (pipe2(err_pipe, O_CLOEXEC) != 0) {
        close(data_pipe[0]); close(data_pipe[1]);
        r = jd_fail(err, JD_ERR_IO, "pipe: %s", strerror(errno));
        goto fail;
    }
    double t0 = jd_clock_ms();
    pid_t pid = fork();
    if (pid < 0) {
        close(data_pipe[0]); close(data_pipe[1]); close(err_pipe[0]); close(err_pipe[1]);
        r = jd_fail(err, JD_ERR_IO, "fork: %s", strerror(errno));
        goto fail;
    }
    if (pid == 0) {
        close(data_pipe[0]);
        close(err_pipe[0]);
        child_main(&d, buf, n, data_pipe[1], err_pipe[1]);
    }
    close(data_pipe[1]);
    close(err_pipe[1]);

    reader rd = {data_pipe[0], t0 + d.timeout_ms, d.path, d.timeout_ms};
    jd_draco_record_header h;
    int eof = 0, status = 0;
    r = read_exact(&rd, &h, sizeof h, &eof, err);
    if (r == JD_OK && (h.magic != JD_DRACO_RECORD_MAGIC || h.num_vertices == 0 ||
                       h.num_vertices > d.max_vertices || h.num_faces > d.max_faces ||
                       h.num_faces == 0)) {
        r = jd_fail(err, JD_ERR_FORMAT, "%s: decoder returned an implausible mesh header", d.path);
    }
    if (r == JD_OK) st.declared_faces = h.faces_read;
    uint32_t *idx32 = NULL;
    if (r == JD_OK) {
        out->num_vertices = h.num_vertices;
        size_t nv = h.num_vertices;
        out->positions = jd_arena_alloc(a, sizeof(float) * 3 * nv, 16, "mesh positions", err);
        out->normals = jd_arena_alloc(a, sizeof(float) * 3 * nv, 16, "mesh normals", err);
        if (h.flags & JD_DRACO_HAS_UVS)
            out->uvs = jd_arena_alloc(a, sizeof(float) * 2 * nv, 16, "mesh uvs", err);
        idx32 = jd_arena_alloc_top(a, sizeof(uint32_t) * 3 * (size_t)h.num_faces, 16, "mesh indices (scratch)", err);
        if (!out->positions || !out->normals || !idx32 || ((h.flags & JD_DRACO_HAS_UVS) && !out->uvs))
            r = JD_ERR_BUDGET;
    }
    if (r == JD_OK) r = read_exact(&rd, out->positions, sizeof(float) * 3 * h.num_vertices, &eof, err);
    if (r == JD_OK && (h.flags & JD_DRACO_HAS_NORMALS))
        r = read_exact(&rd, out->normals, sizeof(float) * 3 * h.num_vertices, &eof, err);
    if (r == JD_OK && (h.flags & JD_DRACO_HAS_UVS))
        r = read_exact(&rd, out->uvs, sizeof(float) * 2 * h.num_vertices, &eof, err);
    if (r == JD_OK) r = read_exact(&rd, idx32, sizeof(uint32_t) * 3 * (size_t)h.num_faces, &eof, err);
    if (r == JD_OK && (h.flags & JD_DRACO_HAS_MATERIAL)) {
        r = read_exact(&rd, st.material, sizeof st.material, &eof, err);
        st.material[sizeof st.material - 1] = 0;
    }
    if (r == JD_OK && (h.flags & JD_DRACO_HAS_MEDIUM)) {
        r = read_exact(&rd, &st.medium, sizeof st.medium, &eof, err);
        if (r == JD_OK) take_medium(&st.medium);
    }
    if (r == JD_OK && (h.flags & JD_DRACO_HAS_COLORS)) {
        out->colors = jd_arena_alloc(a, 4 * (size_t)h.num_vertices, 16, "mesh colours", err);
        r = out->colors ? read_exact(&rd, out->colors, 4 * (size_t)h.num_vertices, &eof, err) : JD_ERR_BUDGET;
    }
    if (r == JD_OK && (h.flags & JD_DRACO_HAS_TEXTURE)) {
        uint32_t wh[2] = {0, 0};
        r = read_exact(&rd, wh, sizeof wh, &eof, err);
        /* Powers of two within the asked size, and only with coordinates
         * and colours to use them. */
        if (r == JD_OK && (!wh[0] || !wh[1] || (wh[0] & (wh[0] - 1)) || (wh[1] & (wh[1] - 1)) ||
                           wh[0] > (uint32_t)d.max_texture_size || wh[1] > (uint32_t)d.max_texture_size || !out->uvs ||
                           !out->colors))
            r = jd_fail(err, JD_ERR_FORMAT, "%s: decoder returned an implausible texture (%u x %u)", d.path, wh[0], wh[1]);
        if (r == JD_OK) {
            out->texels = jd_arena_alloc(a, (size_t)wh[0] * wh[1] * 4, 16, "the colour texture", err);
            r = out->texels ? read_exact(&rd, out->texels, (size_t)wh[0] * wh[1] * 4, &eof, err) : JD_ERR_BUDGET;
            out->texture_w = wh[0];
            out->texture_h = wh[1];
        }
    }
    st.decode_ms = jd_clock_ms() - t0;

    reap(pid, r != JD_OK && !eof, &status);
    if (eof || (r == JD_OK && !(WIFEXITED(status) && WEXITSTATUS(status) == 0)))
        r = child_failure(&d, status, err_pipe[0], err);
    close(data_pipe[0]);
    close(err_pipe[0]);
    if (r) goto fail;

    /* Nothing from the decoder is trusted: check before narrowing indices. */
    for (uint32_t i = 0; i < 3 * h.num_faces; i++)
        if (idx32[i] >= h.num_vertices) {
            r = jd_fail(err, JD_ERR_FORMAT,
                        "%s: face %u refers to vertex %u but the mesh has %u vertices; refused",
                        d.path, i / 3, idx32[i], h.num_vertices);
            goto fail;
        }
    /* A mesh with no area (every position equal, a glTF node scaled to
     * zero, an accessor with no bufferView) would draw nothing and exit 0. */
    double most = 0.0;
    for (uint32_t f = 0; f < h.num_faces && !(most > 0.0); f++) {
        const float *p0 = out->positions + 3 * (size_t)idx32[3 * f], *p1 = out->positions + 3 * (size_t)idx32[3 * f + 1],
                    *p2 = out->positions + 3 * (size_t)idx32[3 * f + 2];
        double e1[3], e2[3];
        for (int c = 0; c < 3; c++) {
            e1[c] = (double)p1[c] - (double)p0[c];
            e2[c] = (double)p2[c] - (double)p0[c];
        }
        double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2], cz = e1[0] * e2[1] - e1[1] * e2[0];
        most = cx * cx + cy * cy + cz * cz;
    }
    if (most == 0.0) { /* NaN: the finite check below says so */
        r = jd_fail(err, JD_ERR_FORMAT,
                    "%s: the mesh has no area: %s %u triangle%s degenerate (every position equal, a node scaled "
                    "to zero, or positions with no data); refused",
                    d.path, h.num_faces == 1 ? "its" : "all its", h.num_faces, h.num_faces == 1 ? " is" : "s are");
        goto fail;
    }
    r = jd_mesh_set_indices(out, idx32, 3 * h.num_faces, d.allow_32bit_indices, a, err);
    if (r) {
        if (r == JD_ERR_UNSUPPORTED) {
            jd_error inner = *err;
            jd_fail(err, r, "%s: %s", d.path, inner.msg);
        }
        goto fail;
    }
    r = jd_mesh_validate(out, d.path, err);
    if (!r && (h.flags & JD_DRACO_HAS_NORMALS))
        r = jd_mesh_check_finite(out->normals, out->num_vertices, 3, "normal", d.path, err);
    if (!r && out->uvs) r = jd_mesh_check_finite(out->uvs, out->num_vertices, 2, "texture coordinate", d.path, err);
    if (r) goto fail;
    jd_mesh_compute_bounds(out);
    if (out->colors) {
        jd_mesh_albedo_prepare(out);
        st.coloured = 1;
        memcpy(st.albedo_mean, out->albedo_mean, sizeof st.albedo_mean);
        st.texture_w = out->texture_w;
        st.texture_h = out->texture_h;
    }
    /* Culling and the light map take the winding for the outside; shading
     * takes the normals: both are made to agree with the enclosed volume. */
    jd_mesh_orient_outward(out);
    if (h.flags & JD_DRACO_HAS_NORMALS) {
        jd_mesh_fix_normals(out);
        jd_mesh_normals_follow_winding(out);
    } else {
        jd_mesh_compute_normals(out);
        out->normals_computed = 1;
    }
    jd_arena_top_reset(a, top);
    if (stats) *stats = st;
    return JD_OK;

fail:
    if (r == JD_ERR_BUDGET && err && !strstr(err->msg, d.path)) {
        jd_error inner = *err;
        jd_fail(err, r, "%s: %s", d.path, inner.msg);
    }
    jd_arena_top_reset(a, top);
    jd_arena_reset(a, bottom);
    memset(out, 0, sizeof *out);
    if (stats) *stats = st;
    return r;
}
