/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_checks.c - the debug invariants (src/core/check.h) hold on real
 * states and catch what they are for.
 *
 * 1. The coarse dam break's particles: the grid (sorted and binned,
 *    plain and periodic) and the neighbour list pass sph_grid_check and
 *    sph_nlist_check.
 * 2. Each check fails, with a message, on a corrupted copy: two row
 *    entries swapped, a neighbour dropped from a row, a cell offset moved.
 */
#include "config.h"

#include <stdio.h>
#include <string.h>

#include "case/case.h"
#include "core/particles.h"
#include "neighbours/grid.h"
#include "solver/sim.h"
#include "testsim.h"
#include "testutil.h"

static sph_case c;
static sph_sim *s;

static void load(void) {
  sph_error err;
  CU_ASSERT_FATAL(sph_test_open_sim("cases/martin_moyce_coarse.yaml", NULL, 0, &c, &s) == 0);
  for (int k = 0; k < 30; k++)
    CU_ASSERT_FATAL(sph_sim_step(s, c.t_end, &err) == 0);
}

static void test_real_state_passes(void) {
  load();
  sph_particles *p = sph_sim_particles(s);
  sph_error err;
  const double support = 2.0 * c.h;
  for (int periodic = 0; periodic < 2; periodic++) {
    sph_grid g;
    sph_grid_init(&g);
    const double x0 = -0.01, x1 = 0.24;
    int rc = periodic ? sph_grid_build_periodic(&g, p, support * 1.000001, SPH_AXIS_X, x0, x1,
                                                1u << 20, &err)
                      : sph_grid_build(&g, p, support * 1.000001, 1u << 20, &err);
    CU_ASSERT_FATAL(rc == 0);
    CU_ASSERT(sph_grid_check(&g, p->n) == NULL);
    sph_nlist l;
    sph_nlist_init(&l);
    CU_ASSERT_FATAL(sph_nlist_build(&l, &g, p, support, 0.0, periodic ? x1 - x0 : 0.0, &err) == 0);
    CU_ASSERT(sph_nlist_check(&l, p, support) == NULL);
    /* binned without sorting, with a skin */
    CU_ASSERT_FATAL(sph_grid_bin(&g, p, support * 1.2, periodic, x0, x1, 1u << 20, &err) == 0);
    CU_ASSERT(sph_grid_check(&g, p->n) == NULL);
    CU_ASSERT_FATAL(
        sph_nlist_build(&l, &g, p, support, 0.2 * support, periodic ? x1 - x0 : 0.0, &err) == 0);
    CU_ASSERT(sph_nlist_check(&l, p, support) == NULL);
    sph_nlist_free(&l);
    sph_grid_free(&g);
  }
}

static void test_corruption_caught(void) {
  sph_particles *p = sph_sim_particles(s);
  sph_error err;
  const double support = 2.0 * c.h;
  sph_grid g;
  sph_grid_init(&g);
  CU_ASSERT_FATAL(sph_grid_build(&g, p, support * 1.000001, 1u << 20, &err) == 0);
  sph_nlist l;
  sph_nlist_init(&l);
  CU_ASSERT_FATAL(sph_nlist_build(&l, &g, p, support, 0.0, 0.0, &err) == 0);
  size_t i = 0; /* a particle whose row has at least 2 entries (a 2-D row: plain indices) */
  while (l.count[i] < 2)
    i++;
  uint8_t *first = l.rows + l.off[i]; /* its entries */
  const size_t esz = 4;
  uint8_t t[8], swapped[8]; /* entries 0 and 1 swapped */
  memcpy(t, first, 2 * esz);
  memcpy(swapped, t + esz, esz);
  memcpy(swapped + esz, t, esz);
  memcpy(first, swapped, 2 * esz);
  const char *m = sph_nlist_check(&l, p, support);
  CU_ASSERT(m != NULL && strstr(m, "not sorted") != NULL);
  printf("\n  swapped entries: %s", m ? m : "(not caught)");
  memcpy(first, t, 2 * esz); /* restored */
  CU_ASSERT(sph_nlist_check(&l, p, support) == NULL);
  l.count[i]--; /* a row longer than its count */
  m = sph_nlist_check(&l, p, support);
  CU_ASSERT(m != NULL && strstr(m, "not its count") != NULL);
  printf("\n  miscounted row: %s", m ? m : "(not caught)");
  l.count[i]++;
  size_t far = 1, len; /* a particle not in row 0, moved next to particle 0: row 0 lacks it */
  const uint32_t *row0 = sph_nlist_row(&l, 0, &len);
  for (size_t k = 0; k < len; k++)
    if (row0[k] == far) far++; /* (the row is in increasing order) */
  CU_ASSERT_FATAL(far < p->n);
  const double fx = p->x[far], fy = p->y[far];
  p->x[far] = p->x[0] + 0.1 * c.h;
  p->y[far] = p->y[0];
  m = sph_nlist_check(&l, p, support);
  CU_ASSERT(m != NULL && strstr(m, "lacks") != NULL);
  printf("\n  missing neighbour: %s", m ? m : "(not caught)");
  p->x[far] = fx;
  p->y[far] = fy;
  CU_ASSERT(sph_nlist_check(&l, p, support) == NULL);
  size_t cell = 0; /* a cell with particles: move its end one back */
  while (g.start[cell + 1] == g.start[cell])
    cell++;
  g.start[cell + 1]--;
  m = sph_grid_check(&g, p->n);
  CU_ASSERT(m != NULL);
  printf("\n  moved cell offset: %s", m ? m : "(not caught)");
  g.start[cell + 1]++;
  CU_ASSERT(sph_grid_check(&g, p->n) == NULL);
  sph_nlist_free(&l);
  sph_grid_free(&g);
  sph_sim_free(s);
  sph_case_free(&c);
}

int main(void) {
  CU_TestInfo tests[] = {
      {"grid and neighbour list of a real state pass the checks", test_real_state_passes},
      {"a swapped, a dropped and a misplaced entry are caught", test_corruption_caught},
      CU_TEST_INFO_NULL,
  };
  return sph_test_main("debug invariants", tests);
}
