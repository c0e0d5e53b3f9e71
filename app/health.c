#include "health.h"

#include <dirent.h>
#include <fcntl.h>
#include <stdlib.h>
#include <sys/syscall.h>
#include <unistd.h>

static double rss_mib(void)
{
    char buf[128];
    int fd = open("/proc/self/statm", O_RDONLY | O_CLOEXEC);
    if (fd < 0) return -1;
    ssize_t n = read(fd, buf, sizeof buf - 1);
    close(fd);
    if (n <= 0) return -1;
    buf[n] = 0;
    char *p = buf;
    strtoul(p, &p, 10); /* total size; the resident pages follow */
    unsigned long pages = strtoul(p, NULL, 10);
    return (double)pages * (double)sysconf(_SC_PAGESIZE) / (1024.0 * 1024.0);
}

/* getdents64 into a stack buffer: opendir would allocate. */
static int count_fds(void)
{
    int fd = open("/proc/self/fd", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return -1;
    char buf[4096];
    int count = 0;
    for (;;) {
        long n = syscall(SYS_getdents64, fd, buf, sizeof buf);
        if (n <= 0) break;
        for (long at = 0; at < n;) {
            unsigned short reclen = *(unsigned short *)(buf + at + 16); /* d_reclen of linux_dirent64 */
            const char *name = buf + at + 19;
            if (name[0] != '.') count++;
            at += reclen;
        }
    }
    close(fd);
    return count - 1; /* not the descriptor that reads the folder */
}

void jd_health_sample(jd_health *h)
{
    static jd_gl_names first;
    static unsigned probes;
    h->rss_mib = rss_mib();
    h->fds = count_fds();
    jd_gl_names now;
    jd_gl_probe_names(&now);
    if (!probes) first = now;
    unsigned a[4] = {now.texture, now.buffer, now.framebuffer, now.renderbuffer};
    unsigned b[4] = {first.texture, first.buffer, first.framebuffer, first.renderbuffer};
    for (int k = 0; k < 4; k++) h->gl_new[k] = a[k] > b[k] ? a[k] - b[k] : 0;
    probes++;
}

void jd_health_print(FILE *f, const jd_health *h)
{
    fprintf(f, ", rss %.1f MiB, fds %d, new GL objects %u/%u/%u/%u", h->rss_mib, h->fds, h->gl_new[0],
            h->gl_new[1], h->gl_new[2], h->gl_new[3]);
}
