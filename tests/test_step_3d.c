/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_step_3d.c - the time step of the default scheme does not collapse
 * when two particles meet head on (issue 56, point 2), in 3-D (built with
 * -DSPH_DIM=3, linked with src/libsph3.la).
 *
 * What collapsed: the 3-D Lobovsky tank under the Riemann scheme (then with
 * paper B's step rule) shrank its step geometrically from 1.8e-4 s to
 * 5e-14 s, a hundred steps an episode, episode after episode from t = 0.36 s
 * at dx = 0.015 m. The pair that set the step each time: two fluid
 * particles of the flow's mirror symmetry about the tank's centre plane
 * (the lattice, and so every sum, is symmetric about it) meeting head on at
 * the plane, 4e-5 dx apart. Paper B's rule 0.3 h / (c + sigma) takes
 * sigma = max_j |h v_ij . r_ij| / r_ij^2, the artificial viscosity's
 * stability condition, which grows as 1/r for such a pair: each step then
 * moves them 0.3 of their distance closer and the next step is 0.7 of this
 * one. The Riemann pressure's pair force vanishes with the kernel gradient
 * as r -> 0, so nothing in the scheme needs that step; the default scheme
 * takes the acoustic rule 0.3 h / max(c + |v|) (ZH17's).
 *
 * The test: cases/hydrostatic_3d.yaml (still water, dx = 0.01 m) with two
 * fluid particles in the middle of the tank put 0.1 dx apart across y, at
 * the same x and z, closing at 0.1 m/s. Under the default scheme no step of
 * the next 120 is below 1e-3 of the first; under the same scheme with paper
 * B's rule (the Riemann scheme's until issue 56: the mechanism) the step
 * falls below 1e-3 of the first within them. With the default's leap-frog
 * the pair's half-step velocities are set too (they are its state).
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "case/case.h"
#include "core/particles.h"
#include "solver/diag.h"
#include "solver/sim.h"
#include "testutil.h"

/* The steps the test takes after putting the pair in. */
#define STEPS 120

/* The smallest step over STEPS steps of the still tank with the pair put in, relative to the
 * first step of the run; rule NULL: the scheme's. */
static double smallest_step(const char *rule) {
  const char *sets[2] = {"time.end=1.0", rule};
  sph_case c;
  sph_error err;
  if (sph_case_load(sph_test_src("cases/hydrostatic_3d.yaml"), sets, rule ? 2 : 1, &c, &err)) {
    printf("\n    %s", err.msg);
    return NAN;
  }
  sph_sim *s = NULL;
  if (sph_sim_create(&c, &s, &err)) {
    printf("\n    %s", err.msg);
    sph_case_free(&c);
    return NAN;
  }
  CU_ASSERT_FATAL(sph_sim_step(s, c.t_end, &err) == 0);
  sph_diag_row row;
  sph_sim_diag(s, &row);
  const double dt0 = row.dt;
  /* two fluid particles in the middle, y-neighbours on the lattice: put them 0.1 dx apart
   * about their midpoint, closing at 0.1 m/s */
  sph_particles *p = sph_sim_particles(s);
  size_t a = p->n, b = p->n;
  const double dx = c.dx;
  for (size_t i = 0; i < p->n && b == p->n; i++) {
    if (p->kind[i] != SPH_KIND_FLUID || fabs(p->x[i] - 0.105) > 0.3 * dx ||
        fabs(p->y[i] - 0.045) > 0.3 * dx || fabs(p->z[i] - 0.055) > 0.3 * dx)
      continue;
    a = i;
    for (size_t j = 0; j < p->n; j++)
      if (p->kind[j] == SPH_KIND_FLUID && fabs(p->x[j] - p->x[i]) < 0.3 * dx &&
          fabs(p->z[j] - p->z[i]) < 0.3 * dx && fabs(p->y[j] - p->y[i] - dx) < 0.3 * dx)
        b = j;
  }
  CU_ASSERT_FATAL(a < p->n && b < p->n);
  const double ym = 0.5 * (p->y[a] + p->y[b]);
  p->y[a] = ym - 0.05 * dx, p->y[b] = ym + 0.05 * dx;
  p->x[b] = p->x[a], p->z[b] = p->z[a];
  p->vy[a] = 0.05, p->vy[b] = -0.05;
  if (c.integrator == SPH_INTEGRATOR_LEAPFROG) /* its state is the half-step velocity */
    p->vyh[a] = 0.05, p->vyh[b] = -0.05;
  double smallest = INFINITY;
  for (int k = 0; k < STEPS; k++) {
    const int rc = sph_sim_step(s, c.t_end, &err);
    if (rc && strstr(err.msg, "time step collapse")) { /* below the step's floor: stopped */
      printf("\n    step %d: %.60s...", k, err.msg);
      smallest = 0.0;
      break;
    }
    if (rc) printf("\n    step %d: %s", k, err.msg);
    CU_ASSERT_FATAL(rc == 0);
    sph_sim_diag(s, &row);
    if (row.dt < smallest) smallest = row.dt;
    if (smallest < 1e-4 * dt0) break; /* collapsed: what the test asks is known */
  }
  /* the run's own record of its steps: the first, and the smallest the rule chose */
  double first, least, t_least;
  CU_ASSERT(sph_sim_step_range(s, &first, &least, &t_least) == 1);
  CU_ASSERT_EQUAL(first, dt0);
  if (smallest > 0.0) CU_ASSERT_EQUAL(least, fmin(dt0, smallest));
  sph_sim_free(s);
  sph_case_free(&c);
  return smallest / dt0;
}

static void test_pair_head_on(void) {
  const double ours = smallest_step(NULL);
  const double paper_b = smallest_step("numerics.time_step.rule=paper_b");
  printf("\n  the smallest of 120 steps after the pair was put in (or of those until one is "
         "below 1e-4), over the first step: default scheme %.3g, with paper B's rule %.3g",
         ours, paper_b);
  CU_ASSERT(ours >= 1e-3);
  CU_ASSERT(paper_b < 1e-3);
}

int main(void) {
  CU_TestInfo tests[] = {
      {"two particles meeting head on: the default scheme's step holds", test_pair_head_on},
      CU_TEST_INFO_NULL};
  return sph_test_main("step_3d", tests);
}
