/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * snapcmp.h - comparing snapshots in the tests of restart and interruption
 * (test_restart.c, test_interrupt.c): dataset by dataset, bit for bit.
 */
#ifndef SPH_TEST_SNAPCMP_H
#define SPH_TEST_SNAPCMP_H

#include <stddef.h>

/* Compares time, step, dt, particle count, the list of /particles fields
 * and every field's values (as read back, bit for bit) of two snapshots.
 * Returns 0 when equal; otherwise prints the first difference to stdout
 * (prefixed by what) and returns 1. With restart != 0 the restart records'
 * ledger, first_step, gauge levels, storage order and half-step arrays are
 * compared too. */
int snapcmp(const char *what, const char *a, const char *b, int restart);

/* 1 if the snapshot opens and every field of /particles reads, with all
 * float values finite; else prints why and returns 0. *n and *t get the
 * particle count and time (if not NULL). */
int snapcmp_complete(const char *path, size_t *n, double *t);

/* Whole-file comparison: 0 if the two files hold the same bytes. */
int snapcmp_files(const char *a, const char *b);

#endif
