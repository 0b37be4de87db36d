/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * loops_scalar.c - the scalar loop's instances (loops.h): one
 * function per term set of SCALAR_LOOPS, and their table.
 */
#include "config.h"

#include "solver/loops.h"

#include "solver/interact.h"

#define LOOP(k, Fc) SPH_LOOP_FUNCTION(interact_scalar_##k, v1, static, Fc)
SCALAR_LOOPS(LOOP)

#define ENTRY(k, Fc) {(Fc), interact_scalar_##k},
static const sph_loop_entry entries[] = {SCALAR_LOOPS(ENTRY)};
const sph_loop_table sph_loops_scalar = {entries, sizeof entries / sizeof entries[0]};
