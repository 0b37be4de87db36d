/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * interp.c - the SPH interpolation of interp.h on a grid of points.
 *
 * Particles go into square cells of side 2 max h (a counting sort, stable,
 * so each cell keeps id order); a point visits the 3 x 3 cells around its
 * own. Wall particles count with the volume of their number density (see
 * below), fluid particles with m / rho. The kernels are the solver's own
 * (src/core/kernel_shape.h: the cubic spline of paper A eq. 8 and the
 * Wendland C2 kernel, support 2h), the one the snapshot names.
 */
#include "config.h"

#include "interp.h"

#include "interp3d.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

double rinterp_w(int k, double r, double h) {
  double w, dw;
  sph_shape_w_dw(k, r, h, &w, &dw);
  return w;
}

/* W at distance sqrt(r2 + off^2): in 2-D, or on a plane through 3-D. */
static double kernel_at(const rinterp_in *in, double r2, double off, double h) {
  return in->off ? rinterp3_w(in->kernel, sqrt(r2 + off * off), h)
                 : rinterp_w(in->kernel, sqrt(r2), h);
}

int rinterp_kernel_of(const sph_snapshot *s) {
  const int k = sph_shape_of_name(sph_snapshot_text(s, "kernel"));
  if (k >= 0) return k;
  /* a snapshot written before the kernel attribute: its parameter listing */
  const char *parameters = sph_snapshot_text(s, "parameters");
  const char *p = parameters ? strstr(parameters, "numerics.kernel:") : NULL;
  if (!p) return RKERNEL_CUBIC;
  p += strlen("numerics.kernel:");
  while (*p == ' ')
    p++;
  return strncmp(p, "wendland_c2", 11) == 0 ? RKERNEL_WENDLAND_C2 : RKERNEL_CUBIC;
}

int rinterp_is_fluid(double sf) { return sf >= 0.5; }

int rinterp_field(const rinterp_in *in, const rinterp_grid *g, double *f, double *sf, double *sw,
                  sph_error *err) {
  const size_t np = (size_t)g->nx * (size_t)g->ny;
  for (size_t k = 0; k < np; k++) {
    f[k] = NAN;
    sf[k] = sw[k] = 0.0;
  }
  /* the particles' box and the cell size */
  double hmax = 0.0, bx0 = INFINITY, bx1 = -INFINITY, by0 = INFINITY, by1 = -INFINITY;
  size_t used = 0;
  for (size_t i = 0; i < in->n; i++) {
    if (!(in->h[i] > 0.0) || !isfinite(in->x[i]) || !isfinite(in->y[i]) || !(in->vol[i] > 0.0))
      continue;
    hmax = fmax(hmax, in->h[i]);
    bx0 = fmin(bx0, in->x[i]);
    bx1 = fmax(bx1, in->x[i]);
    by0 = fmin(by0, in->y[i]);
    by1 = fmax(by1, in->y[i]);
    used++;
  }
  if (used == 0) return 0;
  double cell = 2.0 * hmax;
  /* at most about four cells per particle, whatever the spread */
  while (((bx1 - bx0) / cell + 1.0) * ((by1 - by0) / cell + 1.0) > 4.0 * (double)used + 1e6)
    cell *= 2.0;
  const long cx = (long)((bx1 - bx0) / cell) + 1, cy = (long)((by1 - by0) / cell) + 1;
  size_t *start = calloc((size_t)(cx * cy + 1), sizeof *start);
  size_t *order = malloc(used * sizeof *order);
  long *cell_of = malloc(in->n * sizeof *cell_of);
  if (!start || !order || !cell_of) {
    free(start);
    free(order);
    free(cell_of);
    return sph_error_set(err, "--smooth: out of memory for %zu particles", in->n);
  }
  for (size_t i = 0; i < in->n; i++) {
    cell_of[i] = -1;
    if (!(in->h[i] > 0.0) || !isfinite(in->x[i]) || !isfinite(in->y[i]) || !(in->vol[i] > 0.0))
      continue;
    long a = (long)((in->x[i] - bx0) / cell), b = (long)((in->y[i] - by0) / cell);
    if (a >= cx) a = cx - 1;
    if (b >= cy) b = cy - 1;
    cell_of[i] = b * cx + a;
    start[cell_of[i] + 1]++;
  }
  for (long c = 0; c < cx * cy; c++)
    start[c + 1] += start[c];
  size_t *fill = malloc((size_t)(cx * cy) * sizeof *fill);
  if (!fill) {
    free(start);
    free(order);
    free(cell_of);
    return sph_error_set(err, "--smooth: out of memory");
  }
  memcpy(fill, start, (size_t)(cx * cy) * sizeof *fill);
  for (size_t i = 0; i < in->n; i++)
    if (cell_of[i] >= 0) order[fill[cell_of[i]]++] = i;
  free(fill);
  /* wall particles' volumes from their number density, 1 / sum_k W_jk over
   * every particle k: walls of any spacing (a layer at dx/2 of another)
   * then fill their space once, whatever mass and density they carry */
  double *vol = malloc(in->n * sizeof *vol);
  if (!vol) {
    free(start);
    free(order);
    free(cell_of);
    return sph_error_set(err, "--smooth: out of memory");
  }
  for (size_t i = 0; i < in->n; i++) {
    vol[i] = in->vol[i];
    if (!in->wall[i] || cell_of[i] < 0) continue;
    const long a = cell_of[i] % cx, b = cell_of[i] / cx;
    double sum = 0.0;
    for (long bb = b - 1; bb <= b + 1; bb++)
      for (long aa = a - 1; aa <= a + 1; aa++) {
        if (aa < 0 || aa >= cx || bb < 0 || bb >= cy) continue;
        for (size_t k = start[bb * cx + aa]; k < start[bb * cx + aa + 1]; k++) {
          const size_t q = order[k];
          const double dx = in->x[i] - in->x[q], dy = in->y[i] - in->y[q];
          sum +=
              kernel_at(in, dx * dx + dy * dy, in->off ? in->off[i] - in->off[q] : 0.0, in->h[i]);
        }
      }
    vol[i] = sum > 0.0 ? 1.0 / sum : 0.0;
  }
  for (int j = 0; j < g->ny; j++) {
    const double py = g->y1 - (j + 0.5) * g->step;
    const long b = (long)floor((py - by0) / cell);
    for (int i = 0; i < g->nx; i++) {
      const double px = g->x0 + (i + 0.5) * g->step;
      const long a = (long)floor((px - bx0) / cell);
      double s_f = 0.0, s_w = 0.0, s_v = 0.0;
      for (long bb = b - 1; bb <= b + 1; bb++) {
        if (bb < 0 || bb >= cy) continue;
        for (long aa = a - 1; aa <= a + 1; aa++) {
          if (aa < 0 || aa >= cx) continue;
          const long c = bb * cx + aa;
          for (size_t k = start[c]; k < start[c + 1]; k++) {
            const size_t p = order[k];
            const double dx = px - in->x[p], dy = py - in->y[p];
            const double r2 = dx * dx + dy * dy, h = in->h[p];
            const double o = in->off ? in->off[p] : 0.0;
            if (r2 + o * o >= 4.0 * h * h) continue;
            const double vw = vol[p] * kernel_at(in, r2, o, h);
            if (in->wall[p]) {
              s_w += vw;
            } else {
              s_f += vw;
              s_v += vw * in->val[p];
            }
          }
        }
      }
      const size_t q = (size_t)j * g->nx + i;
      sf[q] = s_f;
      sw[q] = s_w;
      if (s_f > 0.0) f[q] = s_v / s_f;
    }
  }
  free(vol);
  free(start);
  free(order);
  free(cell_of);
  return 0;
}
