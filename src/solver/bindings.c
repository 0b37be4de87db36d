/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * bindings.c - the foreign-function surface of libsph (bindings.h): a case
 * on the heap, the sizes of the structures a binding mirrors, the
 * library's free, and the thread count. Nothing here computes; it lets a
 * program that cannot read C headers call what they declare.
 */
#include "config.h"

#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "solver/bindings.h"
#include "solver/run.h"

sph_case *sph_bind_case_new(void) { return calloc(1, sizeof(sph_case)); }

void sph_bind_case_delete(sph_case *c) {
  if (!c) return;
  sph_case_free(c);
  free(c);
}

size_t sph_bind_sizeof(const char *name) {
  if (!name) return 0;
  if (!strcmp(name, "sph_error")) return sizeof(sph_error);
  if (!strcmp(name, "sph_run_options")) return sizeof(sph_run_options);
  if (!strcmp(name, "sph_run_result")) return sizeof(sph_run_result);
  return 0;
}

void sph_bind_free(void *p) { free(p); }

int sph_set_threads(int n) {
#ifdef _OPENMP
  if (n > 0) omp_set_num_threads(n);
  return omp_get_max_threads();
#else
  (void)n;
  return 1;
#endif
}
