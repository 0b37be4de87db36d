/*
 * test_grid.c - the cell-linked list (grid.h) against a brute-force search.
 *
 * For random particle sets (and sets with particles exactly on cell edges
 * and at exactly the support distance), the neighbours found through the
 * grid's three index ranges equal the pairs found by testing every pair;
 * the sort is stable (ids keep their order within a cell) and a permutation
 * of the store carries every field along.
 */
#include "config.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "grid.h"
#include "particles.h"
#include "testutil.h"

static unsigned long long rng = 88172645463325252ULL;
static double uniform(void) {
  rng ^= rng << 13;
  rng ^= rng >> 7;
  rng ^= rng << 17;
  return (double)(rng >> 11) / 9007199254740992.0;
}

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
  const double s2 = support * support;
  int64_t *a = malloc(p->n * sizeof *a), *b = malloc(p->n * sizeof *b);
  size_t mismatches = 0, pairs = 0;
  for (size_t i = 0; i < p->n; i++) {
    size_t na = 0, nb = 0;
    size_t lo[3], hi[3];
    sph_grid_ranges(&g, i, lo, hi);
    for (int k = 0; k < 3; k++)
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
    const long ca = g.cy[i - 1] * g.nx + g.cx[i - 1], cb = g.cy[i] * g.nx + g.cx[i];
    CU_ASSERT(ca <= cb);
  }
  free(a);
  free(b);
  sph_grid_free(&g);
}

static void test_random_sets(void) {
  for (int trial = 0; trial < 5; trial++) {
    sph_particles p;
    sph_error err;
    CU_ASSERT_FATAL(sph_particles_init(&p, 16, &err) == 0);
    const size_t n = 500 + 400 * (size_t)trial;
    const double L = 0.1 * (trial + 1);
    for (size_t i = 0; i < n; i++)
      sph_particles_add(&p, L * uniform() - 0.3, 0.5 * L * uniform() + 2.0, 0, 0, 1000, 1, 0.01,
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
  for (size_t i = 0; i < p.n; i++) perm[i] = i;
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
    size_t lo[3], hi[3], cnt = 0;
    sph_grid_ranges(&g, i, lo, hi);
    for (int k = 0; k < 3; k++)
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
  for (int i = 0; i < 100; i++) perm[i] = (size_t)(99 - i);
  double work[100];
  sph_particles_permute(&p, perm, work);
  for (int i = 0; i < 100; i++) {
    const int o = 99 - i;
    CU_ASSERT(p.id[i] == o && p.x[i] == o && p.y[i] == -o && p.vx[i] == 2 * o &&
              p.vy[i] == 3 * o && p.rho[i] == 1000 + o && p.mass[i] == 1 + o &&
              p.h[i] == 0.5 * o && p.kind[i] == o % 2 && p.u[i] == 7.0 * o &&
              p.flags[i] == o % 3);
  }
  sph_particles_free(&p);
}

int main(void) {
  CU_TestInfo tests[] = {{"grid neighbours equal brute force (random sets)", test_random_sets},
                         {"particles on cell edges and at exactly 2h", test_cell_edges},
                         {"permutation carries every field", test_permute_carries_fields},
                         CU_TEST_INFO_NULL};
  return sph_test_main("grid", tests);
}
