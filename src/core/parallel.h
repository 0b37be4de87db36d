/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * parallel.h - when a particle loop is worth running on several threads.
 *
 * Every parallel loop in the library is per particle (each iteration writes
 * only its own particle) or a min/max reduction, so its result is the same
 * on any number of threads; running a small store on one thread changes
 * nothing but the time. Below sph_omp_min() particles (2048) the cost of
 * starting and joining a parallel region exceeds the work, and on a loaded
 * machine waiting threads can cost far more, so such loops run serially.
 * The test hook SPH_TEST_OMP_MIN (environment; doc/testing.md) overrides the threshold (the
 * determinism test sets it to 0 so that small cases do run in parallel).
 */
#ifndef SPH_PARALLEL_H
#define SPH_PARALLEL_H

#include <stddef.h>
#include <stdint.h>

#ifdef _OPENMP
#include <omp.h>
#endif

/* This thread's number and the size of its team (0 and 1 outside a parallel
 * region, and in a build without OpenMP). */
static inline int sph_thread(void) {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}
static inline int sph_threads(void) {
#ifdef _OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}

/* The team size a parallel region will have (1 without OpenMP). */
static inline int sph_max_threads(void) {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

/* The threshold, read from SPH_TEST_OMP_MIN once (default 2048). */
long sph_omp_min(void);
#define SPH_OMP_MIN sph_omp_min()

/* The team a loop over n items gets from `#pragma omp parallel if (n >
 * SPH_OMP_MIN)`: what sph_steal_reset needs before such a region. */
static inline int sph_team_size(size_t n) { return (long)n > SPH_OMP_MIN ? sph_max_threads() : 1; }

/* The slice [*lo, *hi) of 0..n-1 that part t of `parts` takes when the cost
 * of items 0..i-1 is prefix[i] - prefix[0] (prefix nondecreasing):
 * contiguous slices of about equal cost, found by bisection. The loops of
 * a step split by their rows' costs this way rather than by item count: the
 * dense bottom of a tank otherwise leaves one thread waiting for the other,
 * and a dynamic schedule hands each particle's outputs to a different
 * thread at every pass (their cache lines then move between the cores).
 * Which thread takes an item never changes a result: items are independent. */
void sph_share(const size_t *prefix, size_t n, int t, int parts, size_t *lo, size_t *hi);

/* The calling thread's slice of 0..n-1 in its team: by `prefix` when given
 * (n + 1 entries), else by counts, in the learned shares below (equal
 * shares, sph_share's slices, until a stealing loop of a team of this size
 * has been learned from). Every loop over the store in a step takes the
 * neighbour list's slices (its cost prefix, grid.h), so each thread writes
 * and reads the same particles in every loop. */
void sph_slice(const size_t *prefix, size_t n, size_t *lo, size_t *hi);

/* ---- the learned split ----
 *
 * On a virtual machine one core can run 10-20 % slower than the other for
 * a whole run. Stealing (below) keeps such a team busy to the end of a
 * loop, but at a price: the stolen rows' data sit in the other core's
 * cache, so they cross between the cores twice a step (to the thief, and
 * back to the owner in the next loops), and the loops that do not steal
 * wait for the slower core. So every stealing loop also records how much
 * of its cost each thread took (both finish together, so that is each
 * core's share of the speed), and sph_steal_learn, called after the loop,
 * moves the team's shares a sixteenth of the way to what it measured.
 * sph_slice and sph_steal_reset then split by those shares: the faster
 * core's slice grows in every loop of the step, little is left to steal,
 * and the slices stay put from loop to loop. The shares are the process's
 * (they describe its threads, not a simulation), kept for one team size
 * at a time, at least half an equal share each; only the split depends
 * on them, never a result (items are independent). SPH_TEST_BALANCE=equal in
 * the environment keeps the shares equal (for benchmarks). Learning and
 * reading happen outside parallel regions or in regions that only read:
 * call sph_steal_learn from one thread, between regions. */
void sph_balance_reset(void);

/* Shares f[0..parts) (summing to 1) each raised to at least half an even
 * share, 0.5 / parts, by scaling the rest of the way down: they still sum
 * to 1 (the learned split above, and the processes' cut by measured work:
 * solver/ranks.c). */
void sph_shares_at_least_half(double *f, int parts);

/* The monotonic clock, in seconds from some fixed point: what the library
 * times itself with (the lane loops' trial, the processes' waits and work). */
double sph_seconds(void);

/* The learned share of part t of `parts` (1/parts when none is learned
 * for that team size). */
double sph_balance_share(int t, int parts);

/* ---- slices with stealing ----
 *
 * The interaction loop's rows cost the same on every thread only on
 * average: from pass to pass one core or the other is held up (cache
 * misses, an interrupt, the host), by 5-25 % of a pass, and the other
 * waits at the join. With stealing, each thread starts on its sph_share
 * slice and takes chunks from the front of it; a thread whose slice is
 * used up takes chunks from the back of another's. Which thread computes
 * a row never changes a result (rows are independent), so this balances
 * the pass without touching determinism, and most rows stay with the
 * thread that owns them in every other loop of the step.
 *
 * Use: sph_steal_reset (serially, before the parallel region, for the team
 * size the region will have), then in the region
 *   size_t lo, hi;
 *   while (sph_steal_next(&s, grain, &lo, &hi)) for (i = lo; i < hi; i++) ...
 * Every row is handed out exactly once whatever the team size turns out to
 * be: threads without a slice of their own only steal, and slices without
 * a thread are stolen. Needs n < 2^32 (sph_steal_reset fails otherwise). */
typedef struct sph_steal_slot {
  uint64_t range; /* front (low 32 bits) and back (high 32 bits) of a slice */
  uint64_t done;  /* the cost thread t has taken since the reset */
  char pad[48];   /* one cache line per slot */
} sph_steal_slot;
typedef struct sph_steal {
  void *mem;            /* the allocation (slots aligned to 64 bytes in it) */
  sph_steal_slot *slot; /* parts slots */
  const size_t *prefix; /* the costs (NULL: one per row) */
  int parts, cap;
  int team; /* the size of the team that ran the loop */
} sph_steal;

/* Gives part t of `parts` its slice in the learned shares (prefix may be
 * NULL: by counts); prefix must stay valid until the loop has run and
 * sph_steal_learn has read it. Returns -1 when n >= 2^32 or memory is
 * short. */
int sph_steal_reset(sph_steal *s, const size_t *prefix, size_t n, int parts);

/* The calling thread's next chunk [*lo, *hi): from the front of its own
 * slice, else (at least `grain` rows, half of what is left) from the back
 * of another's; 0 when every row has been handed out. */
int sph_steal_next(sph_steal *s, size_t grain, size_t *lo, size_t *hi);

/* After the loop: moves the learned shares toward the cost each thread
 * took (when the team had one slice per thread). */
void sph_steal_learn(sph_steal *s);

void sph_steal_free(sph_steal *s);

#endif
