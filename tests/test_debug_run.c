/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_debug_run.c - short runs with every debug invariant on.
 *
 * This program links tests/libsph_debug.la: the library's sources that hold
 * the costly checks (the grid, the force pass, the ledger, the simulation)
 * compiled with SPH_DEBUG_CHECKS (what --enable-debug-checks gives a whole
 * build), the rest libsph's own objects, so that every `make check` also
 * runs the costly checks once: the grid and the neighbour list after every
 * build, finite rates after every pass, the ledger's exact mass and finite
 * totals at every row. A broken invariant aborts with its file, line and
 * condition, and the test fails. The cases cover the loops' term sets:
 * the coarse dam break (lanes, XSPH) with the ledger (scalar), the wet bed
 * with its moving gate and stress tensor, the periodic inclined plane with
 * h* = 2h (variable h), the SPS dam break, and the hydrostatic tank with
 * mirror walls and the MLS filter.
 */
#include "config.h"

#include <stdio.h>

#include "sph.h"
#include "testsim.h"
#include "testutil.h"

static void steps(const char *rel, const char *const *set, size_t n_set, int n) {
  sph_error err;
  sph_case c;
  sph_sim *s;
  CU_ASSERT_FATAL(sph_test_open_sim(rel, set, n_set, &c, &s) == 0);
  int ok = 1;
  for (int k = 0; k < n && ok; k++) {
    ok = sph_sim_step(s, c.t_end, &err) == 0;
    sph_diag_row row;
    sph_sim_diag(s, &row); /* the ledger's invariants */
  }
  CU_ASSERT(ok);
  printf("\n  %s: %ld steps to t = %.4g s with the debug checks on", rel, sph_sim_steps(s),
         sph_sim_time(s));
  sph_sim_free(s);
  sph_case_free(&c);
}

static void test_cases(void) {
  const char *energy[] = {"output.energy=true"};
  steps("cases/martin_moyce_coarse.yaml", NULL, 0, 60);
  steps("cases/martin_moyce_coarse.yaml", energy, 1, 40);
  const char *wet[] = {"numerics.dx=0.01"};
  steps("cases/wet_bed_dam_break.yaml", wet, 1, 40);
  const char *plane[] = {"free_surface.h_factor=2", "numerics.integrator=leapfrog"};
  steps("cases/inclined_plane.yaml", plane, 2, 40);
  steps("cases/sps_dam_break_coarse.yaml", NULL, 0, 40);
  const char *mirror[] = {"geometry.tank.boundary=mirror", "numerics.density_filter.kind=mls",
                          "numerics.density_filter.every=5"};
  steps("tests/data/still_tank.yaml", mirror, 3, 40);
}

int main(void) {
  CU_TestInfo tests[] = {
      {"short runs of six cases with every invariant checked", test_cases},
      CU_TEST_INFO_NULL,
  };
  return sph_test_main("debug-check runs", tests);
}
