/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * interp3d.c - the kernel sum and Shepard field of interp3d.h.
 *
 * This file is compiled as 3-D (SPH_DIM 3 before any header) so that the
 * kernels of src/core/kernel_shape.h carry their 3-D normalisation: the
 * solver's own functions, nothing copied. It includes no header whose
 * types depend on the dimension.
 *
 * Scattering, not gathering: each particle visits the lattice points of
 * the box around its support, so the work is (particles) x (points per
 * support), wherever the lattice has empty space.
 */
#include "config.h"

#define SPH_DIM 3
#include "core/kernel_shape.h"

#include "interp3d.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int usable(const rinterp3_in *in, size_t i) {
  return !in->wall[i] && in->h[i] > 0.0 && in->vol[i] > 0.0 && isfinite(in->x[i]) &&
         isfinite(in->y[i]) && isfinite(in->z[i]) && isfinite(in->h[i]);
}

double rinterp3_w(int kernel, double r, double h) {
  double w, dw;
  sph_shape_w_dw(kernel, r, h, &w, &dw);
  return w;
}

size_t rgrid3_points(const rgrid3 *g) {
  return (size_t)g->n[0] * (size_t)g->n[1] * (size_t)g->n[2];
}

int rgrid3_fit(const rinterp3_in *in, double step, rgrid3 *g, sph_error *err) {
  if (!(step > 0.0) || !isfinite(step))
    return sph_error_set(err, "surface: the cell size must be > 0 (got %g)", step);
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  double hmax = 0.0;
  for (size_t i = 0; i < in->n; i++) {
    if (!usable(in, i)) continue;
    const double p[3] = {in->x[i], in->y[i], in->z[i]};
    for (int a = 0; a < 3; a++) {
      lo[a] = fmin(lo[a], p[a]);
      hi[a] = fmax(hi[a], p[a]);
    }
    hmax = fmax(hmax, in->h[i]);
  }
  if (!(hmax > 0.0)) return sph_error_set(err, "surface: no fluid particles");
  double points = 1.0;
  for (int a = 0; a < 3; a++) {
    const double margin = SPH_KERNEL_SUPPORT * hmax + step;
    g->origin[a] = lo[a] - margin;
    const double n = ceil((hi[a] + margin - g->origin[a]) / step) + 1.0;
    points *= n;
    g->n[a] = n < 1e9 ? (int)n : 1000000000;
  }
  g->step = step;
  if (points > (double)RGRID3_MAX_POINTS)
    return sph_error_set(err,
                         "surface: a lattice of %d x %d x %d points at a cell of %g m is over "
                         "the limit of %zu points: give a larger cell",
                         g->n[0], g->n[1], g->n[2], step, (size_t)RGRID3_MAX_POINTS);
  return 0;
}

/* The first and last index of the lattice's points along one axis within
 * radius of coordinate c. */
static void span(const rgrid3 *g, int a, double c, double radius, int *first, int *last) {
  const double u = (c - g->origin[a]) / g->step, r = radius / g->step;
  *first = (int)fmax(0.0, ceil(u - r));
  *last = (int)fmin((double)(g->n[a] - 1), floor(u + r));
}

int rinterp3_sum(const rinterp3_in *in, const rgrid3 *g, double *s, double *f, sph_error *err) {
  const size_t np = rgrid3_points(g);
  double *sv = NULL;
  if (f && !(sv = calloc(np ? np : 1, sizeof *sv)))
    return sph_error_set(err, "surface: out of memory for %zu lattice points", np);
  memset(s, 0, np * sizeof *s);
  const size_t nx = (size_t)g->n[0], nxy = nx * (size_t)g->n[1];
  for (size_t p = 0; p < in->n; p++) {
    if (!usable(in, p)) continue;
    const double c[3] = {in->x[p], in->y[p], in->z[p]}, h = in->h[p];
    const double radius = SPH_KERNEL_SUPPORT * h, r2max = radius * radius;
    int i0, i1, j0, j1, k0, k1;
    span(g, 0, c[0], radius, &i0, &i1);
    span(g, 1, c[1], radius, &j0, &j1);
    span(g, 2, c[2], radius, &k0, &k1);
    for (int k = k0; k <= k1; k++) {
      const double dz = g->origin[2] + k * g->step - c[2];
      for (int j = j0; j <= j1; j++) {
        const double dy = g->origin[1] + j * g->step - c[1], ryz = dy * dy + dz * dz;
        if (ryz >= r2max) continue;
        const size_t row = (size_t)k * nxy + (size_t)j * nx;
        for (int i = i0; i <= i1; i++) {
          const double dx = g->origin[0] + i * g->step - c[0], r2 = dx * dx + ryz;
          if (r2 >= r2max) continue;
          double w, dw;
          sph_shape_w_dw(in->kernel, sqrt(r2), h, &w, &dw);
          const double vw = in->vol[p] * w;
          s[row + (size_t)i] += vw;
          if (sv) sv[row + (size_t)i] += vw * in->val[p];
        }
      }
    }
  }
  if (f)
    for (size_t q = 0; q < np; q++)
      f[q] = s[q] > 0.0 ? sv[q] / s[q] : NAN;
  free(sv);
  return 0;
}
