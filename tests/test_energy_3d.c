/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_energy_3d.c - the energy ledger in 3-D (built with -DSPH_DIM=3,
 * linked with src/libsph3.la; doc/dimensions.md): the 3-D energy box
 * (tests/data/energy_box_3d.yaml, the 2-D box of test_energy with a width of
 * 0.025 m along y: a column collapsing in a closed box, no artificial
 * viscosity, step factor 0.15, 2000 fluid particles) closes its balance
 * kinetic + potential + internal - boundary work within 1e-4 of E0 at
 * t = 0.1 s with each wall model the 3-D build has (dynamic, fixed_layers;
 * measured 8.1e-6), the momentum balance along every axis to round-off, and
 * the column falls (kinetic energy above 5 % of the potential energy it had
 * above its final centre of mass).
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "case/case.h"
#include "solver/diag.h"
#include "solver/sim.h"
#include "testutil.h"

#if SPH_DIM != 3
#error "test_energy_3d is built with -DSPH_DIM=3"
#endif

static void run_box(const char *model) {
  char set[128];
  snprintf(set, sizeof set, "geometry.tank.boundary=%s", model);
  const char *const sets[1] = {set};
  sph_case c;
  sph_error err;
  int rc = sph_case_load(sph_test_src("tests/data/energy_box_3d.yaml"), sets, 1, &c, &err);
  if (rc) printf("\n    %s", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  sph_sim *s = NULL;
  CU_ASSERT_FATAL(sph_sim_create(&c, &s, &err) == 0);
  sph_diag_row a, b;
  sph_sim_diag(s, &a);
  while (sph_sim_time(s) < c.t_end) {
    rc = sph_sim_step(s, c.t_end, &err);
    if (rc) printf("\n    %s", err.msg);
    CU_ASSERT_FATAL(rc == 0);
  }
  sph_sim_diag(s, &b);
  const double p = fabs(b.momentum_x) + fabs(b.momentum_y) + fabs(b.momentum_z) + b.mass;
  printf("\n    %s: %ld steps, |dE/E0| %.2g, momentum residuals %.2g %.2g %.2g, kinetic %.4g J",
         model, sph_sim_steps(s), fabs(b.deviation), b.momentum_residual_x, b.momentum_residual_y,
         b.momentum_residual_z, b.kinetic);
  CU_ASSERT(b.ledger == 1 && a.ledger == 1);
  CU_ASSERT(fabs(b.deviation) <= 1e-4);
  CU_ASSERT(fabs(b.momentum_residual_x) < 1e-12 * p);
  CU_ASSERT(fabs(b.momentum_residual_y) < 1e-12 * p);
  CU_ASSERT(fabs(b.momentum_residual_z) < 1e-12 * p);
  CU_ASSERT(b.kinetic > 0.05 * (a.potential - b.potential + b.kinetic));
  CU_ASSERT(b.n_fluid == 2000);
  sph_sim_free(s);
  sph_case_free(&c);
}

static void test_dynamic(void) { run_box("dynamic"); }
static void test_fixed_layers(void) { run_box("fixed_layers"); }

int main(void) {
  CU_TestInfo tests[] = {{"3-D energy box, dynamic walls: closed within 1e-4", test_dynamic},
                         {"3-D energy box, fixed layers: closed within 1e-4", test_fixed_layers},
                         CU_TEST_INFO_NULL};
  return sph_test_main("energy_3d", tests);
}
