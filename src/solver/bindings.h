/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * bindings.h - what a binding from another language needs beyond the C
 * headers: the Python module (python/sph, doc/python.md) calls libsph
 * through ctypes, which knows neither the size of an sph_case nor the
 * layout of a structure unless it is told. A binding holds a case on the
 * heap (sph_bind_case_new), mirrors sph_error, sph_run_options and
 * sph_run_result and checks its mirrors against sph_bind_sizeof when it
 * loads the library, and frees what the library allocated with
 * sph_bind_free (its own malloc's free).
 */
#ifndef SPH_BINDINGS_H
#define SPH_BINDINGS_H

#include <stddef.h>

#include "case/case.h"

#ifdef __cplusplus
extern "C" {
#endif

/* An empty case on the heap, for sph_case_parse; NULL if out of memory. */
sph_case *sph_bind_case_new(void);
/* Frees what the case holds (sph_case_free) and the case; NULL is fine. */
void sph_bind_case_delete(sph_case *c);

/* sizeof the named public structure ("sph_error", "sph_run_options",
 * "sph_run_result"); 0 for any other name. */
size_t sph_bind_sizeof(const char *name);

/* free() for memory the library returned (sph_case_describe's text). */
void sph_bind_free(void *p);

/* The OpenMP threads the following runs use (n > 0; n <= 0 keeps the
 * number in force): the number now in force, 1 in a build without OpenMP.
 * Results are the same bits for any number. */
int sph_set_threads(int n);

#ifdef __cplusplus
}
#endif

#endif
