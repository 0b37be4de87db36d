/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * jobs.c - the worker pool of jobs.h, by fork(2).
 *
 * Task i goes to worker i mod W, fixed before any work starts, so which
 * process draws a frame never depends on timing; frames are independent
 * and written atomically, so the output files are the same whatever W is
 * (llvmpipe renders identically in any process; see the determinism test).
 * Workers are forked before any GL context exists - a context does not
 * survive fork - and each makes its own. A worker reports its failed-task
 * count through its exit status (capped at 255; the parent recounts from
 * the status) and writes its error lines straight to stderr, one fprintf
 * per line. The parent flushes its stdio buffers before forking and the
 * children leave with _exit, so no buffer is written twice.
 */
#include "config.h"

#include "jobs.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

int rjobs_cpus(void) {
  long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n < 1 ? 1 : n > 256 ? 256 : (int)n;
}

/* Runs the tasks of worker w of W; returns how many failed. */
static size_t run_share(size_t n, size_t w, size_t W, const rjobs_ops *ops, void *ctx,
                        const char *prog) {
  sph_error err = {""};
  void *worker = ops->worker_init ? ops->worker_init(ctx, &err) : NULL;
  size_t mine = w < n ? (n - w + W - 1) / W : 0;
  if (ops->worker_init && !worker) {
    fprintf(stderr, "%s: %s\n", prog, err.msg);
    return mine;
  }
  size_t failed = 0;
  for (size_t i = w; i < n; i += W) {
    err.msg[0] = '\0';
    if (ops->task(ctx, worker, i, &err) != 0) {
      fprintf(stderr, "%s: %s\n", prog, err.msg);
      failed++;
    }
  }
  if (ops->worker_fini) ops->worker_fini(worker);
  return failed;
}

size_t rjobs_run(size_t n, int workers, const rjobs_ops *ops, void *ctx, const char *prog) {
  if (n == 0) return 0;
  size_t W = workers < 1 ? 1 : (size_t)workers;
  if (W > n) W = n;
  if (W == 1) return run_share(n, 0, 1, ops, ctx, prog);
  pid_t *pid = calloc(W, sizeof *pid);
  if (!pid) {
    fprintf(stderr, "%s: out of memory; rendering in one process\n", prog);
    return run_share(n, 0, 1, ops, ctx, prog);
  }
  fflush(NULL);
  size_t failed = 0;
  for (size_t w = 0; w < W; w++) {
    pid[w] = fork();
    if (pid[w] == 0) {
      size_t f = run_share(n, w, W, ops, ctx, prog);
      fflush(NULL);
      _exit(f > 255 ? 255 : (int)f);
    }
    if (pid[w] < 0) {
      /* no process: do this share here, after the others are started */
      fprintf(stderr, "%s: fork failed (%s); rendering share %zu in the main process\n", prog,
              strerror(errno), w);
    }
  }
  for (size_t w = 0; w < W; w++) {
    size_t mine = (n - w + W - 1) / W;
    if (pid[w] < 0) {
      failed += run_share(n, w, W, ops, ctx, prog);
      continue;
    }
    int st = 0;
    while (waitpid(pid[w], &st, 0) < 0 && errno == EINTR) {
    }
    if (WIFEXITED(st)) {
      size_t f = (size_t)WEXITSTATUS(st);
      failed += f == 255 ? mine : f;
    } else {
      fprintf(stderr, "%s: worker %zu died (signal %d)\n", prog, w,
              WIFSIGNALED(st) ? WTERMSIG(st) : 0);
      failed += mine;
    }
  }
  free(pid);
  return failed;
}
