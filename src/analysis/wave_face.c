/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * wave_face.c - the front face of a breaking wave (definitions in
 * wave_face.h).
 */
#include "config.h"

#include "analysis/wave_face.h"

#include <math.h>
#include <stdlib.h>

#include "physics/kernel.h" /* SPH_PI */

/* A particle's height: y in 2-D, z in 3-D (z up, doc/dimensions.md); in
 * 3-D the face is that of the water's profile over the whole width (the
 * highest particles at each x and height, whatever their y). */
static double up(const sph_particles *p, size_t i) { return p->pos[SPH_DIM - 1][i]; }

static int fluid_in(const sph_particles *p, size_t i, double x0, double x1) {
  return sph_particles_liquid(p, i) && p->x[i] >= x0 && p->x[i] <= x1;
}

/* The highest fluid particle in [x0, x1] (ties: larger x); -1 if none. */
static long crest(const sph_particles *p, double x0, double x1) {
  long c = -1;
  for (size_t i = 0; i < p->n; i++) {
    if (!fluid_in(p, i, x0, x1)) continue;
    if (c < 0 || up(p, i) > up(p, (size_t)c) || (up(p, i) == up(p, (size_t)c) && p->x[i] > p->x[c]))
      c = (long)i;
  }
  return c;
}

/* x of the toe: the start of the first column (width dx, column k centred
 * on xc + k dx, k >= 1) whose highest fluid particle is below ylo or that
 * holds none; x1 if every column up to x1 is higher. */
static int toe(const sph_particles *p, double xc, double ylo, double dx, double x1, double *xt,
               sph_error *err) {
  const double span = (x1 - xc) / dx + 1.0;
  if (!(span < 1e8)) return sph_error_set(err, "wave face: window of %g columns", span);
  const size_t k_max = (size_t)span + 1;
  double *top = malloc(k_max * sizeof *top);
  if (!top) return sph_error_set(err, "wave face: out of memory for %zu columns", k_max);
  for (size_t k = 0; k < k_max; k++)
    top[k] = -INFINITY;
  for (size_t i = 0; i < p->n; i++) {
    if (!fluid_in(p, i, xc + 0.5 * dx, x1)) continue;
    const size_t k = (size_t)floor((p->x[i] - xc) / dx + 0.5);
    if (k < k_max && up(p, i) > top[k]) top[k] = up(p, i);
  }
  *xt = x1;
  for (size_t k = 1; k < k_max; k++)
    if (top[k] < ylo) {
      *xt = xc + ((double)k - 0.5) * dx;
      break;
    }
  free(top);
  return 0;
}

int sph_wave_face_measure(const sph_particles *p, double level, double dx, double x0, double x1,
                          sph_wave_face *f, sph_error *err) {
  f->crest_x = f->crest_y = f->toe_x = f->angle = NAN;
  f->bands = 0;
  if (!p || !isfinite(level) || !(dx > 0.0) || !isfinite(dx) || !isfinite(x0) || !isfinite(x1) ||
      !(x1 > x0))
    return sph_error_set(err,
                         "wave face: need particles, a finite level, dx > 0 and x0 < x1 "
                         "(got level %g, dx %g, window [%g, %g])",
                         level, dx, x0, x1);
  const long c = crest(p, x0, x1);
  if (c < 0) return 1;
  const double xc = p->x[c], yc = up(p, (size_t)c);
  f->crest_x = xc;
  f->crest_y = yc;
  if (yc - level < 4.0 * dx) return 1;
  const double ylo = level + 0.25 * (yc - level);
  double xt = x1;
  if (toe(p, xc, ylo, dx, x1, &xt, err)) return -1;
  f->toe_x = xt;
  const size_t nb = (size_t)floor((yc - ylo) / dx);
  double *lead = malloc((nb ? nb : 1) * sizeof *lead);
  if (!lead) return sph_error_set(err, "wave face: out of memory for %zu bands", nb);
  for (size_t b = 0; b < nb; b++)
    lead[b] = -INFINITY;
  for (size_t i = 0; i < p->n; i++) {
    if (!fluid_in(p, i, x0, xt) || p->x[i] >= xt || up(p, i) < ylo) continue;
    const double u = floor((up(p, i) - ylo) / dx);
    if (u < 0.0 || u >= (double)nb) continue;
    const size_t b = (size_t)u;
    if (p->x[i] > lead[b]) lead[b] = p->x[i];
  }
  /* least squares x_f = a + s y over the bands that hold particles
   * (centred sums: two passes) */
  double my = 0.0, mx = 0.0;
  int m = 0;
  for (size_t b = 0; b < nb; b++)
    if (isfinite(lead[b])) {
      my += ylo + ((double)b + 0.5) * dx;
      mx += lead[b];
      m++;
    }
  f->bands = m;
  if (m < 3) {
    free(lead);
    return 1;
  }
  my /= m;
  mx /= m;
  double syy = 0.0, sxy = 0.0;
  for (size_t b = 0; b < nb; b++)
    if (isfinite(lead[b])) {
      const double dy = ylo + ((double)b + 0.5) * dx - my;
      syy += dy * dy;
      sxy += dy * (lead[b] - mx);
    }
  free(lead);
  const double s = sxy / syy;
  f->angle = 90.0 + atan(s) * (180.0 / SPH_PI);
  return 0;
}
