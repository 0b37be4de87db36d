/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_energy_3d.c - the energy ledger in 3-D (built with -DSPH_DIM=3,
 * linked with src/libsph3.la; doc/dimensions.md): the 3-D energy box
 * (tests/data/energy_box_3d.yaml, the 2-D box of test_energy with a width of
 * 0.025 m along y: a column collapsing in a closed box, no artificial
 * viscosity, step factor 0.15, 2000 fluid particles) closes its balance
 * kinetic + potential + internal - boundary work within 1e-4 of E0 with each
 * wall model the 3-D build has: dynamic and mdbc walls over the case's
 * 0.1 s (measured 8.4e-6 and 4.8e-6); fixed layers, the same particles as
 * dynamic walls, the same bits as them (compared at 0.01 s); repulsive walls,
 * mirror planes, mdbc free-slip walls and mdbc walls with particle shifting
 * (its moves booked) over 0.05 s; the corrected gradient of the pressure and
 * continuity on dynamic and mdbc walls over 0.05 s; mdbc walls the same bits
 * on one thread and two (compared at 0.02 s); a piston plate does the
 * quasi-static work. The momentum balance holds along every axis to
 * round-off, and the column falls (kinetic energy above 5 % of the potential
 * energy it had above its final centre of mass). The shorter runs keep
 * make check within its 10 minutes (doc/testing.md).
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "case/case.h"
#include "solver/diag.h"
#include "solver/sim.h"
#include "testutil.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#if SPH_DIM != 3
#error "test_energy_3d is built with -DSPH_DIM=3"
#endif

/* The box with a tank of wall model `model`, and one more --set `extra`
 * (or NULL); the last diagnostics row into *out (NULL: not wanted). */
static void run_box_until(const char *model, const char *extra, const char *end,
                          sph_diag_row *out) {
  char set[128];
  snprintf(set, sizeof set, "geometry.tank.boundary=%s", model);
  const char *sets[3] = {set, NULL, NULL};
  size_t n = 1;
  if (extra) sets[n++] = extra;
  if (end) sets[n++] = end;
  sph_case c;
  sph_error err;
  int rc = sph_case_load(sph_test_src("tests/data/energy_box_3d.yaml"), sets, n, &c, &err);
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
  printf("\n    %s%s%s: %ld steps, |dE/E0| %.2g, momentum residuals %.2g %.2g %.2g, kinetic %.4g J",
         model, extra ? ", " : "", extra ? extra : "", sph_sim_steps(s), fabs(b.deviation),
         b.momentum_residual_x, b.momentum_residual_y, b.momentum_residual_z, b.kinetic);
  CU_ASSERT(b.ledger == 1 && a.ledger == 1);
  CU_ASSERT(fabs(b.deviation) <= 1e-4);
  CU_ASSERT(fabs(b.momentum_residual_x) < 1e-12 * p);
  CU_ASSERT(fabs(b.momentum_residual_y) < 1e-12 * p);
  CU_ASSERT(fabs(b.momentum_residual_z) < 1e-12 * p);
  CU_ASSERT(b.kinetic > 0.05 * (a.potential - b.potential + b.kinetic));
  CU_ASSERT(b.n_fluid == 2000);
  if (out) *out = b;
  sph_sim_free(s);
  sph_case_free(&c);
}

/* The box to its case's end (t = 0.1 s). */
static void run_box(const char *model, const char *extra, sph_diag_row *out) {
  run_box_until(model, extra, NULL, out);
}

/* The end time of the shorter runs: time={end: T, output_interval: T}. */
#define SHORT_END "time={end: 0.05, output_interval: 0.05}"

static void test_dynamic(void) { run_box("dynamic", NULL, NULL); }

/* Morris' fixed layers are the dynamic walls' particles (walls.c): the same bits to the end */
static void test_fixed_layers(void) {
  sph_diag_row d, f;
  const char *end = "time={end: 0.01, output_interval: 0.01}";
  run_box_until("dynamic", NULL, end, &d);
  run_box_until("fixed_layers", NULL, end, &f);
  CU_ASSERT(d.step == f.step && d.kinetic == f.kinetic && d.potential == f.potential &&
            d.internal == f.internal && d.momentum_x == f.momentum_x &&
            d.momentum_z == f.momentum_z && d.deviation == f.deviation);
}
static void test_repulsive(void) { run_box_until("repulsive", NULL, SHORT_END, NULL); }
static void test_mirror(void) { run_box_until("mirror", NULL, SHORT_END, NULL); }

/* the corrected gradient (numerics.gradient_correction): the continuity takes the pressure's
 * L_ij grad_i W_ij, so the pressure's work is the internal energy's change, on dynamic and on
 * mdbc walls */
static void test_corrected(void) {
  run_box_until("dynamic", "numerics.gradient_correction=true", SHORT_END, NULL);
  run_box_until("mdbc", "numerics.gradient_correction=true", SHORT_END, NULL);
}

/* particle shifting with mdbc walls: the ledger books its moves'
 * potential energy (shifting_drift), and the balance still closes */
static void test_shifting(void) {
  sph_diag_row b;
  run_box_until("mdbc", "numerics.shifting.coefficient=2", SHORT_END, &b);
  printf(", shifting_drift %.3g J", b.shifting_drift);
  CU_ASSERT(b.shifting == 1);
  CU_ASSERT(b.shifting_drift != 0.0);
}

/* mdbc walls, and free-slip ones; mdbc walls on one thread and on two give
 * the same bits (the sums of every particle's energies and momenta) */
static void test_mdbc(void) {
  run_box("mdbc", NULL, NULL);
  run_box_until("mdbc", "geometry.tank.free_slip=true", SHORT_END, NULL);
#ifdef _OPENMP
  sph_diag_row two, one;
  const char *end = "time={end: 0.02, output_interval: 0.02}";
  const int saved = omp_get_max_threads(); /* (make check runs tests on one thread) */
  omp_set_num_threads(2);
  run_box_until("mdbc", NULL, end, &two);
  omp_set_num_threads(1);
  run_box_until("mdbc", NULL, end, &one);
  omp_set_num_threads(saved);
  CU_ASSERT(one.kinetic == two.kinetic && one.potential == two.potential &&
            one.internal == two.internal && one.momentum_x == two.momentum_x &&
            one.momentum_y == two.momentum_y && one.momentum_z == two.momentum_z &&
            one.boundary_work == two.boundary_work && one.step == two.step);
#endif
}

/* A plate across the tank pushed into still water (tests/data/piston_3d.yaml,
 * the 2-D piston of test_energy across 0.05 m): the ledger's boundary work
 * is the quasi-static work plus the wave's (linear shallow water, as in
 * 2-D) across the width within 3 % (measured 0.01028 J against 0.01020 J,
 * +0.8 %), and the balance closes within 1e-4. */
static void test_piston(void) {
  sph_case c;
  sph_error err;
  int rc = sph_case_load(sph_test_src("tests/data/piston_3d.yaml"), NULL, 0, &c, &err);
  if (rc) printf("\n    %s", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  sph_sim *s = NULL;
  CU_ASSERT_FATAL(sph_sim_create(&c, &s, &err) == 0);
  while (sph_sim_time(s) < c.t_end)
    CU_ASSERT_FATAL(sph_sim_step(s, c.t_end, &err) == 0);
  sph_diag_row b;
  sph_sim_diag(s, &b);
  const double rho = 1000.0, g = 9.81, H = 0.1, V = 0.02, T = 0.2, W = 0.05;
  const double eta = V * H / sqrt(g * H);
  const double expect = W * (0.5 * rho * g * H * H * V * T + rho * g * eta * H * V * T);
  printf("\n    piston plate: work %.5g J (quasi-static with the wave %.5g J, %+.1f %%), |dE/E0| "
         "%.2g",
         b.boundary_work, expect, 100.0 * (b.boundary_work / expect - 1.0), fabs(b.deviation));
  CU_ASSERT(fabs(b.boundary_work - expect) < 0.03 * expect);
  CU_ASSERT(fabs(b.deviation) < 1e-4);
  sph_sim_free(s);
  sph_case_free(&c);
}

int main(void) {
  CU_TestInfo tests[] = {
      {"3-D energy box, dynamic walls: closed within 1e-4", test_dynamic},
      {"3-D energy box, fixed layers: the dynamic walls' bits", test_fixed_layers},
      {"3-D energy box, repulsive walls: closed within 1e-4", test_repulsive},
      {"3-D energy box, mirror planes: closed within 1e-4", test_mirror},
      {"3-D energy box, the corrected gradient on dynamic and mdbc walls: closed within 1e-4",
       test_corrected},
      {"3-D energy box, mdbc walls (and free-slip): closed within 1e-4", test_mdbc},
      {"3-D energy box, mdbc walls and shifting: closed within 1e-4", test_shifting},
      {"3-D piston plate: the quasi-static work, closed within 1e-4", test_piston},
      CU_TEST_INFO_NULL};
  return sph_test_main("energy_3d", tests);
}
