/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * dim.h - the number of space dimensions, a compile-time constant.
 *
 * The solver is written for SPH_DIM dimensions and compiled once per
 * dimension (as SWIFT's dimension.h fixes it at configure time), so loops
 * over the axes unroll and a 2-D build pays nothing for a third axis. Today
 * every build is 2-D; the 3-D build is the next step (doc/method.md).
 *
 *   SPH_DIM    2 (or 3)
 *   SPH_SYM    the independent components of a symmetric tensor: 3 in 2-D
 *              (xx, xy, yy), 6 in 3-D
 */
#ifndef SPH_DIM_H
#define SPH_DIM_H

#ifndef SPH_DIM
#define SPH_DIM 2
#endif
#if SPH_DIM != 2 && SPH_DIM != 3
#error "SPH_DIM must be 2 or 3"
#endif

#define SPH_SYM (SPH_DIM * (SPH_DIM + 1) / 2)

/* h^-d: the factor a kernel's normalisation takes from the smoothing
 * length, as products left to right ((1/h) (1/h) in 2-D). */
static inline double sph_pow_dim(double a, double inv_h) {
#if SPH_DIM == 2
  return a * inv_h * inv_h;
#else
  return a * inv_h * inv_h * inv_h;
#endif
}

#endif
