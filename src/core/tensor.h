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

#if SPH_DIM == 2
enum { SPH_XX = 0, SPH_XY = 1, SPH_YY = 2 };
#else
enum { SPH_XX = 0, SPH_XY = 1, SPH_XZ = 2, SPH_YY = 3, SPH_YZ = 4, SPH_ZZ = 5 };
#endif

/* Per-particle arrays of a symmetric tensor, by name (pre##xx, ...) and by
 * component (arr[SPH_XX], ...; the same pointers). */
#if SPH_DIM == 2
#define SPH_SYM_ARRAYS(arr, pre)                                                                   \
  SPH_ANONYMOUS union {                                                                            \
    SPH_ANONYMOUS struct { double *pre##xx, *pre##xy, *pre##yy; };                                 \
    double *arr[SPH_SYM];                                                                          \
  }
#else
#define SPH_SYM_ARRAYS(arr, pre)                                                                   \
  SPH_ANONYMOUS union {                                                                            \
    SPH_ANONYMOUS struct { double *pre##xx, *pre##xy, *pre##xz, *pre##yy, *pre##yz, *pre##zz; };   \
    double *arr[SPH_SYM];                                                                          \
  }
#endif

/* The component of a symmetric tensor at row a, column b (axes). */
static inline int sph_sym_index(int a, int b) {
#if SPH_DIM == 2
  return a + b;
#else
  static const int k[3][3] = {
      {SPH_XX, SPH_XY, SPH_XZ}, {SPH_XY, SPH_YY, SPH_YZ}, {SPH_XZ, SPH_YZ, SPH_ZZ}};
  return k[a][b];
#endif
}

#if SPH_DIM == 2
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
#else
/* a = m^-1 where m is invertible enough (det m > min_det, and m_xx and the
 * leading 2x2 minor positive: m positive definite), else the identity.
 * The inverse by cofactors. Returns 1 where it inverted. */
static inline int sph_sym_inverse_or_identity(const double m[SPH_SYM], double min_det,
                                              double a[SPH_SYM]) {
  const double xx = m[SPH_XX], xy = m[SPH_XY], xz = m[SPH_XZ];
  const double yy = m[SPH_YY], yz = m[SPH_YZ], zz = m[SPH_ZZ];
  const double cxx = yy * zz - yz * yz, cxy = xz * yz - xy * zz, cxz = xy * yz - xz * yy;
  const double det = xx * cxx + xy * cxy + xz * cxz, minor = xx * yy - xy * xy;
  for (int k = 0; k < SPH_SYM; k++)
    a[k] = 0.0;
  a[SPH_XX] = a[SPH_YY] = a[SPH_ZZ] = 1.0;
  if (!(det > min_det && xx > 0.0 && minor > 0.0)) return 0;
  a[SPH_XX] = cxx / det;
  a[SPH_XY] = cxy / det;
  a[SPH_XZ] = cxz / det;
  a[SPH_YY] = (xx * zz - xz * xz) / det;
  a[SPH_YZ] = (xy * xz - xx * yz) / det;
  a[SPH_ZZ] = minor / det;
  return 1;
}

/* b = sym(t a) = (t a + (t a)^T) / 2 of two symmetric tensors. */
static inline void sph_sym_product(const double t[SPH_SYM], const double a[SPH_SYM],
                                   double b[SPH_SYM]) {
  double c[3][3]; /* c = t a */
  for (int r = 0; r < 3; r++)
    for (int q = 0; q < 3; q++)
      c[r][q] = (t[sph_sym_index(r, 0)] * a[sph_sym_index(0, q)] +
                 t[sph_sym_index(r, 1)] * a[sph_sym_index(1, q)]) +
                t[sph_sym_index(r, 2)] * a[sph_sym_index(2, q)];
  for (int r = 0; r < 3; r++)
    for (int q = r; q < 3; q++)
      b[sph_sym_index(r, q)] = r == q ? c[r][r] : 0.5 * (c[r][q] + c[q][r]);
}
#endif

#endif
