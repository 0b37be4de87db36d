/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * kernel.c - out-of-line forms of the kernel evaluator (see kernel.h), for
 * tests and for code off the hot path. The interaction loops use the
 * static inline sph_cubic_w_dw directly.
 */
#include "config.h"

#include "physics/kernel.h"

#include <math.h>

double sph_cubic_w(double r, double h) {
  double w, dw;
  sph_cubic_w_dw(r, h, &w, &dw);
  return w;
}

double sph_kernel_w(sph_kernel_kind k, double r, double h) {
  double w, dw;
  sph_kernel_w_dw(k, r, h, &w, &dw);
  return w;
}
