/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_grid_3d.c - the particle store, the cell-linked list and the
 * neighbour list as the 3-D build compiles them: this file is built with
 * -DSPH_DIM=3 and linked with src/libsph3.la, the library's sources compiled
 * for three dimensions (issue 37). The 2-D build's are checked by test_grid.
 *
 * The store: a per-axis field has a z array, the same by name and by axis;
 * sph_particles_add_at sets every axis; a permutation carries z along. The
 * grid: for random sets in boxes of every aspect (each axis the shortest in
 * turn), the directions are the axes in increasing extent, the store is in
 * cell-key order, and the neighbours found through the nine rows of the
 * 3x3x3 cells equal brute force; with particles on cell faces, edges and
 * corners a lattice particle has exactly its 6 face neighbours within 1.01
 * dx; periodic in x, with particles a little outside the period, the
 * minimum-image neighbours equal brute force; the counting sort gives the
 * same permutation on teams of 1 to 3 threads. The neighbour list: rows
 * equal brute force within its radius (sorted, binned, periodic), in
 * increasing storage index; fresh after moves under skin/2 in any direction,
 * stale after one beyond it along z.
 */
#include "config.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/particles.h"
#include "neighbours/grid.h"
#include "testutil.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#if SPH_DIM != 3
#error "test_grid_3d is built with -DSPH_DIM=3"
#endif

static unsigned long long rng = 88172645463325252ULL;
static double uniform(void) { return sph_test_uniform(&rng); }

/* A store of n particles uniform in the box [0, L[0]] x [0, L[1]] x [0, L[2]]
 * shifted by (-0.3, 2, 0.7). */
static void random_store(sph_particles *p, size_t n, const double L[3]) {
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(p, 16, &err) == 0);
  for (size_t i = 0; i < n; i++) {
    const double x[3] = {L[0] * uniform() - 0.3, L[1] * uniform() + 2.0, L[2] * uniform() + 0.7};
    const double v[3] = {0.0, 0.0, 0.0};
    CU_ASSERT_FATAL(sph_particles_add_at(p, x, v, 1000, 1, 0.01, SPH_KIND_FLUID, &err) >= 0);
  }
}

/* The axis that wraps in the periodic checks below (x unless a test sets it). */
static int paxis = SPH_AXIS_X;

/* The squared distance of i and j, the axis paxis taken as the minimum image over period (0:
 * none). */
static double dist2(const sph_particles *p, size_t i, size_t j, double period) {
  double d[3];
  for (int a = 0; a < 3; a++)
    d[a] = p->pos[a][i] - p->pos[a][j];
  if (period > 0.0) d[paxis] -= period * nearbyint(d[paxis] / period);
  return d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
}

static int cmp_i64(const void *a, const void *b) {
  const int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
  return (x > y) - (x < y);
}

/* The cell key of storage index i. */
static size_t key_of(const sph_grid *g, size_t i) {
  return ((size_t)g->cell_of[2][i] * (size_t)g->ncell[1] + (size_t)g->cell_of[1][i]) *
             (size_t)g->ncell[0] +
         (size_t)g->cell_of[0][i];
}

/* Grid neighbours (every range of sph_grid_ranges_all) against brute force
 * for every particle, the store in key order, the directions by extent. */
static void check_grid(sph_particles *p, double support, double period) {
  sph_grid g;
  sph_grid_init(&g);
  sph_error err;
  const double cell = support * (1.0 + 1e-9);
  const int rc = period > 0.0
                     ? sph_grid_build_periodic(&g, p, cell, paxis, 0.0, period, 1u << 24, &err)
                     : sph_grid_build(&g, p, cell, 1u << 24, &err);
  CU_ASSERT_FATAL(rc == 0);
  if (period > 0.0) {
    CU_ASSERT_EQUAL(g.axis[0], paxis);
    CU_ASSERT_EQUAL(g.periodic, 1 + paxis);
    CU_ASSERT_DOUBLE_EQUAL(sph_grid_period(&g), period, 1e-12);
  }
  double ext[3];
  for (int d = 0; d < 3; d++) {
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < p->n; i++)
      lo = fmin(lo, p->pos[d][i]), hi = fmax(hi, p->pos[d][i]);
    ext[d] = hi - lo;
  }
  for (int d = period > 0.0 ? 2 : 1; d < 3; d++) /* increasing extent */
    CU_ASSERT(ext[g.axis[d - 1]] <= ext[g.axis[d]]);
  for (size_t i = 1; i < p->n; i++)
    CU_ASSERT(key_of(&g, i - 1) <= key_of(&g, i));
  const double s2 = support * support;
  int64_t *a = malloc(p->n * sizeof *a), *b = malloc(p->n * sizeof *b);
  size_t mismatches = 0, pairs = 0;
  for (size_t i = 0; i < p->n; i++) {
    size_t na = 0, nb = 0, lo[SPH_GRID_RANGES], hi[SPH_GRID_RANGES];
    sph_grid_ranges_all(&g, i, lo, hi);
    for (int k = 0; k < SPH_GRID_RANGES; k++)
      for (size_t j = lo[k]; j < hi[k]; j++)
        if (j != i && dist2(p, i, j, period) < s2) a[na++] = p->id[j];
    for (size_t j = 0; j < p->n; j++)
      if (j != i && dist2(p, i, j, period) < s2) b[nb++] = p->id[j];
    qsort(a, na, sizeof *a, cmp_i64);
    qsort(b, nb, sizeof *b, cmp_i64);
    pairs += nb;
    mismatches += na != nb || memcmp(a, b, na * sizeof *a);
  }
  CU_ASSERT_EQUAL(mismatches, 0);
  CU_ASSERT(pairs > p->n); /* more than one neighbour each on average */
  CU_ASSERT_PTR_NULL(sph_grid_check(&g, p->n));
  free(a);
  free(b);
  sph_grid_free(&g);
}

static void test_store_axes(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 4, &err) == 0);
  CU_ASSERT_EQUAL(SPH_STORE_DIM, 3);
  CU_ASSERT_PTR_EQUAL(p.pos[SPH_AXIS_Z], p.z);
  CU_ASSERT_PTR_EQUAL(p.vel[SPH_AXIS_Z], p.vz);
  CU_ASSERT_PTR_EQUAL(p.acc[SPH_AXIS_Z], p.az);
  CU_ASSERT_PTR_EQUAL(p.rest[SPH_AXIS_Z], p.zr);
  CU_ASSERT_PTR_EQUAL(p.mirror_offset[SPH_AXIS_Z], p.mz);
  for (int i = 0; i < 40; i++) { /* grows past its first capacity */
    const double x[3] = {i, 2.0 * i, 3.0 * i}, v[3] = {-i, -2.0 * i, -3.0 * i};
    CU_ASSERT_FATAL(sph_particles_add_at(&p, x, v, 1000, 1, 0.01, SPH_KIND_FLUID, &err) == i);
  }
  int bad = 0;
  for (size_t i = 0; i < p.n; i++)
    bad += p.z[i] != 3.0 * (double)i || p.vz[i] != -3.0 * (double)i || p.zr[i] != p.z[i] ||
           p.mz[i] != 0.0 || p.y[i] != 2.0 * (double)i;
  CU_ASSERT_EQUAL(bad, 0);
  size_t perm[40];
  double work[40];
  for (size_t i = 0; i < 40; i++)
    perm[i] = 39 - i;
  sph_particles_permute(&p, perm, work);
  for (size_t i = 0; i < p.n; i++)
    bad += p.z[i] != 3.0 * (double)(39 - i) || p.vz[i] != -3.0 * (double)(39 - i) ||
           p.id[i] != (int64_t)(39 - i);
  CU_ASSERT_EQUAL(bad, 0);
  sph_particles_free(&p);
}

static void test_random_sets(void) {
  /* each axis the shortest in turn, and a cube */
  const double box[4][3] = {{0.1, 0.2, 0.3}, {0.3, 0.1, 0.2}, {0.2, 0.3, 0.1}, {0.2, 0.2, 0.2}};
  for (int t = 0; t < 4; t++) {
    sph_particles p;
    random_store(&p, 1500, box[t]);
    check_grid(&p, 0.03, 0.0);
    sph_particles_free(&p);
  }
}

/* A lattice of spacing dx with a grid of cells exactly dx: particles sit on
 * cell faces, edges and corners. An interior particle has 6 neighbours
 * within 1.01 dx, 18 within 1.5 dx, 26 within 1.8 dx. */
static void test_lattice(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 16, &err) == 0);
  const double dx = 0.25, v[3] = {0, 0, 0};
  for (int k = 0; k < 6; k++)
    for (int j = 0; j < 7; j++)
      for (int i = 0; i < 5; i++) {
        const double x[3] = {i * dx, j * dx, k * dx};
        sph_particles_add_at(&p, x, v, 1000, 1, 0.01, SPH_KIND_FLUID, &err);
      }
  const double f[3] = {1.01, 1.5, 1.8};
  const size_t expect[3] = {6, 18, 26};
  for (int c = 0; c < 3; c++) {
    sph_grid g;
    sph_grid_init(&g);
    CU_ASSERT_FATAL(sph_grid_build(&g, &p, f[c] * dx, 1u << 20, &err) == 0);
    size_t wrong = 0;
    for (size_t i = 0; i < p.n; i++) {
      const double x = p.x[i] / dx, y = p.y[i] / dx, z = p.z[i] / dx;
      if (x < 1 || x > 3 || y < 1 || y > 5 || z < 1 || z > 4) continue; /* interior only */
      size_t lo[SPH_GRID_ROWS], hi[SPH_GRID_ROWS], cnt = 0;
      sph_grid_ranges(&g, i, lo, hi);
      for (int k = 0; k < SPH_GRID_ROWS; k++)
        for (size_t j = lo[k]; j < hi[k]; j++)
          cnt += j != i && dist2(&p, i, j, 0.0) < f[c] * f[c] * dx * dx;
      wrong += cnt != expect[c];
    }
    CU_ASSERT_EQUAL(wrong, 0);
    sph_grid_free(&g);
  }
  sph_particles_free(&p);
}

static void test_periodic(void) {
  const double box[2][3] = {{0.3, 0.1, 0.2}, {0.1, 0.2, 0.3}}; /* x longest; x shortest */
  const double period[2] = {0.3, 0.1};
  for (int t = 0; t < 2; t++) {
    sph_particles p;
    double L[3] = {box[t][0], box[t][1], box[t][2]};
    random_store(&p, 1200, L);
    for (size_t i = 0; i < p.n; i++)
      p.x[i] += 0.3; /* into [0, L) */
    p.x[0] = period[t] + 0.002, p.x[1] = -0.002, p.x[2] = 0.0;
    check_grid(&p, 0.03, period[t]);
    sph_particles_free(&p);
  }
  sph_particles p;
  const double L[3] = {0.08, 0.1, 0.1};
  random_store(&p, 100, L);
  sph_grid g;
  sph_grid_init(&g);
  sph_error err;
  /* 0.05 is under 2 cells of 0.03: refused; 0.08 makes 2 columns */
  CU_ASSERT(sph_grid_build_periodic(&g, &p, 0.03, SPH_AXIS_X, -0.3, -0.25, 1u << 20, &err) != 0);
  CU_ASSERT(strstr(err.msg, "fewer than 2 cells") != NULL);
  CU_ASSERT(sph_grid_build_periodic(&g, &p, 0.03, SPH_AXIS_X, -0.3, -0.22, 1u << 20, &err) == 0);
  CU_ASSERT_EQUAL(g.ncell[0], 2);
  CU_ASSERT(sph_grid_build_periodic(&g, &p, 0.03, 3, -0.3, 0.0, 1u << 20, &err) != 0);
  CU_ASSERT(strstr(err.msg, "axis") != NULL);
  sph_grid_free(&g);
  sph_particles_free(&p);
}

static void test_sort_any_team(void) {
  sph_particles p;
  const double L[3] = {0.4, 0.3, 0.2};
  random_store(&p, 6000, L);
  sph_grid g[3];
  sph_error err;
  for (int k = 0; k < 3; k++) {
    sph_grid_init(&g[k]);
#ifdef _OPENMP
    omp_set_num_threads(k + 1);
#endif
    CU_ASSERT_FATAL(sph_grid_bin(&g[k], &p, 0.05, 0, 0.0, 0.0, 1u << 24, &err) == 0);
  }
#ifdef _OPENMP
  omp_set_num_threads(2);
#endif
  const size_t cells = sph_grid_cells(&g[0]);
  CU_ASSERT_FATAL(cells < p.n);
  for (int k = 1; k < 3; k++) {
    CU_ASSERT(memcmp(g[k].perm, g[0].perm, p.n * sizeof *g[0].perm) == 0);
    CU_ASSERT(memcmp(g[k].start, g[0].start, (cells + 1) * sizeof *g[0].start) == 0);
  }
  for (int k = 0; k < 3; k++)
    sph_grid_free(&g[k]);
  sph_particles_free(&p);
}

/* The list against brute force within support + skin, rows (written out
 * from their runs, grid.h) increasing; returns the list's bytes per entry. */
static double check_list(sph_particles *p, double support, double skin, double period, int binned) {
  sph_grid g;
  sph_grid_init(&g);
  sph_nlist l;
  sph_nlist_init(&l);
  sph_error err;
  const double cell = (support + skin) * (1.0 + 1e-9);
  int rc;
  if (binned)
    rc = sph_grid_bin(&g, p, cell, period > 0.0 ? 1 + paxis : 0, 0.0, period, 1u << 24, &err);
  else if (period > 0.0)
    rc = sph_grid_build_periodic(&g, p, cell, paxis, 0.0, period, 1u << 24, &err);
  else
    rc = sph_grid_build(&g, p, cell, 1u << 24, &err);
  CU_ASSERT_FATAL(rc == 0);
  CU_ASSERT_FATAL(sph_nlist_build(&l, &g, p, support, skin, period, &err) == 0);
  const double r2 = (support + skin) * (support + skin);
  size_t bad = 0, pairs = 0, listed = 0;
  for (size_t i = 0; i < p->n; i++) {
    size_t len;
    const uint32_t *row = sph_nlist_row(&l, i, &len);
    bad += len != l.count[i];
    listed += l.count[i];
    size_t k = 0;
    for (size_t j = 0; j < p->n; j++) {
      if (j == i || !(dist2(p, i, j, period) < r2)) continue;
      pairs++;
      bad += k >= l.count[i] || row[k] != j;
      k++;
    }
    bad += k != l.count[i];
  }
  CU_ASSERT_EQUAL(bad, 0);
  CU_ASSERT(pairs > p->n);
  CU_ASSERT_EQUAL(listed, pairs);
  CU_ASSERT_PTR_NULL(sph_nlist_check(&l, p, support));
  const double per_entry = (double)l.off[p->n] / (double)listed;
  sph_nlist_free(&l);
  sph_grid_free(&g);
  return per_entry;
}

static void test_list(void) {
  for (int t = 0; t < 4; t++) {
    sph_particles p;
    const double L[3] = {0.2, 0.15, 0.1};
    random_store(&p, 1500, L);
    for (size_t i = 0; i < p.n; i++)
      p.x[i] += 0.3; /* into [0, 0.2) */
    const double b = check_list(&p, 0.025, 0.004 * t, t >= 2 ? 0.2 : 0.0, t % 2);
    CU_ASSERT(b > 2.0 && b < 2.5); /* one run a row: two bytes an entry, six a row */
    sph_particles_free(&p);
  }
  /* every particle every other's neighbour: rows of 599 entries, one run */
  sph_particles p;
  const double L[3] = {0.01, 0.01, 0.01};
  random_store(&p, 600, L);
  const double b = check_list(&p, 0.05, 0.0, 0.0, 0);
  CU_ASSERT_DOUBLE_EQUAL(b, (6.0 + 2.0 * 599.0) / 599.0, 1e-12);
  sph_particles_free(&p);
}

/* Wall rows with their fluid neighbours only (grid.h, wall_fluid_only): 2000 particles in a box
 * 0.3 deep, the lower half walls; a wall particle more than the list's radius below the fluid
 * is dry (no candidate range of it holds fluid: none is walked), one nearer lists its fluid
 * neighbours (only the ranges that hold fluid walked), a fluid particle every neighbour; each
 * row against brute force, on a sorted grid, a binned one (the store in another order) and a
 * grid periodic along x (a row's ranges split at the seam). */
static void test_list_wall_fluid_only(void) {
  for (int grid = 0; grid < 3; grid++) {
    const int binned = grid == 1;
    const double period = grid == 2 ? 0.2 : 0.0;
    sph_particles p;
    const double L[3] = {0.2, 0.15, 0.3}, support = 0.025, skin = 0.004;
    random_store(&p, 2000, L); /* z in [0.7, 1.0) */
    for (size_t i = 0; i < p.n && period > 0.0; i++)
      p.x[i] += 0.3; /* into [0, 0.2), the period */
    for (size_t i = 0; i < p.n; i++)
      if (p.z[i] < 0.85) p.kind[i] = SPH_KIND_WALL;
    if (binned) /* another storage order: the grid does not sort it */
      for (size_t i = 0; i + 1 < p.n; i += 2) {
        const double t = p.z[i];
        p.z[i] = p.z[i + 1], p.z[i + 1] = t;
        const int32_t k = p.kind[i];
        p.kind[i] = p.kind[i + 1], p.kind[i + 1] = k;
      }
    sph_grid g;
    sph_grid_init(&g);
    sph_nlist l;
    sph_nlist_init(&l);
    l.wall_fluid_only = 1;
    sph_error err;
    const double cell = (support + skin) * (1.0 + 1e-9);
    const int rc = binned ? sph_grid_bin(&g, &p, cell, 0, 0.0, 0.0, 1u << 24, &err)
                   : period > 0
                       ? sph_grid_build_periodic(&g, &p, cell, paxis, 0.0, period, 1u << 24, &err)
                       : sph_grid_build(&g, &p, cell, 1u << 24, &err);
    CU_ASSERT_FATAL(rc == 0);
    CU_ASSERT_EQUAL(g.sorted, !binned);
    for (int build = 0; build < 2; build++) { /* the first build sizes the rows, then again */
      CU_ASSERT_FATAL(sph_nlist_build(&l, &g, &p, support, skin, period, &err) == 0);
      const double r2 = (support + skin) * (support + skin);
      size_t bad = 0, dry = 0, wet = 0, fluid = 0;
      for (size_t i = 0; i < p.n; i++) {
        size_t len;
        const uint32_t *row = sph_nlist_row(&l, i, &len);
        bad += len != l.count[i];
        size_t k = 0;
        for (size_t j = 0; j < p.n; j++) {
          if (j == i || !(dist2(&p, i, j, period) < r2)) continue;
          if (p.kind[i] == SPH_KIND_WALL && p.kind[j] != SPH_KIND_FLUID) continue;
          bad += k >= len || row[k] != j;
          k++;
        }
        bad += k != len;
        if (p.kind[i] == SPH_KIND_FLUID)
          fluid += len > 0;
        else if (len)
          wet++;
        else
          dry++;
      }
      CU_ASSERT_EQUAL(bad, 0);
      CU_ASSERT(dry > 500 && wet > 50 && fluid > 500); /* every kind of row is there */
      if (bad || !(dry > 500 && wet > 50 && fluid > 500))
        printf("\n    grid %d build %d: %zu rows wrong; %zu dry, %zu wet walls, %zu fluid", grid,
               build, bad, dry, wet, fluid);
    }
    sph_nlist_free(&l);
    sph_grid_free(&g);
    sph_particles_free(&p);
  }
}

/* Rows whose entries span more than SPH_NLIST_RUN_MAX storage indices are
 * split into runs: 70 000 particles on a line 0.1 apart (no neighbours)
 * but for a cluster of storage indices 0, 1, 2, 40 000 and 69 999 in a
 * binned grid (the store keeps its order): row 0 is {1, 2, 40000, 69999},
 * runs {1, 2, 40000} and {69999}; row 69999 is {0, 1, 2, 40000}, one run. */
static void test_list_runs_split(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 16, &err) == 0);
  const size_t n = 70000, near[5] = {0, 1, 2, 40000, 69999};
  for (size_t i = 0; i < n; i++) {
    int in = 0;
    for (int k = 0; k < 5; k++)
      in |= near[k] == i;
    const double x[3] = {in ? 0.001 * (double)(i % 7) : 1.0 + 0.1 * (double)i, 1.0, 0.5};
    const double v[3] = {0.0, 0.0, 0.0};
    CU_ASSERT_FATAL(sph_particles_add_at(&p, x, v, 1000, 1, 0.01, SPH_KIND_FLUID, &err) >= 0);
  }
  sph_grid g;
  sph_grid_init(&g);
  sph_nlist l;
  sph_nlist_init(&l);
  CU_ASSERT_FATAL(sph_grid_bin(&g, &p, 0.021, 0, 0.0, 0.0, 1u << 24, &err) == 0);
  CU_ASSERT_FATAL(sph_nlist_build(&l, &g, &p, 0.02, 0.0, 0.0, &err) == 0);
  size_t listed = 0;
  for (size_t i = 0; i < n; i++)
    listed += l.count[i];
  CU_ASSERT_EQUAL(listed, 20);
  for (int k = 0; k < 5; k++) {
    size_t len;
    const uint32_t *row = sph_nlist_row(&l, near[k], &len);
    CU_ASSERT_EQUAL_FATAL(len, 4);
    for (size_t q = 0, m = 0; q < 5; q++)
      if (q != (size_t)k) CU_ASSERT_EQUAL(row[m++], near[q]);
  }
  CU_ASSERT_EQUAL(l.off[1] - l.off[0], 2 * 6 + 2 * 4); /* row 0: two runs */
  CU_ASSERT_EQUAL(l.off[n] - l.off[n - 1], 6 + 2 * 4); /* row 69999: one */
  /* rows 0, 1, 2 and 40000 reach from 0 or 1 to 69999: two runs each */
  CU_ASSERT_EQUAL(l.off[n], 4 * (2 * 6 + 2 * 4) + (6 + 2 * 4));
  CU_ASSERT_PTR_NULL(sph_nlist_check(&l, &p, 0.02));
#ifdef _OPENMP
  { /* built for one thread, read by two: the second writes rows into a buffer of its own */
    const int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    CU_ASSERT_FATAL(sph_nlist_build(&l, &g, &p, 0.02, 0.0, 0.0, &err) == 0);
    CU_ASSERT_EQUAL(l.dec_threads, 1);
    int bad = 0;
#pragma omp parallel num_threads(2) reduction(+ : bad)
    for (int k = 0; k < 5; k++) {
      size_t len;
      const uint32_t *row = sph_nlist_row(&l, near[k], &len);
      bad += len != 4;
      for (size_t q = 0, m = 0; q < 5 && len == 4; q++)
        if (q != (size_t)k) bad += row[m++] != near[q];
    }
    CU_ASSERT_EQUAL(bad, 0);
    omp_set_num_threads(saved);
  }
#endif
  uint16_t o[4], swapped[4]; /* row 69999's offsets, 1 and 2 swapped: caught */
  uint8_t *run = l.rows + l.off[n - 1] + SPH_NLIST_RUN_HEAD;
  memcpy(o, run, sizeof o);
  memcpy(swapped, o, sizeof o);
  swapped[1] = o[2], swapped[2] = o[1];
  memcpy(run, swapped, sizeof o);
  const char *m = sph_nlist_check(&l, &p, 0.02);
  CU_ASSERT(m != NULL && strstr(m, "not sorted") != NULL);
  memcpy(run, o, sizeof o);
  CU_ASSERT_PTR_NULL(sph_nlist_check(&l, &p, 0.02));
  sph_nlist_free(&l);
  sph_grid_free(&g);
  sph_particles_free(&p);
}

static void test_list_fresh(void) {
  sph_particles p;
  const double L[3] = {0.2, 0.15, 0.1};
  random_store(&p, 1500, L);
  const double support = 0.025, skin = 0.006;
  sph_grid g;
  sph_grid_init(&g);
  sph_nlist l;
  sph_nlist_init(&l);
  sph_error err;
  CU_ASSERT_FATAL(sph_grid_build(&g, &p, (support + skin) * (1 + 1e-9), 1u << 24, &err) == 0);
  CU_ASSERT_FATAL(sph_nlist_build(&l, &g, &p, support, skin, 0.0, &err) == 0);
  CU_ASSERT(sph_nlist_fresh(&l, &p));
  for (size_t i = 0; i < p.n; i++) { /* random directions, |d| < 0.49 skin/2 */
    double u[3], n2 = 0.0;
    for (int d = 0; d < 3; d++)
      u[d] = uniform() - 0.5, n2 += u[d] * u[d];
    const double s = 0.49 * 0.5 * skin * (i % 7 ? uniform() : 1.0) / sqrt(n2);
    for (int d = 0; d < 3; d++)
      p.pos[d][i] += s * u[d];
  }
  CU_ASSERT_FATAL(sph_nlist_fresh(&l, &p));
  size_t missing = 0;
  for (size_t i = 0; i < p.n; i++)
    for (size_t j = 0; j < p.n; j++) {
      if (j == i || !(dist2(&p, i, j, 0.0) < support * support)) continue;
      int found = 0;
      size_t len;
      const uint32_t *row = sph_nlist_row(&l, i, &len);
      for (size_t k = 0; k < len; k++)
        found |= row[k] == j;
      missing += !found;
    }
  CU_ASSERT_EQUAL(missing, 0);
  const double z5 = p.z[5];
  p.z[5] = sph_nlist_ref(&l, SPH_AXIS_Z, 5) + 0.51 * skin;
  CU_ASSERT(!sph_nlist_fresh(&l, &p));
  p.z[5] = z5;
  CU_ASSERT(sph_nlist_fresh(&l, &p));
  sph_nlist_free(&l);
  sph_grid_free(&g);
  sph_particles_free(&p);
}

/* Periodic along y and along z: the same store shifted into [0, period) along the axis that
 * wraps, its grid and list against brute force with the minimum image along that axis, the
 * axis the grid's direction 0 (its rows wrap) whatever the extents. */
static void test_periodic_yz(void) {
  for (int a = SPH_AXIS_Y; a <= SPH_AXIS_Z; a++)
    for (int t = 0; t < 2; t++) {
      sph_particles p;
      double L[3] = {0.2, 0.15, 0.1};
      L[a] = t ? 0.3 : 0.1; /* the periodic axis the longest, then the shortest */
      random_store(&p, 1500, L);
      const double shift[3] = {0.3, -2.0, -0.7}; /* random_store's offsets undone */
      for (size_t i = 0; i < p.n; i++)
        p.pos[a][i] += shift[a];
      p.pos[a][0] = L[a] + 0.002, p.pos[a][1] = -0.002, p.pos[a][2] = 0.0;
      paxis = a;
      check_grid(&p, 0.03, L[a]);
      check_list(&p, 0.025, 0.004, L[a], t);
      /* the list's freshness measures a move across the seam as its minimum image */
      sph_grid g;
      sph_grid_init(&g);
      sph_nlist l;
      sph_nlist_init(&l);
      sph_error err;
      CU_ASSERT_FATAL(
          sph_grid_build_periodic(&g, &p, 0.03 * (1 + 1e-9), a, 0.0, L[a], 1u << 24, &err) == 0);
      CU_ASSERT_FATAL(sph_nlist_build(&l, &g, &p, 0.025, 0.005, L[a], &err) == 0);
      CU_ASSERT_EQUAL(l.paxis, a);
      const size_t i = 7;
      const double r = sph_nlist_ref(&l, a, i);
      p.pos[a][i] = r + (r < 0.5 * L[a] ? L[a] : -L[a]) + 0.001;
      CU_ASSERT(sph_nlist_fresh(&l, &p)); /* moved 0.001 < skin/2 through the seam */
      p.pos[a][i] += 0.002;
      CU_ASSERT(!sph_nlist_fresh(&l, &p));
      paxis = SPH_AXIS_X;
      sph_nlist_free(&l);
      sph_grid_free(&g);
      sph_particles_free(&p);
    }
}

int main(void) {
  CU_TestInfo tests[] = {
      {"3-D store: z by name and by axis, set by add_at, carried by permute", test_store_axes},
      {"3-D grid neighbours equal brute force (boxes of every aspect)", test_random_sets},
      {"3-D lattice on cell faces: 6, 18 and 26 neighbours", test_lattice},
      {"3-D grid periodic in x against brute force (minimum image)", test_periodic},
      {"3-D grid and list periodic in y and in z against brute force", test_periodic_yz},
      {"3-D counting sort: the same order on teams of 1 to 3 threads", test_sort_any_team},
      {"3-D neighbour list equals brute force (sorted, binned, periodic)", test_list},
      {"3-D fluid-only wall rows: dry walls empty, wet walls their fluid (sorted, binned, "
       "periodic)",
       test_list_wall_fluid_only},
      {"3-D rows spanning more than 65535 indices are split into runs", test_list_runs_split},
      {"3-D neighbour list: fresh within skin/2, stale beyond along z", test_list_fresh},
      CU_TEST_INFO_NULL};
  return sph_test_main("grid_3d", tests);
}
