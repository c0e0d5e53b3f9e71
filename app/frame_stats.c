#include "frame_stats.h"

#include <stdlib.h>

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

void jd_sort_times(double *t, int n) { qsort(t, (size_t)n, sizeof(double), cmp_double); }

double jd_percentile(const double *sorted, int n, double q)
{
    if (n <= 0) return 0.0;
    double pos = q * (n - 1);
    int i = (int)pos;
    double f = pos - i;
    return i + 1 < n ? sorted[i] * (1 - f) + sorted[i + 1] * f : sorted[n - 1];
}
