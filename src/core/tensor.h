/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * tensor.h - symmetric tensors of SPH_DIM dimensions (core/dim.h) as arrays
 * of their SPH_SYM independent components, in the order xx, xy, yy (2-D;
 * xx, xy, xz, yy, yz, zz in 3-D): the strain rate, the viscous stress, the
 * kernel-gradient moment and its inverse. Each helper writes its products
 * in a fixed order, the order the results' bits were first made with.
 */
#ifndef SPH_TENSOR_H
#define SPH_TENSOR_H

#include "core/dim.h"

#if SPH_DIM != 2
#error "core/tensor.h: only the 2-D forms are written yet"
#endif

enum { SPH_XX = 0, SPH_XY = 1, SPH_YY = 2 };

/* a = m^-1 where m is invertible enough (det m > min_det and m_xx > 0),
 * else the identity: the kernel-gradient correction's L = M^-1 (forces.h).
 * Returns 1 where it inverted. */
static inline int sph_sym_inverse_or_identity(const double m[SPH_SYM], double min_det,
                                              double a[SPH_SYM]) {
  const double det = m[SPH_XX] * m[SPH_YY] - m[SPH_XY] * m[SPH_XY];
  a[SPH_XX] = 1.0, a[SPH_XY] = 0.0, a[SPH_YY] = 1.0;
  if (!(det > min_det && m[SPH_XX] > 0.0)) return 0;
  a[SPH_XX] = m[SPH_YY] / det;
  a[SPH_XY] = -m[SPH_XY] / det;
  a[SPH_YY] = m[SPH_XX] / det;
  return 1;
}

/* b = sym(t a) = (t a + (t a)^T) / 2 of two symmetric tensors. */
static inline void sph_sym_product(const double t[SPH_SYM], const double a[SPH_SYM],
                                   double b[SPH_SYM]) {
  const double txx = t[SPH_XX], txy = t[SPH_XY], tyy = t[SPH_YY];
  const double axx = a[SPH_XX], axy = a[SPH_XY], ayy = a[SPH_YY];
  b[SPH_XX] = txx * axx + txy * axy;
  b[SPH_YY] = txy * axy + tyy * ayy;
  b[SPH_XY] = 0.5 * ((txx * axy + txy * ayy) + (txy * axx + tyy * axy));
}

#endif
