/* libFuzzer: the command-line parser of every command. The input is the
 * argument list, arguments split at NUL bytes; its first byte picks the
 * command. Run with -close_fd_mask=3: the parser's one-line errors are
 * its output, and the fuzzer does not need them. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "options.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1 || size > 4096) return 0;
    static const int commands[] = {JD_OPT_RENDER, JD_OPT_BENCH, JD_OPT_INFO, JD_OPT_VIEW,
                                   JD_OPT_KIOSK,  JD_OPT_REFERENCE, JD_OPT_METRIC};
    int command = commands[data[0] % (sizeof commands / sizeof commands[0])];
    char *text = malloc(size + 1);
    char **argv = malloc(sizeof(char *) * (size + 3));
    if (!text || !argv) abort();
    memcpy(text, data + 1, size - 1);
    text[size - 1] = 0;
    int argc = 0;
    argv[argc++] = "jade";
    argv[argc++] = "cmd";
    for (size_t at = 0; at < size - 1; at += strlen(text + at) + 1) argv[argc++] = text + at;
    argv[argc] = NULL;
    jd_options o;
    jd_options_defaults(&o);
    if (jd_options_parse(&o, command, "cmd", argc, argv, 2) > 0) jd_options_finish(&o, "cmd");
    free(argv);
    free(text);
    return 0;
}
