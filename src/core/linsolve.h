/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * linsolve.h - small dense linear systems (n <= 4: the moment matrices of
 * the linear moving-least-squares fits in 3-D, physics/filter.c and
 * walls/wall_velocity.c) by Gaussian elimination with partial pivoting.
 *
 * The system sits in the first n columns of an augmented matrix whose rows
 * hold SPH_LINSOLVE_COLS numbers; its right-hand sides in the columns n ..
 * ncol - 1. Every operation is written in a fixed order, so a system always
 * gives the same bits.
 */
#ifndef SPH_LINSOLVE_H
#define SPH_LINSOLVE_H

#include <math.h>

/* Room for a 4 x 4 system and up to 4 right-hand sides. */
#define SPH_LINSOLVE_COLS 8

/* Reduces a (n rows, ncol columns used) to upper-triangular form, the
 * right-hand sides with it; returns det A (0 when a pivot is exactly zero:
 * the elimination stops there and the system has no unique solution). */
static inline double sph_linsolve_eliminate(int n, int ncol, double a[][SPH_LINSOLVE_COLS]) {
  double det = 1.0;
  for (int c = 0; c < n; c++) {
    int piv = c;
    for (int r = c + 1; r < n; r++)
      if (fabs(a[r][c]) > fabs(a[piv][c])) piv = r;
    if (piv != c) {
      for (int k = 0; k < ncol; k++) {
        const double tmp = a[c][k];
        a[c][k] = a[piv][k];
        a[piv][k] = tmp;
      }
      det = -det;
    }
    det *= a[c][c];
    if (a[c][c] == 0.0) break;
    for (int r = c + 1; r < n; r++) {
      const double f = a[r][c] / a[c][c];
      for (int k = c; k < ncol; k++)
        a[r][k] -= f * a[c][k];
    }
  }
  return det;
}

/* The solution x (n values) for the right-hand side in column `col` of a
 * reduced by sph_linsolve_eliminate (whose det was not 0). */
static inline void sph_linsolve_back(int n, int col, double a[][SPH_LINSOLVE_COLS], double *x) {
  for (int r = n - 1; r >= 0; r--) {
    double v = a[r][col];
    for (int k = r + 1; k < n; k++)
      v -= a[r][k] * x[k];
    x[r] = v / a[r][r];
  }
}

#endif
