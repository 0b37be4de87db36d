/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * grid.h - the cell-linked list ("dynamic grid" of paper A §2).
 *
 * Square (cubic) cells of side >= the smoothing radius cover the particles'
 * bounding box. The cells are those of one global grid: cell k along an
 * axis holds floor(x / cell) = k (origin 0; a periodic axis counts its
 * columns from the period's start), whatever particles the box holds.
 * Building the grid sorts the particle store by cell with a counting sort
 * (row-major cell key over the global cell coordinates, the directions
 * fixed by sph_grid_orient), and within a cell by particle id: the storage
 * order after a build is a function of each particle's position and id
 * alone, so any subset of the particles (a rank's, with its ghosts) sorts
 * into the order the whole set gives it, whatever the previous order and
 * never depending on the thread count. The neighbours of a particle are
 * the particles of the 3x3 (3x3x3) block of cells around its own; because a
 * row of three cells is one contiguous range, a neighbour walk is three
 * (nine) index ranges.
 */
#ifndef SPH_GRID_H
#define SPH_GRID_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "core/dim.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/particles.h"

/* The grid's directions: direction 0 runs along a row of cells (consecutive
 * keys), direction SPH_DIM - 1 is the slowest. Each is one of the store's
 * axes (axis[k]): the axes in increasing extent of the particles' box, ties
 * in axis order, so rows run along the shortest side and the threads'
 * slices of the sorted store (whole rows, planes in 3-D) meet across the
 * longest; a periodic grid has its periodic axis as direction 0 (its rows wrap). In 2-D
 * that is rows along x unless the box is wider than tall. The extents are
 * those sph_grid_orient fixed (the case's particles at the start, so that a
 * restart and every subset sort alike), or else each build's own box. */
typedef struct sph_grid {
  int axis[SPH_DIM];          /* the store axis (SPH_AXIS_*) of each direction */
  int oriented;               /* 1: the directions come from orient_ext */
  double orient_ext[SPH_DIM]; /* the extents sph_grid_orient fixed, per store axis */
  double lo[SPH_DIM];         /* the lower corner of cell 0 along each direction */
  double cell;                /* cell side */
  double cellx;        /* cell width along direction 0: = cell, or period/ncell[0] when periodic */
  int periodic;        /* 0, or 1 + the store axis that wraps around: then direction 0 */
  int sorted;          /* the store is in cell order (sph_grid_build*); 0 after
                          sph_grid_bin: cell c holds perm[start[c]] .. perm[start[c+1]-1] */
  long ncell[SPH_DIM]; /* cells along each direction */
  size_t *start;       /* cells + 1 offsets into the sorted store */
  int32_t *cell_of[SPH_DIM]; /* the cell coordinate along each direction of the particle at each
                                storage index (each ncell below 2^31: the build checks); one
                                array of SPH_DIM x cap_particles, cell_of[d] its d-th part,
                                which is also the scratch of the store's permutation (the
                                coordinates are written after it): until 2026-11-28 a scratch
                                array of its own, 8 bytes a particle */
  size_t cap_cells, cap_particles;
  uint32_t *key;          /* scratch: each particle's cell (fewer than 2^32 cells: the build
                             checks; 64-bit until 2026-11-28) */
  size_t *perm, *count;   /* scratch */
  size_t *hist, cap_hist; /* scratch: one count per cell per thread */
  void *block;            /* the one allocation of cell_of, key and perm (arrays.h) */
} sph_grid;

/* Eight bytes a particle of scratch (for sph_particles_permute and the
 * like), for as many particles as the last build had: the cell
 * coordinates' array, which it overwrites (build the grid again before
 * walking it). */
static inline void *sph_grid_scratch(sph_grid *g) { return g->cell_of[0]; }

/* The number of cells. */
static inline size_t sph_grid_cells(const sph_grid *g) {
  size_t c = 1;
  for (int k = 0; k < SPH_DIM; k++)
    c *= (size_t)g->ncell[k];
  return c;
}
/* The period of a periodic grid (along its direction 0), 0 if it is not periodic. */
static inline double sph_grid_period(const sph_grid *g) {
  return g->periodic ? g->cellx * (double)g->ncell[0] : 0.0;
}

void sph_grid_init(sph_grid *g);
void sph_grid_free(sph_grid *g);
/* Fixes the grid's directions (above) from the extents of p's bounding box,
 * for every later build: the solver calls it once, on the case's particles
 * as set up, before the first build (and before a restart's state is
 * read), so the directions are a function of the case alone. */
void sph_grid_orient(sph_grid *g, const sph_particles *p);

/* Sorts p by cell (cells of side `cell`) and fills the cell offsets. Fails
 * if the bounding box would need more than max_cells cells (particles far
 * apart: the caller's domain check should have caught it). */
int sph_grid_build(sph_grid *g, sph_particles *p, double cell, size_t max_cells, sph_error *err);
/* The same for a domain periodic along store axis `axis` (SPH_AXIS_X; in
 * 3-D also Y or Z) over [px0, px1): columns are (px1 - px0)/nx >= cell wide
 * (nx >= 2: a pair within a cell of each other is then so through one image
 * only, its minimum image; with nx <= 3 a row is walked whole, each column
 * once); a particle outside [px0, px1) (by less than a period) is binned in
 * the column of its periodic image. */
int sph_grid_build_periodic(sph_grid *g, sph_particles *p, double cell, int axis, double px0,
                            double px1, size_t max_cells, sph_error *err);

/* Bins p by cell like sph_grid_build_periodic (periodic = 1 + its axis) or
 * sph_grid_build, without reordering the store: the cell lists are
 * positions into g->perm (the storage indices in cell order, stable), and
 * g->sorted = 0. Only sph_nlist_build reads such a grid. */
int sph_grid_bin(sph_grid *g, const sph_particles *p, double cell, int periodic, double px0,
                 double px1, size_t max_cells, sph_error *err);

/* The rows of cells around a particle's cell: 3 in 2-D (below, same,
 * above along direction 1), 9 in 3-D (direction 2 outer, direction 1 inner),
 * in increasing key order. */
#if SPH_DIM == 2
#define SPH_GRID_ROWS 3
#else
#define SPH_GRID_ROWS 9
#endif
/* The key of the first cell (along direction 0) of row r around the cell
 * c (its coordinates along each direction) of a grid of n cells along each
 * direction, or -1 when that row is outside the grid. */
static inline long sph_grid_row(const long c[SPH_DIM], const long n[SPH_DIM], int r) {
#if SPH_DIM == 2
  const long y = c[1] - 1 + r;
  if (y < 0 || y >= n[1]) return -1;
  return y * n[0];
#else
  const long y = c[1] - 1 + r % 3, z = c[2] - 1 + r / 3;
  if (y < 0 || y >= n[1] || z < 0 || z >= n[2]) return -1;
  return (z * n[1] + y) * n[0];
#endif
}
/* The cell coordinates of the particle at storage index i, and the grid's
 * cells per direction, as the row walks take them. */
static inline void sph_grid_cell_at(const sph_grid *g, size_t i, long c[SPH_DIM], long n[SPH_DIM]) {
  for (int d = 0; d < SPH_DIM; d++)
    c[d] = g->cell_of[d][i], n[d] = g->ncell[d];
}

/* The SPH_GRID_ROWS contiguous index ranges [lo[k], hi[k]) holding the
 * neighbour candidates of the particle stored at index i (each row spanning
 * three cells) in a grid that is not periodic. Rows outside the grid give
 * empty ranges. */
static inline void sph_grid_ranges(const sph_grid *g, size_t i, size_t lo[SPH_GRID_ROWS],
                                   size_t hi[SPH_GRID_ROWS]) {
  long c[SPH_DIM], n[SPH_DIM];
  sph_grid_cell_at(g, i, c, n);
  const long cx = c[0], nx = n[0];
  const long xa = cx > 0 ? cx - 1 : 0;
  const long xb = cx + 1 < nx ? cx + 1 : nx - 1;
  for (int k = 0; k < SPH_GRID_ROWS; k++) {
    const long row = sph_grid_row(c, n, k);
    if (row < 0) {
      lo[k] = hi[k] = 0;
      continue;
    }
    lo[k] = g->start[row + xa];
    hi[k] = g->start[row + xb + 1];
  }
}

/* x_i - x_j = d as the minimum image in a domain periodic over `period`
 * along its axis (period > 0); d unchanged when period is 0. The one helper
 * of the grid, the filters, free-surface detection and the repulsive force. */
static inline double sph_grid_min_image(double d, double period) {
  if (period > 0.0) {
    if (d > 0.5 * period)
      d -= period;
    else if (d < -0.5 * period)
      d += period;
  }
  return d;
}

/* Any grid, periodic or not: up to SPH_GRID_RANGES contiguous index ranges [lo[k], hi[k]) holding
 * the neighbour candidates of the particle stored at index i: per row one range of three cells,
 * or two when the row wraps around a periodic seam. Unused and out-of-grid ranges are empty. */
#define SPH_GRID_RANGES (2 * SPH_GRID_ROWS)
static inline void sph_grid_ranges_all(const sph_grid *g, size_t i, size_t lo[SPH_GRID_RANGES],
                                       size_t hi[SPH_GRID_RANGES]) {
  long c[SPH_DIM], n[SPH_DIM];
  sph_grid_cell_at(g, i, c, n);
  const long cx = c[0], nx = n[0];
  for (int k = 0; k < SPH_GRID_RANGES; k++)
    lo[k] = hi[k] = 0;
  for (int r = 0; r < SPH_GRID_ROWS; r++) {
    const long first = sph_grid_row(c, n, r);
    if (first < 0) continue;
    const size_t *row = g->start + first;
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

/* ---- the neighbour list (Verlet list) ------------------------------------------------
 *
 * For every particle i, the particles j != i that stood closer than
 * `radius` to it when the list was built, in increasing storage index (on
 * a sorted grid that is the grid's walk order, rows below, same, above, so
 * a sum over a row runs in the same order as over the grid's ranges).
 *
 * A row is stored as runs (bytes rows[off[i]] .. rows[off[i + 1] - 1]):
 * each run a 16-bit count c (1 .. SPH_NLIST_RUN_MAX), a 32-bit base index b
 * and c 16-bit offsets o_k, the entries b + o_k (numbers as the processor
 * stores them); a run holds the next entries of the row as long as they
 * stay within b + SPH_NLIST_RUN_MAX. A row of a sorted store spans two
 * rows of cells either side of its own (planes in 3-D), some thousands to
 * tens of thousands of indices, so it is one run at two bytes an entry, six
 * more a row: 3-D SPHERIC Test 2 at dx = 0.02 m, 74 entries a row, holds
 * its list in about 160 bytes a particle where four bytes an entry took
 * 297. sph_nlist_decode writes row i out as indices (increasing, count[i]
 * of them); the passes read rows that way. With wall_fluid_only set (3-D
 * dynamic walls at rest: sim's choice) a wall particle's row holds its
 * fluid neighbours only, so the dry walls' rows are empty.
 *
 * With radius = support + skin the list stays complete for the support
 * (every pair closer than `support` is in it) as long as no particle has
 * moved more than skin/2 since the build: |r_ij(now)| <= |r_ij(build)| + 2
 * max displacement. sph_nlist_fresh checks exactly that (a max over the
 * particles, exact in any order), so a list is reused across the stages and
 * steps of a run only while it is provably complete, and rebuilt (grid
 * sort + list) otherwise. Interaction loops still test r < support for
 * every listed pair, so which pairs interact never depends on the skin;
 * only the summation order does (the storage order of the last sort).
 */
/* The cost of a particle in a pass, in neighbour pairs: its row's length
 * (half of it for a wall particle, which sums only the continuity term and
 * the step rule's sigma) plus this much for the per-particle work (the
 * integrator's update, the row's final sums). Measured on the a/100 dam
 * break on 2 threads: with wall rows at full length the thread holding the
 * tank floor finished its interaction loops 0.85 s earlier in all (of
 * 17.5 s), halved 0.4-0.56 s. */
#define SPH_NLIST_ROW_COST 8
/* Rows per chunk of the list's fill loop: a thread fills a chunk's rows
 * into a buffer of its own and appends it to the list in chunk order. */
#define SPH_NLIST_CHUNK 256

typedef struct sph_nlist {
  int valid;         /* built, and the store not reordered since */
  int paxis;         /* the store axis that wraps (the grid's; 0 when none) */
  size_t n;          /* particles at the build */
  double radius;     /* list radius: support + skin */
  double skin;       /* radius - support */
  double period;     /* > 0: minimum image along axis paxis with this period */
  size_t *off;       /* n + 1 byte offsets of the rows' runs in rows */
  uint32_t *count;   /* neighbours of each particle */
  uint32_t maxcount; /* the longest row */
  uint8_t *rows;     /* the rows' runs (above), SPH_NLIST_SLACK bytes past the last */
  /* positions at the build (sph_nlist_ref): with a skin, less origin, in single
   * precision, ref_err the largest distance any is off (sph_nlist_fresh adds it to the
   * moves; 24 bytes a particle until 2026-11-28, 12 since); without a skin exactly, in
   * exact (a list without a skin is fresh until the first move, however small). Each set
   * is untouched (no resident memory) where the other is used. */
  float *ref[SPH_DIM];
  double *exact[SPH_DIM];
  double origin[SPH_DIM];
  double ref_err;
  uint64_t order;      /* the store's order count at the build (a reordered store is detected;
                          until 2026-11-28 each particle's id was kept, 8 bytes a particle) */
  int wall_fluid_only; /* set by the caller before a build: a wall particle's row holds its
                          fluid neighbours only (a fluid particle's every neighbour), for
                          schemes where a wall-wall pair adds +-0 to every sum of a wall row
                          (sim.c, wall_rows_fluid_only; doc/memory.md) */
  const unsigned char *no_row; /* set by the caller before a build, or NULL: the particles of
                                  id k < no_row_n with no_row[k] set get an empty row (a rank's
                                  ghosts beyond the reach of its own particles' chains of
                                  passes: solver/ranks.c); other rows list them as before */
  size_t no_row_n;
  size_t cap_n, cap_rows;
  uint32_t *dec;     /* per thread a row written out (sph_nlist_row): dec_stride entries each */
  size_t dec_stride; /* maxcount + SPH_NLIST_SLACK */
  int dec_threads;   /* threads it has room for */
  size_t *cost;    /* n + 1: prefix sums of the particles' costs (SPH_NLIST_ROW_COST), the split of
                      the loops over the store among threads (parallel.h) */
  void *block;     /* the one allocation of off ... cost (arrays.h) */
  long builds;     /* number of builds (statistics) */
  uint64_t serial; /* a number no other build of any list has had (0: none yet): what a
                      caller found from the rows holds while it is the same */
} sph_nlist;

void sph_nlist_init(sph_nlist *l);
void sph_nlist_free(sph_nlist *l);
/* Frees l's arrays and keeps what its caller set (wall_fluid_only,
 * no_row): an empty list that the next build fills as the first. */
void sph_nlist_release(sph_nlist *l);

/* Builds the list of p from g (built or binned on p's current positions
 * with cells of side >= radius) for pairs closer than radius = support +
 * skin; periodic grids take the minimum image along their periodic axis
 * with period = the grid's period (px1 - px0). */
int sph_nlist_build(sph_nlist *l, const sph_grid *g, const sph_particles *p, double support,
                    double skin, double period, sph_error *err);

/* 1 if the list built earlier on p is still complete for its support:
 * the same particles in the same storage order (the store's order count:
 * particles.h), every one
 * within skin/2 (less a rounding margin) of where it stood at the build,
 * or none moved at all (so a list without a skin is fresh until the first
 * move). */
int sph_nlist_fresh(const sph_nlist *l, const sph_particles *p);

/* The position along axis d of particle i at the build of l: exact
 * without a skin, within l->ref_err with one. */
static inline double sph_nlist_ref(const sph_nlist *l, int d, size_t i) {
  return l->skin > 0.0 ? l->origin[d] + (double)l->ref[d][i] : l->exact[d][i];
}

/* Debug invariants (src/core/check.h), run after every build in a build
 * with --enable-debug-checks and by tests/test_checks.c: NULL if they hold,
 * else what is broken (a static buffer).
 * sph_grid_check: the cell offsets cover the n particles once, in order,
 * and every particle sits in the cell its position gives.
 * sph_nlist_check: every row is sorted by storage index (no i, no index
 * twice, none out of range) and holds every particle closer than
 * `support` (all pairs up to 20 000 particles, a sample of rows above). */
const char *sph_grid_check(const sph_grid *g, size_t n);
const char *sph_nlist_check(const sph_nlist *l, const sph_particles *p, double support);

/* x_i - x_j along store axis a as the list l measures it: the minimum
 * image along its periodic axis (in 2-D only x wraps). */
static inline double sph_nlist_sep(const sph_nlist *l, int a, double xi, double xj) {
#if SPH_DIM == 2
  return a ? xi - xj : sph_grid_min_image(xi - xj, l->period);
#else
  return a == l->paxis ? sph_grid_min_image(xi - xj, l->period) : xi - xj;
#endif
}

/* Whether rows are stored as runs: in 3-D. A 2-D row holds some 28
 * entries, and four bytes each, 112 a particle, are a small part of its
 * memory; reading them through runs cost 2-11 % more instructions on the
 * shipped 2-D cases (bench/regress), so 2-D rows are plain indices, off[i]
 * = 4 x the entries before row i. */
#if SPH_DIM == 3
#define SPH_NLIST_RUNS 1
#else
#define SPH_NLIST_RUNS 0
#endif
/* The most entries of a run and the largest offset in it; the bytes of a
 * run's count and base; bytes past a row that sph_nlist_decode may read,
 * and entries past a written-out row it may write. */
#define SPH_NLIST_RUN_MAX 65535u
#define SPH_NLIST_RUN_HEAD 6
#define SPH_NLIST_SLACK 16

/* Writes row i of l out as its count[i] storage indices in increasing
 * order into out, which has room for count[i] + SPH_NLIST_SLACK entries
 * (the entries past count[i] are scratch); returns how many it wrote
 * (count[i] in a list that is not corrupt). */
static inline uint32_t sph_nlist_decode(const sph_nlist *l, size_t i, uint32_t *restrict out) {
  const uint8_t *restrict s = l->rows + l->off[i], *const e = l->rows + l->off[i + 1];
  if (!SPH_NLIST_RUNS) {
    memcpy(out, s, (size_t)(e - s));
    return (uint32_t)((size_t)(e - s) / 4);
  }
  uint32_t n = 0;
  while (s < e) {
    uint16_t c16;
    uint32_t base;
    memcpy(&c16, s, sizeof c16);
    memcpy(&base, s + 2, sizeof base);
    const uint32_t c = c16;
    s += SPH_NLIST_RUN_HEAD;
#ifdef __SSE2__ /* eight entries at a time: offsets widened to 32 bits, the base added */
    const __m128i b = _mm_set1_epi32((int)base), zero = _mm_setzero_si128();
    for (uint32_t k = 0; k < c; k += 8) {
      const __m128i v = _mm_loadu_si128((const __m128i *)(const void *)(s + 2 * k));
      __m128i *o = (__m128i *)(void *)(out + n + k);
      _mm_storeu_si128(o, _mm_add_epi32(_mm_unpacklo_epi16(v, zero), b));
      _mm_storeu_si128(o + 1, _mm_add_epi32(_mm_unpackhi_epi16(v, zero), b));
    }
#else
    for (uint32_t k = 0; k < c; k++) {
      uint16_t o;
      memcpy(&o, s + 2 * k, sizeof o);
      out[n + k] = base + o;
    }
#endif
    s += 2 * (size_t)c;
    n += c;
  }
  return n;
}

/* A buffer of the calling thread for `entries` indices, for a team larger
 * than the one the list was built for (grid.c: kept per thread, grown as
 * needed; the program stops with a message if there is no memory for it). */
uint32_t *sph_nlist_spare_row(size_t entries);

/* Whether particle i's row is left empty: its id is one the caller named
 * in l->no_row. */
static inline int sph_nlist_empty_row(const sph_nlist *l, const sph_particles *p, size_t i) {
  if (!l->no_row) return 0;
  const int64_t id = p->id[i];
  return id >= 0 && (uint64_t)id < l->no_row_n && l->no_row[id];
}

/* Row i of l written out (sph_nlist_decode) into the calling thread's
 * buffer in l (in 2-D the row in place), its length in *cnt: valid until
 * the same thread's next call. A thread beyond those the list has buffers
 * for (a team made larger after the build) writes into a buffer of its
 * own (sph_nlist_spare_row). */
static inline const uint32_t *sph_nlist_row(const sph_nlist *l, size_t i, size_t *cnt) {
  if (!SPH_NLIST_RUNS) { /* the row in place */
    *cnt = l->count[i];
    return (const uint32_t *)(const void *)(l->rows + l->off[i]);
  }
  const int t = sph_thread();
  uint32_t *out =
      t < l->dec_threads ? l->dec + (size_t)t * l->dec_stride : sph_nlist_spare_row(l->dec_stride);
  *cnt = sph_nlist_decode(l, i, out);
  return out;
}

/* Row i of l as the loops that cut it read it: its one run in place (o
 * non-NULL: the entries base + o[k]) or, when it has more, written out
 * (sph_nlist_row: the entries e[k]); len entries. */
typedef struct sph_nlist_view {
  const uint16_t *o;
  const uint32_t *e;
  uint32_t base;
  size_t len;
} sph_nlist_view;
static inline sph_nlist_view sph_nlist_view_of(const sph_nlist *l, size_t i) {
  sph_nlist_view v = {NULL, NULL, 0, l->count[i]};
  const uint8_t *s = l->rows + l->off[i];
  if (!SPH_NLIST_RUNS) {
    v.e = (const uint32_t *)(const void *)s;
  } else if (l->off[i + 1] - l->off[i] == SPH_NLIST_RUN_HEAD + 2 * v.len) { /* one run (or none) */
    memcpy(&v.base, s + 2, sizeof v.base);
    v.o = (const uint16_t *)(const void *)(s + SPH_NLIST_RUN_HEAD); /* rows are 2-byte aligned */
  } else {
    v.e = sph_nlist_row(l, i, &v.len);
  }
  return v;
}

/* An offset in entries of row i's place, at least the entries of the rows
 * before it (a row's bytes are at least twice its entries, four times in
 * 2-D): rows of entries laid out per particle, as the list's, fit there. */
static inline size_t sph_nlist_slot(const sph_nlist *l, size_t i) {
  return l->off[i] / (SPH_NLIST_RUNS ? 2 : 4);
}

/* Forgets the list (after the store was reordered). */
static inline void sph_nlist_invalidate(sph_nlist *l) { l->valid = 0; }

#endif
