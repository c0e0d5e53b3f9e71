/* Preloaded into the kiosk by tools/kms-test.sh's guest (LD_PRELOAD), to
 * make vkms look like the drivers jade must fall back on: JADE_REFUSE=cap
 * refuses atomic modesetting itself (DRM_CLIENT_CAP_ATOMIC, as a driver
 * without it answers), JADE_REFUSE=modeset refuses atomic commits that set
 * the mode (a driver whose atomic path rejects what jade asks).
 * JADE_REFUSE=fence makes EGL offer native fences (EGL_ANDROID_native_fence_sync,
 * which the guest's software EGL lacks) whose fds are not fences at all
 * (/dev/null), so the kernel refuses the flips that carry them as the
 * plane's IN_FENCE_FD, as a driver refusing the GPU's fences would.
 * Everything else goes to libdrm and EGL. Built as a shared object; Linux only. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
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

/* EGL, for JADE_REFUSE=fence: the extensions list with native fences, and
 * the three functions jade looks up for them. */
#define EGL_EXTENSIONS_NAME 0x3055 /* EGL_EXTENSIONS */

const char *eglQueryString(void *dpy, int32_t name)
{
    const char *(*real)(void *, int32_t) = (const char *(*)(void *, int32_t))dlsym(RTLD_NEXT, "eglQueryString");
    const char *s = real ? real(dpy, name) : NULL;
    if (name != EGL_EXTENSIONS_NAME || !s || !refuses("fence")) return s;
    static char more[8192];
    snprintf(more, sizeof more, "%s EGL_KHR_fence_sync EGL_ANDROID_native_fence_sync", s);
    return more;
}

static void *fake_create_sync(void *dpy, unsigned type, const int32_t *attribs)
{
    (void)dpy, (void)type, (void)attribs;
    return (void *)1;
}

static unsigned fake_destroy_sync(void *dpy, void *sync)
{
    (void)dpy, (void)sync;
    return 1;
}

static int fake_dup_fence(void *dpy, void *sync)
{
    (void)dpy, (void)sync;
    return open("/dev/null", O_RDONLY | O_CLOEXEC);
}

typedef void (*any_fn)(void);

any_fn eglGetProcAddress(const char *name)
{
    if (refuses("fence")) {
        if (!strcmp(name, "eglCreateSyncKHR")) return (any_fn)fake_create_sync;
        if (!strcmp(name, "eglDestroySyncKHR")) return (any_fn)fake_destroy_sync;
        if (!strcmp(name, "eglDupNativeFenceFDANDROID")) return (any_fn)fake_dup_fence;
    }
    any_fn (*real)(const char *) = (any_fn(*)(const char *))dlsym(RTLD_NEXT, "eglGetProcAddress");
    return real ? real(name) : NULL;
}
