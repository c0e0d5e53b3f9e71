#include "progress.h"

#include <stdio.h>
#include <unistd.h>

#include "clock.h"

void jd_progress_start(jd_progress *p, const char *label, double total, int enabled)
{
    p->label = label;
    p->total = total > 0 ? total : 1;
    p->start_ms = p->last_ms = jd_clock_ms();
    p->tty = isatty(2);
    p->last_tenth = -1;
    p->enabled = enabled;
}

static void draw(jd_progress *p, double done, int final)
{
    double now = jd_clock_ms(), el = (now - p->start_ms) / 1000.0, f = done / p->total;
    if (f > 1) f = 1;
    char eta[48];
    if (final) snprintf(eta, sizeof eta, "done in %.1f s", el);
    else if (f > 0.02 && el > 0.5) snprintf(eta, sizeof eta, "%.0f s, about %.0f s left", el, el * (1 - f) / f);
    else snprintf(eta, sizeof eta, "%.0f s", el);
    if (p->tty) {
        char bar[31];
        int fill = (int)(f * 30);
        for (int i = 0; i < 30; i++) bar[i] = i < fill ? '=' : i == fill ? '>' : ' ';
        bar[30] = 0;
        fprintf(stderr, "\r%-10s [%s] %3.0f%%  %-28s", p->label, bar, f * 100, eta);
        if (final) fputc('\n', stderr);
    } else {
        fprintf(stderr, "%s: %3.0f%%  %s\n", p->label, f * 100, eta);
    }
    fflush(stderr);
}

void jd_progress_update(jd_progress *p, double done)
{
    if (!p->enabled) return;
    double now = jd_clock_ms();
    if (p->tty) {
        if (now - p->last_ms < 100) return;
        p->last_ms = now;
        draw(p, done, 0);
    } else {
        int tenth = (int)(10 * done / p->total);
        if (tenth <= p->last_tenth || tenth >= 10) return;
        p->last_tenth = tenth;
        if (tenth > 0) draw(p, done, 0);
    }
}

void jd_progress_finish(jd_progress *p)
{
    if (p->enabled) draw(p, p->total, 1);
}
