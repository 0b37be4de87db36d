/*
 * parallel.h - when a particle loop is worth running on several threads.
 *
 * Every parallel loop in the library is per particle (each iteration writes
 * only its own particle) or a min/max reduction, so its result is the same
 * on any number of threads; running a small store on one thread changes
 * nothing but the time. Below sph_omp_min() particles (2048) the cost of
 * starting and joining a parallel region exceeds the work, and on a loaded
 * machine waiting threads can cost far more, so such loops run serially.
 * The environment variable SPH_OMP_MIN overrides the threshold (the
 * determinism test sets it to 0 so that small cases do run in parallel).
 */
#ifndef SPH_PARALLEL_H
#define SPH_PARALLEL_H

#include <stddef.h>

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

/* The threshold, read from SPH_OMP_MIN once (default 2048). */
long sph_omp_min(void);
#define SPH_OMP_MIN sph_omp_min()

/* The slice [*lo, *hi) of 0..n-1 that part t of `parts` takes when the cost
 * of items 0..i-1 is prefix[i] - prefix[0] (prefix nondecreasing):
 * contiguous slices of about equal cost, found by bisection. The loops of
 * a step split by their rows' costs this way rather than by item count: the
 * dense bottom of a tank otherwise leaves one thread waiting for the other,
 * and a dynamic schedule hands each particle's outputs to a different
 * thread at every pass (their cache lines then move between the cores).
 * Which thread takes an item never changes a result: items are independent. */
void sph_share(const size_t *prefix, size_t n, int t, int parts, size_t *lo, size_t *hi);

/* The calling thread's slice of 0..n-1 in its team: sph_share by `prefix`
 * when given (n + 1 entries), else equal counts. Every loop over the store
 * in a step takes the neighbour list's slices (its cost prefix, grid.h),
 * so each thread writes and reads the same particles in every loop. */
void sph_slice(const size_t *prefix, size_t n, size_t *lo, size_t *hi);

#endif
