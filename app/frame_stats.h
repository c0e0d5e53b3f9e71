/* Frame-time figures, one definition for every command that prints them. */
#ifndef JD_FRAME_STATS_H
#define JD_FRAME_STATS_H

/* Sorts n times in place, ascending. */
void jd_sort_times(double *t, int n);
/* The q-quantile (0.5 median, 0.95 p95) of n sorted times, interpolated
 * between neighbours. */
double jd_percentile(const double *sorted, int n, double q);

#endif
