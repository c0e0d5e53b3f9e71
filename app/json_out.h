/* JSON strings out: the one place jade escapes text for JSON, so a file
 * name with a quote, a control character or bytes that are not UTF-8
 * cannot break what bench, metric and reference print. */
#ifndef JD_JSON_OUT_H
#define JD_JSON_OUT_H
#include <stdio.h>

/* Writes `s` as a quoted JSON string: quotes, backslashes and control
 * characters escaped, each byte of invalid UTF-8 as U+FFFD. */
void jd_json_string(FILE *f, const char *s);

#endif
