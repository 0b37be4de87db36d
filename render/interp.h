/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * interp.h - the SPH interpolation of a snapshot's field on a grid of
 * points (the centres of a plot's pixels), for the --smooth view.
 *
 * At a point x, over the fluid particles j (volume V_j = m_j / rho_j,
 * smoothing length h_j, the case's kernel W of support 2 h_j):
 *   S_f(x) = sum_j V_j W(|x - x_j|, h_j)                  (kernel sum)
 *   f(x)   = sum_j f_j V_j W(|x - x_j|, h_j) / S_f(x)     (Shepard 1968)
 * - the SPH estimate of a field (paper A §2: A(x) = sum_j V_j A_j W), divided
 * by the kernel sum so that a constant field stays constant where the
 * support is cut by the free surface. Inside the fluid S_f is close to 1;
 * it falls to 0 across the fluid's edge within about one h, and is 1/2
 * where a half-plane of particles ends (half a spacing beyond its last
 * row, where discs of diameter dx would end). A point is fluid where
 * S_f >= 1/2: at a free surface and at a wall alike (a gap between the
 * fluid and a wall stays visible); a convex corner of the fluid is
 * rounded with a radius of about h. S_w(x) is the same sum over wall
 * particles, each with the volume 1 / sum_k W_jk of its number density
 * (walls carry whatever mass and density their model gives them): the
 * free-surface outline is the level S_f = 1/2 away from walls
 * (S_w < RINTERP_WALL_NEAR at every corner of a cell).
 * On a plane through a 3-D snapshot (a slice) the same sums run over the
 * particles near the plane, each at its 3-D distance, with the kernel's
 * 3-D normalisation: the 3-D interpolation at points of the plane.
 */
#ifndef SPH_RENDER_INTERP_H
#define SPH_RENDER_INTERP_H

#include <stddef.h>

#include "core/error.h"
#include "core/kernel_shape.h"
#include "io/snapshot.h"

enum { RKERNEL_CUBIC = SPH_SHAPE_CUBIC_SPLINE, RKERNEL_WENDLAND_C2 = SPH_SHAPE_WENDLAND_C2 };

typedef struct rinterp_in {
  size_t n;
  const double *x, *y, *h, *vol, *val; /* per particle; vol = m / rho */
  const unsigned char *wall;           /* 1 for wall particles */
  int kernel;                          /* RKERNEL_* */
  const double *off; /* a plane through a 3-D snapshot (slice.h): each particle's distance
                        from it, and the 3-D kernel; NULL in 2-D */
} rinterp_in;

/* The grid: nx x ny points, point (i, j) at (x0 + (i + 1/2) step,
 * y1 - (j + 1/2) step), row j = 0 at the top (the order of image rows). */
typedef struct rinterp_grid {
  int nx, ny;
  double x0, y1, step;
} rinterp_grid;

/* Fills f, sf and sw (nx * ny values each, row-major; f is NaN where
 * S_f = 0). Deterministic: each point sums its particles in id order. */
int rinterp_field(const rinterp_in *in, const rinterp_grid *g, double *f, double *sf, double *sw,
                  sph_error *err);
#define RINTERP_WALL_NEAR 0.25

/* Whether a point with fluid kernel sum sf is inside the fluid (above). */
int rinterp_is_fluid(double sf);
/* The kernel of a snapshot: its `kernel` attribute, or in a snapshot
 * written before it had one, the `numerics.kernel` line of its
 * `parameters`; the cubic spline if neither names one. */
int rinterp_kernel_of(const sph_snapshot *s);
/* W(r, h) of kernel k in 2-D. */
double rinterp_w(int k, double r, double h);

#endif
