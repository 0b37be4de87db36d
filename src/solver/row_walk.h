/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * row_walk.h - walking one particle's neighbour row: the row written out
 * (ROW) and each pair's separation with the minimum image over a periodic
 * axis (SEP), for the interaction loops (interact.h) and the passes that
 * walk the same rows beside them (diffusion.c). Internal to src/solver/.
 */
#ifndef SPH_ROW_WALK_H
#define SPH_ROW_WALK_H

#include <stddef.h>
#include <stdint.h>

#include "core/dim.h"
#include "neighbours/grid.h"
#include "solver/force_pass.h"

/* The bit of a term set F that asks for the minimum image (interact.h's
 * F_PERIODIC is this bit). */
#define SPH_ROW_PERIODIC 16u

/* The neighbour row of i in the list l: j = row_[0], ..., row_[len_ - 1], written out into the
 * calling thread's buffer of the list (sph_nlist_row). */
#define ROW(l, i, row_, len_)                                                                      \
  size_t len_;                                                                                     \
  const uint32_t *restrict row_ = sph_nlist_row((l), (i), &len_);

/* The period along axis a: fp->period on the axis that wraps, 0 on the others (sep_x and
 * LANE_MIN_IMAGE with a period of 0 leave a separation as it is, bit for bit). */
#if SPH_DIM == 2 /* only x wraps in 2-D: the period as the loops have always read it */
#define period_along(fp, a) ((fp)->period)
#else
#define period_along(fp, a) ((fp)->periodic && (fp)->paxis == (a) ? (fp)->period : 0.0)
#endif

/* x_i - x_j with the minimum image when periodic (any axis: period 0 on one that does not
 * wrap). */
static inline __attribute__((always_inline)) double sep_x(double xi, double xj, double period,
                                                          double half, const unsigned F) {
  double d = xi - xj;
  if (F & SPH_ROW_PERIODIC) {
    if (d > half)
      d -= period;
    else if (d < -half)
      d += period;
  }
  return d;
}

/* x_i - x_j along axis a (a literal) with the minimum image when periodic: in 2-D only x
 * wraps. */
#define SEP(fp, a, xi, xj, F)                                                                      \
  (SPH_DIM == 2 && (a) ? (xi) - (xj)                                                               \
                       : sep_x(xi, xj, period_along(fp, a), 0.5 * period_along(fp, a), F))

#endif
