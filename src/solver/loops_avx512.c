/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * loops_avx512.c - the AVX-512 eight-lane loop's instances (loops.h): one
 * function per term set of LANE_LOOPS, and their table.
 */
#include "config.h"

#include "solver/loops.h"

#include "solver/interact.h"

#ifdef SPH_LANES_AVX512

#define LOOP(k, Fc)                                                                                \
  SPH_LOOP_FUNCTION(interact_avx512_##k, v8z, static __attribute__((target("avx512f"))), Fc)
LANE_LOOPS(LOOP)

#define ENTRY(k, Fc) {(Fc), interact_avx512_##k},
static const sph_loop_entry entries[] = {LANE_LOOPS(ENTRY)};
const sph_loop_table sph_loops_avx512 = {entries, sizeof entries / sizeof entries[0]};
#endif
