/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * dim.h - the number of space dimensions, a compile-time constant.
 *
 * The solver is written for SPH_DIM dimensions and compiled once per
 * dimension (as SWIFT's dimension.h fixes it at configure time), so loops
 * over the axes unroll and a 2-D build pays nothing for a third axis. The
 * 2-D build is libsph, the 3-D build libsph3 (doc/dimensions.md); both
 * are installed, each with its own header folder.
 *
 *   SPH_DIM    2 (or 3)
 *   SPH_SYM    the independent components of a symmetric tensor: 3 in 2-D
 *              (xx, xy, yy), 6 in 3-D
 */
#ifndef SPH_DIM_H
#define SPH_DIM_H

/* SPH_LIBRARY_DIM: 0 in the source tree, where the build chooses SPH_DIM
 * (2 unless told); in an installed header folder, that library's dimension
 * (make install writes it: 2 in include/sph, 3 in include/sph3), so an
 * includer cannot give the headers another layout than the library's. */
#define SPH_LIBRARY_DIM 0
#if SPH_LIBRARY_DIM
#if defined(SPH_DIM) && SPH_DIM != SPH_LIBRARY_DIM
#error "SPH_DIM differs from the dimension of the library these headers belong to"
#endif
#undef SPH_DIM
#define SPH_DIM SPH_LIBRARY_DIM
#endif
#ifndef SPH_DIM
#define SPH_DIM 2
#endif
#if SPH_DIM != 2 && SPH_DIM != 3
#error "SPH_DIM must be 2 or 3"
#endif

#define SPH_SYM (SPH_DIM * (SPH_DIM + 1) / 2)

/* Code written once for both dimensions:
 *   SPH_XYZ(x, y, z)  the components of a vector: x, y in 2-D (z is not
 *                     even read), x, y, z in 3-D, as in {{SPH_XYZ(dx, dy, dz)}}
 *   SPH_IF3(...)      its argument in 3-D, nothing in 2-D: the statements
 *                     of the third axis */
#if SPH_DIM == 2
#define SPH_XYZ(x, y, z) x, y
#define SPH_IF3(...)
#else
#define SPH_XYZ(x, y, z) x, y, z
#define SPH_IF3(...) __VA_ARGS__
#endif

/* The squared length of a separation given by its components, added in
 * axis order (the 2-D build's operations; dz is read in 3-D only, so in 2-D
 * it need not exist). */
#if SPH_DIM == 2
#define SPH_NORM2(dx, dy, dz) ((dx) * (dx) + (dy) * (dy))
#else
#define SPH_NORM2(dx, dy, dz) ((dx) * (dx) + (dy) * (dy) + (dz) * (dz))
#endif

/* The mass of a particle of density rho on a lattice of spacing dx:
 * rho dx^SPH_DIM, multiplied in that order ((rho dx) dx (dx)). */
static inline double sph_lattice_mass(double rho, double dx) {
  double m = rho;
  for (int a = 0; a < SPH_DIM; a++)
    m *= dx;
  return m;
}

/* The vertical axis: y in 2-D, z in 3-D (the last one; doc/dimensions.md).
 * In a box of 2 * SPH_DIM bounds (x0, x1, y0, y1, ...) its lower bound is at
 * 2 * SPH_UP. */
#define SPH_UP (SPH_DIM - 1)

/* A field with a name per axis and an array of SPH_DIM (an anonymous
 * union, C11 and a GNU C99 extension; __extension__ keeps -pedantic quiet
 * where the compiler has it): SPH_COMPONENTS(double, g, gx, gy, gz) is
 * g[0], g[1] (, g[2]) under the names gx, gy (, gz); SPH_AXES (particles.h)
 * the same for arrays. */
#if defined(__GNUC__)
#define SPH_ANONYMOUS __extension__
#else
#define SPH_ANONYMOUS
#endif
#define SPH_COMPONENTS(type, arr, a, b, c)                                                         \
  SPH_ANONYMOUS union {                                                                            \
    SPH_ANONYMOUS struct { type SPH_XYZ(a, b, c); };                                               \
    type arr[SPH_DIM];                                                                             \
  }

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
