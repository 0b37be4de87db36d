/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_no_tension.c - a fluid that holds no tension (physics.negative_pressure: false; the
 * density floor of physics/eos.h, doc/method.md, Negative pressure).
 *
 * 1. The floor itself: without it (rho_min 0) every density passes unchanged; with it a
 *    density below rho0 reads rho0 and one above stays as it is.
 * 2. The key: the default scheme's value false, the papers' schemes' and delta-SPH's true, a
 *    case's own value kept over its scheme's; listed in the run's parameters only when false
 *    (so the papers' cases' listings stay as they were); a value that is not a boolean refused
 *    with the key's name.
 * 3. A run (tests/data/restart_no_tension.yaml: a block of water thrown at 1 m/s along the
 *    floor of an adami tank, the default scheme, the ledger on, 0.15 s): with the key false no
 *    fluid particle's density falls below rho0 nor its pressure below 0 after any step, on
 *    either integrator and with the Shepard filter; with it true the same run does fall below rho0
 * (the block leaving the left wall stretches), so the first half can fail; the energy balance
 * closes to 5e-4 of E0 with the floor (measured 1.0e-4; the pairs' heat and force use the same
 * pressure, so the floor changes which pressure acts, not the balance). Threads and restart:
 * test_determinism and test_restart run the same fixture.
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "physics/eos.h"
#include "testsim.h"
#include "testutil.h"

static void test_floor(void) {
  sph_eos e = sph_eos_tait(1000.0, 20.0);
  CU_ASSERT_EQUAL(e.rho_min, 0.0);
  CU_ASSERT_EQUAL(sph_eos_floor(&e, 950.0), 950.0);
  CU_ASSERT_EQUAL(sph_eos_floor(&e, 1003.0), 1003.0);
  e.rho_min = e.rho0;
  CU_ASSERT_EQUAL(sph_eos_floor(&e, 950.0), 1000.0);
  CU_ASSERT_EQUAL(sph_eos_floor(&e, 999.999999), 1000.0);
  CU_ASSERT_EQUAL(sph_eos_floor(&e, 1003.0), 1003.0);
  CU_ASSERT_EQUAL(sph_eos_pressure(&e, sph_eos_floor(&e, 990.0)), 0.0);
}

/* The case's value of the key with the overrides set (n of them), and whether the listing
 * names it. */
static int key_of(const char *const *set, size_t n, int *listed) {
  sph_case c;
  sph_sim *s;
  CU_ASSERT_FATAL(sph_test_open_sim("tests/data/restart_default.yaml", set, n, &c, &s) == 0);
  const int v = c.negative_pressure;
  char *d = sph_case_describe(&c);
  CU_ASSERT_FATAL(d != NULL);
  *listed = strstr(d, "physics.negative_pressure: false\n") != NULL;
  CU_ASSERT(v || strstr(d, "negative_pressure: true") == NULL);
  free(d);
  sph_sim_free(s);
  sph_case_free(&c);
  return v;
}

static void test_key(void) {
  const char *paper[] = {"numerics.scheme=paper_b"}, *delta[] = {"numerics.scheme=delta_sph"};
  const char *on[] = {"physics.negative_pressure=true"};
  int listed;
  /* the default scheme: no tension, listed */
  CU_ASSERT_EQUAL(key_of(NULL, 0, &listed), 0);
  CU_ASSERT(listed);
  /* the papers' schemes and delta-SPH: the continuity's density, not listed */
  CU_ASSERT_EQUAL(key_of(paper, 1, &listed), 1);
  CU_ASSERT(!listed);
  CU_ASSERT_EQUAL(key_of(delta, 1, &listed), 1);
  CU_ASSERT(!listed);
  /* the case's own value over its scheme's */
  CU_ASSERT_EQUAL(key_of(on, 1, &listed), 1);
  CU_ASSERT(!listed);
  /* not a boolean: refused, the key named */
  char *dir = sph_test_tmpdir(), args[8192], out[8192];
  snprintf(args, sizeof args, "run -q '%s' -o '%s/run' --set physics.negative_pressure=maybe",
           sph_test_src("tests/data/restart_default.yaml"), dir);
  const int rc = sph_test_sph(args, dir, out, sizeof out);
  printf("\n  %s", out);
  CU_ASSERT(rc != 0);
  CU_ASSERT(strstr(out, "physics.negative_pressure") != NULL);
  sph_test_rmtree(dir);
  free(dir);
}

/* Runs the fixture to its end with negative_pressure as given, the integrator and the density
 * filter (a YAML mapping, or "{kind: none}"); returns the lowest fluid density over all steps
 * in rho0 and the lowest fluid pressure in *pmin. */
static double lowest_density(const char *negative, const char *integrator, const char *filter,
                             double *pmin) {
  char k1[64], k2[64], k3[96];
  snprintf(k1, sizeof k1, "physics.negative_pressure=%s", negative);
  snprintf(k2, sizeof k2, "numerics.integrator=%s", integrator);
  snprintf(k3, sizeof k3, "numerics.density_filter=%s", filter);
  const char *sets[] = {k1, k2, k3};
  sph_case c;
  sph_sim *s;
  sph_error err;
  CU_ASSERT_FATAL(sph_test_open_sim("tests/data/restart_no_tension.yaml", sets, 3, &c, &s) == 0);
  double lo = INFINITY;
  *pmin = INFINITY;
  while (sph_sim_time(s) < c.t_end) {
    const int rc = sph_sim_step(s, c.t_end, &err);
    if (rc) printf("\n%s\n", err.msg);
    CU_ASSERT_FATAL(rc == 0);
    const sph_particles *p = sph_sim_particles(s);
    for (size_t i = 0; i < p->n; i++) {
      if (p->kind[i] != SPH_KIND_FLUID) continue;
      if (p->rho[i] < lo) lo = p->rho[i];
      if (p->p[i] < *pmin) *pmin = p->p[i];
    }
  }
  lo /= c.rho0;
  sph_sim_free(s);
  sph_case_free(&c);
  return lo;
}

static void test_run(void) {
  /* both integrators, and the leap-frog with the Shepard filter every 5 steps (the floor on
   * the filtered density) */
  static const char *const integrators[] = {"leapfrog", "predictor_corrector", "leapfrog"};
  static const char *const filters[] = {"{kind: none}", "{kind: none}",
                                        "{kind: shepard, every: 5}"};
  for (int k = 0; k < 3; k++) {
    double pmin_on, pmin_off;
    const double with = lowest_density("true", integrators[k], filters[k], &pmin_on);
    const double without = lowest_density("false", integrators[k], filters[k], &pmin_off);
    printf("\n  %s, filter %s: lowest density %.6f rho0 (pressure %.1f Pa) with tension, %.6f "
           "rho0 (%.1f Pa) without",
           integrators[k], filters[k], with, pmin_on, without, pmin_off);
    CU_ASSERT(with < 0.999);
    CU_ASSERT(without >= 1.0);
    CU_ASSERT(pmin_off >= 0.0);
  }
  /* the balance, from the run's own diagnostics */
  char *dir = sph_test_tmpdir(), args[8192], out[8192], path[4200];
  snprintf(args, sizeof args, "run -q '%s' -o '%s/run' --set output.snapshots=false",
           sph_test_src("tests/data/restart_no_tension.yaml"), dir);
  CU_ASSERT_FATAL(sph_test_sph_ok(args, dir, out, sizeof out) == 0);
  snprintf(path, sizeof path, "%s/run/diagnostics.csv", dir);
  double *col[1] = {NULL};
  const long n = sph_test_csv(path, "energy_deviation", col);
  CU_ASSERT_FATAL(n >= 7); /* t = 0, 0.025, ..., 0.15 */
  double worst = 0.0;
  for (long r = 0; r < n; r++)
    if (fabs(col[0][r]) > worst) worst = fabs(col[0][r]);
  printf("\n  energy balance: largest deviation %.2e of E0 over %ld rows", worst, n);
  CU_ASSERT(worst < 5e-4);
  free(col[0]);
  sph_test_rmtree(dir);
  free(dir);
}

int main(void) {
  CU_TestInfo tests[] = {{"the density floor", test_floor},
                         {"physics.negative_pressure: read, listed, refused", test_key},
                         {"a run: no density below rho0, the balance closed", test_run},
                         CU_TEST_INFO_NULL};
  return sph_test_main("no tension", tests);
}
