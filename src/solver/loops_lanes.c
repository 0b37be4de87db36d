/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * loops_lanes.c - the portable four-lane loop's instances (loops.h): one
 * function per term set of PORTABLE_LOOPS, and their table.
 */
#include "config.h"

#include "solver/loops.h"

#include "solver/interact.h"

#define LOOP(k, Fc) SPH_LOOP_FUNCTION(interact_all_##k, v4e, static, Fc)
PORTABLE_LOOPS(LOOP)

#define ENTRY(k, Fc) {(Fc), interact_all_##k},
static const sph_loop_entry entries[] = {PORTABLE_LOOPS(ENTRY)};
const sph_loop_table sph_loops_lanes = {entries, sizeof entries / sizeof entries[0]};
