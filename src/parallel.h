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

/* The threshold, read from SPH_OMP_MIN once (default 2048). */
long sph_omp_min(void);
#define SPH_OMP_MIN sph_omp_min()

#endif
