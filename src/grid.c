/*
 * grid.c - cell-linked list with a stable counting sort (see grid.h).
 *
 * Build: (1) bounding box of all particles (min/max: exact, order-free);
 * (2) cell coordinates per particle; (3) counting sort by row-major key,
 * stable because particles are placed in increasing old index; (4) the
 * store is permuted into cell order. All steps are serial or per-particle,
 * so the result does not depend on the number of threads.
 */
#include "config.h"

#include "grid.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void sph_grid_init(sph_grid *g) { memset(g, 0, sizeof *g); }

void sph_grid_free(sph_grid *g) {
  free(g->start);
  free(g->cx);
  free(g->cy);
  free(g->key);
  free(g->perm);
  free(g->count);
  free(g->work);
  memset(g, 0, sizeof *g);
}

static int reserve(sph_grid *g, size_t n, size_t cells, sph_error *err) {
  if (n > g->cap_particles) {
    size_t cap = n + n / 4 + 16;
    void *a = realloc(g->cx, cap * sizeof *g->cx);
    if (a) g->cx = a;
    void *b = realloc(g->cy, cap * sizeof *g->cy);
    if (b) g->cy = b;
    void *c = realloc(g->key, cap * sizeof *g->key);
    if (c) g->key = c;
    void *d = realloc(g->perm, cap * sizeof *g->perm);
    if (d) g->perm = d;
    void *e = realloc(g->work, cap * 8);
    if (e) g->work = e;
    if (!a || !b || !c || !d || !e) return sph_error_set(err, "grid: out of memory for %zu particles", n);
    g->cap_particles = cap;
  }
  if (cells + 1 > g->cap_cells) {
    size_t cap = cells + 1 + cells / 4;
    void *a = realloc(g->start, cap * sizeof *g->start);
    if (a) g->start = a;
    void *b = realloc(g->count, cap * sizeof *g->count);
    if (b) g->count = b;
    if (!a || !b) return sph_error_set(err, "grid: out of memory for %zu cells", cells);
    g->cap_cells = cap;
  }
  return 0;
}

/* The shared build: bounding box in y (and in x unless periodic), keys,
 * stable counting sort, permutation. */
static int build(sph_grid *g, sph_particles *p, double cell, int periodic, double px0,
                 double px1, size_t max_cells, sph_error *err) {
  const size_t n = p->n;
  if (!(cell > 0.0)) return sph_error_set(err, "grid: cell size must be positive");
  double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
  for (size_t i = 0; i < n; i++) {
    if (p->x[i] < xmin) xmin = p->x[i];
    if (p->x[i] > xmax) xmax = p->x[i];
    if (p->y[i] < ymin) ymin = p->y[i];
    if (p->y[i] > ymax) ymax = p->y[i];
  }
  if (n == 0) xmin = xmax = ymin = ymax = 0.0;
  if (!isfinite(xmin) || !isfinite(xmax) || !isfinite(ymin) || !isfinite(ymax))
    return sph_error_set(err, "grid: particle position is not finite");
  double cellx = cell;
  if (periodic) {
    /* between the two stages of a step particles may stand up to one step's
     * travel outside the period; further is an error */
    if (xmin < px0 - (px1 - px0) || xmax >= px1 + (px1 - px0))
      return sph_error_set(err, "grid: a particle is more than a period outside [%g, %g)", px0,
                           px1);
    const double ncol = floor((px1 - px0) / cell);
    if (ncol < 3)
      return sph_error_set(err, "grid: the period %g holds fewer than 3 cells of %g", px1 - px0,
                           cell);
    xmin = px0;
    xmax = px1;
    cellx = (px1 - px0) / ncol;
  }
  const double fx = periodic ? floor((px1 - px0) / cell) : floor((xmax - xmin) / cell) + 1.0;
  const double fy = floor((ymax - ymin) / cell) + 1.0;
  if (fx * fy > (double)max_cells)
    return sph_error_set(err, "grid: particles spread over %.0f x %.0f cells (limit %zu)", fx, fy,
                         max_cells);
  g->x0 = xmin;
  g->y0 = ymin;
  g->cell = cell;
  g->cellx = cellx;
  g->periodic = periodic;
  g->nx = (long)fx;
  g->ny = (long)fy;
  const size_t cells = (size_t)g->nx * (size_t)g->ny;
  if (reserve(g, n, cells, err)) return -1;

  const double inv = 1.0 / cell, invx = 1.0 / cellx;
  for (size_t i = 0; i < n; i++) {
    long cx = (long)floor((p->x[i] - xmin) * invx);
    long cy = (long)((p->y[i] - ymin) * inv);
    if (periodic) cx = ((cx % g->nx) + g->nx) % g->nx;
    if (cx >= g->nx) cx = g->nx - 1;
    if (cy >= g->ny) cy = g->ny - 1;
    g->key[i] = (size_t)cy * (size_t)g->nx + (size_t)cx;
  }
  /* stable counting sort by key */
  memset(g->count, 0, (cells + 1) * sizeof *g->count);
  for (size_t i = 0; i < n; i++) g->count[g->key[i] + 1]++;
  for (size_t c = 0; c < cells; c++) g->count[c + 1] += g->count[c];
  memcpy(g->start, g->count, (cells + 1) * sizeof *g->start);
  for (size_t i = 0; i < n; i++) g->perm[g->count[g->key[i]]++] = i;
  sph_particles_permute(p, g->perm, g->work);
  for (size_t c = 0; c < cells; c++)
    for (size_t i = g->start[c]; i < g->start[c + 1]; i++) {
      g->cx[i] = (long)(c % (size_t)g->nx);
      g->cy[i] = (long)(c / (size_t)g->nx);
    }
  return 0;
}

int sph_grid_build(sph_grid *g, sph_particles *p, double cell, size_t max_cells,
                   sph_error *err) {
  return build(g, p, cell, 0, 0.0, 0.0, max_cells, err);
}

int sph_grid_build_periodic(sph_grid *g, sph_particles *p, double cell, double px0, double px1,
                            size_t max_cells, sph_error *err) {
  return build(g, p, cell, 1, px0, px1, max_cells, err);
}
