/* A progress bar with an estimate of the time left, on stderr: redrawn in
 * place on a terminal, a line per tenth when stderr is a file or a pipe (CI
 * logs stay readable). */
#ifndef JD_PROGRESS_H
#define JD_PROGRESS_H

typedef struct jd_progress {
    const char *label;
    double total, start_ms, last_ms;
    int tty, last_tenth, enabled;
} jd_progress;

void jd_progress_start(jd_progress *p, const char *label, double total, int enabled);
void jd_progress_update(jd_progress *p, double done);
void jd_progress_finish(jd_progress *p);

#endif
