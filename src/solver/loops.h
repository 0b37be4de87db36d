/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * loops.h - the main pass's loops, one translation unit per flavour, so
 * that `make -j` compiles them at once (forces.c picks one at run time):
 *
 *   loops_scalar.c   the scalar loop (interact_v1): per-particle h, mirror
 *                    walls, `numerics.loop: scalar`
 *   loops_lanes.c    the portable four-lane loop (interact_v4e)
 *   loops_avx2.c     the AVX2 four-lane loop (interact_v4x), where the
 *                    compiler has it (SPH_LANES_AVX, core/lanes.h)
 *   loops_avx512.c   the AVX-512 eight-lane loop (interact_v8z)
 *
 * Each file instantiates its flavour's loop for the term sets of
 * interact.h's lists (SCALAR_LOOPS, PORTABLE_LOOPS, LANE_LOOPS) with
 * SPH_LOOP_FUNCTION and lists them in a table by their Fc. A loop gives the
 * same bits in any file: the pair physics is the same inlined code, and
 * -ffp-contract=off keeps the operations as written.
 */
#ifndef SPH_LOOPS_H
#define SPH_LOOPS_H

#include <stddef.h>

#include "core/parallel.h"
#include "solver/forces.h"

/* One loop: the main pass over every particle for one term set. */
typedef void (*sph_loop_fn)(sph_particles *, const sph_nlist *, const sph_force_params *,
                            sph_force_work *);

/* A loop and its Fc (interact.h); a flavour's table of them. */
typedef struct sph_loop_entry {
  unsigned fc;
  sph_loop_fn fn;
} sph_loop_entry;
typedef struct sph_loop_table {
  const sph_loop_entry *entry;
  size_t n;
} sph_loop_table;

extern const sph_loop_table sph_loops_scalar;
extern const sph_loop_table sph_loops_lanes;
#ifdef SPH_LANES_AVX
extern const sph_loop_table sph_loops_avx2;
#endif
#ifdef SPH_LANES_AVX512
extern const sph_loop_table sph_loops_avx512;
#endif

/* Rows per stolen chunk of the interaction loop: a few microseconds of
 * work, so a thread waits at most that long at the end of a pass. */
#define SPH_STEAL_GRAIN 32
/* Rows between two calls of a first phase's late_progress (force_pass.h). */
#define SPH_PROGRESS_ROWS 2048

/* The loop NAME of flavour FL (interact.h's interact_FL, one particle's
 * row) for the term set Fc, a literal inside its parallel region: each
 * particle writes only its own rates (bitwise the same for any thread
 * count), and the pass's max of cs + sigma (the step rule's) is reduced
 * exactly, in any order. */
#define SPH_LOOP_FUNCTION(NAME, FL, ATTR, Fc)                                                      \
  ATTR void NAME(sph_particles *p, const sph_nlist *l, const sph_force_params *fp,                 \
                 sph_force_work *w) {                                                              \
    const long n = (long)p->n;                                                                     \
    double mx = 0.0;                                                                               \
    _Pragma("omp parallel if (n > SPH_OMP_MIN) reduction(max : mx)") {                             \
      size_t lo, hi, since = 0; /* slices of equal cost, with stealing (parallel.h) */             \
      const int progress = w->phase == 1 && w->late_progress && sph_thread() == 0;                 \
      while (sph_steal_next(&w->steal, SPH_STEAL_GRAIN, &lo, &hi)) {                               \
        if (progress && (since += hi - lo) >= SPH_PROGRESS_ROWS) /* (force_pass.h) */              \
          since = 0, w->late_progress(w->late_ctx);                                                \
        for (size_t i = lo; i < hi; i++) {                                                         \
          if (w->skip_ghosts && (p->flags[i] & SPH_FLAG_GHOST)) continue; /* a rank's (ranks.c) */ \
          if (w->phase && w->late[i] != w->phase) continue;               /* (force_pass.h) */     \
          const double sg = interact_##FL(p, l, fp, w, i, (Fc));                                   \
          if (w->keep_sigma) w->sigma[i] = sg; /* the tests' */                                    \
          const double c = w->hot[i].cs + sg;                                                      \
          if (c > mx) mx = c;                                                                      \
        }                                                                                          \
      }                                                                                            \
    }                                                                                              \
    sph_steal_learn(&w->steal);                                                                    \
    w->cs_sigma_max = mx;                                                                          \
  }

#endif
