/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_conservation.c - mass is exact and total momentum of an isolated
 * fluid patch (no walls, no gravity, random velocities, artificial
 * viscosity and XSPH on) changes only by round-off over 100 steps: every
 * pair term of the momentum equation is antisymmetric (forces.h). The same
 * with paper A's leap-frog (eq. 17-19, numerics.integrator=leapfrog): its
 * kicks add dt sum_i m_i a_i = 0 to the momentum, so it is conserved to
 * round-off as well.
 */
#include "config.h"

#include <math.h>
#include <stdio.h>

#include "case/case.h"
#include "solver/sim.h"
#include "testutil.h"

static double uniform(unsigned long long *s) {
  *s ^= *s << 13;
  *s ^= *s >> 7;
  *s ^= *s << 17;
  return (double)(*s >> 11) / 9007199254740992.0;
}

static void totals(sph_particles *p, double *mass, double *mx, double *my, double *scale) {
  *mass = *mx = *my = *scale = 0.0;
  for (size_t i = 0; i < p->n; i++) {
    *mass += p->mass[i];
    *mx += p->mass[i] * p->vx[i];
    *my += p->mass[i] * p->vy[i];
    *scale += p->mass[i] * sqrt(p->vx[i] * p->vx[i] + p->vy[i] * p->vy[i]);
  }
}

/* Runs tests/data/isolated_patch.yaml with the given overrides, which must
 * select the integrator `want`. */
static void isolated_patch(const char *const *set, size_t n_set, sph_integrator_kind want) {
  sph_case c;
  sph_error err;
  int rc = sph_case_load(sph_test_src("tests/data/isolated_patch.yaml"), set, n_set, &c, &err);
  if (rc) printf("\n%s\n", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  CU_ASSERT_FATAL(c.integrator == want);
  sph_sim *s;
  CU_ASSERT_FATAL(sph_sim_create(&c, &s, &err) == 0);
  sph_particles *p = sph_sim_particles(s);
  CU_ASSERT_EQUAL(p->n, 400);
  unsigned long long seed = 2024;
  for (size_t i = 0; i < p->n; i++) {
    p->vx[i] = 0.2 * (uniform(&seed) - 0.5);
    p->vy[i] = 0.2 * (uniform(&seed) - 0.5);
  }
  double m0, mx0, my0, scale;
  totals(p, &m0, &mx0, &my0, &scale);
  int steps = 0;
  while (sph_sim_time(s) < c.t_end && steps < 1000) {
    rc = sph_sim_step(s, c.t_end, &err);
    if (rc) printf("\n%s\n", err.msg);
    CU_ASSERT_FATAL(rc == 0);
    steps++;
  }
  CU_ASSERT_EQUAL(steps, 100);
  double m1, mx1, my1, scale1;
  totals(p, &m1, &mx1, &my1, &scale1);
  printf("\n  momentum change: %.3e %.3e (scale %.3e); mass %.17g -> %.17g\n", mx1 - mx0, my1 - my0,
         scale, m0, m1);
  /* masses never change: the same numbers summed in another order may
   * differ in the last bit only, so compare per-particle */
  for (size_t i = 0; i < p->n; i++)
    CU_ASSERT_EQUAL(p->mass[i], c.rho0 * c.dx * c.dx);
  CU_ASSERT_DOUBLE_EQUAL(m1, m0, 1e-14 * m0);
  CU_ASSERT(fabs(mx1 - mx0) < 1e-13 * scale);
  CU_ASSERT(fabs(my1 - my0) < 1e-13 * scale);
  /* and the flow did something (the test would be empty otherwise) */
  CU_ASSERT(fabs(scale1 - scale) > 1e-6 * scale);
  sph_sim_free(s);
  sph_case_free(&c);
}

static void test_isolated_patch(void) {
  isolated_patch(NULL, 0, SPH_INTEGRATOR_PREDICTOR_CORRECTOR);
}

static void test_isolated_patch_leapfrog(void) {
  const char *set[] = {"numerics.integrator=leapfrog"};
  isolated_patch(set, 1, SPH_INTEGRATOR_LEAPFROG);
}

int main(void) {
  CU_TestInfo tests[] = {
      {"isolated patch: exact mass, momentum to round-off over 100 steps", test_isolated_patch},
      {"isolated patch with the leap-frog (paper A eq. 17-19): the same",
       test_isolated_patch_leapfrog},
      CU_TEST_INFO_NULL};
  return sph_test_main("conservation", tests);
}
