/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_filter.c - the density re-initialisation filters (filter.h).
 *
 * The particle sets are jittered lattices (seeded xorshift) with random
 * positive volumes V_b, masses m_b = rho_b V_b and, in most sets, two rows of
 * wall particles at the bottom. With those masses, sum_b m_b W^MLS_ab =
 * sum_b rho_b V_b W^MLS_ab, and the MLS correction makes that exact for any
 * linear rho_b whatever the (positive) V_b: so MLS must return the linear
 * field to rounding everywhere, edges and corners (one-sided
 * neighbourhoods) included. Shepard must return a constant field to
 * rounding and must NOT return a linear one near the edge.
 *
 * The fast filters are compared with a deliberately naive oracle: all
 * pairs, the 3x3 system solved by Gaussian elimination with partial
 * pivoting in physical units (a different algorithm from the cofactors in
 * filter.c). Also: independence of the storage order (to rounding) and of
 * the thread count (bitwise), the fallback on degenerate neighbourhoods,
 * the parameters (walls, variable h, periodic grid), names and errors.
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/particles.h"
#include "neighbours/grid.h"
#include "physics/filter.h"
#include "physics/kernel.h"
#include "testutil.h"

static unsigned long long rng;
static void seed(unsigned long long s) { rng = s * 2654435761ULL + 88172645463325252ULL; }
static double uniform(void) { return sph_test_uniform(&rng); }

static const double DX = 0.01; /* lattice spacing (m) */
static const double H = 0.013; /* 1.3 dx, paper B */

/* Density fields. */
static double field_linear(double x, double y) { return 1000.0 + 2000.0 * x - 1500.0 * y; }
static double field_const(double x, double y) {
  (void)x;
  (void)y;
  return 1012.5;
}
static double field_noisy(double x, double y) {
  return 1000.0 + 30.0 * sin(40.0 * x) * cos(25.0 * y) + 5.0 * (uniform() - 0.5);
}
typedef double (*field_fn)(double x, double y);

/* nx x ny lattice of spacing DX, jittered by up to +-jit DX in each
 * direction; the lowest wall_rows rows are wall particles; volumes
 * DX^2 (1 +- 0.2); rho from f, m = rho V; h = H (times 1 +- varh). */
static void make_set(sph_particles *p, int nx, int ny, double jit, int wall_rows, field_fn f,
                     double varh, unsigned long long s) {
  sph_error err;
  seed(s);
  CU_ASSERT_FATAL(sph_particles_init(p, (size_t)(nx * ny), &err) == 0);
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++) {
      const double x = (i + 0.5 + jit * (2.0 * uniform() - 1.0)) * DX;
      const double y = (j + 0.5 + jit * (2.0 * uniform() - 1.0)) * DX;
      const double vol = DX * DX * (1.0 + 0.4 * (uniform() - 0.5));
      const double rho = f(x, y);
      const double h = H * (1.0 + varh * (2.0 * uniform() - 1.0));
      sph_particles_add(p, x, y, 0, 0, rho, rho * vol, h,
                        j < wall_rows ? SPH_KIND_WALL : SPH_KIND_FLUID, &err);
    }
}

static double max_h(const sph_particles *p) {
  double m = 0.0;
  for (size_t i = 0; i < p->n; i++)
    if (p->h[i] > m) m = p->h[i];
  return m;
}

/* Builds the grid for p with cells of 2 * hmax. */
static void build_grid(sph_grid *g, sph_particles *p, double hmax) {
  sph_error err;
  CU_ASSERT_FATAL(sph_grid_build(g, p, SPH_CUBIC_SUPPORT * hmax, 1u << 24, &err) == 0);
}

/* Runs a filter kind on p (grid rebuilt); returns the fallback count. */
static size_t run_filter(sph_filter_kind k, sph_particles *p, const sph_filter_params *fp) {
  sph_grid g;
  sph_grid_init(&g);
  build_grid(&g, p, fp->h > 0.0 ? fp->h : max_h(p));
  double *scratch = malloc((p->n + 1) * sizeof *scratch);
  sph_error err;
  size_t fb = 12345;
  const int rc = sph_filter_apply(k, p, &g, fp, scratch, &fb, &err);
  if (rc) printf("\nfilter error: %s\n", err.msg);
  CU_ASSERT_EQUAL(rc, 0);
  free(scratch);
  sph_grid_free(&g);
  return fb;
}

/* ---- the naive oracle ----------------------------------------------------- */

/* Solves the 3x3 system A z = e0 by Gaussian elimination with partial
 * pivoting; returns z. */
static void solve3(double a[3][3], double z[3]) {
  double b[3] = {1.0, 0.0, 0.0};
  for (int c = 0; c < 3; c++) {
    int piv = c;
    for (int r = c + 1; r < 3; r++)
      if (fabs(a[r][c]) > fabs(a[piv][c])) piv = r;
    for (int k = 0; k < 3; k++) {
      double t = a[c][k];
      a[c][k] = a[piv][k];
      a[piv][k] = t;
    }
    double t = b[c];
    b[c] = b[piv];
    b[piv] = t;
    for (int r = c + 1; r < 3; r++) {
      const double f = a[r][c] / a[c][c];
      for (int k = c; k < 3; k++)
        a[r][k] -= f * a[c][k];
      b[r] -= f * b[c];
    }
  }
  for (int r = 2; r >= 0; r--) {
    double s = b[r];
    for (int k = r + 1; k < 3; k++)
      s -= a[r][k] * z[k];
    z[r] = s / a[r][r];
  }
}

/* The filtered densities by brute force, indexed by id. period > 0: x is
 * periodic with that period. ratio_min receives the smallest
 * det(A)/(tr A/3)^3 (positions in units of h_a) over the filtered
 * particles. */
static void oracle(sph_filter_kind k, const sph_particles *p, const sph_filter_params *fp,
                   double period, double *out, double *ratio_min) {
  *ratio_min = 1.0;
  for (size_t a = 0; a < p->n; a++) {
    const int filtered =
        p->kind[a] == SPH_KIND_FLUID || (fp->filter_walls && p->kind[a] == SPH_KIND_WALL);
    if (!filtered || k == SPH_FILTER_NONE) {
      out[p->id[a]] = p->rho[a];
      continue;
    }
    const double ha = fp->h > 0.0 ? fp->h : p->h[a];
    double A[3][3] = {{0}}, M[3] = {0}, As[3][3] = {{0}};
    for (size_t b = 0; b < p->n; b++) {
      if (fp->same_kind_only && p->kind[b] != p->kind[a]) continue;
      double dx = p->x[a] - p->x[b];
      if (period > 0.0) dx -= period * round(dx / period);
      const double dy = p->y[a] - p->y[b];
      const double hab = fp->h > 0.0 ? fp->h : 0.5 * (ha + p->h[b]);
      const double w = sph_cubic_w(sqrt(dx * dx + dy * dy), hab);
      if (w == 0.0) continue;
      const double P[3] = {1.0, dx, dy}, Ps[3] = {1.0, dx / ha, dy / ha};
      for (int r = 0; r < 3; r++) {
        M[r] += p->mass[b] * w * P[r];
        for (int c = 0; c < 3; c++) {
          A[r][c] += p->mass[b] / p->rho[b] * w * P[r] * P[c];
          As[r][c] += p->mass[b] / p->rho[b] * w * Ps[r] * Ps[c];
        }
      }
    }
    const double det = As[0][0] * (As[1][1] * As[2][2] - As[1][2] * As[2][1]) -
                       As[0][1] * (As[1][0] * As[2][2] - As[1][2] * As[2][0]) +
                       As[0][2] * (As[1][0] * As[2][1] - As[1][1] * As[2][0]);
    const double t = (As[0][0] + As[1][1] + As[2][2]) / 3.0;
    const double ratio = det / (t * t * t);
    if (ratio < *ratio_min) *ratio_min = ratio;
    if (k == SPH_FILTER_SHEPARD || ratio < fp->mls_det_min) {
      out[p->id[a]] = M[0] / A[0][0];
    } else {
      double z[3];
      solve3(A, z);
      out[p->id[a]] = z[0] * M[0] + z[1] * M[1] + z[2] * M[2];
    }
  }
}

/* Largest relative difference between p->rho (by id) and ref. */
static double max_rel_diff(const sph_particles *p, const double *ref) {
  double e = 0.0;
  for (size_t i = 0; i < p->n; i++) {
    const double d = fabs(p->rho[i] - ref[p->id[i]]) / fabs(ref[p->id[i]]);
    if (d > e) e = d;
  }
  return e;
}

/* ---- tests ---------------------------------------------------------------- */

/* MLS returns a linear field to rounding on an irregular set, everywhere:
 * interior, edges and corners, walls too when they are filtered. */
static void test_mls_linear_exact(void) {
  /* case 0: defaults; 1: walls filtered too; 2: same-kind neighbours only */
  for (int c = 0; c < 3; c++) {
    sph_particles p;
    make_set(&p, 30, 20, 0.3, 2, field_linear, 0.0, 11 + (unsigned)c);
    sph_filter_params fp;
    sph_filter_params_default(&fp, H);
    fp.filter_walls = c == 1;
    fp.same_kind_only = c == 2;
    double *before = malloc(p.n * sizeof *before);
    for (size_t i = 0; i < p.n; i++)
      before[p.id[i]] = p.rho[i];
    const size_t fb = run_filter(SPH_FILTER_MLS, &p, &fp);
    CU_ASSERT_EQUAL(fb, 0);
    double emax = 0.0, eedge = 0.0;
    size_t changed = 0;
    for (size_t i = 0; i < p.n; i++) {
      const double exact = field_linear(p.x[i], p.y[i]);
      const double e = fabs(p.rho[i] - exact) / exact;
      if (e > emax) emax = e;
      const int edge = p.x[i] < 2 * H || p.x[i] > 0.3 - 2 * H || p.y[i] > 0.2 - 2 * H;
      if (edge && e > eedge) eedge = e;
      if (p.kind[i] == SPH_KIND_WALL && !fp.filter_walls)
        CU_ASSERT(p.rho[i] == before[p.id[i]]); /* untouched, bitwise */
      if (p.rho[i] != before[p.id[i]]) changed++;
    }
    printf("\n  MLS linear field, case %d: max relative error %.2e (edge/corner %.2e) ", c, emax,
           eedge);
    CU_ASSERT(emax < 1e-12);
    CU_ASSERT(changed > 0);
    free(before);
    sph_particles_free(&p);
  }
}

/* The same with per-particle h (pair-mean kernel). */
static void test_mls_linear_variable_h(void) {
  sph_particles p;
  make_set(&p, 25, 25, 0.3, 2, field_linear, 0.25, 21);
  sph_filter_params fp;
  sph_filter_params_default(&fp, 0.0);
  fp.filter_walls = 1;
  CU_ASSERT_EQUAL(run_filter(SPH_FILTER_MLS, &p, &fp), 0);
  double emax = 0.0;
  for (size_t i = 0; i < p.n; i++) {
    const double exact = field_linear(p.x[i], p.y[i]);
    const double e = fabs(p.rho[i] - exact) / exact;
    if (e > emax) emax = e;
  }
  printf("\n  MLS linear field, variable h: max relative error %.2e ", emax);
  CU_ASSERT(emax < 1e-12);
  sph_particles_free(&p);
}

/* Shepard: a constant exactly; a linear field not (first-order error at
 * the edge, where the neighbourhood is one-sided). */
static void test_shepard_constant_not_linear(void) {
  sph_particles p;
  make_set(&p, 30, 20, 0.3, 2, field_const, 0.0, 31);
  sph_filter_params fp;
  sph_filter_params_default(&fp, H);
  fp.filter_walls = 1;
  run_filter(SPH_FILTER_SHEPARD, &p, &fp);
  double emax = 0.0;
  for (size_t i = 0; i < p.n; i++) {
    const double e = fabs(p.rho[i] - 1012.5) / 1012.5;
    if (e > emax) emax = e;
  }
  printf("\n  Shepard constant field: max relative error %.2e ", emax);
  CU_ASSERT(emax < 1e-14);
  sph_particles_free(&p);

  make_set(&p, 30, 20, 0.3, 2, field_linear, 0.0, 32);
  run_filter(SPH_FILTER_SHEPARD, &p, &fp);
  double eedge = 0.0, einner = 0.0;
  for (size_t i = 0; i < p.n; i++) {
    const double exact = field_linear(p.x[i], p.y[i]);
    const double e = fabs(p.rho[i] - exact) / exact;
    const int edge = p.x[i] < DX || p.x[i] > 0.3 - DX || p.y[i] < DX || p.y[i] > 0.2 - DX;
    const int inner =
        p.x[i] > 3 * H && p.x[i] < 0.3 - 3 * H && p.y[i] > 3 * H && p.y[i] < 0.2 - 3 * H;
    if (edge && e > eedge) eedge = e;
    if (inner && e > einner) einner = e;
  }
  printf("\n  Shepard linear field: max relative error at the edge %.2e, inside %.2e ", eedge,
         einner);
  CU_ASSERT(eedge > 1e-3);   /* about 0.4 h times the gradient */
  CU_ASSERT(einner < eedge); /* jitter only inside */
  sph_particles_free(&p);
}

/* Fast filters against the brute-force oracle on a non-linear field, in
 * each configuration of the parameters. */
static void test_against_oracle(void) {
  for (int c = 0; c < 8; c++) {
    const sph_filter_kind k = (c & 1) ? SPH_FILTER_SHEPARD : SPH_FILTER_MLS;
    sph_particles p;
    make_set(&p, 24, 18, 0.35, 2, field_noisy, (c & 4) ? 0.2 : 0.0, 41 + (unsigned)c);
    sph_filter_params fp;
    sph_filter_params_default(&fp, (c & 4) ? 0.0 : H);
    fp.filter_walls = (c & 2) != 0;
    fp.same_kind_only = (c & 2) != 0;
    double *ref = malloc(p.n * sizeof *ref), rmin;
    oracle(k, &p, &fp, 0.0, ref, &rmin);
    run_filter(k, &p, &fp);
    const double d = max_rel_diff(&p, ref);
    printf("\n  oracle, %s walls_filtered=%d same_kind_only=%d h=%s: max rel diff %.2e"
           " (min det ratio %.3f) ",
           sph_filter_name(k), fp.filter_walls, fp.same_kind_only, fp.h > 0 ? "const" : "var", d,
           rmin);
    CU_ASSERT(d < 1e-12);
    CU_ASSERT(rmin > 10 * SPH_FILTER_MLS_DET_MIN); /* a lattice corner is far from the limit */
    free(ref);
    sph_particles_free(&p);
  }
}

/* A new storage order changes sums by rounding only. */
static void test_storage_order(void) {
  for (int k = SPH_FILTER_MLS; k <= SPH_FILTER_SHEPARD; k++) {
    sph_particles a, b;
    make_set(&a, 30, 20, 0.3, 2, field_noisy, 0.0, 51);
    make_set(&b, 30, 20, 0.3, 2, field_noisy, 0.0, 51);
    size_t *perm = malloc(b.n * sizeof *perm);
    double *work = malloc(b.n * sizeof *work);
    for (size_t i = 0; i < b.n; i++)
      perm[i] = i;
    for (size_t i = b.n - 1; i > 0; i--) {
      const size_t j = (size_t)(uniform() * (double)(i + 1));
      const size_t t = perm[i];
      perm[i] = perm[j];
      perm[j] = t;
    }
    sph_particles_permute(&b, perm, work);
    sph_filter_params fp;
    sph_filter_params_default(&fp, H);
    run_filter((sph_filter_kind)k, &a, &fp);
    run_filter((sph_filter_kind)k, &b, &fp);
    double *ra = malloc(a.n * sizeof *ra);
    for (size_t i = 0; i < a.n; i++)
      ra[a.id[i]] = a.rho[i];
    const double d = max_rel_diff(&b, ra);
    printf("\n  %s, shuffled store: max rel diff %.2e ", sph_filter_name((sph_filter_kind)k), d);
    CU_ASSERT(d < 1e-13);
    free(ra);
    free(perm);
    free(work);
    sph_particles_free(&a);
    sph_particles_free(&b);
  }
}

/* Bitwise the same result with 1 and 4 threads. */
static void test_thread_count(void) {
#ifdef _OPENMP
  const int saved = omp_get_max_threads();
  for (int k = SPH_FILTER_MLS; k <= SPH_FILTER_SHEPARD; k++) {
    double *res[2];
    for (int t = 0; t < 2; t++) {
      omp_set_num_threads(t ? 4 : 1);
      sph_particles p;
      make_set(&p, 100, 60, 0.3, 2, field_noisy, 0.0, 61);
      sph_filter_params fp;
      sph_filter_params_default(&fp, H);
      fp.filter_walls = 1;
      run_filter((sph_filter_kind)k, &p, &fp);
      res[t] = malloc(p.n * sizeof *res[t]);
      memcpy(res[t], p.rho, p.n * sizeof *res[t]);
      sph_particles_free(&p);
    }
    CU_ASSERT(memcmp(res[0], res[1], 100 * 60 * sizeof *res[0]) == 0);
    free(res[0]);
    free(res[1]);
  }
  omp_set_num_threads(saved);
#else
  printf("\n  (built without OpenMP: thread-count test skipped) ");
#endif
}

/* Degenerate neighbourhoods: an isolated particle, a pair, a collinear
 * row: MLS falls back to Shepard (bitwise the Shepard filter's value),
 * nothing is NaN, and an isolated particle keeps its density. */
static void test_degenerate_fallback(void) {
  sph_particles p, q;
  sph_error err;
  sph_particles_init(&p, 16, &err);
  sph_particles_add(&p, 5.0, 5.0, 0, 0, 1003.0, 0.1003, H, SPH_KIND_FLUID, &err);  /* isolated */
  sph_particles_add(&p, -5.0, 0.0, 0, 0, 1001.0, 0.1001, H, SPH_KIND_FLUID, &err); /* a pair */
  sph_particles_add(&p, -5.0 + DX, 0.0, 0, 0, 999.0, 0.0999, H, SPH_KIND_FLUID, &err);
  for (int i = 0; i < 10; i++) /* a collinear row, on a slant */
    sph_particles_add(&p, 2.0 + 0.6 * DX * i, -3.0 + 0.8 * DX * i, 0, 0, 1000.0 + i, 0.1, H,
                      SPH_KIND_FLUID, &err);
  sph_particles_init(&q, 16, &err);
  for (size_t i = 0; i < p.n; i++)
    sph_particles_add(&q, p.x[i], p.y[i], 0, 0, p.rho[i], p.mass[i], H, SPH_KIND_FLUID, &err);
  sph_filter_params fp;
  sph_filter_params_default(&fp, H);
  const size_t fb = run_filter(SPH_FILTER_MLS, &p, &fp);
  CU_ASSERT_EQUAL(fb, 13);
  run_filter(SPH_FILTER_SHEPARD, &q, &fp);
  for (size_t i = 0; i < p.n; i++) {
    CU_ASSERT(isfinite(p.rho[i]));
    CU_ASSERT(p.rho[i] == q.rho[i]);
    if (p.id[i] == 0) CU_ASSERT(fabs(p.rho[i] - 1003.0) <= 1e-15 * 1003.0);
  }
  sph_particles_free(&q);
  sph_particles_free(&p);
  /* a filament: one row with perpendicular jitter of 1e-3 h is degenerate
   * for the threshold; two rows dx apart are not */
  for (int rows = 1; rows <= 2; rows++) {
    sph_particles_init(&p, 64, &err);
    seed(91);
    for (int r = 0; r < rows; r++)
      for (int i = 0; i < 30; i++)
        sph_particles_add(&p, i * DX, r * DX + 1e-3 * H * (2.0 * uniform() - 1.0), 0, 0, 1000.0,
                          0.1, H, SPH_KIND_FLUID, &err);
    const size_t nf = run_filter(SPH_FILTER_MLS, &p, &fp);
    printf("\n  filament of %d row(s): %zu of %zu particles fall back ", rows, nf, p.n);
    CU_ASSERT_EQUAL(nf, rows == 1 ? p.n : 0);
    for (size_t i = 0; i < p.n; i++)
      CU_ASSERT(isfinite(p.rho[i]));
    sph_particles_free(&p);
  }
  /* with the fallback disabled the exactly singular cases still fall back */
  fp.mls_det_min = 0.0;
  sph_particles_init(&p, 4, &err);
  sph_particles_add(&p, 0.0, 0.0, 0, 0, 1000.0, 0.1, H, SPH_KIND_FLUID, &err);
  CU_ASSERT_EQUAL(run_filter(SPH_FILTER_MLS, &p, &fp), 1);
  CU_ASSERT(isfinite(p.rho[0]));
  sph_particles_free(&p);
}

#ifdef SPH_GRID_RANGES
/* A grid periodic in x: the sums wrap across the seam; a field linear in y
 * (periodic in x) is exact there, and a non-linear periodic field matches
 * the oracle with minimum-image pair vectors. */
static double field_periodic(double x, double y) {
  return 1000.0 + 800.0 * y + 20.0 * sin(2.0 * SPH_PI * x / 0.2);
}
static void test_periodic(void) {
  for (int c = 0; c < 2; c++) {
    const sph_filter_kind k = c ? SPH_FILTER_SHEPARD : SPH_FILTER_MLS;
    sph_particles p;
    make_set(&p, 20, 15, 0.0, 2, c ? field_periodic : field_linear, 0.0, 71);
    for (size_t i = 0; i < p.n; i++) { /* make it linear in y only */
      if (!c) p.rho[i] = 1000.0 + 800.0 * p.y[i];
      p.mass[i] = p.rho[i] * DX * DX;
    }
    sph_filter_params fp;
    sph_filter_params_default(&fp, H);
    double *ref = malloc(p.n * sizeof *ref), rmin;
    oracle(k, &p, &fp, 0.2, ref, &rmin);
    sph_grid g;
    sph_grid_init(&g);
    sph_error err;
    CU_ASSERT_FATAL(sph_grid_build_periodic(&g, &p, 2 * H, SPH_AXIS_X, 0.0, 0.2, 1u << 20, &err) ==
                    0);
    double *scratch = malloc(p.n * sizeof *scratch);
    CU_ASSERT(sph_filter_apply(k, &p, &g, &fp, scratch, NULL, &err) == 0);
    const double d = max_rel_diff(&p, ref);
    printf("\n  periodic, %s: max rel diff to oracle %.2e ", sph_filter_name(k), d);
    CU_ASSERT(d < 1e-12);
    if (!c)
      for (size_t i = 0; i < p.n; i++)
        CU_ASSERT(fabs(p.rho[i] - (1000.0 + 800.0 * p.y[i])) < 1e-12 * p.rho[i]);
    free(scratch);
    free(ref);
    sph_grid_free(&g);
    sph_particles_free(&p);
  }
}
#endif

static void test_names(void) {
  sph_filter_kind k;
  sph_error err;
  for (int i = 0; i < 3; i++) {
    CU_ASSERT(sph_filter_from_name(sph_filter_name((sph_filter_kind)i), &k, &err) == 0);
    CU_ASSERT_EQUAL((int)k, i);
  }
  CU_ASSERT_STRING_EQUAL(sph_filter_name(SPH_FILTER_MLS), "mls");
  CU_ASSERT_STRING_EQUAL(sph_filter_name(SPH_FILTER_SHEPARD), "shepard");
  CU_ASSERT_STRING_EQUAL(sph_filter_name(SPH_FILTER_NONE), "none");
  CU_ASSERT_STRING_EQUAL(sph_filter_name((sph_filter_kind)7), "?");
  CU_ASSERT(sph_filter_kind_names[3] == NULL);
  CU_ASSERT(sph_filter_from_name("MLS2", &k, &err) != 0);
  CU_ASSERT(strstr(err.msg, "MLS2") && strstr(err.msg, "none, mls, shepard"));
}

/* none leaves rho alone; bad arguments are errors and change nothing. */
static void test_none_and_errors(void) {
  sph_particles p;
  make_set(&p, 10, 10, 0.3, 2, field_noisy, 0.0, 81);
  double *before = malloc(p.n * sizeof *before);
  sph_grid g;
  sph_grid_init(&g);
  build_grid(&g, &p, H);
  memcpy(before, p.rho, p.n * sizeof *before);
  double *scratch = malloc(p.n * sizeof *scratch);
  sph_filter_params fp;
  sph_filter_params_default(&fp, H);
  sph_error err;
  size_t fb = 99;
  CU_ASSERT(sph_filter_apply(SPH_FILTER_NONE, &p, &g, &fp, scratch, &fb, &err) == 0);
  CU_ASSERT_EQUAL(fb, 0);
  CU_ASSERT(sph_filter_mls(&p, &g, &fp, NULL, NULL, &err) != 0);
  CU_ASSERT(strstr(err.msg, "scratch") != NULL);
  fp.h = -1.0;
  CU_ASSERT(sph_filter_shepard(&p, &g, &fp, scratch, NULL, &err) != 0);
  fp.h = 2.0 * H; /* support 4H > cell 2H */
  CU_ASSERT(sph_filter_mls(&p, &g, &fp, scratch, NULL, &err) != 0);
  CU_ASSERT(strstr(err.msg, "smaller than the support") != NULL);
  fp.h = H;
  fp.mls_det_min = 1.0;
  CU_ASSERT(sph_filter_mls(&p, &g, &fp, scratch, NULL, &err) != 0);
  sph_filter_params_default(&fp, 0.0);
  p.h[3] = 0.0;
  CU_ASSERT(sph_filter_mls(&p, &g, &fp, scratch, NULL, &err) != 0);
  CU_ASSERT(strstr(err.msg, "smoothing length") != NULL);
  p.h[3] = H;
  CU_ASSERT(sph_filter_apply((sph_filter_kind)9, &p, &g, &fp, scratch, NULL, &err) != 0);
  CU_ASSERT(memcmp(before, p.rho, p.n * sizeof *before) == 0);
  /* an empty store is fine (the grid is not even looked at) */
  sph_particles e;
  sph_particles_init(&e, 1, &err);
  sph_grid ge;
  sph_grid_init(&ge);
  sph_filter_params_default(&fp, H);
  CU_ASSERT(sph_filter_mls(&e, &ge, &fp, NULL, NULL, &err) == 0);
  sph_grid_free(&ge);
  sph_particles_free(&e);
  free(scratch);
  free(before);
  sph_grid_free(&g);
  sph_particles_free(&p);
}

int main(void) {
  /* run the filters' loops in parallel however small the test sets are */
  setenv("SPH_TEST_OMP_MIN", "0", 1);
  CU_TestInfo tests[] = {
      {"MLS reproduces a linear field on an irregular set", test_mls_linear_exact},
      {"MLS linear field with variable h", test_mls_linear_variable_h},
      {"Shepard: constant exact, linear not", test_shepard_constant_not_linear},
      {"fast filters against the brute-force oracle", test_against_oracle},
      {"independent of the storage order", test_storage_order},
      {"independent of the thread count (bitwise)", test_thread_count},
      {"degenerate neighbourhoods fall back to Shepard", test_degenerate_fallback},
#ifdef SPH_GRID_RANGES
      {"periodic grid", test_periodic},
#endif
      {"names", test_names},
      {"none, and argument errors", test_none_and_errors},
      CU_TEST_INFO_NULL,
  };
  return sph_test_main("filter", tests);
}
