#ifndef JD_ALLOC_COUNT_H
#define JD_ALLOC_COUNT_H
/* Counts every heap call the process makes (jade, libc, the GL driver) while
 * counting is on: the figure bench reports for the frame loop. */
void jd_alloc_count_start(void);
unsigned long jd_alloc_count_stop(void);
#endif
