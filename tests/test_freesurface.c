/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_freesurface.c - free-surface detection (freesurface.h, paper A §7).
 *
 * Two oracles stand beside the module: a brute-force neighbour search (every
 * pair, no grid) that must give the same flags as the grid path, and a
 * geometric one that samples points on each circle and tests them against
 * every disc directly, with no arcs at all. The configurations: the arc
 * union alone (wrap-around, containment, touching and tiny gaps, order),
 * the disc rules, a square lattice (exactly the outer ring), a block with a
 * hole (the rim too), a block on walls, a hexagonal lattice, a layer
 * periodic in x, an isolated particle and pairs, coincident particles,
 * touching arcs in every rotation, and a lattice whose
 * particles sit on cell edges at equal and tangent distances, in shuffled
 * storage orders and with 1..3 threads. Every configuration is detected
 * five ways, which must agree flag for flag: from the grid with the cheap
 * certificates, from the grid by the arc test alone (exact_only), with the
 * interior certificate four neighbours at a time (AVX2) and one at a time, and from
 * the rows of a neighbour list without and with a skin. The certificates
 * are also tested alone, on random disc sets drawn at their edges.
 *
 * Golden files golden/freesurface/{hole,degenerate}.csv freeze the flags of
 * two configurations; `test_freesurface --regen` (with SPH_SRCDIR set to
 * the source tree) rewrites them instead of comparing.
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/particles.h"
#include "neighbours/grid.h"
#include "physics/freesurface.h"
#include "physics/kernel.h"
#include "testutil.h"

#define TWO_PI (2.0 * SPH_PI)

static int regen; /* --regen: write the golden files instead of comparing */

static unsigned long long rng = 0x9E3779B97F4A7C15ULL;
static double uniform(void) { return sph_test_uniform(&rng); }

/* ---- configurations ------------------------------------------------------ */

typedef struct pt {
  double x, y, h;
  int32_t kind;
} pt;

typedef struct cloud {
  pt *p;
  size_t n, cap;
  double period; /* > 0: periodic in x over [0, period) */
} cloud;

/* x_a - x_b, the minimum image in a periodic cloud. */
static double sep_x(const cloud *c, double xa, double xb) {
  double d = xa - xb;
  if (c->period > 0.0) d -= c->period * round(d / c->period);
  return d;
}

static void put(cloud *c, double x, double y, double h, int32_t kind) {
  if (c->n == c->cap) {
    c->cap = c->cap ? 2 * c->cap : 64;
    c->p = realloc(c->p, c->cap * sizeof *c->p);
  }
  c->p[c->n++] = (pt){x, y, h, kind};
}

/* nx x ny square lattice of spacing dx from (x0, y0). */
static void square(cloud *c, int nx, int ny, double x0, double y0, double dx, double h,
                   int32_t kind) {
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++)
      put(c, x0 + i * dx, y0 + j * dx, h, kind);
}

/* A random permutation of 0..n-1. */
static size_t *shuffled(size_t n) {
  size_t *perm = malloc((n ? n : 1) * sizeof *perm);
  for (size_t i = 0; i < n; i++)
    perm[i] = i;
  for (size_t i = n; i > 1; i--) {
    size_t k = (size_t)(uniform() * (double)i);
    size_t t = perm[i - 1];
    perm[i - 1] = perm[k];
    perm[k] = t;
  }
  return perm;
}

/* Loads c into a store (ids = indices in c), optionally permutes the
 * storage order, builds a grid of side `cell` (<= 0: 2 f max h plus a
 * hair), detects, and writes the flag of each id to out. Returns the
 * count the module reports; asserts it equals the flags set. */
static size_t detect(const cloud *c, const size_t *order, double f, double cell, uint8_t *out) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, c->n, &err) == 0);
  double hmax = 0.0;
  for (size_t i = 0; i < c->n; i++) {
    sph_particles_add(&p, c->p[i].x, c->p[i].y, 0, 0, 1000, 1, c->p[i].h, c->p[i].kind, &err);
    p.flags[i] = 0x80u; /* another bit, which detection must keep */
    if (c->p[i].h > hmax) hmax = c->p[i].h;
  }
  if (order) {
    double *work = malloc((c->n ? c->n : 1) * sizeof *work);
    sph_particles_permute(&p, order, work);
    free(work);
  }
  if (cell <= 0.0) cell = 2.0 * f * hmax * (1.0 + 1e-9);
  if (cell <= 0.0) cell = 1.0; /* empty store */
  sph_grid g;
  sph_grid_init(&g);
  if (c->period > 0.0)
    CU_ASSERT_FATAL(
        sph_grid_build_periodic(&g, &p, cell, SPH_AXIS_X, 0.0, c->period, 1u << 24, &err) == 0);
  if (c->period <= 0.0) CU_ASSERT_FATAL(sph_grid_build(&g, &p, cell, 1u << 24, &err) == 0);
  sph_freesurface_params fp = {.radius_factor = f, .period = c->period};
  size_t count = 12345, set = 0;
  int rc = sph_freesurface_detect(&p, &g, &fp, &count, &err);
  if (rc) fprintf(stderr, "detect: %s\n", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  for (size_t i = 0; i < p.n; i++) {
    CU_ASSERT((p.flags[i] & 0x80u) != 0);
    CU_ASSERT((p.flags[i] & 0x7Eu) == 0);
    out[p.id[i]] = p.flags[i] & SPH_FLAG_FREE_SURFACE;
    set += out[p.id[i]];
  }
  CU_ASSERT_EQUAL(count, set);
  /* the same flags from the arc test alone (no certificates), and from the
   * rows of a neighbour list (without a skin, and with one on a coarser
   * grid) instead of the grid's cells */
  uint8_t *first = malloc(p.n ? p.n : 1);
  for (size_t i = 0; i < p.n; i++)
    first[i] = p.flags[i];
  sph_freesurface_params exact = fp;
  exact.exact_only = 1;
  size_t n_exact = 0, n_list = 0, n_skin = 0, differ = 0;
  CU_ASSERT_FATAL(sph_freesurface_detect(&p, &g, &exact, &n_exact, &err) == 0);
  for (size_t i = 0; i < p.n; i++)
    differ += p.flags[i] != first[i];
  sph_nlist l;
  sph_nlist_init(&l);
  CU_ASSERT_FATAL(sph_nlist_build(&l, &g, &p, cell, 0.0, c->period, &err) == 0);
  rc = sph_freesurface_detect_list(&p, &l, &fp, &n_list, &err);
  if (rc) fprintf(stderr, "detect_list: %s\n", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  for (size_t i = 0; i < p.n; i++)
    differ += p.flags[i] != first[i];
  /* the interior certificate one neighbour at a time (without AVX2) */
  sph_freesurface_params one = fp;
  one.scalar = 1;
  size_t n_one = 0;
  CU_ASSERT_FATAL(sph_freesurface_detect_list(&p, &l, &one, &n_one, &err) == 0);
  CU_ASSERT_EQUAL(n_one, count);
  for (size_t i = 0; i < p.n; i++)
    differ += p.flags[i] != first[i];
  if (c->period <= 0.0 || c->period >= 3.0 * 1.5 * cell) {
    sph_grid g2;
    sph_grid_init(&g2);
    if (c->period > 0.0)
      CU_ASSERT_FATAL(sph_grid_build_periodic(&g2, &p, 1.5 * cell, SPH_AXIS_X, 0.0, c->period,
                                              1u << 24, &err) == 0);
    if (c->period <= 0.0) CU_ASSERT_FATAL(sph_grid_build(&g2, &p, 1.5 * cell, 1u << 24, &err) == 0);
    /* the coarser grid reorders the store: compare by id */
    for (size_t i = 0; i < p.n; i++)
      first[i] = out[p.id[i]];
    CU_ASSERT_FATAL(sph_nlist_build(&l, &g2, &p, cell, 0.5 * cell, c->period, &err) == 0);
    CU_ASSERT_FATAL(sph_freesurface_detect_list(&p, &l, &fp, &n_skin, &err) == 0);
    for (size_t i = 0; i < p.n; i++)
      differ += (p.flags[i] & SPH_FLAG_FREE_SURFACE) != first[i];
    sph_grid_free(&g2);
  } else {
    n_skin = count;
  }
  CU_ASSERT_EQUAL(differ, 0);
  CU_ASSERT_EQUAL(n_exact, count);
  CU_ASSERT_EQUAL(n_list, count);
  CU_ASSERT_EQUAL(n_skin, count);
  free(first);
  sph_nlist_free(&l);
  sph_grid_free(&g);
  sph_particles_free(&p);
  return count;
}

/* Oracle 1: the same rules, every pair, no grid. */
static void brute_force(const cloud *c, double f, uint8_t *out) {
  sph_arc *buf = malloc((c->n ? c->n : 1) * sizeof *buf);
  for (size_t i = 0; i < c->n; i++) {
    out[i] = 0;
    if (c->p[i].kind != SPH_KIND_FLUID) continue;
    size_t m = 0;
    int full = 0;
    for (size_t j = 0; j < c->n && !full; j++) {
      if (j == i) continue;
      int r = sph_freesurface_disc(sep_x(c, c->p[j].x, c->p[i].x), c->p[j].y - c->p[i].y,
                                   f * c->p[i].h, f * c->p[j].h, &buf[m]);
      if (r == SPH_DISC_FULL) full = 1;
      if (r == SPH_DISC_ARC) m++;
    }
    out[i] = !full && !sph_freesurface_arcs_cover(buf, m);
  }
  free(buf);
}

/* Oracle 2: samples ns points of circle i and tests each against every
 * closed disc j directly. Valid away from the degenerate cases (no
 * coincident particles, no gaps narrower than 2 pi / ns). */
static int sampled_uncovered(const cloud *c, size_t i, double f, int ns) {
  const double ri = f * c->p[i].h;
  /* discs farther than ri + rj cannot hold a sample (a tangent one, one point) */
  size_t *near = malloc((c->n ? c->n : 1) * sizeof *near), m = 0;
  for (size_t j = 0; j < c->n; j++) {
    const double dx = sep_x(c, c->p[j].x, c->p[i].x), dy = c->p[j].y - c->p[i].y;
    if (j != i && sqrt(dx * dx + dy * dy) < ri + f * c->p[j].h) near[m++] = j;
  }
  int uncovered = 0;
  for (int s = 0; s < ns && !uncovered; s++) {
    const double phi = TWO_PI * (s + 0.5) / ns;
    const double px = c->p[i].x + ri * cos(phi), py = c->p[i].y + ri * sin(phi);
    int covered = 0;
    for (size_t k = 0; k < m && !covered; k++) {
      const size_t j = near[k];
      const double dx = sep_x(c, px, c->p[j].x), dy = py - c->p[j].y, rj = f * c->p[j].h;
      covered = dx * dx + dy * dy <= rj * rj;
    }
    uncovered = !covered;
  }
  free(near);
  return uncovered;
}

static size_t mismatches(const uint8_t *a, const uint8_t *b, size_t n) {
  size_t k = 0;
  for (size_t i = 0; i < n; i++)
    k += a[i] != b[i];
  return k;
}

/* Runs the detection in a second, shuffled storage order and (with
 * OpenMP) with 1, 2 and 3 threads; every run must equal `ref`. */
static void check_invariance(const cloud *c, double f, double cell, const uint8_t *ref) {
  uint8_t *got = malloc(c->n + 1);
  size_t *perm = shuffled(c->n);
  detect(c, perm, f, cell, got);
  CU_ASSERT_EQUAL(mismatches(ref, got, c->n), 0);
  detect(c, NULL, f, cell, got); /* the same run again */
  CU_ASSERT_EQUAL(mismatches(ref, got, c->n), 0);
#ifdef _OPENMP
  const int saved = omp_get_max_threads();
  for (int t = 1; t <= 3; t++) {
    omp_set_num_threads(t);
    detect(c, perm, f, cell, got);
    CU_ASSERT_EQUAL(mismatches(ref, got, c->n), 0);
    detect(c, NULL, f, cell, got);
    CU_ASSERT_EQUAL(mismatches(ref, got, c->n), 0);
  }
  omp_set_num_threads(saved);
#endif
  free(perm);
  free(got);
}

/* ---- golden files --------------------------------------------------------- */

/* Compares (or with --regen writes) golden/freesurface/<name>.csv: one row
 * per particle in id order with its position, kind and flag. */
static void golden(const char *name, const char *what, const cloud *c, const uint8_t *flags) {
  size_t cap = 256 + 64 * c->n, len = 0;
  char *text = malloc(cap);
  len += (size_t)snprintf(text + len, cap - len,
                          "# golden: free-surface flags of %s (tests/test_freesurface.c)\n"
                          "# regenerate: SPH_SRCDIR=<source tree> tests/test_freesurface --regen\n"
                          "id,x,y,kind,free_surface\n",
                          what);
  for (size_t i = 0; i < c->n; i++)
    len += (size_t)snprintf(text + len, cap - len, "%zu,%.6f,%.6f,%d,%d\n", i, c->p[i].x, c->p[i].y,
                            (int)c->p[i].kind, (int)flags[i]);
  char rel[256];
  snprintf(rel, sizeof rel, "golden/freesurface/%s.csv", name);
  const char *path = sph_test_src(rel);
  if (regen) {
    mkdir(sph_test_src("golden"), 0777);
    mkdir(sph_test_src("golden/freesurface"), 0777);
    FILE *fw = fopen(path, "w");
    CU_ASSERT_FATAL(fw != NULL);
    fwrite(text, 1, len, fw);
    fclose(fw);
    printf("\n  wrote %s\n", path);
    free(text);
    return;
  }
  FILE *fr = fopen(path, "r");
  if (!fr) fprintf(stderr, "\n  missing golden file %s (run with --regen)\n", path);
  CU_ASSERT_FATAL(fr != NULL);
  char *old = malloc(len + 2);
  size_t got = fread(old, 1, len + 1, fr);
  fclose(fr);
  CU_ASSERT_EQUAL(got, len);
  if (got == len && memcmp(old, text, len) != 0) {
    size_t k = 0, line = 1;
    while (old[k] == text[k])
      line += text[k++] == '\n';
    fprintf(stderr, "\n  %s differs from the golden file at line %zu\n", path, line);
    CU_FAIL("golden file differs");
  }
  free(old);
  free(text);
}

/* ---- the disc rules and the arc union ------------------------------------- */

static void test_disc_rules(void) {
  sph_arc a = {-99, -99};
  /* apart, and externally tangent: nothing */
  CU_ASSERT_EQUAL(sph_freesurface_disc(3.0, 0.0, 1.0, 1.0, &a), SPH_DISC_NONE);
  CU_ASSERT_EQUAL(sph_freesurface_disc(0.0, -2.0, 1.0, 1.0, &a), SPH_DISC_NONE);
  CU_ASSERT_EQUAL(sph_freesurface_disc(1.5, 2.0, 1.0, 1.5, &a), SPH_DISC_NONE); /* d = 2.5 */
  /* a small disc inside circle i, touching it or not: nothing */
  CU_ASSERT_EQUAL(sph_freesurface_disc(0.5, 0.0, 2.0, 1.0, &a), SPH_DISC_NONE);
  CU_ASSERT_EQUAL(sph_freesurface_disc(1.0, 0.0, 2.0, 1.0, &a), SPH_DISC_NONE);
  /* a disc containing circle i, touching it inside or not: all */
  CU_ASSERT_EQUAL(sph_freesurface_disc(0.5, 0.0, 1.0, 2.0, &a), SPH_DISC_FULL);
  CU_ASSERT_EQUAL(sph_freesurface_disc(0.0, 1.0, 1.0, 2.0, &a), SPH_DISC_FULL);
  /* coincident: equal or smaller radius nothing, larger all */
  CU_ASSERT_EQUAL(sph_freesurface_disc(0.0, 0.0, 1.0, 1.0, &a), SPH_DISC_NONE);
  CU_ASSERT_EQUAL(sph_freesurface_disc(0.0, 0.0, 1.0, 0.5, &a), SPH_DISC_NONE);
  CU_ASSERT_EQUAL(sph_freesurface_disc(0.0, 0.0, 1.0, 1.5, &a), SPH_DISC_FULL);
  CU_ASSERT_EQUAL(a.lo, -99); /* untouched by NONE and FULL */
  /* equal radii at d = R: half-width pi/3 around the direction of j */
  CU_ASSERT_EQUAL(sph_freesurface_disc(0.0, 1.0, 1.0, 1.0, &a), SPH_DISC_ARC);
  CU_ASSERT_DOUBLE_EQUAL(a.lo, SPH_PI / 2 - SPH_PI / 3, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(a.hi, SPH_PI / 2 + SPH_PI / 3, 1e-15);
  /* 3-4-5: the disc of radius 5 at distance 4 covers exactly half of the
   * circle of radius 3 (the chord through the intersection points passes
   * through i) */
  CU_ASSERT_EQUAL(sph_freesurface_disc(-4.0, 0.0, 3.0, 5.0, &a), SPH_DISC_ARC);
  CU_ASSERT_DOUBLE_EQUAL(a.lo, SPH_PI / 2, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(a.hi, 3 * SPH_PI / 2, 1e-15);
  /* the arc end points are the intersection points of the two circles */
  for (int k = 0; k < 200; k++) {
    const double ri = 0.5 + uniform(), rj = 0.5 + uniform();
    const double d = fabs(ri - rj) + (ri + rj - fabs(ri - rj)) * (0.01 + 0.98 * uniform());
    const double t = TWO_PI * uniform(), dx = d * cos(t), dy = d * sin(t);
    CU_ASSERT_EQUAL_FATAL(sph_freesurface_disc(dx, dy, ri, rj, &a), SPH_DISC_ARC);
    CU_ASSERT(a.lo <= a.hi && a.hi - a.lo <= TWO_PI && a.lo >= -TWO_PI && a.hi <= TWO_PI);
    const double e[2] = {a.lo, a.hi};
    for (int s = 0; s < 2; s++) {
      const double ex = ri * cos(e[s]) - dx, ey = ri * sin(e[s]) - dy;
      CU_ASSERT_DOUBLE_EQUAL(sqrt(ex * ex + ey * ey), rj, 1e-9);
    }
    /* and its midpoint lies inside disc j */
    const double m = 0.5 * (a.lo + a.hi), mx = ri * cos(m) - dx, my = ri * sin(m) - dy;
    CU_ASSERT(mx * mx + my * my < rj * rj);
  }
}

static int cover2(double l0, double h0, double l1, double h1) {
  sph_arc a[2] = {{l0, h0}, {l1, h1}};
  return sph_freesurface_arcs_cover(a, 2);
}

static void test_arcs_basic(void) {
  const double tol = SPH_FREESURFACE_GAP_TOL;
  CU_ASSERT_EQUAL(sph_freesurface_arcs_cover(NULL, 0), 0);
  sph_arc one = {0.0, 6.0};
  CU_ASSERT_EQUAL(sph_freesurface_arcs_cover(&one, 1), 0);
  one = (sph_arc){-SPH_PI, SPH_PI}; /* one arc of the whole turn */
  CU_ASSERT_EQUAL(sph_freesurface_arcs_cover(&one, 1), 1);
  one = (sph_arc){1.0, 1.0 + TWO_PI - 1e-6};
  CU_ASSERT_EQUAL(sph_freesurface_arcs_cover(&one, 1), 0);
  /* touching halves: closed arcs join */
  CU_ASSERT_EQUAL(cover2(0.0, SPH_PI, SPH_PI, TWO_PI), 1);
  CU_ASSERT_EQUAL(cover2(SPH_PI, TWO_PI, 0.0, SPH_PI), 1);
  CU_ASSERT_EQUAL(cover2(-SPH_PI / 2, SPH_PI / 2, SPH_PI / 2, 3 * SPH_PI / 2), 1);
  /* tiny gaps: 1e-6 is open, 2 tol is open, tol and tol/2 close (the gap
   * of exactly tol: its end is fl(pi + tol) on both sides of the test) */
  CU_ASSERT_EQUAL(cover2(0.0, SPH_PI, SPH_PI + tol, TWO_PI), 1);
  CU_ASSERT_EQUAL(cover2(0.0, SPH_PI, SPH_PI + 1e-6, TWO_PI), 0);
  CU_ASSERT_EQUAL(cover2(0.0, SPH_PI, SPH_PI + 2 * tol, TWO_PI), 0);
  CU_ASSERT_EQUAL(cover2(0.0, SPH_PI, SPH_PI + 0.5 * tol, TWO_PI), 1);
  CU_ASSERT_EQUAL(cover2(0.0, SPH_PI - 2 * tol, SPH_PI, TWO_PI), 0);
  /* the gap at the seam 0 = 2 pi */
  CU_ASSERT_EQUAL(cover2(0.0, SPH_PI, SPH_PI, TWO_PI - 1e-6), 0);
  CU_ASSERT_EQUAL(cover2(1e-6, SPH_PI, SPH_PI, TWO_PI), 0);
  CU_ASSERT_EQUAL(cover2(0.5 * tol, SPH_PI, SPH_PI, TWO_PI), 1);
  /* wrap-around: arcs crossing the seam, written either side of it */
  CU_ASSERT_EQUAL(cover2(-1.0, 2.0, 2.0, TWO_PI - 1.0), 1);
  CU_ASSERT_EQUAL(cover2(-1.0, 2.0, 2.0, TWO_PI - 1.0 - 1e-6), 0);
  CU_ASSERT_EQUAL(cover2(5.0, 7.0, 0.7, 5.0), 1);
  CU_ASSERT_EQUAL(cover2(5.0, 6.9, 0.7, 5.0), 0);
  CU_ASSERT_EQUAL(cover2(-TWO_PI, -TWO_PI + 3.5, 3.5, TWO_PI), 1);
  CU_ASSERT_EQUAL(cover2(-TWO_PI + 3.5, 0.0, 0.0, 3.5), 1);
  CU_ASSERT_EQUAL(cover2(-TWO_PI + 3.5, -1e-6, 0.0, 3.5), 0);
  /* one arc contains the other: the gap stays */
  CU_ASSERT_EQUAL(cover2(0.0, 5.0, 1.0, 2.0), 0);
  /* a gap left between many overlapping arcs, found after the seam */
  {
    sph_arc a[6] = {{-0.5, 1.0}, {0.9, 2.0}, {1.5, 3.0}, {3.0, 4.0}, {4.2, 5.0}, {4.9, 5.9}};
    CU_ASSERT_EQUAL(sph_freesurface_arcs_cover(a, 6), 0); /* gap (4, 4.2) */
    sph_arc b[6] = {{-0.5, 1.0}, {0.9, 2.0}, {1.5, 3.0}, {3.0, 4.3}, {4.2, 5.0}, {4.9, 5.9}};
    CU_ASSERT_EQUAL(sph_freesurface_arcs_cover(b, 6), 1);
  }
}

/* Every order of the same arcs gives the same answer (Heap's algorithm over
 * all 720 orders of 6 arcs, for a covering and a non-covering set). */
static void test_arcs_order(void) {
  const sph_arc sets[2][6] = {
      {{-0.5, 1.0}, {1.0, 2.0}, {1.5, 3.0}, {3.0, 4.3}, {4.2, 5.0}, {5.0, TWO_PI - 0.5}},
      {{-0.5, 1.0}, {1.0, 2.0}, {1.5, 3.0}, {3.0, 4.3}, {4.2, 5.0}, {5.0, TWO_PI - 0.6}}};
  for (int s = 0; s < 2; s++) {
    sph_arc a[6], work[6];
    memcpy(a, sets[s], sizeof a);
    int c[6] = {0}, orders = 0, agree = 0;
    const int want = 1 - s;
    for (int i = 0; i < 6;) {
      memcpy(work, a, sizeof work);
      orders++;
      agree += sph_freesurface_arcs_cover(work, 6) == want;
      /* next permutation (Heap) */
      while (i < 6 && c[i] >= i)
        c[i++] = 0;
      if (i == 6) break;
      const int k = (i % 2) ? c[i] : 0;
      sph_arc t = a[k];
      a[k] = a[i];
      a[i] = t;
      c[i]++;
      i = 0;
    }
    CU_ASSERT_EQUAL(orders, 720);
    CU_ASSERT_EQUAL(agree, 720);
  }
}

/* Random discs around a unit circle: the exact answer equals the sampled
 * one (oracle 2), and both answers occur often. */
static void test_arcs_random(void) {
  int covered = 0, uncovered = 0, wrong = 0;
  for (int trial = 0; trial < 400; trial++) {
    cloud c = {0};
    put(&c, 0.0, 0.0, 1.0, SPH_KIND_FLUID);
    const int k = 1 + (int)(uniform() * 9);
    for (int j = 0; j < k; j++) {
      const double r = 2.2 * uniform(), t = TWO_PI * uniform();
      put(&c, r * cos(t), r * sin(t), 0.6 + 0.8 * uniform(), SPH_KIND_FLUID);
    }
    uint8_t bf[16];
    brute_force(&c, 1.0, bf);
    const int s = sampled_uncovered(&c, 0, 1.0, 1 << 15);
    wrong += bf[0] != s;
    covered += !bf[0];
    uncovered += bf[0];
    free(c.p);
  }
  CU_ASSERT_EQUAL(wrong, 0);
  CU_ASSERT(covered > 40);
  CU_ASSERT(uncovered > 40);
}

/* ---- lattices --------------------------------------------------------------- */

/* (1) 10 x 10 square lattice, h = 1.3 dx: exactly the outer ring. */
static void test_square_block(void) {
  const int n = 10;
  const double dx = 0.1;
  cloud c = {0};
  square(&c, n, n, 0.0, 0.0, dx, 1.3 * dx, SPH_KIND_FLUID);
  uint8_t got[100], bf[100];
  CU_ASSERT_EQUAL(detect(&c, NULL, 1.0, 0.0, got), 4 * (n - 1));
  size_t wrong = 0;
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      const int ring = i == 0 || j == 0 || i == n - 1 || j == n - 1;
      wrong += got[j * n + i] != ring;
    }
  CU_ASSERT_EQUAL(wrong, 0);
  brute_force(&c, 1.0, bf);
  CU_ASSERT_EQUAL(mismatches(got, bf, c.n), 0);
  for (size_t i = 0; i < c.n; i++)
    CU_ASSERT_EQUAL(got[i], sampled_uncovered(&c, i, 1.0, 4096));
  check_invariance(&c, 1.0, 0.0, got);
  free(c.p);
}

/* (2) 24 x 24 block with a round hole: the outer ring and the hole's rim. */
static void test_hole(void) {
  const int n = 24;
  const double dx = 0.1, h = 1.3 * dx;
  cloud c = {0};
  int *ii = malloc(n * n * sizeof *ii), *jj = malloc(n * n * sizeof *jj);
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      /* hole: centre (11.5, 11.5) dx, radius sqrt(20) dx, decided in
       * integers so no site sits on the edge */
      const int a = 2 * i - 23, b = 2 * j - 23;
      if (a * a + b * b < 80) continue;
      ii[c.n] = i;
      jj[c.n] = j;
      put(&c, i * dx, j * dx, h, SPH_KIND_FLUID);
    }
  uint8_t *got = malloc(c.n), *bf = malloc(c.n);
  size_t count = detect(&c, NULL, 1.0, 0.0, got);
  size_t ring = 0, rim = 0, far_flagged = 0, ring_missed = 0, sampled_wrong = 0;
  for (size_t k = 0; k < c.n; k++) {
    const int on_ring = ii[k] == 0 || jj[k] == 0 || ii[k] == n - 1 || jj[k] == n - 1;
    const double a = ii[k] - 11.5, b = jj[k] - 11.5;
    /* a circle can reach the hole only from within sqrt(20) + 2.6 dx */
    const int near = sqrt(a * a + b * b) < sqrt(20.0) + 2.6;
    ring_missed += on_ring && !got[k];
    far_flagged += !on_ring && !near && got[k];
    ring += on_ring;
    rim += !on_ring && got[k];
    sampled_wrong += got[k] != sampled_uncovered(&c, k, 1.0, 4096);
  }
  CU_ASSERT_EQUAL(ring_missed, 0);
  CU_ASSERT_EQUAL(far_flagged, 0);
  CU_ASSERT_EQUAL(sampled_wrong, 0);
  CU_ASSERT(rim >= 20);
  CU_ASSERT_EQUAL(count, ring + rim);
  /* the four rim sites facing the hole along its axes */
  for (size_t k = 0; k < c.n; k++) {
    const int i = ii[k], j = jj[k];
    if ((j == 11 && (i == 7 || i == 16)) || (i == 11 && (j == 7 || j == 16)))
      CU_ASSERT_EQUAL(got[k], 1);
    if ((j == 11 && (i == 4 || i == 19)) || (i == 11 && (j == 4 || j == 19)))
      CU_ASSERT_EQUAL(got[k], 0);
  }
  brute_force(&c, 1.0, bf);
  CU_ASSERT_EQUAL(mismatches(got, bf, c.n), 0);
  check_invariance(&c, 1.0, 0.0, got);
  golden("hole", "a 24 x 24 square lattice (dx = 0.1, h = 1.3 dx) with a round hole", &c, got);
  free(ii);
  free(jj);
  free(got);
  free(bf);
  free(c.p);
}

/* Walls cover but are never flagged: a fluid block on three wall layers. */
static void test_walls(void) {
  const int n = 8;
  const double dx = 0.1, h = 1.3 * dx;
  cloud c = {0};
  square(&c, n + 6, 3, -3 * dx, -3 * dx, dx, h, SPH_KIND_WALL);
  const size_t nw = c.n;
  square(&c, n, n, 0.0, 0.0, dx, h, SPH_KIND_FLUID);
  uint8_t *got = malloc(c.n), *bf = malloc(c.n);
  detect(&c, NULL, 1.0, 0.0, got);
  size_t wrong = 0;
  for (size_t k = 0; k < nw; k++)
    wrong += got[k] != 0;
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) /* the bottom row rests on the wall */
      wrong += got[nw + (size_t)(j * n + i)] != (i == 0 || i == n - 1 || j == n - 1);
  CU_ASSERT_EQUAL(wrong, 0);
  brute_force(&c, 1.0, bf);
  CU_ASSERT_EQUAL(mismatches(got, bf, c.n), 0);
  check_invariance(&c, 1.0, 0.0, got);
  free(got);
  free(bf);
  free(c.p);
}

/* A hexagonal lattice: the interior is not flagged, the top and bottom
 * rows are. */
static void test_hexagonal(void) {
  const int nx = 12, ny = 12;
  const double dx = 0.1;
  for (int variant = 0; variant < 2; variant++) {
    const double h = variant ? dx : 1.3 * dx;
    cloud c = {0};
    for (int j = 0; j < ny; j++)
      for (int i = 0; i < nx; i++)
        put(&c, (i + 0.5 * (j % 2)) * dx, j * dx * sqrt(3.0) / 2, h, SPH_KIND_FLUID);
    uint8_t *got = malloc(c.n), *bf = malloc(c.n);
    detect(&c, NULL, 1.0, 0.0, got);
    size_t interior_flagged = 0, edge_missed = 0;
    for (int j = 0; j < ny; j++)
      for (int i = 0; i < nx; i++) {
        const uint8_t f = got[j * nx + i];
        if (i >= 2 && i < nx - 2 && j >= 2 && j < ny - 2) interior_flagged += f;
        if (j == 0 || j == ny - 1 || (j % 2 == 0 && i == 0) || (j % 2 == 1 && i == nx - 1))
          edge_missed += !f;
      }
    CU_ASSERT_EQUAL(interior_flagged, 0);
    CU_ASSERT_EQUAL(edge_missed, 0);
    brute_force(&c, 1.0, bf);
    CU_ASSERT_EQUAL(mismatches(got, bf, c.n), 0);
    size_t sampled_wrong = 0;
    for (size_t k = 0; k < c.n; k++)
      sampled_wrong += got[k] != sampled_uncovered(&c, k, 1.0, 4096);
    CU_ASSERT_EQUAL(sampled_wrong, 0);
    free(got);
    free(bf);
    free(c.p);
  }
}

/* (3) an isolated particle, pairs, and coincident particles. */
static void test_isolated_and_pairs(void) {
  uint8_t got[4];
  cloud c = {0};
  put(&c, 0.3, 0.7, 0.1, SPH_KIND_FLUID);
  CU_ASSERT_EQUAL(detect(&c, NULL, 1.0, 0.0, got), 1);
  CU_ASSERT_EQUAL(got[0], 1);
  put(&c, 0.45, 0.7, 0.1, SPH_KIND_FLUID); /* a pair 1.5 h apart */
  CU_ASSERT_EQUAL(detect(&c, NULL, 1.0, 0.0, got), 2);
  CU_ASSERT(got[0] == 1 && got[1] == 1);
  c.p[1].x = 0.3; /* coincident, equal h: a duplicate hides nothing */
  CU_ASSERT_EQUAL(detect(&c, NULL, 1.0, 0.0, got), 2);
  CU_ASSERT(got[0] == 1 && got[1] == 1);
  c.p[1].h = 0.2; /* coincident, larger h: it contains the other circle */
  CU_ASSERT_EQUAL(detect(&c, NULL, 1.0, 0.0, got), 1);
  CU_ASSERT(got[0] == 0 && got[1] == 1);
  c.p[1].kind = SPH_KIND_WALL; /* a wall covers, and is not flagged */
  CU_ASSERT_EQUAL(detect(&c, NULL, 1.0, 0.0, got), 0);
  CU_ASSERT(got[0] == 0 && got[1] == 0);
  c.n = 1;
  c.p[0].kind = SPH_KIND_WALL; /* a lone wall particle: not flagged */
  CU_ASSERT_EQUAL(detect(&c, NULL, 1.0, 0.0, got), 0);
  CU_ASSERT_EQUAL(got[0], 0);
  c.n = 0; /* an empty store */
  CU_ASSERT_EQUAL(detect(&c, NULL, 1.0, 0.0, got), 0);
  free(c.p);
}

/* (5a) Arcs that touch in exact arithmetic: a particle with three
 * neighbours at distance R, 120 degrees apart, has three arcs of half-width
 * 60 degrees meeting end to end. Rounding of atan2 and acos leaves gaps or
 * overlaps of ~1e-16 rad; the tolerance makes it covered in all 720
 * rotations (half-degree steps, so arc ends fall on the seam too) and in
 * the mirror image. Moving the neighbours out by 1e-9 R opens gaps of
 * ~1e-9 rad (flagged everywhere); by 1e-13 R, gaps below the tolerance
 * (covered everywhere). */
static void test_touching_rotations(void) {
  const double R = 0.1;
  const double stretch[3] = {1.0, 1.0 + 1e-9, 1.0 + 1e-13};
  const int want[3] = {0, 1, 0};
  for (int s = 0; s < 3; s++) {
    int agree = 0, outer_flagged = 0;
    for (int k = 0; k < 1440; k++) {
      const double phi = (k % 720) * SPH_PI / 360.0, mirror = k < 720 ? 1.0 : -1.0;
      cloud c = {0};
      put(&c, 1.0, 2.0, R, SPH_KIND_FLUID);
      for (int m = 0; m < 3; m++) {
        const double t = phi + m * TWO_PI / 3, d = R * stretch[s];
        put(&c, 1.0 + d * cos(t), 2.0 + mirror * d * sin(t), R, SPH_KIND_FLUID);
      }
      uint8_t got[4];
      detect(&c, NULL, 1.0, 0.0, got);
      agree += got[0] == want[s];
      outer_flagged += got[1] + got[2] + got[3];
      free(c.p);
    }
    CU_ASSERT_EQUAL(agree, 1440);
    CU_ASSERT_EQUAL(outer_flagged, 3 * 1440);
  }
}

/* (5b) Arcs that touch exactly in floating point: circle i of radius 3,
 * neighbours of radius 5 at (+-4, 0) each cover a closed half, meeting at
 * +-pi/2 (acos(0) = pi/2 exactly as rounded). Covered; moved out by 1e-6,
 * the halves part and i is flagged. */
static void test_touching_exact(void) {
  for (int s = 0; s < 2; s++) {
    const double e = s ? 1e-6 : 0.0;
    cloud c = {0};
    put(&c, 0.0, 0.0, 3.0, SPH_KIND_FLUID);
    put(&c, 4.0 + e, 0.0, 5.0, SPH_KIND_WALL);
    put(&c, -4.0 - e, 0.0, 5.0, SPH_KIND_WALL);
    uint8_t got[3];
    CU_ASSERT_EQUAL(detect(&c, NULL, 1.0, 0.0, got), (size_t)s);
    CU_ASSERT_EQUAL(got[0], s);
    free(c.p);
  }
}

/* (5c) A lattice with spacing dx = 0.125 and R = h = dx, grid cells of
 * exactly 2R = 0.25: every other particle sits on a cell edge, pairs two
 * sites apart are exactly tangent (d = R_i + R_j, covering nothing), all
 * distances are exact. Added: a duplicate of an interior and of an edge
 * site (coincident, equal h), and a particle tangent to an edge particle
 * from outside. Expected: the outer ring, both copies of the edge site and
 * the tangent particle; the same in every storage order and thread count,
 * and as in golden/freesurface/degenerate.csv. */
static void test_degenerate_lattice(void) {
  const int n = 16;
  const double dx = 0.125;
  cloud c = {0};
  square(&c, n, n, 0.0, 0.0, dx, dx, SPH_KIND_FLUID);
  put(&c, 5 * dx, 7 * dx, dx, SPH_KIND_FLUID);  /* duplicate of interior site (5, 7) */
  put(&c, 9 * dx, 15 * dx, dx, SPH_KIND_FLUID); /* duplicate of edge site (9, 15) */
  put(&c, 4 * dx, -2 * dx, dx, SPH_KIND_FLUID); /* tangent to edge site (4, 0) */
  uint8_t *got = malloc(c.n), *bf = malloc(c.n);
  const size_t count = detect(&c, NULL, 1.0, 2 * dx, got);
  size_t wrong = 0;
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++)
      wrong += got[j * n + i] != (i == 0 || j == 0 || i == n - 1 || j == n - 1);
  CU_ASSERT_EQUAL(wrong, 0);
  CU_ASSERT_EQUAL(got[n * n], 0);
  CU_ASSERT_EQUAL(got[n * n + 1], 1);
  CU_ASSERT_EQUAL(got[n * n + 2], 1);
  CU_ASSERT_EQUAL(count, 4 * (n - 1) + 2);
  brute_force(&c, 1.0, bf);
  CU_ASSERT_EQUAL(mismatches(got, bf, c.n), 0);
  for (int t = 0; t < 3; t++)
    check_invariance(&c, 1.0, 2 * dx, got);
  golden("degenerate",
         "a 16 x 16 square lattice (dx = h = 0.125, cells 2h) with coincident and tangent "
         "particles",
         &c, got);
  free(got);
  free(bf);
  free(c.p);
}

/* A random cloud with varied h and some walls: the grid path equals the
 * brute-force oracle, in any storage order and thread count; also with a
 * radius factor of 2 on a grid of cells 4 h. */
static void test_random_cloud(void) {
  for (int trial = 0; trial < 3; trial++) {
    cloud c = {0};
    const double h0 = 0.01, f = trial == 2 ? 2.0 : 1.0;
    for (int k = 0; k < 1500; k++)
      put(&c, 0.4 * uniform(), 0.3 * uniform(), h0 * (0.8 + 0.4 * uniform()),
          uniform() < 0.2 ? SPH_KIND_WALL : SPH_KIND_FLUID);
    uint8_t *got = malloc(c.n), *bf = malloc(c.n);
    const size_t count = detect(&c, NULL, f, 0.0, got);
    brute_force(&c, f, bf);
    CU_ASSERT_EQUAL(mismatches(got, bf, c.n), 0);
    CU_ASSERT(count > 0 && count < c.n);
    check_invariance(&c, f, 0.0, got);
    free(got);
    free(bf);
    free(c.p);
  }
}

/* Periodic in x (the inclined plane of paper A §7): a layer of fluid on
 * walls, both periodic, straddling the seam. Only the top row is flagged;
 * on a plain grid the two ends are flagged too. Also with h* = 2 h on the
 * top row (larger discs, cells of 4 h). */
static void test_periodic(void) {
  const int nx = 24, ny = 5;
  const double dx = 0.1, h = 1.3 * dx;
  for (int variant = 0; variant < 3; variant++) {
    cloud c = {0};
    c.period = variant == 1 ? 0.0 : nx * dx;
    const double x0 = -6.5 * dx; /* a quarter of the layer lies left of x = 0 */
    square(&c, nx, 2, x0, -2 * dx, dx, h, SPH_KIND_WALL);
    const size_t nw = c.n;
    square(&c, nx, ny, x0, 0.0, dx, h, SPH_KIND_FLUID);
    if (variant == 2)
      for (int i = 0; i < nx; i++)
        c.p[nw + (size_t)((ny - 1) * nx + i)].h = 2 * h;
    uint8_t *got = malloc(c.n), *bf = malloc(c.n);
    const size_t count = detect(&c, NULL, 1.0, 0.0, got);
    size_t wrong = 0;
    for (size_t k = 0; k < nw; k++)
      wrong += got[k];
    for (int j = 0; j < ny; j++)
      for (int i = 0; i < nx; i++) {
        const int ends = variant == 1 && (i == 0 || i == nx - 1);
        wrong += got[nw + (size_t)(j * nx + i)] != (j == ny - 1 || ends);
      }
    CU_ASSERT_EQUAL(wrong, 0);
    CU_ASSERT_EQUAL(count, variant == 1 ? (size_t)(nx + 2 * (ny - 1)) : (size_t)nx);
    brute_force(&c, 1.0, bf);
    CU_ASSERT_EQUAL(mismatches(got, bf, c.n), 0);
    size_t sampled_wrong = 0;
    for (size_t k = nw; k < c.n; k++)
      sampled_wrong += got[k] != sampled_uncovered(&c, k, 1.0, 4096);
    CU_ASSERT_EQUAL(sampled_wrong, 0);
    check_invariance(&c, 1.0, 0.0, got);
    free(got);
    free(bf);
    free(c.p);
  }
}

/* ---- errors and the h* helper -------------------------------------------------- */

static void test_errors(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 16, &err) == 0);
  for (int k = 0; k < 9; k++)
    sph_particles_add(&p, 0.1 * (k % 3), 0.1 * (k / 3), 0, 0, 1000, 1, 0.1, SPH_KIND_FLUID, &err);
  sph_grid g;
  sph_grid_init(&g);
  CU_ASSERT_FATAL(sph_grid_build(&g, &p, 0.2, 1u << 20, &err) == 0);
  sph_freesurface_params fp = SPH_FREESURFACE_DEFAULTS;
  CU_ASSERT_EQUAL(fp.radius_factor, 1.0);
  size_t count = 0;
  CU_ASSERT_EQUAL(sph_freesurface_detect(&p, &g, &fp, &count, &err), 0);
  CU_ASSERT_EQUAL(count, 8);
  CU_ASSERT_EQUAL(sph_freesurface_detect(&p, &g, NULL, NULL, &err), 0); /* NULL: defaults */
  /* bad factors */
  const double bad[3] = {0.0, -1.0, NAN};
  for (int k = 0; k < 3; k++) {
    fp.radius_factor = bad[k];
    err.msg[0] = 0;
    CU_ASSERT_EQUAL(sph_freesurface_detect(&p, &g, &fp, &count, &err), -1);
    CU_ASSERT(strstr(err.msg, "radius factor") != NULL);
  }
  /* a factor whose discs outgrow the cells */
  fp.radius_factor = 1.5;
  CU_ASSERT_EQUAL(sph_freesurface_detect(&p, &g, &fp, &count, &err), -1);
  CU_ASSERT(strstr(err.msg, "larger cells") != NULL);
  fp.radius_factor = 1.0;
  /* one h larger than the cells allow, then a zero h */
  p.h[4] = 0.11;
  CU_ASSERT_EQUAL(sph_freesurface_detect(&p, &g, &fp, &count, &err), -1);
  CU_ASSERT(strstr(err.msg, "larger cells") != NULL);
  p.h[4] = 0.0;
  CU_ASSERT_EQUAL(sph_freesurface_detect(&p, &g, &fp, &count, &err), -1);
  CU_ASSERT(strstr(err.msg, "smoothing length") != NULL);
  p.h[4] = 0.1;
  /* a grid built on another store */
  sph_particles_add(&p, 0.05, 0.05, 0, 0, 1000, 1, 0.1, SPH_KIND_FLUID, &err);
  CU_ASSERT_EQUAL(sph_freesurface_detect(&p, &g, &fp, &count, &err), -1);
  CU_ASSERT(strstr(err.msg, "grid") != NULL);
  sph_grid g0;
  sph_grid_init(&g0); /* never built */
  CU_ASSERT_EQUAL(sph_freesurface_detect(&p, &g0, &fp, &count, &err), -1);
  /* periods: given to a plain grid, missing or wrong for a periodic one */
  CU_ASSERT_FATAL(sph_grid_build(&g, &p, 0.2, 1u << 20, &err) == 0);
  CU_ASSERT_EQUAL(sph_freesurface_detect(&p, &g, &fp, &count, &err), 0);
  fp.period = 1.0;
  CU_ASSERT_EQUAL(sph_freesurface_detect(&p, &g, &fp, &count, &err), -1);
  CU_ASSERT(strstr(err.msg, "not periodic") != NULL);
  CU_ASSERT_FATAL(sph_grid_build_periodic(&g, &p, 0.2, SPH_AXIS_X, 0.0, 1.0, 1u << 20, &err) == 0);
  CU_ASSERT_EQUAL(sph_freesurface_detect(&p, &g, &fp, &count, &err), 0);
  fp.period = 0.0;
  CU_ASSERT_EQUAL(sph_freesurface_detect(&p, &g, &fp, &count, &err), -1);
  CU_ASSERT(strstr(err.msg, "periodic") != NULL);
  fp.period = 1.1;
  CU_ASSERT_EQUAL(sph_freesurface_detect(&p, &g, &fp, &count, &err), -1);
  fp.period = -1.0;
  CU_ASSERT_EQUAL(sph_freesurface_detect(&p, &g, &fp, &count, &err), -1);
  CU_ASSERT(strstr(err.msg, "period") != NULL);
  /* a neighbour list: complete and large enough, else refused */
  fp.period = 0.0;
  sph_nlist l;
  sph_nlist_init(&l);
  CU_ASSERT_EQUAL(sph_freesurface_detect_list(&p, &l, &fp, &count, &err), -1); /* never built */
  CU_ASSERT(strstr(err.msg, "list") != NULL);
  CU_ASSERT_FATAL(sph_grid_build(&g, &p, 0.2, 1u << 20, &err) == 0);
  CU_ASSERT_FATAL(sph_nlist_build(&l, &g, &p, 0.15, 0.0, 0.0, &err) == 0);
  CU_ASSERT_EQUAL(sph_freesurface_detect_list(&p, &l, &fp, &count, &err), -1); /* < 2 f h */
  CU_ASSERT(strstr(err.msg, "support of at least 0.2") != NULL);
  CU_ASSERT_FATAL(sph_nlist_build(&l, &g, &p, 0.2, 0.0, 0.0, &err) == 0);
  CU_ASSERT_EQUAL(sph_freesurface_detect_list(&p, &l, &fp, &count, &err), 0);
  fp.period = 1.0;
  CU_ASSERT_EQUAL(sph_freesurface_detect_list(&p, &l, &fp, &count, &err), -1);
  CU_ASSERT(strstr(err.msg, "period") != NULL);
  fp.period = 0.0;
  p.x[0] += 1e-9; /* a move: a list without a skin is no longer complete */
  CU_ASSERT_EQUAL(sph_freesurface_detect_list(&p, &l, &fp, &count, &err), -1);
  CU_ASSERT(strstr(err.msg, "not complete") != NULL);
  sph_nlist_free(&l);
  sph_grid_free(&g);
  sph_particles_free(&p);
}

static void test_apply_h(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 16, &err) == 0);
  const int32_t kind[6] = {SPH_KIND_FLUID, SPH_KIND_FLUID, SPH_KIND_WALL,
                           SPH_KIND_WALL,  SPH_KIND_FLUID, SPH_KIND_FLUID};
  const uint8_t flags[6] = {0x01, 0x00, 0x01, 0x00, 0x81, 0x80};
  for (int k = 0; k < 6; k++) {
    sph_particles_add(&p, k, 0, 0, 0, 1000, 1, 0.37, kind[k], &err);
    p.flags[k] = flags[k];
  }
  sph_freesurface_apply_h(&p, 0.1, 2.0);
  const double want[6] = {0.2, 0.1, 0.1, 0.1, 0.2, 0.1};
  for (int k = 0; k < 6; k++) {
    CU_ASSERT_EQUAL(p.h[k], want[k]);
    CU_ASSERT_EQUAL(p.flags[k], flags[k]);
  }
  sph_freesurface_apply_h(&p, 0.1, 1.0); /* k = 1 restores h0 everywhere */
  for (int k = 0; k < 6; k++)
    CU_ASSERT_EQUAL(p.h[k], 0.1);
  sph_particles_free(&p);

  /* with detection: a block gets h* = 1.5 h on exactly its ring */
  cloud c = {0};
  square(&c, 6, 6, 0.0, 0.0, 0.1, 0.13, SPH_KIND_FLUID);
  CU_ASSERT_FATAL(sph_particles_init(&p, c.n, &err) == 0);
  for (size_t k = 0; k < c.n; k++)
    sph_particles_add(&p, c.p[k].x, c.p[k].y, 0, 0, 1000, 1, c.p[k].h, c.p[k].kind, &err);
  sph_grid g;
  sph_grid_init(&g);
  CU_ASSERT_FATAL(sph_grid_build(&g, &p, 2 * 0.13 * 1.5 * (1 + 1e-9), 1u << 20, &err) == 0);
  size_t count = 0;
  CU_ASSERT_EQUAL_FATAL(sph_freesurface_detect(&p, &g, NULL, &count, &err), 0);
  sph_freesurface_apply_h(&p, 0.13, 1.5);
  size_t big = 0;
  for (size_t k = 0; k < p.n; k++) {
    const long i = lround(p.x[k] / 0.1), j = lround(p.y[k] / 0.1);
    const int ring = i == 0 || j == 0 || i == 5 || j == 5;
    CU_ASSERT_EQUAL(p.h[k], ring ? 1.5 * 0.13 : 0.13);
    big += p.h[k] > 0.13;
  }
  CU_ASSERT_EQUAL(big, count);
  CU_ASSERT_EQUAL(count, 20);
  sph_grid_free(&g);
  sph_particles_free(&p);
  free(c.p);
}

/* The two certificates (freesurface.c) are only sufficient, and must never
 * contradict the arc test. On a square lattice (h = 1.3 dx) the interior
 * particle is proved covered and a top-row particle proved open at the
 * point straight above it. Then 400000 random sets of 1-12 discs around a
 * unit circle, drawn to sit on the certificates' edges: discs whose arcs
 * are 90 degrees wide to within 1e-5 (the cone test's threshold is 90.001),
 * directions within 1e-9 rad of a cone's edge (every other set with one
 * disc in each cone), radii 1 or 0.3-3, points
 * on the circle within 1e-9 rad of an arc's end; whenever cones_cover
 * says 1 the arcs cover, whenever point_open says 1 they do not, and both
 * certificates fire many times. */
/* The neighbours of a unit square lattice point, radius R each, in the
 * rows from dy = -1 up to dy = top; returns how many. */
static int lattice_neighbours(int top, double R, double *ox, double *oy, double *rr) {
  int n = 0;
  for (int a = -1; a <= 1; a++)
    for (int b = -1; b <= top; b++)
      if (a || b) {
        ox[n] = a;
        oy[n] = b;
        rr[n++] = R;
      }
  return n;
}

/* The interior certificate four candidates at a time (AVX2) gives the
 * bits of the one-at-a-time scan on every set: random clouds, lattice
 * points on the axes and diagonals (the cones' centres), points on the
 * cones' edges |dy| = tan(22.5 deg) |dx| and at the wide bound d = 2 GAMMA R,
 * across a periodic seam, with 0..40 candidates (so every tail length).
 * The flags cannot see a permutation of the cones' bits (eight held cones
 * stay eight): this compares the bits themselves. */
static void test_cones_simd(void) {
  enum { M = 40, NX = 2 * M };
  double x[NX], y[NX];
  uint32_t cand[M];
  const double R = 1.3, t = 0.41421356237309505, w = 2.0 * 0.7071 * R;
  unsigned sets = 0, bad = 0, full = 0;
  for (unsigned s = 0; s < 4000; s++) {
    const size_t m = s % (M + 1);
    const double period = (s % 5 == 4) ? 6.0 : 0.0;
    const double xi = period > 0.0 ? 0.3 * uniform() : 3.0, yi = 2.0;
    for (size_t k = 0; k < m; k++) {
      double dx, dy;
      switch ((s + k) % 4) {
      case 0: /* a random point within 2R */
        dx = (2.0 * uniform() - 1.0) * 2.0 * R, dy = (2.0 * uniform() - 1.0) * 2.0 * R;
        break;
      case 1: /* a lattice neighbour */
        dx = (double)((int)(3.0 * uniform()) - 1), dy = (double)((int)(3.0 * uniform()) - 1);
        break;
      case 2: /* on a cone's edge */
        dx = (uniform() < 0.5 ? -1.0 : 1.0) * (0.5 + uniform());
        dy = (uniform() < 0.5 ? -t : t) * dx;
        if (uniform() < 0.5) {
          const double u = dx;
          dx = dy, dy = u;
        }
        break;
      default: /* at the wide bound, on an axis or a diagonal */
        dx = (uniform() < 0.5 ? -w : w) * (uniform() < 0.5 ? 1.0 : 0.7071067811865476);
        dy = (uniform() < 0.5 ? 0.0 : dx);
        break;
      }
      const size_t j = (k * 7 + s) % NX; /* candidates in scattered storage */
      x[j] = period > 0.0 ? fmod(xi + dx + period, period) : xi + dx;
      y[j] = yi + dy;
      cand[k] = (uint32_t)j;
    }
    const unsigned a = sph_freesurface_cones_equal(x, y, cand, m, xi, yi, period, R, 1);
    const unsigned b = sph_freesurface_cones_equal(x, y, cand, m, xi, yi, period, R, 0);
    if (a != b && bad++ < 5) printf("\n  set %u: scalar cones %02x, four at a time %02x", s, a, b);
    full += a == 0xFFu;
    sets++;
  }
  printf("\n  %u candidate sets, %u with all eight cones held: the two scans agree bit for bit "
         "(%u differ)",
         sets, full, bad);
  CU_ASSERT(bad == 0);
  CU_ASSERT(full > 100 && full < sets - 100); /* both outcomes exercised */
}

static void test_certificates(void) {
  const double R = 1.3; /* h = 1.3 dx, dx = 1 */
  double ox[8], oy[8], rr[8];
  CU_ASSERT_FATAL(lattice_neighbours(1, R, ox, oy, rr) == 8);
  CU_ASSERT(sph_freesurface_cones_cover(ox, oy, rr, 8, R));
  CU_ASSERT(!sph_freesurface_point_open(ox, oy, rr, 8, R, 0.0, R)); /* buried */
  CU_ASSERT_FATAL(lattice_neighbours(0, R, ox, oy, rr) == 5);       /* a top-row particle */
  CU_ASSERT(!sph_freesurface_cones_cover(ox, oy, rr, 5, R));
  CU_ASSERT(sph_freesurface_point_open(ox, oy, rr, 5, R, 0.0, R));
  CU_ASSERT(!sph_freesurface_point_open(ox, oy, rr, 5, R, R, 0.0));
  long cones = 0, open = 0, contradictions = 0;
  for (int trial = 0; trial < 400000; trial++) {
    /* every other trial: one disc per cone (then 0-4 more), so that the
     * cone test has something to prove */
    const int per_cone = trial & 1;
    const int m = per_cone ? 8 + (int)(5 * uniform()) : 1 + (int)(12 * uniform());
    double x[12], y[12], r[12];
    sph_arc arcs[12];
    int na = 0, full = 0;
    for (int k = 0; k < m; k++) {
      r[k] = uniform() < 0.7 ? 1.0 : 0.3 + 2.7 * uniform();
      /* a half-width a near 45 degrees (cos a near 0.7071) or anywhere */
      double ca = uniform() < 0.6 ? 0.70710678 + 2e-5 * (uniform() - 0.5) : 2 * uniform() - 1;
      if (per_cone && k < 8 && uniform() < 0.97) ca = 0.7071 - 1e-5 * uniform(); /* just wide */
      /* the distance d that gives cos a = ca: d^2 - 2 ca d + 1 - r^2 = 0 */
      const double disc = ca * ca - 1.0 + r[k] * r[k];
      double d = disc >= 0.0 ? ca + sqrt(disc) : 0.5 + uniform();
      if (!(d > 0.0)) d = 0.5 * uniform() + 1e-3;
      double th;
      const double u = uniform();
      if (per_cone && k < 8) /* in cone k, often at one of its edges */
        th = (SPH_PI / 4.0) * k +
             (u < 0.5 ? (SPH_PI / 8.0) * (uniform() < 0.5 ? -1 : 1) + 1e-9 * (uniform() - 0.5)
                      : (SPH_PI / 4.0) * (uniform() - 0.5));
      else if (u < 0.4) /* near a cone's edge */
        th = (SPH_PI / 8.0) * (2 * (int)(8 * uniform()) + 1) + 1e-9 * (uniform() - 0.5);
      else if (u < 0.6) /* on an axis or a diagonal */
        th = (SPH_PI / 4.0) * (int)(8 * uniform());
      else
        th = TWO_PI * uniform();
      x[k] = d * cos(th);
      y[k] = d * sin(th);
      const int rc = sph_freesurface_disc(x[k], y[k], 1.0, r[k], &arcs[na]);
      if (rc == SPH_DISC_ARC) na++;
      full |= rc == SPH_DISC_FULL;
    }
    sph_arc copy[12];
    memcpy(copy, arcs, sizeof arcs);
    const int covered = full || sph_freesurface_arcs_cover(copy, (size_t)na);
    const int c1 = sph_freesurface_cones_cover(x, y, r, (size_t)m, 1.0);
    /* a point near an arc's end, or anywhere */
    double phi = TWO_PI * uniform();
    if (na && uniform() < 0.7) {
      const int k = (int)(na * uniform());
      phi = (uniform() < 0.5 ? arcs[k].lo : arcs[k].hi) +
            1e-9 * (uniform() - 0.5) * (uniform() < 0.5 ? 1 : 1e3);
    }
    const int c2 = sph_freesurface_point_open(x, y, r, (size_t)m, 1.0, cos(phi), sin(phi));
    cones += c1;
    open += c2;
    contradictions += (c1 && !covered) + (c2 && covered);
  }
  printf("\n  certificates: covered %ld times, open %ld times, contradictions %ld", cones, open,
         contradictions);
  CU_ASSERT_EQUAL(contradictions, 0);
  CU_ASSERT(cones > 1000);
  CU_ASSERT(open > 10000);
}

int main(int argc, char **argv) {
  setenv("SPH_TEST_OMP_MIN", "0", 1); /* parallel loops even for the small test sets */
  for (int k = 1; k < argc; k++) {
    if (!strcmp(argv[k], "--regen")) {
      regen = 1;
    } else {
      fprintf(stderr, "usage: %s [--regen]\n", argv[0]);
      return 2;
    }
  }
  CU_TestInfo tests[] = {
      {"disc rules", test_disc_rules},
      {"arc union: wrap-around, touching, gaps", test_arcs_basic},
      {"arc union: independent of order", test_arcs_order},
      {"arc union against sampling", test_arcs_random},
      {"square block: the outer ring", test_square_block},
      {"block with a hole: ring and rim", test_hole},
      {"walls cover, never flagged", test_walls},
      {"hexagonal lattice", test_hexagonal},
      {"isolated particle, pairs, coincident", test_isolated_and_pairs},
      {"touching arcs in every rotation", test_touching_rotations},
      {"touching arcs, exact in floating point", test_touching_exact},
      {"cell edges, tangent and coincident", test_degenerate_lattice},
      {"random cloud against brute force", test_random_cloud},
      {"the cheap certificates never contradict the arcs", test_certificates},
      {"the interior certificate four at a time: the bits of one at a time", test_cones_simd},
      {"periodic in x", test_periodic},
      {"errors", test_errors},
      {"h* = k h on the surface", test_apply_h},
      CU_TEST_INFO_NULL};
  return sph_test_main("freesurface", tests);
}
