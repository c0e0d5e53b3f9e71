/* A minimal test harness: CHECK records failures and keeps going, so one
 * run reports every broken expectation; the closing line is the plain
 * "N passed, N failed" that CI reads. */
#ifndef JD_CHECK_H
#define JD_CHECK_H
#include <stdio.h>

static int jd_checks_passed, jd_checks_failed;

#define CHECK(cond, ...)                                                        \
    do {                                                                        \
        if (cond) {                                                             \
            jd_checks_passed++;                                                 \
        } else {                                                                \
            jd_checks_failed++;                                                 \
            printf("FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);              \
            printf(__VA_ARGS__);                                                \
            printf("\n");                                                       \
        }                                                                       \
    } while (0)

static inline int jd_check_summary(const char *suite)
{
    printf("%s: %d passed, %d failed\n", suite, jd_checks_passed, jd_checks_failed);
    return jd_checks_failed ? 1 : 0;
}
#endif
