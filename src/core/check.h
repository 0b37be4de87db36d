/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * check.h - the two levels of checks (after Lua's): cheap argument checks
 * are always on and return errors; costly invariant checks run only in a
 * build configured with --enable-debug-checks (SPH_DEBUG_CHECKS), where a
 * broken invariant is a bug in this library, so it stops the process with
 * the file, line and condition.
 *
 *   SPH_INVARIANT(cond, "what", ...)    checked in debug builds, else nothing
 *   SPH_DEBUG                           1 in debug builds, else 0 (to guard a
 *                                       whole costly check: if (SPH_DEBUG) ...)
 *
 * The invariants checked (each function says where): the grid holds every
 * particle once in its cell (neighbours/grid.c), neighbour rows are sorted
 * and complete (neighbours/grid.c), every rate after an interaction pass is
 * finite (solver/forces.c), and the ledger's total is the sum of its parts
 * (solver/ledger.c).
 */
#ifndef SPH_CHECK_H
#define SPH_CHECK_H

#include <stdio.h>
#include <stdlib.h>

#ifdef SPH_DEBUG_CHECKS
#define SPH_DEBUG 1
#define SPH_INVARIANT(cond, ...)                                                                   \
  do {                                                                                             \
    if (!(cond)) {                                                                                 \
      fprintf(stderr, "%s:%d: invariant broken: %s: ", __FILE__, __LINE__, #cond);                 \
      fprintf(stderr, __VA_ARGS__);                                                                \
      fputc('\n', stderr);                                                                         \
      abort();                                                                                     \
    }                                                                                              \
  } while (0)
#else
#define SPH_DEBUG 0
#define SPH_INVARIANT(cond, ...) ((void)sizeof(cond)) /* not evaluated */
#endif

#endif
