/*
 * grid.h - the cell-linked list ("dynamic grid" of paper A §2).
 *
 * Square cells of side >= the smoothing radius cover the particles' bounding
 * box. Building the grid sorts the particle store by cell with a stable
 * counting sort (row-major cell key), so particles of a cell are contiguous
 * and, within a cell, keep their previous relative order: the neighbour
 * order of every particle is a function of the state alone, never of the
 * thread count. The neighbours of a particle are the particles of the 3x3
 * block of cells around its own; because a row of three cells is one
 * contiguous range, a neighbour walk is three index ranges.
 */
#ifndef SPH_GRID_H
#define SPH_GRID_H

#include <stddef.h>

#include "error.h"
#include "particles.h"

typedef struct sph_grid {
  double x0, y0; /* lower-left corner of cell (0, 0) */
  double cell;   /* cell side (rows); columns are cellx wide */
  double cellx;  /* column width: = cell, or period/nx when periodic in x */
  int periodic;  /* columns wrap around (periodic in x) */
  long nx, ny;   /* cells per row, rows */
  size_t *start; /* nx*ny + 1 offsets into the sorted store */
  long *cx, *cy; /* cell coordinates of each particle (sorted order) */
  size_t cap_cells, cap_particles;
  size_t *key, *perm, *count; /* scratch */
  void *work;                 /* scratch for permutation (8 bytes per particle) */
} sph_grid;

void sph_grid_init(sph_grid *g);
void sph_grid_free(sph_grid *g);

/* Sorts p by cell (cells of side `cell`) and fills the cell offsets. Fails
 * if the bounding box would need more than max_cells cells (particles far
 * apart: the caller's domain check should have caught it). */
int sph_grid_build(sph_grid *g, sph_particles *p, double cell, size_t max_cells,
                   sph_error *err);
/* The same for a domain periodic in x over [px0, px1): columns are
 * (px1 - px0)/nx >= cell wide (nx >= 3); a particle outside [px0, px1)
 * (by less than a period) is binned in the column of its periodic image. */
int sph_grid_build_periodic(sph_grid *g, sph_particles *p, double cell, double px0, double px1,
                            size_t max_cells, sph_error *err);

/* The three contiguous index ranges [lo[k], hi[k]) holding the neighbour
 * candidates of the particle stored at index i (rows below, same, above,
 * each spanning three cells) in a grid that is not periodic. Rows outside
 * the grid give empty ranges. */
static inline void sph_grid_ranges(const sph_grid *g, size_t i, size_t lo[3], size_t hi[3]) {
  const long cx = g->cx[i], cy = g->cy[i];
  const long xa = cx > 0 ? cx - 1 : 0;
  const long xb = cx + 1 < g->nx ? cx + 1 : g->nx - 1;
  for (int k = 0; k < 3; k++) {
    const long y = cy - 1 + k;
    if (y < 0 || y >= g->ny) {
      lo[k] = hi[k] = 0;
      continue;
    }
    lo[k] = g->start[y * g->nx + xa];
    hi[k] = g->start[y * g->nx + xb + 1];
  }
}

/* Any grid, periodic or not: up to SPH_GRID_RANGES contiguous index ranges [lo[k], hi[k]) holding the
 * neighbour candidates of the particle stored at index i: per row (below,
 * same, above) one range of three cells, or two when the row wraps around
 * a periodic seam. Unused and out-of-grid ranges are empty. */
#define SPH_GRID_RANGES 6
static inline void sph_grid_ranges_all(const sph_grid *g, size_t i, size_t lo[SPH_GRID_RANGES],
                                   size_t hi[SPH_GRID_RANGES]) {
  const long cx = g->cx[i], cy = g->cy[i], nx = g->nx;
  for (int k = 0; k < SPH_GRID_RANGES; k++) lo[k] = hi[k] = 0;
  for (int r = 0; r < 3; r++) {
    const long y = cy - 1 + r;
    if (y < 0 || y >= g->ny) continue;
    const size_t *row = g->start + y * nx;
    if (!g->periodic || nx <= 3) { /* nx <= 3 periodic: the whole row, once */
      const long xa = g->periodic ? 0 : (cx > 0 ? cx - 1 : 0);
      const long xb = g->periodic ? nx - 1 : (cx + 1 < nx ? cx + 1 : nx - 1);
      lo[2 * r] = row[xa];
      hi[2 * r] = row[xb + 1];
    } else if (cx == 0) { /* columns nx-1 | 0, 1 */
      lo[2 * r] = row[nx - 1];
      hi[2 * r] = row[nx];
      lo[2 * r + 1] = row[0];
      hi[2 * r + 1] = row[2];
    } else if (cx == nx - 1) { /* columns nx-2, nx-1 | 0 */
      lo[2 * r] = row[nx - 2];
      hi[2 * r] = row[nx];
      lo[2 * r + 1] = row[0];
      hi[2 * r + 1] = row[1];
    } else {
      lo[2 * r] = row[cx - 1];
      hi[2 * r] = row[cx + 2];
    }
  }
}

#endif
