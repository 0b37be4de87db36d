/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * jobs.h - runs independent tasks (one output image each) on several
 * worker processes, each with its own OpenGL context.
 */
#ifndef SPH_RENDER_JOBS_H
#define SPH_RENDER_JOBS_H

#include <stddef.h>

#include "core/error.h"

typedef struct rjobs_ops {
  /* Called once in each worker before its first task (e.g. makes the GL
   * context); NULL with err on failure. */
  void *(*worker_init)(void *ctx, sph_error *err);
  /* Produces task i; non-zero with err on failure. */
  int (*task)(void *ctx, void *worker, size_t i, sph_error *err);
  void (*worker_fini)(void *worker);
} rjobs_ops;

/* The number of online processors (at least 1). */
int rjobs_cpus(void);
/* Runs tasks 0..n-1 on min(workers, n) processes (1: in this process).
 * Each failure is printed to stderr as "<prog>: <message>" and the other
 * tasks go on. Returns the number of tasks that failed (a worker that
 * dies counts all its unfinished tasks). */
size_t rjobs_run(size_t n, int workers, const rjobs_ops *ops, void *ctx, const char *prog);

#endif
