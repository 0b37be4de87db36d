/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * interp3d.h - the SPH interpolation of a 3-D snapshot on a lattice of
 * points: the fluid's kernel sum, whose level 1/2 is the free surface
 * (isosurface.h), and a field, Shepard-normalised, to colour it.
 *
 * At a point x, over the fluid particles j (volume V_j = m_j / rho_j,
 * smoothing length h_j, the case's kernel W with its 3-D normalisation,
 * support 2 h_j):
 *   S(x) = sum_j V_j W(|x - x_j|, h_j)                (kernel sum)
 *   f(x) = sum_j f_j V_j W(|x - x_j|, h_j) / S(x)     (Shepard 1968)
 * as in 2-D (interp.h): S is close to 1 inside the fluid and falls to 0
 * across its edge within about one h, passing 1/2 half a spacing beyond
 * the last layer of a flat surface. Wall particles do not count: the
 * surface closes at the wall's face, where the fluid's own sum is 1/2.
 */
#ifndef SPH_RENDER_INTERP3D_H
#define SPH_RENDER_INTERP3D_H

#include <stddef.h>

#include "core/error.h"

typedef struct rinterp3_in {
  size_t n;
  const double *x, *y, *z, *h, *vol; /* per particle; vol = m / rho */
  const double *val;                 /* the field, or NULL */
  const unsigned char *wall;         /* 1 for wall particles (left out) */
  int kernel;                        /* RKERNEL_* (interp.h) */
} rinterp3_in;

/* A lattice of n[0] x n[1] x n[2] points, point (i, j, k) at
 * origin + (i, j, k) step, stored with i fastest. */
typedef struct rgrid3 {
  int n[3];
  double origin[3];
  double step;
} rgrid3;

/* Most points a lattice may have (16 bytes each with a field: 2 GiB). */
#define RGRID3_MAX_POINTS ((size_t)1 << 27)

/* The lattice of spacing step covering the fluid particles' box widened
 * by their largest support 2h plus one step, so that the kernel sum is 0
 * on its faces and every level set inside it is closed. Fails, naming
 * the size, if it would have more than RGRID3_MAX_POINTS points or there
 * is no fluid particle. */
int rgrid3_fit(const rinterp3_in *in, double step, rgrid3 *g, sph_error *err);
size_t rgrid3_points(const rgrid3 *g);

/* Fills s (the kernel sum) and, if f is not NULL, f (the field; NaN where
 * S = 0) at the lattice's points (rgrid3_points values each). Each
 * particle adds itself to the points within its support, in id order:
 * the result is the same bits on every run. */
int rinterp3_sum(const rinterp3_in *in, const rgrid3 *g, double *s, double *f, sph_error *err);

/* W(r, h) of kernel (RKERNEL_*) with its 3-D normalisation. */
double rinterp3_w(int kernel, double r, double h);

#endif
