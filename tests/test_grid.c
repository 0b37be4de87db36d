/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_grid.c - the cell-linked list (grid.h) against a brute-force search.
 *
 * For random particle sets, wide (rows of cells along y) and tall (rows
 * along x), and sets with particles exactly on cell edges and at exactly
 * the support distance, the neighbours found through the grid's three
 * index ranges equal the pairs found by testing every pair;
 * the sort is stable, gives the same permutation and offsets on teams of
 * 1, 2 and 3 threads (one histogram per thread), and a permutation of the
 * store carries every field along. The sorted order is a function of the
 * particles' positions and ids alone (global cells, then ids): a shuffled
 * store and any subset of it sort into the whole set's order. On a grid periodic in x
 * (sph_grid_build_periodic + sph_grid_ranges_all) the neighbours at
 * minimum-image distance below the support equal brute force with the
 * minimum image, for a period of exactly 3 or 2 cells (whole rows) and longer
 * ones, with particles exactly at px0, within a cell of either side, and a
 * little outside the period (as between the two stages of a step).
 *
 * The neighbour list (sph_nlist): built from a sorted grid and from a
 * binned one (store not reordered), plain and periodic, its rows hold
 * exactly the brute-force pairs within the list radius, in increasing
 * storage index; after random moves of at most skin/2 sph_nlist_fresh
 * says the list still holds every pair within the support (checked by
 * brute force), after a larger move or a reordered store it says rebuild.
 * A whole run gives byte-identical output for any skin (SPH_TEST_SKIN): the
 * rows are in storage order, so the pairs of a sum come in the same order
 * however old the list; and for every flavour of the interaction's lane
 * loop (SPH_TEST_LANES=portable and avx against the default, AVX-512 where
 * the processor has it).
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "core/particles.h"
#include "neighbours/grid.h"
#include "solver/forces.h"
#include "testutil.h"

#ifdef _OPENMP
#include <omp.h>
#endif

static unsigned long long rng = 88172645463325252ULL;
static double uniform(void) { return sph_test_uniform(&rng); }

static int cmp_i64(const void *a, const void *b) {
  int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
  return (x > y) - (x < y);
}

/* Compares grid neighbours with brute force for every particle. */
static void check_against_brute_force(sph_particles *p, double support) {
  sph_grid g;
  sph_grid_init(&g);
  sph_error err;
  CU_ASSERT_FATAL(sph_grid_build(&g, p, support * (1.0 + 1e-9), 1u << 24, &err) == 0);
  /* rows along the longer side of the particles' box */
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (size_t i = 0; i < p->n; i++) {
    x0 = fmin(x0, p->x[i]), x1 = fmax(x1, p->x[i]);
    y0 = fmin(y0, p->y[i]), y1 = fmax(y1, p->y[i]);
  }
  CU_ASSERT_EQUAL(g.axis[0], x1 - x0 > y1 - y0 ? SPH_AXIS_Y : SPH_AXIS_X);
  const double s2 = support * support;
  int64_t *a = malloc(p->n * sizeof *a), *b = malloc(p->n * sizeof *b);
  size_t mismatches = 0, pairs = 0;
  for (size_t i = 0; i < p->n; i++) {
    size_t na = 0, nb = 0;
    size_t lo[SPH_GRID_ROWS], hi[SPH_GRID_ROWS];
    sph_grid_ranges(&g, i, lo, hi);
    for (int k = 0; k < SPH_GRID_ROWS; k++)
      for (size_t j = lo[k]; j < hi[k]; j++) {
        const double dx = p->x[i] - p->x[j], dy = p->y[i] - p->y[j];
        if (j != i && dx * dx + dy * dy < s2) a[na++] = p->id[j];
      }
    for (size_t j = 0; j < p->n; j++) {
      const double dx = p->x[i] - p->x[j], dy = p->y[i] - p->y[j];
      if (j != i && dx * dx + dy * dy < s2) b[nb++] = p->id[j];
    }
    qsort(a, na, sizeof *a, cmp_i64);
    qsort(b, nb, sizeof *b, cmp_i64);
    pairs += nb;
    if (na != nb || memcmp(a, b, na * sizeof *a)) mismatches++;
  }
  CU_ASSERT_EQUAL(mismatches, 0);
  CU_ASSERT(pairs > 0);
  /* cell order, and stable: ids increase within each cell when the store
   * started in id order */
  for (size_t i = 1; i < p->n; i++) {
    const long ca = g.cell_of[1][i - 1] * g.ncell[0] + g.cell_of[0][i - 1],
               cb = g.cell_of[1][i] * g.ncell[0] + g.cell_of[0][i];
    CU_ASSERT(ca <= cb);
  }
  free(a);
  free(b);
  sph_grid_free(&g);
}

static void test_random_sets(void) {
  for (int trial = 0; trial < 6; trial++) {
    sph_particles p;
    sph_error err;
    CU_ASSERT_FATAL(sph_particles_init(&p, 16, &err) == 0);
    const size_t n = 500 + 400 * (size_t)(trial % 5);
    const double L = 0.1 * (trial % 5 + 1);
    /* wide boxes (rows along y), and a tall one (rows along x) */
    const double w = trial < 5 ? L : 0.3 * L, hgt = trial < 5 ? 0.5 * L : L;
    for (size_t i = 0; i < n; i++)
      sph_particles_add(&p, w * uniform() - 0.3, hgt * uniform() + 2.0, 0, 0, 1000, 1, 0.01,
                        SPH_KIND_FLUID, &err);
    check_against_brute_force(&p, 0.02 + 0.005 * trial);
    sph_particles_free(&p);
  }
}

/* Particles on a lattice whose spacing divides the cell size: many sit
 * exactly on cell edges, and many pairs are exactly `support` apart (those
 * are not neighbours: W vanishes there). */
static void test_cell_edges(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 16, &err) == 0);
  const double support = 0.25;
  for (int j = 0; j < 30; j++)
    for (int i = 0; i < 30; i++)
      sph_particles_add(&p, 0.125 * i, 0.125 * j, 0, 0, 1000, 1, 0.1, SPH_KIND_FLUID, &err);
  /* shuffle storage order (ids stay), then sort */
  size_t *perm = malloc(p.n * sizeof *perm);
  for (size_t i = 0; i < p.n; i++)
    perm[i] = i;
  for (size_t i = p.n - 1; i > 0; i--) {
    size_t k = (size_t)(uniform() * (double)(i + 1));
    size_t t = perm[i];
    perm[i] = perm[k];
    perm[k] = t;
  }
  double *work = malloc(p.n * sizeof *work);
  sph_particles_permute(&p, perm, work);
  check_against_brute_force(&p, support);
  /* a particle in the interior has exactly the 8 lattice neighbours within
   * 0.25 (distance 0.125 and 0.177), not the 4 at exactly 0.25 */
  sph_grid g;
  sph_grid_init(&g);
  sph_grid_build(&g, &p, support * (1 + 1e-9), 1u << 20, &err);
  for (size_t i = 0; i < p.n; i++) {
    if (p.id[i] != 15 * 30 + 15) continue;
    size_t lo[SPH_GRID_ROWS], hi[SPH_GRID_ROWS], cnt = 0;
    sph_grid_ranges(&g, i, lo, hi);
    for (int k = 0; k < SPH_GRID_ROWS; k++)
      for (size_t j = lo[k]; j < hi[k]; j++) {
        const double dx = p.x[i] - p.x[j], dy = p.y[i] - p.y[j];
        if (j != i && dx * dx + dy * dy < support * support) cnt++;
      }
    CU_ASSERT_EQUAL(cnt, 8);
  }
  sph_grid_free(&g);
  free(perm);
  free(work);
  sph_particles_free(&p);
}

/* x_i - x_j reduced to the minimum image, |d| <= period/2: by remainder,
 * not by the solver's single correction, so it holds however far apart. */
static double min_image(double d, double period) {
  d = fmod(d, period);
  if (d > 0.5 * period) d -= period;
  if (d < -0.5 * period) d += period;
  return d;
}

/* Neighbours of every particle through the periodic grid's ranges against
 * brute force with the minimum image; also checks that no candidate is
 * listed twice (the ranges of a row never overlap). Returns the number of
 * neighbour pairs found. */
static size_t check_periodic(sph_particles *p, double support, double cell, double px0,
                             double px1) {
  sph_grid g;
  sph_grid_init(&g);
  sph_error err;
  const int rc = sph_grid_build_periodic(&g, p, cell, SPH_AXIS_X, px0, px1, 1u << 24, &err);
  if (rc) printf("\n%s\n", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  CU_ASSERT(g.periodic);
  CU_ASSERT(g.ncell[0] >= 2 && g.cellx >= cell);
  const double period = px1 - px0, s2 = support * support;
  int64_t *a = malloc(p->n * sizeof *a), *b = malloc(p->n * sizeof *b);
  unsigned char *seen = calloc(p->n, 1);
  CU_ASSERT_FATAL(a && b && seen);
  size_t mismatches = 0, duplicates = 0, pairs = 0;
  for (size_t i = 0; i < p->n; i++) {
    size_t na = 0, nb = 0;
    size_t lo[SPH_GRID_RANGES], hi[SPH_GRID_RANGES];
    sph_grid_ranges_all(&g, i, lo, hi);
    for (int k = 0; k < SPH_GRID_RANGES; k++)
      for (size_t j = lo[k]; j < hi[k]; j++) {
        if (seen[j]) duplicates++;
        seen[j] = 1;
        const double dx = min_image(p->x[i] - p->x[j], period), dy = p->y[i] - p->y[j];
        if (j != i && dx * dx + dy * dy < s2) a[na++] = p->id[j];
      }
    for (int k = 0; k < SPH_GRID_RANGES; k++)
      for (size_t j = lo[k]; j < hi[k]; j++)
        seen[j] = 0;
    for (size_t j = 0; j < p->n; j++) {
      const double dx = min_image(p->x[i] - p->x[j], period), dy = p->y[i] - p->y[j];
      if (j != i && dx * dx + dy * dy < s2) b[nb++] = p->id[j];
    }
    qsort(a, na, sizeof *a, cmp_i64);
    qsort(b, nb, sizeof *b, cmp_i64);
    pairs += nb;
    if (na != nb || memcmp(a, b, na * sizeof *a)) mismatches++;
  }
  CU_ASSERT_EQUAL(mismatches, 0);
  CU_ASSERT_EQUAL(duplicates, 0);
  /* cell order with the columns of the period */
  for (size_t i = 0; i < p->n; i++)
    CU_ASSERT(g.cell_of[0][i] >= 0 && g.cell_of[0][i] < g.ncell[0]);
  for (size_t i = 1; i < p->n; i++)
    CU_ASSERT(g.cell_of[1][i - 1] * g.ncell[0] + g.cell_of[0][i - 1] <=
              g.cell_of[1][i] * g.ncell[0] + g.cell_of[0][i]);
  free(a);
  free(b);
  free(seen);
  sph_grid_free(&g);
  return pairs;
}

/* n random particles over [px0, px1) x [y0, y0 + height), then particles
 * exactly at px0, within one cell of either side (inside and, by less than
 * a cell, outside the period), and pairs exactly `support` apart across
 * the seam (not neighbours). */
static void periodic_set(sph_particles *p, size_t n, double px0, double px1, double y0,
                         double height, double cell, double support) {
  sph_error err;
  const double period = px1 - px0;
  for (size_t i = 0; i < n; i++)
    sph_particles_add(p, px0 + period * uniform(), y0 + height * uniform(), 0, 0, 1000, 1, 0.1,
                      SPH_KIND_FLUID, &err);
  for (int k = 0; k < 20; k++) {
    const double y = y0 + height * uniform();
    sph_particles_add(p, px0, y, 0, 0, 1000, 1, 0.1, SPH_KIND_FLUID, &err);
    sph_particles_add(p, px0 + cell * uniform(), y0 + height * uniform(), 0, 0, 1000, 1, 0.1,
                      SPH_KIND_FLUID, &err);
    sph_particles_add(p, px1 - cell * uniform(), y0 + height * uniform(), 0, 0, 1000, 1, 0.1,
                      SPH_KIND_FLUID, &err);
    /* between the stages of a step a particle may stand just outside */
    if (k % 4 == 0) {
      sph_particles_add(p, px1 + 0.5 * cell * uniform(), y0 + height * uniform(), 0, 0, 1000, 1,
                        0.1, SPH_KIND_FLUID, &err);
      sph_particles_add(p, px0 - 0.5 * cell * uniform(), y0 + height * uniform(), 0, 0, 1000, 1,
                        0.1, SPH_KIND_FLUID, &err);
    }
  }
  /* exactly `support` apart through the seam: px0 + s/4 and px1 - 3s/4 */
  sph_particles_add(p, px0 + 0.25 * support, y0 + 0.5 * height, 0, 0, 1000, 1, 0.1, SPH_KIND_FLUID,
                    &err);
  sph_particles_add(p, px1 - 0.75 * support, y0 + 0.5 * height, 0, 0, 1000, 1, 0.1, SPH_KIND_FLUID,
                    &err);
}

/* A period of exactly 3 cells, and of 2 (the shortest taken): every row is
 * one whole range, and each pair is counted once although it lies in
 * neighbouring columns both ways (with 2, through the seam and not). */
static void test_periodic_three_cells(void) {
  for (int trial = 0; trial < 8; trial++) {
    sph_particles p;
    sph_error err;
    CU_ASSERT_FATAL(sph_particles_init(&p, 16, &err) == 0);
    const int cols = 3 - trial / 4;
    const double support = 0.25, cell = 0.25; /* binary fractions: the period is whole cells */
    const double px0 = -0.5 + 0.25 * (trial % 4), px1 = px0 + cols * cell;
    periodic_set(&p, 300 + 100 * (size_t)(trial % 4), px0, px1, 1.0, 1.5, cell, support);
    sph_grid g;
    sph_grid_init(&g);
    CU_ASSERT_FATAL(sph_grid_build_periodic(&g, &p, cell, SPH_AXIS_X, px0, px1, 1u << 20, &err) ==
                    0);
    CU_ASSERT_EQUAL(g.ncell[0], cols);
    CU_ASSERT_EQUAL(g.cellx, cell);
    sph_grid_free(&g);
    CU_ASSERT(check_periodic(&p, support, cell, px0, px1) > 0);
    sph_particles_free(&p);
  }
}

/* Longer periods (not a whole number of cells: columns are widened to
 * period/nx), with the support equal to the cell or a little below. */
static void test_periodic_long(void) {
  for (int trial = 0; trial < 4; trial++) {
    sph_particles p;
    sph_error err;
    CU_ASSERT_FATAL(sph_particles_init(&p, 16, &err) == 0);
    const double support = 0.02 + 0.005 * trial;
    const double cell = support * (1.0 + 1e-9);
    const double px0 = 0.3 - 0.1 * trial, px1 = px0 + (10.37 + 3.1 * trial) * cell;
    periodic_set(&p, 800 + 300 * (size_t)trial, px0, px1, -0.2, 8 * cell, cell, support);
    sph_grid g;
    sph_grid_init(&g);
    CU_ASSERT_FATAL(sph_grid_build_periodic(&g, &p, cell, SPH_AXIS_X, px0, px1, 1u << 20, &err) ==
                    0);
    CU_ASSERT(g.ncell[0] > 3);
    sph_grid_free(&g);
    CU_ASSERT(check_periodic(&p, support, cell, px0, px1) > 0);
    sph_particles_free(&p);
  }
}

/* A period shorter than 2 cells is refused with a message; 2.8 cells make
 * 2 columns. */
static void test_periodic_too_short(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 16, &err) == 0);
  sph_particles_add(&p, 0.1, 0.1, 0, 0, 1000, 1, 0.1, SPH_KIND_FLUID, &err);
  sph_grid g;
  sph_grid_init(&g);
  err.msg[0] = 0;
  CU_ASSERT(sph_grid_build_periodic(&g, &p, 0.25, SPH_AXIS_X, 0.0, 0.45, 1u << 20, &err) != 0);
  CU_ASSERT(strstr(err.msg, "fewer than 2 cells") != NULL);
  CU_ASSERT(strstr(err.msg, "at least 0.5") != NULL);
  CU_ASSERT(sph_grid_build_periodic(&g, &p, 0.25, SPH_AXIS_X, 0.0, 0.7, 1u << 20, &err) == 0);
  CU_ASSERT_EQUAL(g.ncell[0], 2);
  sph_grid_free(&g);
  sph_particles_free(&p);
}

/* Cell coordinates are 32-bit: a grid of 2^31 cells or more along a side
 * is refused before anything is allocated, however many cells are
 * allowed; one just under the bound in cells is not refused for its side. */
static void test_grid_side_bound(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 16, &err) == 0);
  sph_particles_add(&p, 0.0, 0.0, 0, 0, 1000, 1, 0.1, SPH_KIND_FLUID, &err);
  sph_particles_add(&p, 2147483648.0, 0.0, 0, 0, 1000, 1, 0.1, SPH_KIND_FLUID, &err);
  sph_grid g;
  sph_grid_init(&g);
  err.msg[0] = 0;
  CU_ASSERT(sph_grid_build(&g, &p, 1.0, SIZE_MAX, &err) != 0); /* 2^31 + 1 cells a side */
  CU_ASSERT(strstr(err.msg, "2^31 - 1 a side") != NULL);
  CU_ASSERT(g.ncell[0] == 0); /* nothing built */
  p.x[1] = 2147483645.0;      /* 2^31 - 2 cells: within the side's bound, over max_cells */
  err.msg[0] = 0;
  CU_ASSERT(sph_grid_build(&g, &p, 1.0, 1u << 20, &err) != 0);
  CU_ASSERT(strstr(err.msg, "limit 1048576") != NULL);
  sph_grid_free(&g);
  sph_particles_free(&p);
}

static void test_permute_carries_fields(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 4, &err) == 0);
  for (int i = 0; i < 100; i++) {
    sph_particles_add(&p, i, -i, 2 * i, 3 * i, 1000 + i, 1 + i, 0.5 * i, i % 2, &err);
    p.u[i] = 7.0 * i;
    p.flags[i] = (uint8_t)(i % 3);
  }
  size_t perm[100];
  for (int i = 0; i < 100; i++)
    perm[i] = (size_t)(99 - i);
  double work[100];
  sph_particles_permute(&p, perm, work);
  for (int i = 0; i < 100; i++) {
    const int o = 99 - i;
    CU_ASSERT(p.id[i] == o && p.x[i] == o && p.y[i] == -o && p.vx[i] == 2 * o && p.vy[i] == 3 * o &&
              p.rho[i] == 1000 + o && p.mass[i] == 1 + o && p.h[i] == 0.5 * o &&
              p.kind[i] == o % 2 && p.u[i] == 7.0 * o && p.flags[i] == o % 3);
  }
  sph_particles_free(&p);
}

/* Each per-axis field of the store is reachable by name and by axis, the
 * same arrays, after the store has grown and been permuted. */
static void test_fields_by_axis(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 4, &err) == 0);
  for (int i = 0; i < 100; i++) /* grows from 16 */
    CU_ASSERT_FATAL(sph_particles_add(&p, i, -i, 2 * i, 3 * i, 1000, 1, 0.5, 0, &err) == i);
  size_t perm[100];
  for (int i = 0; i < 100; i++)
    perm[i] = (size_t)(99 - i);
  double work[100];
  sph_particles_permute(&p, perm, work);
  CU_ASSERT_EQUAL(SPH_STORE_DIM, 2);
  double *const by_name[][2] = {{p.x, p.y},     {p.vx, p.vy},   {p.x0, p.y0},
                                {p.vx0, p.vy0}, {p.ax, p.ay},   {p.vxh, p.vyh},
                                {p.xr, p.yr},   {p.xsx, p.xsy}, {p.mx, p.my}};
  double *const *const by_axis[] = {p.pos,  p.vel,  p.pos0, p.vel0,         p.acc,
                                    p.velh, p.rest, p.xsph, p.mirror_offset};
  enum { FIELDS = sizeof by_axis / sizeof by_axis[0] };
  CU_ASSERT_EQUAL(sizeof by_name / sizeof by_name[0], FIELDS);
  for (int f = 0; f < FIELDS; f++) {
    CU_ASSERT(by_name[f][0] != NULL && by_name[f][0] != by_name[f][1]);
    CU_ASSERT(by_axis[f][SPH_AXIS_X] == by_name[f][0]);
    CU_ASSERT(by_axis[f][SPH_AXIS_Y] == by_name[f][1]);
  }
  for (int i = 0; i < 100; i++) {
    const int o = 99 - i;
    CU_ASSERT(p.pos[SPH_AXIS_X][i] == o && p.pos[SPH_AXIS_Y][i] == -o);
    CU_ASSERT(p.vel[SPH_AXIS_X][i] == 2 * o && p.vel[SPH_AXIS_Y][i] == 3 * o);
  }
  p.acc[SPH_AXIS_Y][7] = 42.0; /* a write by axis is read by name */
  CU_ASSERT(p.ay[7] == 42.0);
  sph_particles_free(&p);
}

/* Pages of [a, a + bytes) resident in memory (mincore). */
static size_t resident_pages(const void *a, size_t bytes) {
  const size_t page = (size_t)sysconf(_SC_PAGESIZE);
  const uintptr_t lo = (uintptr_t)a / page * page,
                  hi = ((uintptr_t)a + bytes + page - 1) / page * page;
  const size_t n = (hi - lo) / page;
  unsigned char *v = malloc(n);
  CU_ASSERT_FATAL(v != NULL);
  CU_ASSERT_FATAL(mincore((void *)lo, hi - lo, v) == 0);
  size_t r = 0;
  for (size_t k = 0; k < n; k++)
    r += v[k] & 1u;
  free(v);
  return r;
}

/* A store limited to the arrays in use (particles.h, SPH_ARRAYS_*): the
 * other groups stay zero through growth and permutation, and their pages
 * are never touched (out of the resident set); a group turned on later
 * starts from zeros, the rest positions from the present ones, and is
 * carried from then on. */
static void test_unused_groups_untouched(void) {
  enum { N = 200000 };
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 16, &err) == 0);
  /* by default every group but the phases' (which change what a pass computes) */
  CU_ASSERT_EQUAL(p.live, SPH_ARRAYS_ALL & ~SPH_ARRAYS_PHASE);
  CU_ASSERT_FATAL(sph_particles_limit(&p, 0) == 0);
  for (int i = 0; i < N; i++) /* grows 14 times */
    CU_ASSERT_FATAL(sph_particles_add(&p, i, -i, 0, 0, 1000, 1, 0.01, SPH_KIND_FLUID, &err) == i);
  CU_ASSERT(sph_particles_limit(&p, SPH_ARRAYS_ALL) == -1); /* only while empty */
  size_t *perm = malloc(N * sizeof *perm);
  double *work = malloc(N * sizeof *work);
  CU_ASSERT_FATAL(perm && work);
  for (size_t i = 0; i < N; i++)
    perm[i] = (size_t)N - 1 - i;
  sph_particles_permute(&p, perm, work);
  const size_t bytes = N * sizeof(double);
  /* pages every one of which the store wrote */
  CU_ASSERT(resident_pages(p.x, bytes) * (size_t)sysconf(_SC_PAGESIZE) >= bytes);
  double *const unused[] = {p.u, p.u0, p.du, p.vxh, p.vyh, p.rhoh, p.uh, p.xr, p.yr, p.mx, p.my};
  size_t touched = 0;
  for (size_t k = 0; k < sizeof unused / sizeof *unused; k++)
    touched += resident_pages(unused[k], bytes);
  touched += resident_pages(p.phase, N) + resident_pages(p.wphase, N); /* (group PHASE) */
  CU_ASSERT_EQUAL(touched, 0);
  int ok = 1;
  for (int i = 0; i < N; i++)
    ok &= p.x[i] == N - 1 - i && p.id[i] == N - 1 - i;
  CU_ASSERT(ok);
  /* rest positions on: the present positions, then carried by a permutation */
  sph_particles_use(&p, SPH_ARRAYS_REST | SPH_ARRAYS_HEAT);
  CU_ASSERT_EQUAL(p.live, SPH_ARRAYS_REST | SPH_ARRAYS_HEAT);
  for (size_t i = 0; i < N; i++) {
    perm[i] = (size_t)N - 1 - i;
    p.u[i] = 0.5 * (double)i;
  }
  sph_particles_permute(&p, perm, work);
  ok = 1;
  for (int i = 0; i < N; i++)
    ok &= p.x[i] == i && p.xr[i] == i && p.yr[i] == -i && p.u[i] == 0.5 * (N - 1 - i);
  CU_ASSERT(ok);
  /* the groups still off are still untouched (not read here either: mincore
   * counts a page read from the kernel's zero page as present) */
  CU_ASSERT_EQUAL(resident_pages(p.vxh, bytes) + resident_pages(p.mx, bytes), 0);
  sph_particles_free(&p);
  /* the leap-frog's half step without the heat: vxh carried, uh (both
   * groups) untouched */
  CU_ASSERT_FATAL(sph_particles_init(&p, N, &err) == 0);
  CU_ASSERT_FATAL(sph_particles_limit(&p, SPH_ARRAYS_HALF_STEP) == 0);
  for (size_t i = 0; i < N; i++) {
    CU_ASSERT_FATAL(
        sph_particles_add(&p, (double)i, 0.0, 0, 0, 1000, 1, 0.01, SPH_KIND_FLUID, &err) >= 0);
    p.vxh[i] = (double)i;
  }
  sph_particles_permute(&p, perm, work);
  ok = 1;
  for (int i = 0; i < N; i++)
    ok &= p.vxh[i] == N - 1 - i && p.x[i] == N - 1 - i;
  CU_ASSERT(ok);
  CU_ASSERT_EQUAL(resident_pages(p.uh, bytes) + resident_pages(p.u, bytes), 0);
  free(perm);
  free(work);
  sph_particles_free(&p);
}

/* The list of p (built on a sorted or a binned grid) against brute force
 * with radius support + skin: same pairs, rows in increasing storage index,
 * as long as their counts; returns the list's bytes per entry. */
static double check_list(sph_particles *p, double support, double skin, double period, int binned) {
  sph_grid g;
  sph_grid_init(&g);
  sph_nlist l;
  sph_nlist_init(&l);
  sph_error err;
  const double cell = (support + skin) * (1.0 + 1e-9), px1 = period;
  int rc;
  if (binned)
    rc = sph_grid_bin(&g, p, cell, period > 0.0, 0.0, px1, 1u << 24, &err);
  else if (period > 0.0)
    rc = sph_grid_build_periodic(&g, p, cell, SPH_AXIS_X, 0.0, px1, 1u << 24, &err);
  else
    rc = sph_grid_build(&g, p, cell, 1u << 24, &err);
  CU_ASSERT_FATAL(rc == 0);
  CU_ASSERT_FATAL(sph_nlist_build(&l, &g, p, support, skin, period, &err) == 0);
  const double r2 = (support + skin) * (support + skin);
  size_t bad = 0, pairs = 0, listed = 0;
  for (size_t i = 0; i < p->n; i++) {
    size_t len;
    const uint32_t *row = sph_nlist_row(&l, i, &len);
    listed += l.count[i];
    size_t k = 0;
    for (size_t j = 0; j < p->n; j++) {
      double dx = p->x[i] - p->x[j];
      if (period > 0.0) dx -= period * nearbyint(dx / period);
      const double dy = p->y[i] - p->y[j];
      if (j == i || !(dx * dx + dy * dy < r2)) continue;
      pairs++;
      if (k >= l.count[i] || row[k] != j) bad++;
      k++;
    }
    if (k != l.count[i]) bad++;
    if (len != l.count[i]) bad++;
  }
  CU_ASSERT_EQUAL(bad, 0);
  CU_ASSERT(pairs > 0);
  CU_ASSERT_EQUAL(listed, pairs);
  const double per_entry = (double)l.off[p->n] / (double)listed;
  sph_nlist_free(&l);
  sph_grid_free(&g);
  return per_entry;
}

static void random_store(sph_particles *p, size_t n, double L) {
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(p, 16, &err) == 0);
  for (size_t i = 0; i < n; i++)
    sph_particles_add(p, L * uniform(), 0.5 * L * uniform() + 1.0, 0, 0, 1000, 1, 0.01,
                      SPH_KIND_FLUID, &err);
}

static void test_list_brute_force(void) {
  for (int trial = 0; trial < 4; trial++) {
    sph_particles p;
    random_store(&p, 600 + 300 * (size_t)trial, 0.2);
    const int binned = trial % 2, periodic = trial >= 2;
    check_list(&p, 0.02, 0.004 * trial, periodic ? 0.2 : 0.0, binned);
    /* the periodic image of a particle a little outside the period */
    if (periodic) p.x[0] = 0.2 + 0.001, p.x[1] = -0.001;
    check_list(&p, 0.02, 0.003, periodic ? 0.2 : 0.0, !binned);
    sph_particles_free(&p);
  }
  /* dense rows (a cell holds some 360 particles): 2-D rows are plain
   * indices, four bytes an entry, no slot unused (grid.h) */
  sph_particles p;
  random_store(&p, 2000, 0.2);
  for (int kind = 0; kind < 3; kind++)
    CU_ASSERT_EQUAL(check_list(&p, 0.05, 0.01, kind == 2 ? 0.2 : 0.0, kind == 1), 4.0);
  sph_particles_free(&p);
}

/* Rows left empty by id (grid.h, no_row: a rank's farther ghosts): those
 * rows hold nothing, every other row is the row of the list built without
 * it, and the empty rows' particles are still listed in the others. */
static void test_list_no_row(void) {
  sph_particles p;
  random_store(&p, 900, 0.2);
  unsigned char *no_row = calloc(p.n, 1);
  CU_ASSERT_FATAL(no_row != NULL);
  for (size_t k = 0; k < p.n; k += 3)
    no_row[k] = 1;
  sph_grid g;
  sph_grid_init(&g);
  sph_nlist a, b;
  sph_nlist_init(&a);
  sph_nlist_init(&b);
  sph_error err;
  CU_ASSERT_FATAL(sph_grid_build(&g, &p, 0.024, 1u << 24, &err) == 0);
  CU_ASSERT_FATAL(sph_nlist_build(&a, &g, &p, 0.02, 0.004, 0.0, &err) == 0);
  b.no_row = no_row, b.no_row_n = p.n;
  CU_ASSERT_FATAL(sph_nlist_build(&b, &g, &p, 0.02, 0.004, 0.0, &err) == 0);
  CU_ASSERT(sph_nlist_check(&b, &p, 0.02) == NULL);
  size_t bad = 0, empty = 0, listed_empty = 0;
  for (size_t i = 0; i < p.n; i++) {
    size_t na, nb;
    const uint32_t *ra = sph_nlist_row(&a, i, &na);
    uint32_t row[4096];
    CU_ASSERT_FATAL(na < 4096);
    memcpy(row, ra, na * sizeof *row);
    const uint32_t *rb = sph_nlist_row(&b, i, &nb);
    if (no_row[p.id[i]]) {
      empty++;
      bad += nb != 0;
      continue;
    }
    bad += nb != na || (na && memcmp(row, rb, na * sizeof *row) != 0);
    for (size_t k = 0; k < nb; k++)
      listed_empty += no_row[p.id[rb[k]]];
  }
  CU_ASSERT_EQUAL(bad, 0);
  CU_ASSERT(empty == (p.n + 2) / 3);
  CU_ASSERT(listed_empty > 0);
  sph_nlist_free(&a);
  sph_nlist_free(&b);
  sph_grid_free(&g);
  free(no_row);
  sph_particles_free(&p);
}

/* The store's arrays by name, and a store gathered from another and put
 * back array by array (solver/ranks.c): the arrays asked for, the others
 * left as they were, and the arrays in which a value changed. */
static void test_gather_put(void) {
  const unsigned long long x = sph_particles_array_bits("x"), rho = sph_particles_array_bits("rho");
  CU_ASSERT(x != 0 && rho != 0 && (x & rho) == 0);
  CU_ASSERT((x & sph_particles_array_bits("x0 xsx xr")) == 0); /* whole words only */
  CU_ASSERT(sph_particles_array_bits("x rho") == (x | rho));
  CU_ASSERT(sph_particles_array_bits("no such array") == 0);
  sph_particles p, q;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 4, &err) == 0);
  CU_ASSERT_FATAL(sph_particles_init(&q, 4, &err) == 0);
  for (int i = 0; i < 50; i++)
    sph_particles_add(&p, i, -i, 2 * i, 3 * i, 1000 + i, 1, 0.5, SPH_KIND_FLUID, &err);
  const size_t which[3] = {5, 17, 42}, at[3] = {0, 1, 2};
  CU_ASSERT_FATAL(sph_particles_gather(&q, &p, which, 3, SPH_PARTICLES_ALL, &err) == 0);
  CU_ASSERT(q.n == 3 && q.x[1] == 17 && q.vy[2] == 126 && q.id[0] == 5 && q.rho[2] == 1042);
  q.vx[0] = -1.0; /* not gathered below: left as it is */
  p.x[5] = 500.0, p.rho[5] = 7.0;
  CU_ASSERT_FATAL(sph_particles_gather(&q, &p, which, 3, x, &err) == 0);
  CU_ASSERT(q.x[0] == 500.0 && q.rho[0] == 1005.0 && q.vx[0] == -1.0);
  /* back into p: only the arrays asked for, and which of them changed */
  q.rho[1] = 9.0, q.vx[1] = 9.0;
  CU_ASSERT(sph_particles_put(&p, which, &q, at, 3, rho | x, 1) == rho);
  CU_ASSERT(p.rho[17] == 9.0 && p.vx[17] == 34.0 && p.rho[5] == 1005.0 && p.x[5] == 500.0);
  CU_ASSERT(sph_particles_put(&p, which, &q, at, 3, rho | x, 1) == 0);
  q.rho[2] = 1.0;
  CU_ASSERT(sph_particles_put(&p, which, &q, at, 3, SPH_PARTICLES_ALL, 0) == 0);
  CU_ASSERT(p.rho[42] == 1.0 && p.vx[17] == 9.0);
  /* blocks of a set of arrays, array by array: the size of the records of
   * those arrays, set back into other particles, the other arrays untouched */
  const unsigned long long xr = x | rho;
  unsigned char buf[3 * 2 * sizeof(double) + 1];
  buf[sizeof buf - 1] = 0xA5;
  CU_ASSERT(sph_particles_record_size_of(&p, xr) == 2 * sizeof(double));
  sph_particles_pack_block(&p, which, 3, xr, buf);
  CU_ASSERT(buf[sizeof buf - 1] == 0xA5); /* nothing past the block */
  double first[2];
  memcpy(first, buf, sizeof first); /* x of 5 and 17 first */
  CU_ASSERT(first[0] == 500.0 && first[1] == 17.0);
  const size_t to[3] = {0, 1, 2};
  sph_particles_unpack_block(&p, to, 3, xr, buf);
  CU_ASSERT(p.x[0] == 500.0 && p.x[1] == 17.0 && p.x[2] == 42.0);
  CU_ASSERT(p.rho[0] == 1005.0 && p.rho[1] == 9.0 && p.rho[2] == 1.0);
  CU_ASSERT(p.vx[0] == 0.0 && p.vx[2] == 4.0 && p.y[1] == -1.0);
  sph_particles_free(&p);
  sph_particles_free(&q);
}

/* The counting sort on teams of 1 to 3 threads (one histogram per thread
 * when the store is above the serial threshold and has more particles
 * than cells): the same permutation and cell offsets, and each cell's
 * particles in increasing index. */
static void test_sort_any_team(void) {
  enum { N = 6000 };
  sph_particles p;
  random_store(&p, N, 0.2);
  const double cell = 0.01; /* 20 x 10 cells: far fewer than particles */
  sph_grid g[3];
  sph_error err;
  for (int k = 0; k < 3; k++) {
    sph_grid_init(&g[k]);
#ifdef _OPENMP
    omp_set_num_threads(k + 1);
#endif
    CU_ASSERT_FATAL(sph_grid_bin(&g[k], &p, cell, 0, 0.0, 0.0, 1u << 24, &err) == 0);
  }
#ifdef _OPENMP
  omp_set_num_threads(2);
#endif
  const size_t cells = sph_grid_cells(&g[0]);
  CU_ASSERT_FATAL(cells < N);
  int ordered = 1;
  for (size_t c = 0; c < cells; c++)
    for (size_t k = g[0].start[c] + 1; k < g[0].start[c + 1]; k++)
      ordered &= g[0].perm[k - 1] < g[0].perm[k];
  CU_ASSERT(ordered);
  CU_ASSERT_EQUAL(g[0].start[cells], N);
  for (int k = 1; k < 3; k++) {
    CU_ASSERT(memcmp(g[k].start, g[0].start, (cells + 1) * sizeof *g[0].start) == 0);
    CU_ASSERT(memcmp(g[k].perm, g[0].perm, N * sizeof *g[0].perm) == 0);
  }
  for (int k = 0; k < 3; k++)
    sph_grid_free(&g[k]);
  sph_particles_free(&p);
}

/* The ids of a store sorted by an oriented grid, in storage order. */
static int64_t *sorted_ids(sph_particles *p, const double ext[2], double cell, int periodic,
                           double period) {
  sph_grid g;
  sph_grid_init(&g);
  g.oriented = 1;
  memcpy(g.orient_ext, ext, 2 * sizeof *ext);
  sph_error err;
  const int rc = periodic
                     ? sph_grid_build_periodic(&g, p, cell, SPH_AXIS_X, 0.0, period, 1u << 24, &err)
                     : sph_grid_build(&g, p, cell, 1u << 24, &err);
  CU_ASSERT_FATAL(rc == 0);
  int64_t *ids = malloc(p->n * sizeof *ids);
  memcpy(ids, p->id, p->n * sizeof *ids);
  sph_grid_free(&g);
  return ids;
}

/* The order a sort gives is a function of the particles' positions and ids
 * alone (grid.h: global cells, then ids), the summation order the MPI ranks
 * need: a store shuffled and sorted again comes out in the same order, and
 * any subset of it (a rank's particles, its ghosts among them, moved by a
 * whole number of cells or not) sorts into the whole set's order
 * restricted to it, whatever its own bounding box. Plain and periodic. */
static void test_global_order(void) {
  for (int periodic = 0; periodic < 2; periodic++) {
    enum { N = 3000 };
    sph_particles p;
    random_store(&p, N, 0.2);
    for (size_t i = 0; i < 40; i++) /* some on cell edges, some sharing a spot */
      p.x[i] = 0.01 * (double)(i % 20), p.y[i] = 1.0 + 0.01 * (double)(i / 20);
    const double ext[2] = {0.2, 0.1}, cell = 0.01;
    int64_t *all = sorted_ids(&p, ext, cell, periodic, 0.2);
    /* shuffled: the same order */
    size_t *perm = malloc(N * sizeof *perm);
    double *work = malloc(N * sizeof *work);
    for (size_t i = 0; i < N; i++)
      perm[i] = i;
    for (size_t i = N - 1; i > 0; i--) {
      const size_t k = (size_t)(uniform() * (double)(i + 1)), t = perm[i];
      perm[i] = perm[k], perm[k] = t;
    }
    sph_particles_permute(&p, perm, work);
    int64_t *again = sorted_ids(&p, ext, cell, periodic, 0.2);
    CU_ASSERT(memcmp(all, again, N * sizeof *all) == 0);
    /* subsets: a band of x (a rank's slab with its ghosts), and a random third */
    for (int kind = 0; kind < 2; kind++) {
      sph_particles q;
      sph_error err;
      CU_ASSERT_FATAL(sph_particles_init(&q, 16, &err) == 0);
      char *in = calloc(N + 1, 1);
      for (size_t i = 0; i < p.n; i++) {
        const int take = kind ? uniform() < 0.33 : p.x[i] >= 0.07 && p.x[i] < 0.13;
        if (!take) continue;
        const long k =
            sph_particles_add(&q, p.x[i], p.y[i], 0, 0, 1000, 1, 0.01, SPH_KIND_FLUID, &err);
        CU_ASSERT_FATAL(k >= 0);
        q.id[k] = p.id[i];
        in[p.id[i]] = 1;
      }
      int64_t *sub = sorted_ids(&q, ext, cell, periodic, 0.2);
      size_t m = 0, same = 1;
      for (size_t i = 0; i < N; i++)
        if (in[all[i]]) same &= m < q.n && sub[m++] == all[i];
      printf("\n  %s, subset %s: %zu of %d particles, %s", periodic ? "periodic" : "plain",
             kind ? "random third" : "band 0.07 <= x < 0.13", q.n, N,
             same && m == q.n ? "the whole set's order" : "ANOTHER ORDER");
      CU_ASSERT(same && m == q.n);
      free(sub);
      free(in);
      sph_particles_free(&q);
    }
    free(again);
    free(all);
    free(perm);
    free(work);
    sph_particles_free(&p);
  }
}

/* Moves of up to skin/2: the list stays fresh and holds every pair within
 * the support; a larger move, or a reordered store, makes it stale. */
static void test_list_fresh(void) {
  sph_particles p;
  random_store(&p, 1500, 0.2);
  const double support = 0.02, skin = 0.006;
  sph_grid g;
  sph_grid_init(&g);
  sph_nlist l;
  sph_nlist_init(&l);
  sph_error err;
  CU_ASSERT_FATAL(sph_grid_build(&g, &p, (support + skin) * (1 + 1e-9), 1u << 24, &err) == 0);
  CU_ASSERT_FATAL(sph_nlist_build(&l, &g, &p, support, skin, 0.0, &err) == 0);
  CU_ASSERT(sph_nlist_fresh(&l, &p));
  for (size_t i = 0; i < p.n; i++) { /* |d| <= 0.49 skin */
    const double a = 6.283185307179586 * uniform(), d = 0.49 * skin * uniform();
    p.x[i] += 0.5 * d * cos(a);
    p.y[i] += 0.5 * d * sin(a);
    if (i % 7 == 0) { /* some at nearly the largest allowed move */
      p.x[i] += 0.49 * 0.5 * skin * cos(a) - 0.5 * d * cos(a);
      p.y[i] += 0.49 * 0.5 * skin * sin(a) - 0.5 * d * sin(a);
    }
  }
  CU_ASSERT_FATAL(sph_nlist_fresh(&l, &p));
  size_t missing = 0;
  for (size_t i = 0; i < p.n; i++)
    for (size_t j = 0; j < p.n; j++) {
      const double dx = p.x[i] - p.x[j], dy = p.y[i] - p.y[j];
      if (j == i || !(dx * dx + dy * dy < support * support)) continue;
      int found = 0;
      size_t len;
      const uint32_t *row = sph_nlist_row(&l, i, &len);
      for (size_t k = 0; k < len; k++)
        found |= row[k] == j;
      missing += !found;
    }
  CU_ASSERT_EQUAL(missing, 0);
  /* the build's positions in single precision: off by a rounding of the
   * store's extent at most, far below the skin */
  CU_ASSERT(l.ref_err > 0.0 && l.ref_err < 1e-5 * skin);
  const double x5 = p.x[5];
  p.x[5] = sph_nlist_ref(&l, 0, 5) + 0.51 * skin;
  CU_ASSERT(!sph_nlist_fresh(&l, &p));
  p.x[5] = x5;
  CU_ASSERT(sph_nlist_fresh(&l, &p));
  size_t perm[2] = {1, 0};
  double work[2];
  const size_t n = p.n;
  p.n = 2; /* swap the first two particles: a reordered store */
  sph_particles_permute(&p, perm, work);
  p.n = n;
  CU_ASSERT(!sph_nlist_fresh(&l, &p));
  p.n = 2; /* swapped back: the list is still not trusted */
  sph_particles_permute(&p, perm, work);
  p.n = n;
  CU_ASSERT(!sph_nlist_fresh(&l, &p));
  CU_ASSERT_FATAL(sph_grid_build(&g, &p, (support + skin) * (1 + 1e-9), 1u << 24, &err) == 0);
  CU_ASSERT_FATAL(sph_nlist_build(&l, &g, &p, support, skin, 0.0, &err) == 0);
  CU_ASSERT(sph_nlist_fresh(&l, &p));
  sph_particles_move(&p, 7, 7); /* any move of a particle to a storage index */
  CU_ASSERT(!sph_nlist_fresh(&l, &p));
  /* far from the coordinates' origin (x about 1e5 m): the single-precision
   * positions count from the first particle's, so moves of 0.45 skin keep
   * the list fresh there as well */
  for (size_t i = 0; i < p.n; i++)
    p.x[i] += 1e5;
  CU_ASSERT_FATAL(sph_grid_build(&g, &p, (support + skin) * (1 + 1e-9), 1u << 24, &err) == 0);
  CU_ASSERT_FATAL(sph_nlist_build(&l, &g, &p, support, skin, 0.0, &err) == 0);
  CU_ASSERT(l.ref_err < 1e-5 * skin);
  for (size_t i = 0; i < p.n; i++)
    p.y[i] += 0.45 * 0.5 * skin;
  CU_ASSERT(sph_nlist_fresh(&l, &p));
  p.y[9] += 0.3 * skin; /* 0.525 skin in all */
  CU_ASSERT(!sph_nlist_fresh(&l, &p));
  for (size_t i = 0; i < p.n; i++)
    p.x[i] -= 1e5;
  /* without a skin: fresh until the first move, however small */
  CU_ASSERT_FATAL(sph_grid_build(&g, &p, support * (1 + 1e-9), 1u << 24, &err) == 0);
  CU_ASSERT_FATAL(sph_nlist_build(&l, &g, &p, support, 0.0, 0.0, &err) == 0);
  CU_ASSERT(sph_nlist_fresh(&l, &p));
  p.y[3] = nextafter(p.y[3], 1.0);
  CU_ASSERT(!sph_nlist_fresh(&l, &p));
  sph_nlist_free(&l);
  sph_grid_free(&g);
  sph_particles_free(&p);
}

/* A run gives the same bytes for any skin of the neighbour list, with the
 * run-time loop instead of the one compiled for the case's term set, and
 * with every flavour of the interaction's lane loop (the default, AVX-512
 * where the processor has it, against AVX2 and the portable lanes,
 * src/solver/forces.c). */
static void test_run_any_skin(void) {
  enum { N = 6 };
  char *d[N] = {0};
  const char *env[N] = {"SPH_TEST_SKIN=0.05", "SPH_TEST_SKIN=0.15",      "SPH_TEST_SKIN=0.4",
                        "SPH_TEST_RUNTIME=1", "SPH_TEST_LANES=portable", "SPH_TEST_LANES=avx"};
  const int avx = sph_force_loop_available(SPH_LOOP_LANES_AVX);
  const int k_end = avx ? N : N - 1;
  if (!avx) printf("\n  (no AVX2 on this processor: the AVX2 lanes are not compared)");
  printf("\n  the default loop here: %s", sph_force_loop_available(SPH_LOOP_LANES_AVX512)
                                              ? "AVX-512 eight lanes"
                                          : avx ? "AVX2 four lanes"
                                                : "portable four lanes");
  for (int k = 0; k < k_end; k++) {
    d[k] = sph_test_tmpdir();
    char cmd[8192];
    snprintf(cmd, sizeof cmd, "%s '%s' run --quiet --threads 1 '%s' -o '%s' --set time.end=0.1",
             env[k], sph_test_build("src/sph"), sph_test_src("cases/martin_moyce_coarse.yaml"),
             d[k]);
    CU_ASSERT_FATAL(sph_test_system(cmd) == 0);
  }
  for (int k = 1; k < k_end; k++) {
    char cmd[8192];
    snprintf(cmd, sizeof cmd, "diff -r '%s' '%s' >/dev/null", d[0], d[k]);
    CU_ASSERT(sph_test_system(cmd) == 0);
  }
  for (int k = 0; k < k_end; k++) {
    sph_test_rmtree(d[k]);
    free(d[k]);
  }
}

int main(void) {
  CU_TestInfo tests[] = {
      {"grid neighbours equal brute force (random sets)", test_random_sets},
      {"counting sort: the same order on teams of 1 to 3 threads", test_sort_any_team},
      {"the order is the positions' and ids' alone: shuffled, subsets", test_global_order},
      {"particles on cell edges and at exactly 2h", test_cell_edges},
      {"a grid of 2^31 cells a side is refused", test_grid_side_bound},
      {"permutation carries every field", test_permute_carries_fields},
      {"per-axis fields by name and by axis: the same arrays", test_fields_by_axis},
      {"arrays a store does not use stay zero and untouched", test_unused_groups_untouched},
      {"periodic grid, period of exactly 3 and 2 cells, against brute force",
       test_periodic_three_cells},
      {"periodic grid, longer periods, against brute force", test_periodic_long},
      {"periodic grid refuses a period under 2 cells", test_periodic_too_short},
      {"neighbour list equals brute force (sorted, binned, periodic)", test_list_brute_force},
      {"rows left empty by id: the others unchanged", test_list_no_row},
      {"the store gathered and put back array by array", test_gather_put},
      {"neighbour list: fresh within skin/2, stale beyond or reordered", test_list_fresh},
      {"a run is byte-identical for any skin, the run-time loop and every lane flavour",
       test_run_any_skin},
      CU_TEST_INFO_NULL};
  return sph_test_main("grid", tests);
}
