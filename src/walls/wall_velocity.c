/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * wall_velocity.c - the extrapolated (no-slip) velocity of wall particles
 * (see wall_velocity.h).
 */
#include "config.h"

#include "walls/wall_velocity.h"

#include "core/parallel.h"
#include "neighbours/grid.h"
#include "physics/kernel.h"

#include <math.h>
#include <stdlib.h>

/* The most fields one fit serves (velocity: 2). */
#define SPH_FIT_MAX 2

void sph_wall_velocity_work_free(sph_wall_velocity_work *w) {
  free(w->start);
  free(w->idx);
  free(w->key);
  *w = (sph_wall_velocity_work){0};
}

/* The cell layout: columns of width cx from x0 (nx of them; periodic: the
 * whole period), rows of height cy from y0. */
typedef struct layout {
  double x0, y0, cx, cy, period;
  long nx, ny;
} layout;

static long column(const layout *g, double x) {
  double u = x - g->x0;
  if (g->period > 0.0) { /* into [0, period) */
    u = fmod(u, g->period);
    if (u < 0.0) u += g->period;
  }
  long c = (long)floor(u / g->cx);
  return c < 0 ? 0 : c >= g->nx ? g->nx - 1 : c;
}

static long row(const layout *g, double y) {
  long r = (long)floor((y - g->y0) / g->cy);
  return r < 0 ? 0 : r >= g->ny ? g->ny - 1 : r;
}

/* The linear moving-least-squares fit, at the point (x, y), of nf fields
 * f[k] (per-particle arrays) over the fluid particles within reach of it:
 * f ~ c0 + c1 (x_j - x) + c2 (y_j - y), weights W(x - x_j, h_j) (exact
 * for a linear field, also where the kernel is cut by the wall or the
 * surface). Fills fit[3 k .. 3 k + 2] with (c0, c1, c2) per field; where
 * the fit's moment matrix is near singular (fewer than three independent
 * neighbours) the Shepard average sum W f / sum W with a zero gradient.
 * fmax (NULL, or nf values set by the caller) is raised to the largest
 * value of each field among those particles. Returns 0 when no fluid
 * particle reaches the point, else 1. */
static int fit_at(const sph_particles *p, const layout *g, const sph_wall_velocity_work *w,
                  double x, double y, const double *const *f, int nf, double *fit, double *fmax) {
  const double fc = floor((y - g->y0) / g->cy);
  if (fc < -1.0 || fc > (double)g->ny) return 0; /* no row of the grid within reach */
  const long r0 = row(g, y);
  long cols[3], nc = 0;
  const long c0 = column(g, x);
  if (g->period > 0.0 && g->nx <= 3) {
    for (long c = 0; c < g->nx; c++)
      cols[nc++] = c; /* every column, once */
  } else if (g->period > 0.0) {
    cols[nc++] = (c0 + g->nx - 1) % g->nx;
    cols[nc++] = c0;
    cols[nc++] = (c0 + 1) % g->nx;
  } else {
    const double fx = floor((x - g->x0) / g->cx);
    if (fx < -1.0 || fx > (double)g->nx) return 0;
    for (long c = c0 - 1; c <= c0 + 1; c++)
      if (c >= 0 && c < g->nx) cols[nc++] = c;
  }
  double sw = 0.0, sf[SPH_FIT_MAX] = {0}, b1[SPH_FIT_MAX] = {0}, b2[SPH_FIT_MAX] = {0};
  /* linear MLS moments: A = sum W [1 dx dy]^T [1 dx dy], b = sum W f [1 dx dy] */
  double a01 = 0.0, a02 = 0.0, a11 = 0.0, a12 = 0.0, a22 = 0.0;
  for (long r = r0 - 1; r <= r0 + 1; r++) {
    if (r < 0 || r >= g->ny) continue;
    for (long k = 0; k < nc; k++) {
      const size_t cell = (size_t)(r * g->nx + cols[k]);
      for (size_t q = w->start[cell]; q < w->start[cell + 1]; q++) {
        const size_t j = w->idx[q];
        const double dx = sph_grid_min_image(x - p->x[j], g->period), dy = y - p->y[j];
        const double r2 = dx * dx + dy * dy, hj = p->h[j];
        if (r2 >= SPH_CUBIC_SUPPORT * SPH_CUBIC_SUPPORT * hj * hj) continue;
        const double wj = sph_cubic_w(sqrt(r2), hj);
        const double ex = -dx, ey = -dy; /* x_j - x */
        sw += wj;
        a01 += wj * ex;
        a02 += wj * ey;
        a11 += wj * ex * ex;
        a12 += wj * ex * ey;
        a22 += wj * ey * ey;
        for (int m = 0; m < nf; m++) {
          if (fmax && f[m][j] > fmax[m]) fmax[m] = f[m][j];
          sf[m] += wj * f[m][j];
          b1[m] += wj * ex * f[m][j];
          b2[m] += wj * ey * f[m][j];
        }
      }
    }
  }
  if (!(sw > 0.0)) return 0;
  for (int m = 0; m < nf; m++) {
    fit[3 * m] = sf[m] / sw;
    fit[3 * m + 1] = fit[3 * m + 2] = 0.0;
  }
  /* solve [sw a01 a02; a01 a11 a12; a02 a12 a22] c = b by Cramer's rule */
  const double det =
      sw * (a11 * a22 - a12 * a12) - a01 * (a01 * a22 - a12 * a02) + a02 * (a01 * a12 - a11 * a02);
  const double scale = sw * a11 * a22;
  if (scale > 0.0 && fabs(det) > 1e-3 * scale) {
    const double c00 = a11 * a22 - a12 * a12, c01 = -(a01 * a22 - a02 * a12),
                 c02 = a01 * a12 - a02 * a11;
    const double c11 = sw * a22 - a02 * a02, c12 = -(sw * a12 - a01 * a02),
                 c22 = sw * a11 - a01 * a01;
    for (int m = 0; m < nf; m++) {
      fit[3 * m] = (c00 * sf[m] + c01 * b1[m] + c02 * b2[m]) / det;
      fit[3 * m + 1] = (c01 * sf[m] + c11 * b1[m] + c12 * b2[m]) / det;
      fit[3 * m + 2] = (c02 * sf[m] + c12 * b1[m] + c22 * b2[m]) / det;
    }
  }
  return 1;
}

/* The fluid particles of p binned by cell into w (cells at least
 * `support` wide, and not many more than particles), the layout into *gp.
 * 0, 1 when there is no fluid (nothing to fit), or -1 (err). */
static int bin_fluid(const sph_particles *p, double support, double px0, double period, layout *gp,
                     sph_wall_velocity_work *w, sph_error *err) {
  const size_t n = p->n;
  double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
  size_t nf = 0;
  for (size_t i = 0; i < n; i++) {
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    nf++;
    if (p->x[i] < xlo) xlo = p->x[i];
    if (p->x[i] > xhi) xhi = p->x[i];
    if (p->y[i] < ylo) ylo = p->y[i];
    if (p->y[i] > yhi) yhi = p->y[i];
  }
  if (nf == 0) return 1; /* no fluid: nothing to fit */
  /* cells at least `support` wide, and not many more than particles */
  double cell = support;
  *gp = (layout){xlo, ylo, cell, cell, period > 0.0 ? period : 0.0, 1, 1};
  layout g = *gp;
  for (;;) {
    g.cy = cell;
    if (g.period > 0.0) {
      g.x0 = px0;
      g.nx = (long)floor(g.period / cell);
      if (g.nx < 1) g.nx = 1;
      g.cx = g.period / (double)g.nx;
    } else {
      g.cx = cell;
      g.nx = (long)floor((xhi - xlo) / cell) + 1;
    }
    g.ny = (long)floor((yhi - ylo) / cell) + 1;
    if ((double)g.nx * (double)g.ny <= 4.0 * (double)nf + 64.0) break;
    cell *= 2.0;
  }
  const size_t cells = (size_t)(g.nx * g.ny);
  if (cells + 1 > w->cap_cells) {
    size_t *a = realloc(w->start, (cells + 1) * sizeof *a);
    if (!a) return sph_error_set(err, "wall velocity: out of memory for %zu cells", cells);
    w->start = a;
    w->cap_cells = cells + 1;
  }
  if (n > w->cap_n) {
    uint32_t *a = realloc(w->idx, n * sizeof *a);
    if (a) w->idx = a;
    size_t *b = a ? realloc(w->key, n * sizeof *b) : NULL;
    if (!b) return sph_error_set(err, "wall velocity: out of memory for %zu particles", n);
    w->key = b;
    w->cap_n = n;
  }
  /* counting sort of the fluid particles by cell, stable */
  for (size_t c = 0; c <= cells; c++)
    w->start[c] = 0;
  for (size_t i = 0; i < n; i++) {
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    w->key[i] = (size_t)(row(&g, p->y[i]) * g.nx + column(&g, p->x[i]));
    w->start[w->key[i] + 1]++;
  }
  for (size_t c = 0; c < cells; c++)
    w->start[c + 1] += w->start[c];
  for (size_t i = 0; i < n; i++)
    if (p->kind[i] == SPH_KIND_FLUID) w->idx[w->start[w->key[i]]++] = (uint32_t)i;
  for (size_t c = cells; c > 0; c--)
    w->start[c] = w->start[c - 1];
  w->start[0] = 0;
  *gp = g;
  return 0;
}

int sph_wall_velocity(const sph_particles *p, double support, double px0, double period,
                      double *gvx, double *gvy, sph_wall_velocity_work *w, sph_error *err) {
#if SPH_DIM == 3 /* the fit below is the 2-D one (three unknowns) */
  (void)p, (void)support, (void)px0, (void)period, (void)gvx, (void)gvy, (void)w;
  return sph_error_set(err, "wall velocity: extrapolated wall velocities are 2-D only so far");
#endif
  const size_t n = p->n;
  for (size_t i = 0; i < n; i++) {
    gvx[i] = p->vx[i];
    gvy[i] = p->vy[i];
  }
  layout g;
  const int rc = bin_fluid(p, support, px0, period, &g, w, err);
  if (rc) return rc < 0 ? -1 : 0;
  const double *const fields[2] = {p->vx, p->vy};
  const long nl = (long)n;
#pragma omp parallel for schedule(dynamic, 256) if (nl > SPH_OMP_MIN)
  for (long li = 0; li < nl; li++) {
    const size_t i = (size_t)li;
    if (!(p->flags[i] & SPH_FLAG_NO_SLIP) || p->kind[i] != SPH_KIND_WALL) continue;
    double fit[6];
    if (fit_at(p, &g, w, p->x[i] + p->mx[i], p->y[i] + p->my[i], fields, 2, fit, NULL)) {
      gvx[i] = 2.0 * p->vx[i] - fit[0];
      gvy[i] = 2.0 * p->vy[i] - fit[3];
    }
  }
  return 0;
}

int sph_wall_mdbc_density(sph_particles *p, double support, double px0, double period, double rho0,
                          sph_wall_velocity_work *w, sph_error *err) {
#if SPH_DIM == 3 /* the fit below is the 2-D one (three unknowns) */
  (void)p, (void)support, (void)px0, (void)period, (void)rho0, (void)w;
  return sph_error_set(err, "wall velocity: mdbc wall densities are 2-D only so far");
#endif
  layout g;
  const int rc = bin_fluid(p, support, px0, period, &g, w, err);
  if (rc < 0) return -1;
  const double *const fields[1] = {p->rho};
  const long nl = (long)p->n;
#pragma omp parallel for schedule(dynamic, 256) if (nl > SPH_OMP_MIN)
  for (long li = 0; li < nl; li++) {
    const size_t i = (size_t)li;
    if (!(p->flags[i] & SPH_FLAG_MDBC) || p->kind[i] != SPH_KIND_WALL) continue;
    double fit[3], top = -INFINITY, rho = rho0;
    if (rc == 0 && fit_at(p, &g, w, p->x[i] + p->mx[i], p->y[i] + p->my[i], fields, 1, fit, &top)) {
      rho = fit[0] - (fit[1] * p->mx[i] + fit[2] * p->my[i]); /* the fit at the wall particle */
      if (rho > top) rho = top; /* no density the fluid around does not have */
    }
    p->rho[i] = rho > rho0 ? rho : rho0; /* a wall pushes, never pulls */
  }
  return 0;
}
