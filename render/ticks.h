/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * ticks.h - axis ticks at "nice" numbers (1, 2 or 5 times a power of ten)
 * and their labels.
 */
#ifndef SPH_RENDER_TICKS_H
#define SPH_RENDER_TICKS_H

#include <stddef.h>

enum { RTICKS_MAX = 64 };

typedef struct rticks {
  int n;                /* number of ticks */
  double v[RTICKS_MAX]; /* ascending, all inside [lo, hi] (up to round-off) */
  double step;          /* spacing */
  int decimals;         /* digits after the point in fixed notation */
  int exponent;         /* 0: fixed notation; else labels are m e<exponent> */
  int log;              /* ticks of a logarithmic axis (rticks_make_log) */
} rticks;

/* About `target` ticks inside [lo, hi]. lo == hi gives one tick. */
void rticks_make(double lo, double hi, int target, rticks *t);
/* The ticks at the multiples of step (a nice number) inside [lo, hi]. */
void rticks_make_step(double lo, double hi, double step, rticks *t);
/* The next nice number below a nice step: 5 -> 2 -> 1 -> 0.5 (x 10^k). */
double rticks_finer(double step);
/* The label of value v, formatted for the ticks t (same decimals for all). */
void rticks_label(const rticks *t, double v, char *buf, size_t size);
/* Widens [lo, hi] outward to multiples of the step rticks_make would use,
 * so an automatic plot range starts and ends on a tick. */
void rticks_expand(double *lo, double *hi, int target);
/* Ticks of a logarithmic axis over [lo, hi] (0 < lo <= hi): the powers of
 * ten inside, and 2 and 5 times them as well when the range spans fewer
 * than target / 3 decades. Labels are fixed notation ("0.001", "20") when
 * every tick lies in [1e-3, 1e4], else m e<k> ("1e-5", "2e6"). */
void rticks_make_log(double lo, double hi, int target, rticks *t);
/* Widens [lo, hi] (0 < lo <= hi) outward to whole decades. */
void rticks_expand_log(double *lo, double *hi);
/* The nice number nearest x (round) or not below x (!round): 1, 2, 5 x 10^k. */
double rticks_nice(double x, int round);

#endif
