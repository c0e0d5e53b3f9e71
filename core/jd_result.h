/* Result codes and the error record every fallible jade call fills in. */
#ifndef JD_RESULT_H
#define JD_RESULT_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum jd_result {
    JD_OK = 0,
    JD_ERR_ARG,         /* a caller passed a bad value */
    JD_ERR_IO,          /* a file could not be read or written */
    JD_ERR_FORMAT,      /* input is not what it claims to be */
    JD_ERR_LIMIT,       /* input exceeds a configured safety limit */
    JD_ERR_BUDGET,      /* the memory budget given at start-up is too small */
    JD_ERR_TIMEOUT,     /* work ran past its deadline */
    JD_ERR_CRASH,       /* a sandboxed helper died */
    JD_ERR_GL,          /* the GL driver refused something */
    JD_ERR_UNSUPPORTED, /* the device lacks a required capability */
    JD_ERR_PLATFORM     /* display / context creation failed */
} jd_result;

/* Room for a message naming two paths of the longest length Linux allows
 * (4,095 bytes each) and the reason: messages are never cut. */
#define JD_ERROR_MSG_SIZE (2 * 4096 + 512)

/* One line of text saying what failed and why; filled by the call that failed. */
typedef struct jd_error {
    jd_result code;
    char msg[JD_ERROR_MSG_SIZE];
} jd_error;

/* Records code and a printf-style message in err (err may be NULL); returns code. */
jd_result jd_fail(jd_error *err, jd_result code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

const char *jd_result_name(jd_result r);

#ifdef __cplusplus
}
#endif

#endif
