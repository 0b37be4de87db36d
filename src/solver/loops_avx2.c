/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * loops_avx2.c - the AVX2 four-lane loop's instances (loops.h): one
 * function per term set of LANE_LOOPS, and their table.
 */
#include "config.h"

#include "solver/loops.h"

#include "solver/interact.h"

#ifdef SPH_LANES_AVX

#define LOOP(k, Fc)                                                                                \
  SPH_LOOP_FUNCTION(interact_avx_##k, v4x, static __attribute__((target("avx2"))), Fc)
LANE_LOOPS(LOOP)

#define ENTRY(k, Fc) {(Fc), interact_avx_##k},
static const sph_loop_entry entries[] = {LANE_LOOPS(ENTRY)};
const sph_loop_table sph_loops_avx2 = {entries, sizeof entries / sizeof entries[0]};
#endif
