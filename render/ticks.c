/*
 * ticks.c - "nice numbers for graph labels" (P. S. Heckbert, Graphics Gems,
 * 1990): the tick step is the nice number nearest (hi - lo) / (target - 1),
 * and ticks are the integer multiples of it inside the range.
 *
 * Invariants: tick k is computed as k * step (never by repeated addition),
 * so labels do not drift; a value within 1e-9 steps of zero is exactly 0 (no
 * "-0" labels); every label of one axis has the same number of decimals.
 */
#include "config.h"

#include "ticks.h"

#include <math.h>
#include <stdio.h>

double rticks_nice(double x, int round) {
  if (!(x > 0.0) || !isfinite(x)) return 1.0;
  double e = floor(log10(x));
  double p = pow(10.0, e);
  double f = x / p, nf;
  if (round)
    nf = f < 1.5 ? 1.0 : f < 3.0 ? 2.0 : f < 7.0 ? 5.0 : 10.0;
  else
    nf = f <= 1.0 ? 1.0 : f <= 2.0 ? 2.0 : f <= 5.0 ? 5.0 : 10.0;
  return nf * p;
}

static double step_for(double lo, double hi, int target) {
  if (target < 2) target = 2;
  double span = hi - lo;
  if (!(span > 0.0)) span = fabs(lo) > 0.0 ? fabs(lo) : 1.0;
  return rticks_nice(span / (target - 1), 1);
}

static void set_format(rticks *t, double lo, double hi) {
  double big = fmax(fabs(lo), fabs(hi));
  int step_e = (int)floor(log10(t->step) + 1e-9);
  t->exponent = 0;
  t->decimals = step_e < 0 ? -step_e : 0;
  if (big >= 1e5 || (big > 0.0 && big < 1e-3)) {
    int e = (int)floor(log10(big) + 1e-9);
    t->exponent = e == 0 ? 1 : e;
    t->decimals = t->exponent - step_e > 0 ? t->exponent - step_e : 0;
  }
}

void rticks_make(double lo, double hi, int target, rticks *t) {
  if (hi < lo) {
    double s = lo;
    lo = hi;
    hi = s;
  }
  t->n = 0;
  t->step = step_for(lo, hi, target);
  set_format(t, lo, hi);
  double k0 = ceil(lo / t->step - 1e-9), k1 = floor(hi / t->step + 1e-9);
  for (double k = k0; k <= k1 && t->n < RTICKS_MAX; k += 1.0) {
    double v = k * t->step;
    if (fabs(v) < 1e-9 * t->step) v = 0.0;
    t->v[t->n++] = v;
  }
  if (t->n == 0) t->v[t->n++] = lo; /* a degenerate range still gets a label */
}

void rticks_label(const rticks *t, double v, char *buf, size_t size) {
  if (fabs(v) < 1e-9 * t->step) v = 0.0;
  if (t->exponent == 0) {
    snprintf(buf, size, "%.*f", t->decimals, v);
  } else if (v == 0.0) {
    snprintf(buf, size, "0");
  } else {
    snprintf(buf, size, "%.*fe%d", t->decimals, v / pow(10.0, t->exponent), t->exponent);
  }
}

void rticks_expand(double *lo, double *hi, int target) {
  if (!(*hi > *lo)) {
    double pad = fabs(*lo) > 0.0 ? 0.5 * fabs(*lo) : 0.5;
    *lo -= pad;
    *hi += pad;
  }
  double step = step_for(*lo, *hi, target);
  *lo = floor(*lo / step + 1e-9) * step;
  *hi = ceil(*hi / step - 1e-9) * step;
}
