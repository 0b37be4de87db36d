/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * testsim.c - see testsim.h.
 */
#include "config.h"

#include "testsim.h"

#include <stdio.h>

#include "testutil.h"

int sph_test_open_sim(const char *rel, const char *const *set, size_t n_set, sph_case *c,
                      sph_sim **s) {
  sph_error err;
  if (sph_case_load(sph_test_src(rel), set, n_set, c, &err)) {
    printf("\n  %s\n", err.msg);
    return -1;
  }
  if (sph_sim_create(c, s, &err)) {
    printf("\n  %s\n", err.msg);
    sph_case_free(c);
    return -1;
  }
  return 0;
}

int sph_test_run_to(sph_sim *s, double t) {
  sph_error err;
  while (sph_sim_time(s) < t) {
    const int rc = sph_sim_step(s, t, &err);
    if (rc) {
      printf("\n  %s\n", err.msg);
      return rc;
    }
  }
  return 0;
}
