/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * grid.c - cell-linked list with a stable counting sort (see grid.h).
 *
 * Build: (1) bounding box of all particles (min/max: exact, order-free);
 * (2) global cell coordinates per particle (floor(x / cell): the same
 * cell whatever the box); (3) counting sort by row-major key, stable
 * because particles are placed in increasing old index (in parallel, one
 * histogram per thread: the same order); (4) when the store is to be
 * sorted, each cell's particles in increasing id, so that the order no
 * longer depends on the old one; (5) the store is permuted into that
 * order. All steps are serial, per-particle, per-cell or that sort, so
 * the result does not depend on the number of threads.
 */
#include "config.h"

#include "core/lanes.h"
#include "core/parallel.h"

#include "neighbours/grid.h"

#include "core/check.h"

#include "core/arrays.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void sph_grid_init(sph_grid *g) { memset(g, 0, sizeof *g); }

void sph_grid_orient(sph_grid *g, const sph_particles *p) {
  for (int d = 0; d < SPH_DIM; d++) {
    double a = 0.0, b = 0.0;
    for (size_t i = 0; i < p->n; i++) { /* min and max: exact in any order */
      const double x = p->pos[d][i];
      if (i == 0 || x < a) a = x;
      if (i == 0 || x > b) b = x;
    }
    g->orient_ext[d] = b - a;
  }
  g->oriented = 1;
}

void sph_grid_free(sph_grid *g) {
  free(g->start);
  free(g->count);
  free(g->hist);
  free(g->block);
  const int oriented = g->oriented;
  double ext[SPH_DIM];
  memcpy(ext, g->orient_ext, sizeof ext);
  memset(g, 0, sizeof *g);
  g->oriented = oriented; /* the directions outlive the buffers */
  memcpy(g->orient_ext, ext, sizeof ext);
}

/* Room for n particles and `cells` cells. Every per-particle array is
 * rewritten by the build that calls this, so a new block (arrays.h) keeps
 * nothing of the old one. */
static int reserve(sph_grid *g, size_t n, size_t cells, sph_error *err) {
  if (n > g->cap_particles) {
    const size_t cap = n + n / 4 + 16;
    void **arrays[3];
    size_t size[3], k = 0;
    size[k] = SPH_DIM * sizeof *g->cell_of[0], arrays[k++] = (void **)&g->cell_of[0];
    size[k] = sizeof *g->key, arrays[k++] = (void **)&g->key;
    size[k] = sizeof *g->perm, arrays[k++] = (void **)&g->perm;
    if (sph_arrays_regrow(&g->block, cap, 0, k, size, arrays, NULL))
      return sph_error_set(err, "grid: out of memory for %zu particles", n);
    for (int d = 1; d < SPH_DIM; d++)
      g->cell_of[d] = g->cell_of[0] + (size_t)d * cap;
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

/* Stable counting sort of 0..n-1 by g->key into g->perm, and the cells'
 * offsets g->start. Serially, or (a team of several threads, and no more
 * cells than particles) with one histogram per thread over its contiguous
 * slice of the particles: cell by cell, thread t's particles come after
 * those of threads before it, each thread's in increasing index, so the
 * order is the serial sort's, whatever the team. */
static int counting_sort(sph_grid *g, size_t n, size_t cells, sph_error *err) {
  const uint32_t *restrict key = g->key;
  size_t *restrict perm = g->perm;
  const int team = sph_team_size(n);
  if (team <= 1 || cells > n) {
    memset(g->count, 0, (cells + 1) * sizeof *g->count);
    for (size_t i = 0; i < n; i++)
      g->count[key[i] + 1]++;
    for (size_t c = 0; c < cells; c++)
      g->count[c + 1] += g->count[c];
    memcpy(g->start, g->count, (cells + 1) * sizeof *g->start);
    for (size_t i = 0; i < n; i++)
      perm[g->count[key[i]]++] = i;
    return 0;
  }
  const size_t need = (size_t)team * cells;
  if (need > g->cap_hist) {
    void *a = realloc(g->hist, need * sizeof *g->hist);
    if (!a) return sph_error_set(err, "grid: out of memory for %zu cell counts", need);
    g->hist = a;
    g->cap_hist = need;
  }
  size_t *restrict hist = g->hist;
#pragma omp parallel if ((long)n > SPH_OMP_MIN)
  {
    const int t = sph_thread(), nt = sph_threads();
    size_t *restrict h = hist + (size_t)t * cells;
    size_t lo, hi;
    sph_slice(NULL, n, &lo, &hi);
    memset(h, 0, cells * sizeof *h);
    for (size_t i = lo; i < hi; i++)
      h[key[i]]++;
#pragma omp barrier
#pragma omp single
    { /* each count becomes its thread's first place in its cell */
      size_t run = 0;
      for (size_t c = 0; c < cells; c++) {
        g->start[c] = run;
        for (int u = 0; u < nt; u++) {
          const size_t k = hist[(size_t)u * cells + c];
          hist[(size_t)u * cells + c] = run;
          run += k;
        }
      }
      g->start[cells] = run;
    }
    for (size_t i = lo; i < hi; i++)
      perm[h[key[i]]++] = i;
  }
  return 0;
}

/* Each cell's run of g->perm in increasing id (insertion sort: a cell
 * holds a few particles, mostly in id order already from the last sort),
 * ties (equal ids: a store whose ids are not unique) kept in the stable
 * order. Cells are independent, so the result is the serial one. */
static void sort_cells_by_id(sph_grid *g, const int64_t *restrict id, size_t cells) {
  size_t *restrict perm = g->perm;
  const size_t *restrict start = g->start;
  const long lc = (long)cells;
#pragma omp parallel for schedule(static) if (lc > SPH_OMP_MIN)
  for (long c = 0; c < lc; c++)
    for (size_t k = start[c] + 1; k < start[c + 1]; k++) {
      const size_t v = perm[k];
      const int64_t key = id[v];
      size_t m = k;
      for (; m > start[c] && id[perm[m - 1]] > key; m--)
        perm[m] = perm[m - 1];
      perm[m] = v;
    }
}

/* The grid's directions (grid.h): the store's axes in increasing extent,
 * ties in axis order, the periodic axis (periodic - 1) first when periodic. */
static void choose_directions(const double ext[SPH_DIM], int periodic, int axis[SPH_DIM]) {
  int k0 = 0;
  if (periodic) axis[k0++] = periodic - 1;
  for (int d = 0; d < SPH_DIM; d++)
    if (d != periodic - 1) axis[k0++] = d;
  for (int d = periodic ? 2 : 1; d < SPH_DIM; d++) { /* insertion sort: stable */
    const int a = axis[d];
    int k = d;
    for (; k > (periodic ? 1 : 0) && ext[axis[k - 1]] > ext[a]; k--)
      axis[k] = axis[k - 1];
    axis[k] = a;
  }
}

/* The shared build: bounding box (along all axes but a periodic one), the
 * directions, keys, stable counting sort, and the permutation of the store
 * into that order with each cell's particles by id (p != NULL), or only
 * the cell lists in g->perm (p == NULL, the store read through q). */
static int build(sph_grid *g, sph_particles *p, const sph_particles *q, double cell, int periodic,
                 double px0, double px1, size_t max_cells, sph_error *err) {
  if (p) q = p;
  const size_t n = q->n;
  if (!(cell > 0.0)) return sph_error_set(err, "grid: cell size must be positive");
  double lo[SPH_DIM], hi[SPH_DIM];
  const long ln = (long)n;
  for (int d = 0; d < SPH_DIM; d++) {
    const double *restrict x = q->pos[d];
    double a = INFINITY, b = -INFINITY;
#pragma omp parallel for schedule(static) if (ln > SPH_OMP_MIN) reduction(min                      \
                                                                          : a) reduction(max       \
                                                                                         : b)
    for (long i = 0; i < ln; i++) {
      if (x[i] < a) a = x[i];
      if (x[i] > b) b = x[i];
    }
    if (n == 0) a = b = 0.0;
    if (!isfinite(a) || !isfinite(b))
      return sph_error_set(err, "grid: particle position is not finite");
    lo[d] = a, hi[d] = b;
  }
  double ext[SPH_DIM];
  for (int d = 0; d < SPH_DIM; d++)
    ext[d] = g->oriented ? g->orient_ext[d] : hi[d] - lo[d];
  int axis[SPH_DIM];
  choose_directions(ext, periodic, axis);
  double cellx = cell;
  const double inv = 1.0 / cell;
  /* the global cells the box spans along each direction: floor(x / cell)
   * is monotonic in x, so the box's ends give the least and the greatest */
  double c0[SPH_DIM], f[SPH_DIM];
  for (int d = 0; d < SPH_DIM; d++) {
    const double a = floor(lo[axis[d]] * inv), b = floor(hi[axis[d]] * inv);
    if (!(fabs(a) < 0x1p52 && fabs(b) < 0x1p52))
      return sph_error_set(err, "grid: a particle is %g cells of %g from the origin (at most 2^52)",
                           fmax(fabs(a), fabs(b)), cell);
    c0[d] = a;
    f[d] = b - a + 1.0;
  }
  if (periodic) {
    /* between the two stages of a step particles may stand up to one step's
     * travel outside the period; further is an error */
    if (lo[axis[0]] < px0 - (px1 - px0) || hi[axis[0]] >= px1 + (px1 - px0))
      return sph_error_set(err, "grid: a particle is more than a period outside [%g, %g)", px0,
                           px1);
    const double ncol = floor((px1 - px0) / cell);
    if (ncol < 2)
      return sph_error_set(err,
                           "grid: the period %g holds fewer than 2 cells of %g (the support, the "
                           "list's skin and a margin): expected a period of at least %g",
                           px1 - px0, cell, 2.0 * cell);
    cellx = (px1 - px0) / ncol;
    c0[0] = 0.0;
    f[0] = ncol;
  }
  double total = 1.0;
  int too_long = 0;
  for (int d = 0; d < SPH_DIM; d++) {
    total *= f[d];
    too_long |= f[d] > INT32_MAX;
  }
  if (total > (double)max_cells || total >= (double)UINT32_MAX || too_long)
#if SPH_DIM == 2
    return sph_error_set(err,
                         "grid: particles spread over %.0f x %.0f cells (limit %zu, at most 2^32 - "
                         "1, and 2^31 - 1 a side)",
                         f[0], f[1], max_cells);
#else
    return sph_error_set(err,
                         "grid: particles spread over %.0f x %.0f x %.0f cells (limit %zu, at most "
                         "2^32 - 1, and 2^31 - 1 a side)",
                         f[0], f[1], f[2], max_cells);
#endif
  for (int d = 0; d < SPH_DIM; d++) {
    g->axis[d] = axis[d];
    g->lo[d] = periodic && d == 0 ? px0 : c0[d] * cell;
    g->ncell[d] = (long)f[d];
  }
  g->cell = cell;
  g->cellx = cellx;
  g->periodic = periodic;
  const size_t cells = sph_grid_cells(g);
  if (reserve(g, n, cells, err)) return -1;

  const double invx = 1.0 / cellx;
  const double *restrict qx = q->pos[axis[0]], *restrict qy = q->pos[axis[1]];
  const long x0 = (long)c0[0], y0 = (long)c0[1];
  const long nx = g->ncell[0];
#if SPH_DIM == 3
  const double *restrict qz = q->pos[axis[2]];
  const long z0 = (long)c0[2];
  const long ny = g->ncell[1];
#endif
#pragma omp parallel for schedule(static) if (ln > SPH_OMP_MIN)
  for (long i = 0; i < ln; i++) {
    long cx;
    if (periodic) {
      cx = (long)floor((qx[i] - px0) * invx);
      cx = ((cx % nx) + nx) % nx;
    } else
      cx = (long)floor(qx[i] * inv) - x0;
    const long cy = (long)floor(qy[i] * inv) - y0;
#if SPH_DIM == 2
    g->key[i] = (uint32_t)((size_t)cy * (size_t)nx + (size_t)cx);
#else
    const long cz = (long)floor(qz[i] * inv) - z0;
    g->key[i] = (uint32_t)(((size_t)cz * (size_t)ny + (size_t)cy) * (size_t)nx + (size_t)cx);
#endif
  }
  if (counting_sort(g, n, cells, err)) return -1;
  if (p) sort_cells_by_id(g, p->id, cells);
  /* the cell of each storage index: binned only, the particle's own key;
   * sorted, the key of the particle moved there */
  /* (the scratch: cell_of, SPH_DIM x 4 >= 8 bytes a particle, written below) */
  if (p) sph_particles_permute(p, g->perm, sph_grid_scratch(g));
  const uint32_t *restrict key = g->key;
  const size_t *restrict perm = g->perm;
#pragma omp parallel for schedule(static) if (ln > SPH_OMP_MIN)
  for (long i = 0; i < ln; i++) {
    size_t k = p ? key[perm[i]] : key[i];
    for (int d = 0; d < SPH_DIM - 1; d++) {
      g->cell_of[d][i] = (int32_t)(k % (size_t)g->ncell[d]);
      k /= (size_t)g->ncell[d];
    }
    g->cell_of[SPH_DIM - 1][i] = (int32_t)k;
  }
  g->sorted = p != NULL;
  if (SPH_DEBUG) {
    const char *bad = sph_grid_check(g, n);
    SPH_INVARIANT(bad == NULL, "%s", bad);
  }
  return 0;
}

int sph_grid_build(sph_grid *g, sph_particles *p, double cell, size_t max_cells, sph_error *err) {
  return build(g, p, NULL, cell, 0, 0.0, 0.0, max_cells, err);
}

int sph_grid_build_periodic(sph_grid *g, sph_particles *p, double cell, int axis, double px0,
                            double px1, size_t max_cells, sph_error *err) {
  if (axis < 0 || axis >= SPH_DIM)
    return sph_error_set(err, "grid: periodic axis %d is not one of the %d axes", axis, SPH_DIM);
  return build(g, p, NULL, cell, 1 + axis, px0, px1, max_cells, err);
}

int sph_grid_bin(sph_grid *g, const sph_particles *p, double cell, int periodic, double px0,
                 double px1, size_t max_cells, sph_error *err) {
  if (periodic < 0 || periodic > SPH_DIM)
    return sph_error_set(err, "grid: periodic axis %d is not one of the %d axes", periodic - 1,
                         SPH_DIM);
  return build(g, NULL, p, cell, periodic, px0, px1, max_cells, err);
}

/* ---- the neighbour list ------------------------------------------------------------- */

void sph_nlist_init(sph_nlist *l) { memset(l, 0, sizeof *l); }

uint32_t *sph_nlist_spare_row(size_t entries) {
  static _Thread_local uint32_t *buf; /* one per thread, kept for the next call */
  static _Thread_local size_t cap;
  if (entries > cap) {
    uint32_t *a = realloc(buf, entries * sizeof *a);
    if (!a) { /* a few hundred bytes: the process has no memory left at all */
      fprintf(stderr, "sph: out of memory for a neighbour row of %zu entries\n", entries);
      abort();
    }
    buf = a;
    cap = entries;
  }
  return buf;
}

void sph_nlist_free(sph_nlist *l) {
  free(l->block);
  free(l->rows);
  free(l->dec);
  memset(l, 0, sizeof *l);
}

void sph_nlist_release(sph_nlist *l) {
  const int fluid_only = l->wall_fluid_only;
  const unsigned char *no_row = l->no_row;
  const size_t no_row_n = l->no_row_n;
  sph_nlist_free(l);
  l->wall_fluid_only = fluid_only;
  l->no_row = no_row, l->no_row_n = no_row_n;
}

/* The candidate ranges of particle i (sph_grid_ranges_all); with f (the fluid particles before
 * each place of the walk: a fluid-only wall row, fluid_before) those that hold no fluid
 * particle emptied: their entries would all be dropped (keep_fluid), so the row is the same
 * without their walk. */
static inline __attribute__((always_inline)) void fluid_ranges(const sph_grid *g, size_t i,
                                                               const uint32_t *restrict f,
                                                               size_t lo[SPH_GRID_RANGES],
                                                               size_t hi[SPH_GRID_RANGES]) {
  sph_grid_ranges_all(g, i, lo, hi);
  if (f)
    for (int k = 0; k < SPH_GRID_RANGES; k++)
      if (f[hi[k]] == f[lo[k]]) hi[k] = lo[k];
}

/* The candidates of particle i within sqrt(r2max), in the grid's walk
 * order (positions, or storage indices through perm when the grid is only
 * binned), into row (with row NULL: only counted); returns how many. The
 * row needs room for all i's candidates: each is written before the test
 * that keeps it. x holds the store's axes, the periodic one first (grid.h). */
static inline __attribute__((always_inline)) uint32_t
fill_row(const sph_grid *g, const double *const restrict *x, size_t i, double r2max, double period,
         uint32_t *restrict row, const int sorted, const uint32_t *restrict f) {
  size_t lo[SPH_GRID_RANGES], hi[SPH_GRID_RANGES];
  fluid_ranges(g, i, f, lo, hi);
  const size_t *restrict perm = g->perm;
  const double *restrict px = x[0], *restrict py = x[1];
  const double xi = px[i], yi = py[i];
#if SPH_DIM == 3
  const double *restrict pz = x[2];
  const double zi = pz[i];
#endif
  uint32_t c = 0;
  for (int k = 0; k < SPH_GRID_RANGES; k++)
    for (size_t pos = lo[k]; pos < hi[k]; pos++) {
      const size_t j = sorted ? pos : perm[pos];
      const double dx = sph_grid_min_image(xi - px[j], period), dy = yi - py[j];
      SPH_IF3(const double dz = zi - pz[j];)
      const double r2 = SPH_NORM2(dx, dy, dz);
      if (row) row[c] = (uint32_t)j; /* kept only if the next line counts it: no branch */
      c += (uint32_t)((r2 < r2max) & (j != i));
    }
  return c;
}

#ifdef SPH_LANES_AVX
/* fill_row four candidates at a time (AVX2): each candidate's separation
 * and r^2 are fill_row's operations in its own lane (the same bits, so the
 * same rows), the kept indices packed to the front in walk order
 * (v4x_pack32) and stored four at a time, the count advanced once per four;
 * a range's last candidates, fewer than four, one at a time as in fill_row.
 * The row needs room for all i's candidates, as fill_row's. */
static inline __attribute__((always_inline, target("avx2"))) uint32_t
fill_row_v4x(const sph_grid *g, const double *const restrict *x, size_t i, double r2max,
             double period, uint32_t *restrict row, const int sorted, const uint32_t *restrict f) {
  size_t lo[SPH_GRID_RANGES], hi[SPH_GRID_RANGES];
  fluid_ranges(g, i, f, lo, hi);
  const size_t *restrict perm = g->perm;
  const double *restrict px = x[0], *restrict py = x[1];
  const double xi = px[i], yi = py[i];
  const v4x xv = v4x_all(xi), yv = v4x_all(yi), rv = v4x_all(r2max);
  const v4x per = v4x_all(period), hper = v4x_all(0.5 * period), nper = v4x_all(-0.5 * period);
#if SPH_DIM == 3
  const double *restrict pz = x[2];
  const double zi = pz[i];
  const v4x zv = v4x_all(zi);
#endif
  const __m128i iv = _mm_set1_epi32((int)(uint32_t)i), step = _mm_set_epi32(3, 2, 1, 0);
  uint32_t c = 0;
  for (int k = 0; k < SPH_GRID_RANGES; k++) {
    size_t pos = lo[k];
    for (; pos + 4 <= hi[k]; pos += 4) {
      v4x xj, yj;
      __m128i jv;
      SPH_IF3(v4x zj;)
      if (sorted) {
        xj = _mm256_loadu_pd(px + pos);
        yj = _mm256_loadu_pd(py + pos);
        SPH_IF3(zj = _mm256_loadu_pd(pz + pos);)
        jv = _mm_add_epi32(_mm_set1_epi32((int)(uint32_t)pos), step);
      } else {
        const size_t j0 = perm[pos], j1 = perm[pos + 1], j2 = perm[pos + 2], j3 = perm[pos + 3];
        xj = v4x_set(px[j0], px[j1], px[j2], px[j3]);
        yj = v4x_set(py[j0], py[j1], py[j2], py[j3]);
        SPH_IF3(zj = v4x_set(pz[j0], pz[j1], pz[j2], pz[j3]);)
        jv = _mm_set_epi32((int)(uint32_t)j3, (int)(uint32_t)j2, (int)(uint32_t)j1,
                           (int)(uint32_t)j0);
      }
      v4x dx = v4x_sub(xv, xj);
      if (period > 0.0) dx = SPH_LANE_MIN_IMAGE(v4x, dx, per, hper, nper);
      const v4x dy = v4x_sub(yv, yj);
      v4x r2 = v4x_add(v4x_mul(dx, dx), v4x_mul(dy, dy));
      SPH_IF3(const v4x dz = v4x_sub(zv, zj); r2 = v4x_add(r2, v4x_mul(dz, dz));)
      const unsigned near = (unsigned)_mm256_movemask_pd(v4x_lt(r2, rv));
      const unsigned self = (unsigned)_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(jv, iv)));
      const unsigned m = near & ~self;
      if (row) _mm_storeu_si128((__m128i *)(row + c), v4x_pack32(jv, m));
      c += (uint32_t)__builtin_popcount(m);
    }
    for (; pos < hi[k]; pos++) {
      const size_t j = sorted ? pos : perm[pos];
      const double dx = sph_grid_min_image(xi - px[j], period), dy = yi - py[j];
      SPH_IF3(const double dz = zi - pz[j];)
      const double r2 = SPH_NORM2(dx, dy, dz);
      if (row) row[c] = (uint32_t)j;
      c += (uint32_t)((r2 < r2max) & (j != i));
    }
  }
  return c;
}

/* fill_any's choice with fill_row_v4x (a call per row: the build's loops
 * are compiled for any x86-64) */
static __attribute__((target("avx2"))) uint32_t
fill_any_v4x(const sph_grid *g, const double *const restrict *x, size_t i, double r2max,
             double period, uint32_t *restrict row, int sorted, const uint32_t *restrict f) {
  if (sorted && period <= 0.0) return fill_row_v4x(g, x, i, r2max, 0.0, row, 1, f);
  if (sorted) return fill_row_v4x(g, x, i, r2max, period, row, 1, f);
  if (period <= 0.0) return fill_row_v4x(g, x, i, r2max, 0.0, row, 0, f);
  return fill_row_v4x(g, x, i, r2max, period, row, 0, f);
}
#endif

/* fill_row on whichever of the four kinds of grid g is, each with a loop
 * of its own, free of tests that do not change along it (inlined where
 * row is a literal NULL, so the counting loop writes nothing). */
static inline __attribute__((always_inline)) uint32_t
fill_any(const sph_grid *g, const double *const restrict *x, size_t i, double r2max, double period,
         uint32_t *restrict row, int sorted, const uint32_t *restrict f) {
  if (sorted && period <= 0.0) return fill_row(g, x, i, r2max, 0.0, row, 1, f);
  if (sorted) return fill_row(g, x, i, r2max, period, row, 1, f);
  if (period <= 0.0) return fill_row(g, x, i, r2max, 0.0, row, 0, f);
  return fill_row(g, x, i, r2max, period, row, 0, f);
}

/* fill_any, or fill_any_v4x where wide (the processor has AVX2): the same rows. */
static inline __attribute__((always_inline)) uint32_t
fill_rows(const sph_grid *g, const double *const restrict *x, size_t i, double r2max, double period,
          uint32_t *restrict row, int sorted, int wide, const uint32_t *restrict f) {
#ifdef SPH_LANES_AVX
  if (wide) return fill_any_v4x(g, x, i, r2max, period, row, sorted, f);
#else
  (void)wide;
#endif
  return fill_any(g, x, i, r2max, period, row, sorted, f);
}

/* The candidates of particle i: the particles of its 3 x 3 (x 3) cells. */
static size_t candidates(const sph_grid *g, size_t i) {
  size_t lo[SPH_GRID_RANGES], hi[SPH_GRID_RANGES], c = 0;
  sph_grid_ranges_all(g, i, lo, hi);
  for (int k = 0; k < SPH_GRID_RANGES; k++)
    c += hi[k] - lo[k];
  return c;
}

/* Sorts the c entries of row by insertion: linear on the nearly sorted
 * rows of a binned or periodic grid. */
static void sort_row(uint32_t *row, uint32_t c) {
  for (uint32_t a = 1; a < c; a++) {
    const uint32_t v = row[a];
    uint32_t b = a;
    for (; b > 0 && row[b - 1] > v; b--)
      row[b] = row[b - 1];
    row[b] = v;
  }
}

/* The entries of a run that starts at row[k] (of c increasing entries):
 * up to SPH_NLIST_RUN_MAX, all within row[k] + SPH_NLIST_RUN_MAX. */
static inline uint32_t run_length(const uint32_t *row, uint32_t k, uint32_t c) {
  uint32_t m = 1;
  while (k + m < c && m < SPH_NLIST_RUN_MAX && row[k + m] - row[k] <= SPH_NLIST_RUN_MAX)
    m++;
  return m;
}

/* Whether c entries from lo to hi (the least and the largest) make one run. */
static inline int one_run(uint32_t lo, uint32_t hi, uint32_t c) {
  return c <= SPH_NLIST_RUN_MAX && hi - lo <= SPH_NLIST_RUN_MAX;
}

/* The bytes of the runs (grid.h; in 2-D four an entry) of the c entries of row, increasing
 * when `in_order`, else in any order: one run when they span at most SPH_NLIST_RUN_MAX (and are
 * as many at most), else row is sorted first (as fill_sorted would) and its runs counted. */
static size_t runs_size(uint32_t *row, uint32_t c, int in_order) {
  if (!SPH_NLIST_RUNS) return 4 * (size_t)c;
  if (c == 0) return 0;
  uint32_t lo = row[0], hi = row[c - 1];
  if (!in_order)
    for (uint32_t k = 0; k < c; k++) {
      lo = row[k] < lo ? row[k] : lo;
      hi = row[k] > hi ? row[k] : hi;
    }
  if (one_run(lo, hi, c)) return SPH_NLIST_RUN_HEAD + 2 * (size_t)c;
  sort_row(row, c);
  size_t b = 0;
  for (uint32_t k = 0; k < c;) {
    const uint32_t m = run_length(row, k, c);
    b += SPH_NLIST_RUN_HEAD + 2 * (size_t)m;
    k += m;
  }
  return b;
}

/* Writes the runs of a row of c increasing entries at out (runs_size bytes). */
static void runs_write(const uint32_t *row, uint32_t c, uint8_t *restrict out) {
  if (!SPH_NLIST_RUNS) {
    if (c) memcpy(out, row, 4 * (size_t)c); /* (out may be NULL for an empty row: E14's twin) */
    return;
  }
  /* (one run, the common row, without run_length's walk) */
  const int one = c > 0 && one_run(row[0], row[c - 1], c);
  for (uint32_t k = 0; k < c;) {
    const uint32_t m = one ? c : run_length(row, k, c), base = row[k];
    const uint16_t m16 = (uint16_t)m;
    memcpy(out, &m16, sizeof m16);
    memcpy(out + 2, &base, sizeof base);
    uint16_t *restrict o = (uint16_t *)(void *)(out + SPH_NLIST_RUN_HEAD); /* 2-byte aligned */
    for (uint32_t q = 0; q < m; q++)
      o[q] = (uint16_t)(row[k + q] - base);
    out += SPH_NLIST_RUN_HEAD + 2 * (size_t)m;
    k += m;
  }
}

/* Whether particle i's row holds its fluid neighbours only: a wall
 * particle's where l->wall_fluid_only is set (grid.h). */
static inline int fluid_only_row(const sph_nlist *l, const sph_particles *p, size_t i) {
  return l->wall_fluid_only && p->kind[i] != SPH_KIND_FLUID;
}

/* Keeps the fluid particles among row's c entries, in order; returns how
 * many (the rows fluid_only_row names). */
static inline uint32_t keep_fluid(uint32_t *restrict row, uint32_t c,
                                  const int32_t *restrict kind) {
  uint32_t m = 0;
  for (uint32_t k = 0; k < c; k++) {
    row[m] = row[k];
    m += (uint32_t)(kind[row[k]] == SPH_KIND_FLUID);
  }
  return m;
}

/* Row i's entries within sqrt(r2max) in increasing storage index into
 * row (room for all i's candidates); returns their number. */
static inline uint32_t fill_sorted(const sph_grid *g, const double *const *x, size_t i,
                                   double r2max, double period, uint32_t *restrict row, int sorted,
                                   int wide, const uint32_t *restrict f) {
  const uint32_t c = fill_rows(g, x, i, r2max, period, row, sorted, wide, f);
  /* increasing storage index: already so on a sorted grid that is not
   * periodic (rows below, same, above in key order) */
  if (!sorted || period > 0.0) sort_row(row, c);
  return c;
}

/* Room for the per-particle arrays of a list of n particles (every row
 * array is rewritten by the build: nothing to keep). */
static int reserve_list(sph_nlist *l, size_t n, sph_error *err) {
  if (n + 1 <= l->cap_n) return 0;
  const size_t cap = n + 1 + n / 4 + 16;
  void **arrays[2 * SPH_DIM + 3];
  size_t size[2 * SPH_DIM + 3], k = 0;
  size[k] = sizeof *l->off, arrays[k++] = (void **)&l->off;
  size[k] = sizeof *l->count, arrays[k++] = (void **)&l->count;
  for (int d = 0; d < SPH_DIM; d++) {
    size[k] = sizeof *l->ref[d], arrays[k++] = (void **)&l->ref[d];
    size[k] = sizeof *l->exact[d], arrays[k++] = (void **)&l->exact[d];
  }
  size[k] = sizeof *l->cost, arrays[k++] = (void **)&l->cost;
  if (sph_arrays_regrow(&l->block, cap, 0, k, size, arrays, NULL))
    return sph_error_set(err, "grid: out of memory for the neighbour list of %zu particles", n);
  l->cap_n = cap;
  return 0;
}

/* With fluid-only wall rows: the fluid particles before each position of g's walk (n + 1
 * counts), so that a wall particle's fill walks only the candidate ranges that hold fluid
 * (fluid_ranges): none for a dry one (SPHERIC Test 2: most of the tank's and the box's wall
 * particles are dry at any time), fewer for a wet one. NULL where rows are not fluid-only;
 * *no set if out of memory. */
static uint32_t *fluid_before(const sph_nlist *l, const sph_grid *g, const sph_particles *p,
                              int *no) {
  if (!l->wall_fluid_only) return NULL;
  const size_t n = p->n;
  uint32_t *f = malloc((n + 1) * sizeof *f);
  if (!f) {
    *no = 1;
    return NULL;
  }
  f[0] = 0;
  for (size_t pos = 0; pos < n; pos++) {
    const size_t j = g->sorted ? pos : g->perm[pos];
    f[pos + 1] = f[pos] + (uint32_t)(p->kind[j] == SPH_KIND_FLUID);
  }
  return f;
}

/* The first build sizes the rows first: grown chunk by chunk, the block
 * would be copied as it grows and (below glibc's mmap threshold, 32 MB)
 * leave the old copies resident, 10 MB more peak RSS on SPHERIC at dx =
 * 0.02 m. Later builds find the room of the earlier ones (a quarter to
 * spare). f: the fluid counts of fluid_before, or NULL. */
static int size_rows(sph_nlist *l, const sph_grid *g, const sph_particles *p,
                     const double *const *x, double r2max, double period, int sorted, int wide,
                     size_t cmax, const uint32_t *f, sph_error *err) {
  const long ln = (long)p->n;
  size_t total = 0;
  int no = 0;
#pragma omp parallel if (ln > SPH_OMP_MIN) reduction(+ : total) reduction(| : no)
  {
    uint32_t *restrict scratch = malloc((cmax + 1) * sizeof *scratch);
    if (!scratch) no = 1;
#pragma omp for schedule(static)
    for (long li = 0; li < ln; li++) {
      if (!scratch) continue;
      /* (in 2-D only counted: four bytes an entry whatever their order) */
      if (sph_nlist_empty_row(l, p, (size_t)li)) continue;
      const int keep = fluid_only_row(l, p, (size_t)li);
      uint32_t c =
          fill_rows(g, x, (size_t)li, r2max, period, SPH_NLIST_RUNS || keep ? scratch : NULL,
                    sorted, wide, keep ? f : NULL);
      if (keep) c = keep_fluid(scratch, c, p->kind);
      total += runs_size(scratch, c, sorted && period <= 0.0);
    }
    free(scratch);
  }
  if (no) return sph_error_set(err, "grid: out of memory for a scratch row");
  total += SPH_NLIST_SLACK;
  const size_t cap = total + total / 4 + 64;
  if (!(l->rows = malloc(cap)))
    return sph_error_set(err, "grid: out of memory for %zu bytes of neighbours", total);
  l->cap_rows = cap;
  return 0;
}

/* After the rows: the slack past them, the rows' write-out buffers
 * (longest row mc) and the rows' costs, the split of loops among threads. */
static int finish_rows(sph_nlist *l, const sph_particles *p, uint32_t mc, sph_error *err) {
  const size_t n = p->n;
  memset(l->rows + l->off[n], 0, SPH_NLIST_SLACK); /* read, never used, by sph_nlist_decode */
  const int threads = SPH_NLIST_RUNS ? sph_max_threads() : 0; /* (2-D rows are read in place) */
  const size_t stride = (size_t)mc + SPH_NLIST_SLACK;
  if (threads && stride * (size_t)threads > l->dec_stride * (size_t)l->dec_threads) {
    uint32_t *a = realloc(l->dec, stride * (size_t)threads * sizeof *a);
    if (!a) return sph_error_set(err, "grid: out of memory for the rows written out");
    l->dec = a;
  }
  l->dec_stride = stride;
  l->dec_threads = threads;
  l->cost[0] = 0; /* exact: integers */
  for (size_t i = 0; i < n; i++)
    l->cost[i + 1] = l->cost[i] + SPH_NLIST_ROW_COST +
                     (p->kind[i] == SPH_KIND_FLUID ? l->count[i] : l->count[i] / 2);
  return 0;
}

int sph_nlist_build(sph_nlist *l, const sph_grid *g, const sph_particles *p, double support,
                    double skin, double period, sph_error *err) {
  const size_t n = p->n;
  l->valid = 0;
  if (n > UINT32_MAX) return sph_error_set(err, "grid: %zu particles is too many for a list", n);
  if (reserve_list(l, n, err)) return -1;
  /* Rows are stored compactly: in 3-D as runs (grid.h), about two bytes
   * an entry, in 2-D four (doc/memory.md). One pass fills the rows in
   * chunks of SPH_NLIST_CHUNK: a thread fills a chunk's rows into a
   * scratch row as long as the most candidates (fill_row writes every
   * candidate before its test) and writes their runs into a buffer of its
   * own, then appends the buffer to the list in chunk order (an ordered
   * region: the list grows only there), so every distance is computed
   * once. */
  const double radius = support + skin, r2max = radius * radius;
  /* the axes with the periodic one first: fill_row takes the minimum image
   * along its first axis (in 2-D and without periodicity, the store's order) */
  const int paxis = g->periodic ? g->periodic - 1 : 0;
  const double *xs[SPH_DIM];
  xs[0] = p->pos[paxis];
  for (int d = 0, k = 1; d < SPH_DIM; d++)
    if (d != paxis) xs[k++] = p->pos[d];
  const double *const *x = xs;
  const int sorted = g->sorted;
#ifdef SPH_LANES_AVX
  const int wide = sph_cpu_has_avx2();
#else
  const int wide = 0;
#endif
  const long ln = (long)n;
  size_t cmax = 0; /* the most candidates of any particle: the scratch row */
#pragma omp parallel for schedule(static) if (ln > SPH_OMP_MIN) reduction(max : cmax)
  for (long li = 0; li < ln; li++) {
    const size_t c = candidates(g, (size_t)li);
    if (c > cmax) cmax = c;
  }
  int no_f = 0;
  uint32_t *f = fluid_before(l, g, p, &no_f); /* for size_rows and the fill below */
  if (no_f)
    return sph_error_set(err, "grid: out of memory for the fluid counts of %zu particles", n);
  if (l->cap_rows == 0 && size_rows(l, g, p, x, r2max, period, sorted, wide, cmax, f, err)) {
    free(f);
    return -1;
  }
  uint32_t mc = 0;
  double origin[SPH_DIM], off_by[SPH_DIM]; /* the reference positions' (grid.h) */
  for (int d = 0; d < SPH_DIM; d++)
    origin[d] = n ? p->pos[d][0] : 0.0, off_by[d] = 0.0;
  int oom = 0, full = 0; /* a thread's buffers; the list (in the ordered region) */
  size_t used = 0;       /* bytes appended (in the ordered region) */
  const long chunks = (ln + SPH_NLIST_CHUNK - 1) / SPH_NLIST_CHUNK;
  l->off[0] = 0;
#pragma omp parallel if (ln > SPH_OMP_MIN) reduction(max : mc, off_by[:SPH_DIM]) reduction(| : oom)
  {
    uint32_t *restrict scratch = malloc((cmax + 1) * sizeof *scratch);
    uint8_t *buf = NULL;
    size_t cap = 0;
    if (!scratch) oom = 1;
#pragma omp for ordered schedule(dynamic, 1)
    for (long ch = 0; ch < chunks; ch++) {
      const size_t a = (size_t)ch * SPH_NLIST_CHUNK,
                   b = a + SPH_NLIST_CHUNK < n ? a + SPH_NLIST_CHUNK : n;
      size_t bytes = 0;
      for (size_t i = a; i < b && !oom; i++) {
        const int keep = fluid_only_row(l, p, i);
        uint32_t c = sph_nlist_empty_row(l, p, i) ? 0
                                                  : fill_sorted(g, x, i, r2max, period, scratch,
                                                                sorted, wide, keep ? f : NULL);
        if (keep) c = keep_fluid(scratch, c, p->kind);
        const size_t sz = runs_size(scratch, c, 1);
        if (bytes + sz > cap) {
          const size_t nc = 2 * (bytes + sz) + 4096;
          uint8_t *nb = realloc(buf, nc);
          if (!nb) {
            oom = 1;
            break;
          }
          buf = nb, cap = nc;
        }
        runs_write(scratch, c, buf + bytes);
        bytes += sz;
        l->count[i] = c;
        l->off[i + 1] = bytes; /* from the chunk's start: moved to the list's below */
        if (c > mc) mc = c;
        if (skin > 0.0) /* in single precision from the origin, and how far off */
          for (int d = 0; d < SPH_DIM; d++) {
            const double r = p->pos[d][i] - origin[d];
            l->ref[d][i] = (float)r;
            const double e = fabs(r - (double)l->ref[d][i]); /* (exact: Sterbenz) */
            if (e > off_by[d]) off_by[d] = e;
          }
        else
          for (int d = 0; d < SPH_DIM; d++)
            l->exact[d][i] = p->pos[d][i];
      }
#pragma omp ordered
      if (!oom && !full) {
        const size_t need = used + bytes + SPH_NLIST_SLACK;
        if (need > l->cap_rows) {
          const size_t nc = need + need / 4 + 64;
          uint8_t *nr = realloc(l->rows, nc);
          if (nr)
            l->rows = nr, l->cap_rows = nc;
          else
            full = 1;
        }
        if (!full) {
          if (bytes) memcpy(l->rows + used, buf, bytes); /* buf is NULL for a chunk of empty rows */
          for (size_t i = a; i < b; i++)
            l->off[i + 1] += used;
          used += bytes;
        }
      }
    }
    free(scratch);
    free(buf);
  }
  free(f);
  if (oom) return sph_error_set(err, "grid: out of memory for a scratch row");
  if (full) return sph_error_set(err, "grid: out of memory for the neighbours' rows");
  if (finish_rows(l, p, mc, err)) return -1;
  l->maxcount = mc;
  double e2 = 0.0;
  for (int d = 0; d < SPH_DIM; d++) {
    l->origin[d] = origin[d];
    e2 += off_by[d] * off_by[d];
  }
  l->ref_err = sqrt(e2) * (1.0 + 1e-9); /* (rounded up) */
  l->n = n;
  l->radius = radius;
  l->skin = skin;
  l->period = period;
  l->paxis = paxis;
  l->order = p->order;
  l->builds++;
  static uint64_t serials; /* (every list's builds, counted together) */
  l->serial = __atomic_add_fetch(&serials, 1, __ATOMIC_RELAXED);
  l->valid = 1;
  if (SPH_DEBUG) {
    const char *bad = sph_nlist_check(l, p, support);
    SPH_INVARIANT(bad == NULL, "%s", bad);
  }
  return 0;
}

int sph_nlist_fresh(const sph_nlist *l, const sph_particles *p) {
  if (!l->valid || l->n != p->n || l->order != p->order) return 0;
  const long n = (long)p->n;
  const double *restrict x = p->x, *restrict y = p->y;
  SPH_IF3(const double *restrict z = p->z;)
  double d2 = 0.0;
  if (!(l->skin > 0.0)) { /* without a skin: fresh until the first move */
    const double *restrict xr = l->exact[0], *restrict yr = l->exact[1];
    SPH_IF3(const double *restrict zr = l->exact[2];)
#pragma omp parallel for schedule(static) if (n > SPH_OMP_MIN) reduction(max : d2)
    for (long i = 0; i < n; i++) {
      const double dx = sph_nlist_sep(l, 0, x[i], xr[i]), dy = sph_nlist_sep(l, 1, y[i], yr[i]);
      SPH_IF3(const double dz = sph_nlist_sep(l, 2, z[i], zr[i]);)
      const double d = SPH_NORM2(dx, dy, dz);
      if (d > d2) d2 = d;
    }
    return d2 == 0.0;
  }
  const float *restrict xr = l->ref[0], *restrict yr = l->ref[1];
  const double ox = l->origin[0], oy = l->origin[1];
#if SPH_DIM == 3
  const float *restrict zr = l->ref[2];
  const double oz = l->origin[2];
#endif
#pragma omp parallel if (n > SPH_OMP_MIN) reduction(max : d2)
  {
    size_t lo, hi;
    sph_slice(l->cost, p->n, &lo, &hi);
    for (size_t i = lo; i < hi; i++) {
      const double dx = sph_nlist_sep(l, 0, x[i] - ox, (double)xr[i]),
                   dy = sph_nlist_sep(l, 1, y[i] - oy, (double)yr[i]);
      SPH_IF3(const double dz = sph_nlist_sep(l, 2, z[i] - oz, (double)zr[i]);)
      const double d = SPH_NORM2(dx, dy, dz);
      if (d > d2) d2 = d;
    }
  }
  /* max displacement < skin/2: each move as computed, plus how far the
   * single-precision positions of the build are off (ref_err), with a
   * relative margin for the rounding of the sums */
  const double half = 0.5 * l->skin * (1.0 - 1e-6) - l->ref_err;
  return half > 0.0 && d2 < half * half;
}

/* ---- debug invariants ------------------------------------------------------------------ */

static char check_msg[256];

const char *sph_grid_check(const sph_grid *g, size_t n) {
  const size_t cells = sph_grid_cells(g);
  if (g->start[0] != 0 || g->start[cells] != n) {
    snprintf(check_msg, sizeof check_msg, "grid: cell offsets span %zu..%zu, not 0..%zu",
             g->start[0], g->start[cells], n);
    return check_msg;
  }
  for (size_t c = 0; c < cells; c++) {
    if (g->start[c + 1] < g->start[c]) {
      snprintf(check_msg, sizeof check_msg, "grid: cell %zu ends before it starts", c);
      return check_msg;
    }
    for (size_t pos = g->start[c]; pos < g->start[c + 1]; pos++) {
      const size_t i = g->sorted ? pos : g->perm[pos];
      size_t key = 0;
      if (i < n)
        for (int d = SPH_DIM - 1; d >= 0; d--)
          key = key * (size_t)g->ncell[d] + (size_t)g->cell_of[d][i];
      if (i >= n || key != c) {
        snprintf(check_msg, sizeof check_msg,
                 "grid: position %zu of cell %zu holds particle %zu of another cell", pos, c, i);
        return check_msg;
      }
    }
  }
  return NULL;
}

const char *sph_nlist_check(const sph_nlist *l, const sph_particles *p, double support) {
  const size_t n = p->n;
  const double r2 = support * support;
  uint32_t *row = malloc(((size_t)l->maxcount + SPH_NLIST_SLACK) * sizeof *row);
  if (!row) return "neighbour list: no memory to check it";
  for (size_t i = 0; i < n; i++) {
    const uint32_t c = l->count[i] > l->maxcount ? 0 : sph_nlist_decode(l, i, row);
    if (c != l->count[i]) {
      snprintf(check_msg, sizeof check_msg,
               "neighbour list: row %zu holds %u entries, not its count %u", i, c, l->count[i]);
      free(row);
      return check_msg;
    }
    for (uint32_t k = 0; k < l->count[i]; k++)
      if (row[k] >= n || row[k] == i || (k && row[k] <= row[k - 1]) ||
          (fluid_only_row(l, p, i) && p->kind[row[k]] != SPH_KIND_FLUID)) {
        snprintf(check_msg, sizeof check_msg,
                 "neighbour list: row %zu is not sorted or holds %u (or a wall) at entry %u", i,
                 row[k], k);
        free(row);
        return check_msg;
      }
  }
  const size_t stride = n > 20000 ? n / 2000 : 1;
  for (size_t i = 0; i < n; i += stride) {
    if (sph_nlist_empty_row(l, p, i)) continue; /* (left empty by the caller: none to miss) */
    sph_nlist_decode(l, i, row);
    size_t k = 0;
    for (size_t j = 0; j < n; j++) {
      const double dx = sph_nlist_sep(l, 0, p->x[i], p->x[j]);
      const double dy = sph_nlist_sep(l, 1, p->y[i], p->y[j]);
      SPH_IF3(const double dz = sph_nlist_sep(l, 2, p->z[i], p->z[j]);)
      const double r2ij = SPH_NORM2(dx, dy, dz);
      while (k < l->count[i] && row[k] < j)
        k++;
      if (j == i || !(r2ij < r2)) continue;
      if (fluid_only_row(l, p, i) && p->kind[j] != SPH_KIND_FLUID)
        continue; /* a wall row's walls: not listed (wall_fluid_only) */
      if (k == l->count[i] || row[k] != j) {
        snprintf(check_msg, sizeof check_msg,
                 "neighbour list: row %zu lacks particle %zu within the support", i, j);
        free(row);
        return check_msg;
      }
    }
  }
  free(row);
  return NULL;
}
