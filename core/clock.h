/* A monotonic clock in milliseconds: for deadlines and the figures jade
 * prints, never for anything a picture depends on. */
#ifndef JD_CLOCK_H
#define JD_CLOCK_H
double jd_clock_ms(void);
#endif
