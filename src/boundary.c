/*
 * boundary.c - building walls of dynamic particles (see boundary.h).
 *
 * Positions are computed from the segment end points and integer indices
 * (never by accumulating a step), so the same case always gives the same
 * bits.
 */
#include "config.h"

#include "boundary.h"

#include <math.h>

int sph_boundary_add_segment(sph_particles *p, double ax, double ay, double bx, double by,
                             int layers, double dx, double rho, double mass, double h,
                             sph_error *err) {
  const double lx = bx - ax, ly = by - ay;
  const double len = sqrt(lx * lx + ly * ly);
  if (!(len > 0.0)) return sph_error_set(err, "wall segment has zero length");
  const double tx = lx / len, ty = ly / len; /* along the wall */
  const double nx = -ty, ny = tx;            /* left normal */
  long count = (long)floor(len / dx + 0.5);
  if (count < 1) count = 1;
  const double sp = len / (double)count;
  for (int k = 0; k < layers; k++) {
    const double off = 0.5 * dx * (double)k;
    const int odd = k % 2;
    const long npts = odd ? count + 2 : count + 1;
    for (long i = 0; i < npts; i++) {
      const double s = odd ? ((double)i - 0.5) * sp : (double)i * sp;
      const double x = ax + s * tx + off * nx;
      const double y = ay + s * ty + off * ny;
      if (sph_particles_add(p, x, y, 0.0, 0.0, rho, mass, h, SPH_KIND_WALL, err) < 0) return -1;
    }
  }
  return 0;
}

int sph_boundary_add_tank(sph_particles *p, const sph_tank *t, double dx, double rho,
                          double mass, double h, sph_error *err) {
  const double e = 0.5 * dx;
  /* floor, right to left so that the left normal points down (outwards) */
  if (sph_boundary_add_segment(p, t->x1 + e, t->y0 - e, t->x0 - e, t->y0 - e, t->layers, dx, rho,
                               mass, h, err))
    return -1;
  /* left wall, upwards (left normal points to -x) */
  if (sph_boundary_add_segment(p, t->x0 - e, t->y0 + e, t->x0 - e, t->y1, t->layers, dx, rho,
                               mass, h, err))
    return -1;
  /* right wall, downwards (left normal points to +x) */
  if (sph_boundary_add_segment(p, t->x1 + e, t->y1, t->x1 + e, t->y0 + e, t->layers, dx, rho,
                               mass, h, err))
    return -1;
  return 0;
}
