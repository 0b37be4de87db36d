/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * testsim.h - opening a simulation from a case file for the tests that
 * drive the library directly (kept apart from testutil.h so that the
 * renderer's test, which does not link the solver, need not).
 */
#ifndef SPH_TESTSIM_H
#define SPH_TESTSIM_H

#include <stddef.h>

#include "case/case.h"
#include "solver/sim.h"

/* Loads the source tree's case file rel with n_set --set overrides and
 * creates its sim; 0, or -1 with the reason printed (and nothing to free). */
int sph_test_open_sim(const char *rel, const char *const *set, size_t n_set, sph_case *c,
                      sph_sim **s);

/* Steps s to time t; 0, or the failing step's code with its message printed. */
int sph_test_run_to(sph_sim *s, double t);

#endif
