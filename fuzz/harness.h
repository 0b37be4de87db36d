/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * harness.h - the fuzz targets' logic, shared by the AFL++ drivers
 * (fuzz/afl_*.c, built by fuzz/run) and the regression test that replays
 * every crash found (tests/test_fuzz.c, run by `make check`).
 *
 * Each function takes one input as bytes and returns 0; it calls abort()
 * when the code under test breaks an invariant of its API (so AFL++ counts
 * it as a crash), and any memory error it triggers is a crash too (under
 * ASan, or as a signal).
 */
#ifndef SPH_FUZZ_HARNESS_H
#define SPH_FUZZ_HARNESS_H

#include <stddef.h>
#include <stdint.h>

/* The case-file parser: the bytes are a case file; each line of the form
 * "#set KEY=VALUE" (a YAML comment, so the parser skips it) is also given
 * as a --set override, so the override path is fuzzed with the same input.
 * Invariants: a failure leaves a one-line message naming the origin
 * ("fuzz.yaml") or the override; a success gives a case with a name, dx,
 * h, an end time and a fluid block, and a describe text; parsing the same
 * input twice gives the same result (nothing depends on uninitialised
 * memory). */
int sph_fuzz_case(const uint8_t *data, size_t len);

/* The snapshot reader: the bytes are written to the file `scratch` and
 * opened as a snapshot; every header value, every field, the particle
 * store and the restart record are read. Invariants: a failure names the
 * file; a success gives fields of particle_count values, and a restart
 * record whose order is a permutation. */
int sph_fuzz_snapshot(const uint8_t *data, size_t len, const char *scratch);

/* The CSV reader (src/io/csv.h: sph-render plot's tables, diagnostics.csv,
 * gauges.csv, probes.csv, the experiments' tables): the bytes are written
 * to `scratch` and read. Invariants: a failure names the file in one line;
 * a success gives ncol named columns, nrow * ncol values, and every column
 * found by its own name. */
int sph_fuzz_csv(const uint8_t *data, size_t len, const char *scratch);

#endif
