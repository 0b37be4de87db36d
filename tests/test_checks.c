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
  size_t i = 0; /* a particle with at least 3 neighbours */
  while (l.count[i] < 3)
    i++;
  uint32_t *row = l.nb + l.start[i];
  uint32_t t = row[0];
  row[0] = row[1];
  row[1] = t;
  const char *m = sph_nlist_check(&l, p, support);
  CU_ASSERT(m != NULL && strstr(m, "not sorted") != NULL);
  printf("\n  swapped entries: %s", m ? m : "(not caught)");
  row[1] = row[0];
  row[0] = t; /* restored */
  CU_ASSERT(sph_nlist_check(&l, p, support) == NULL);
  l.count[i]--; /* the last neighbour dropped (it is within the support) */
  m = sph_nlist_check(&l, p, support);
  CU_ASSERT(m != NULL && strstr(m, "lacks") != NULL);
  printf("\n  dropped neighbour: %s", m ? m : "(not caught)");
  l.count[i]++;
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
