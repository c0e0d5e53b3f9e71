#include "jd_result.h"

#include <stdarg.h>
#include <stdio.h>

jd_result jd_fail(jd_error *err, jd_result code, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->msg, sizeof err->msg, fmt, ap);
        va_end(ap);
        err->code = code;
    }
    return code;
}

const char *jd_result_name(jd_result r)
{
    switch (r) {
    case JD_OK: return "ok";
    case JD_ERR_ARG: return "bad argument";
    case JD_ERR_IO: return "i/o error";
    case JD_ERR_FORMAT: return "bad format";
    case JD_ERR_LIMIT: return "over limit";
    case JD_ERR_BUDGET: return "memory budget exhausted";
    case JD_ERR_TIMEOUT: return "timed out";
    case JD_ERR_CRASH: return "helper crashed";
    case JD_ERR_GL: return "GL error";
    case JD_ERR_UNSUPPORTED: return "unsupported";
    case JD_ERR_PLATFORM: return "platform error";
    }
    return "unknown";
}
