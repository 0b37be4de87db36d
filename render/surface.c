/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * surface.c - a snapshot's free surface as a mesh (see surface.h).
 */
#include "config.h"

#include "surface.h"

#include <math.h>
#include <stdlib.h>

#include "interp3d.h"

int rsurface_cell(const rsnap *s, double given, double *cell, sph_error *err) {
  if (given > 0.0) {
    *cell = given;
    return 0;
  }
  if (!(s->dx > 0.0))
    return sph_error_set(err, "%s: no particle spacing (attribute dx): give --surface-cell",
                         s->path);
  *cell = 0.5 * s->dx;
  return 0;
}

int rsurface_of(const rsnap *s, double cell, int with_field, rmesh *m, sph_error *err) {
  if (s->dim != 3 || !s->h || !s->vol)
    return sph_error_set(err, "%s: the surface needs a 3-D snapshot with h, mass and rho", s->path);
  const rinterp3_in in = {s->n,    s->x,     s->y, s->z, s->h, s->vol, with_field ? s->val : NULL,
                          s->wall, s->kernel};
  rgrid3 g;
  if (rgrid3_fit(&in, cell, &g, err) != 0) return -1;
  const size_t np = rgrid3_points(&g);
  double *sum = malloc(np * sizeof *sum), *f = NULL;
  if (in.val) f = malloc(np * sizeof *f);
  int rc = 0;
  if (!sum || (in.val && !f))
    rc = sph_error_set(err, "%s: out of memory for a lattice of %zu points", s->path, np);
  if (!rc) rc = rinterp3_sum(&in, &g, sum, f, err);
  if (!rc) rc = rmesh_isosurface(&g, sum, f, RSURFACE_LEVEL, m, err);
  free(sum);
  free(f);
  return rc;
}
