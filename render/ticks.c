/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * ticks.c - "nice numbers for graph labels" (P. S. Heckbert, Graphics Gems,
 * 1990): the tick step is the nice number nearest (hi - lo) / (target - 1),
 * and ticks are the integer multiples of it inside the range.
 *
 * Invariants: tick k is computed as k * step (never by repeated addition),
 * so labels do not drift; a value within 1e-9 steps of zero is exactly 0 (no
 * "-0" labels); every label of one axis has the same number of decimals.
 * A logarithmic axis takes its ticks at m 10^k, m = 1 (and 2, 5 over a
 * short range), each computed from its own k and m.
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
  rticks_make_step(lo, hi, step_for(lo, hi, target), t);
}

double rticks_finer(double step) {
  const double p = pow(10.0, floor(log10(step) + 1e-9)), f = step / p;
  return f > 3.5 ? 2.0 * p : f > 1.5 ? p : 0.5 * p;
}

void rticks_make_step(double lo, double hi, double step, rticks *t) {
  if (hi < lo) {
    double s = lo;
    lo = hi;
    hi = s;
  }
  t->n = 0;
  t->log = 0;
  t->step = step;
  set_format(t, lo, hi);
  double k0 = ceil(lo / t->step - 1e-9), k1 = floor(hi / t->step + 1e-9);
  for (double k = k0; k <= k1 && t->n < RTICKS_MAX; k += 1.0) {
    double v = k * t->step;
    if (fabs(v) < 1e-9 * t->step) v = 0.0;
    t->v[t->n++] = v;
  }
  if (t->n == 0) t->v[t->n++] = lo; /* a degenerate range still gets a label */
}

void rticks_make_log(double lo, double hi, int target, rticks *t) {
  if (hi < lo) {
    const double s = lo;
    lo = hi;
    hi = s;
  }
  t->n = 0;
  t->step = 0.0;
  t->decimals = 0;
  t->exponent = 0;
  t->log = 1;
  if (!(lo > 0.0) || !isfinite(hi)) {
    t->v[t->n++] = 1.0;
    return;
  }
  const int k0 = (int)floor(log10(lo) + 1e-9), k1 = (int)ceil(log10(hi) - 1e-9);
  static const double all[3] = {1.0, 2.0, 5.0};
  const int nm = 3.0 * (double)(k1 - k0) < (double)target ? 3 : 1;
  int fixed = 1;
  for (int k = k0; k <= k1; k++)
    for (int m = 0; m < nm && t->n < RTICKS_MAX; m++) {
      const double v = all[m] * pow(10.0, k);
      if (v < lo * (1.0 - 1e-9) || v > hi * (1.0 + 1e-9)) continue;
      t->v[t->n++] = v;
      if (k < -3 || k > 4) fixed = 0;
    }
  t->exponent = !fixed;
  if (t->n == 0) t->v[t->n++] = lo; /* inside one 1-2-5 gap: a label still */
}

void rticks_expand_log(double *lo, double *hi) {
  if (!(*lo > 0.0) || !(*hi > 0.0)) return;
  *lo = pow(10.0, floor(log10(*lo) + 1e-9));
  *hi = pow(10.0, ceil(log10(*hi) - 1e-9));
  if (!(*hi > *lo)) *hi = 10.0 * *lo;
}

/* A label m e<k> or, when fixed, as many decimals as the value needs. */
static void label_log(const rticks *t, double v, char *buf, size_t size) {
  const int k = (int)floor(log10(v) + 1e-9);
  const double m = v / pow(10.0, k);
  if (!t->exponent)
    snprintf(buf, size, "%.*f", k < 0 ? -k : 0, v);
  else if (fabs(m - floor(m + 0.5)) < 1e-6)
    snprintf(buf, size, "%.0fe%d", m, k);
  else
    snprintf(buf, size, "%.2ge%d", m, k);
}

void rticks_label(const rticks *t, double v, char *buf, size_t size) {
  if (t->log && v > 0.0) {
    label_log(t, v, buf, size);
    return;
  }
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
