/* Preloaded into the kiosk by tools/kms-test.sh's guest (LD_PRELOAD), to
 * make vkms look like the drivers jade must fall back on: JADE_REFUSE=cap
 * refuses atomic modesetting itself (DRM_CLIENT_CAP_ATOMIC, as a driver
 * without it answers), JADE_REFUSE=modeset refuses atomic commits that set
 * the mode (a driver whose atomic path rejects what jade asks). Everything
 * else goes to libdrm. Built as a shared object; Linux only. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define CAP_ATOMIC 3             /* DRM_CLIENT_CAP_ATOMIC */
#define ATOMIC_TEST_ONLY 0x0100  /* DRM_MODE_ATOMIC_TEST_ONLY */
#define ATOMIC_ALLOW_MODESET 0x0400

static int refuses(const char *what)
{
    const char *r = getenv("JADE_REFUSE");
    return r && !strcmp(r, what);
}

int drmSetClientCap(int fd, uint64_t capability, uint64_t value)
{
    if (capability == CAP_ATOMIC && value && refuses("cap")) {
        errno = EOPNOTSUPP;
        return -1;
    }
    int (*real)(int, uint64_t, uint64_t) = (int (*)(int, uint64_t, uint64_t))dlsym(RTLD_NEXT, "drmSetClientCap");
    return real ? real(fd, capability, value) : -1;
}

int drmModeAtomicCommit(int fd, void *req, uint32_t flags, void *user_data)
{
    if ((flags & ATOMIC_ALLOW_MODESET) && !(flags & ATOMIC_TEST_ONLY) && refuses("modeset")) {
        errno = EINVAL;
        return -1;
    }
    int (*real)(int, void *, uint32_t, void *) =
        (int (*)(int, void *, uint32_t, void *))dlsym(RTLD_NEXT, "drmModeAtomicCommit");
    return real ? real(fd, req, flags, user_data) : -1;
}
