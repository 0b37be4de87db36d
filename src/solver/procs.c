/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * procs.c - the processes of a run under an MPI launcher (procs.h).
 *
 * Every call is a collective of MPI_COMM_WORLD made by the main thread
 * (MPI_THREAD_FUNNELED): the OpenMP threads of a process never talk to the
 * others. Without SPH_MPI (the serial build) every function is the
 * one-process answer.
 */
#include "config.h"

#include "solver/procs.h"

#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/parallel.h"

#ifdef SPH_MPI
#include <mpi.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif
#include <time.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif
#endif

static int rank = 0, count = 1;

int sph_procs_built(void) {
#ifdef SPH_MPI
  return 1;
#else
  return 0;
#endif
}

/* The first of the launcher variables that is set, as a number; -1 if none. */
static int launched(const char *const *names) {
  for (; *names; names++) {
    const char *e = getenv(*names);
    if (e && *e) return atoi(e);
  }
  return -1;
}

int sph_procs_launched_rank(void) {
  static const char *const names[] = {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK", NULL};
  const int r = launched(names);
  return r > 0 ? r : 0;
}

int sph_procs_launched_count(void) {
  static const char *const names[] = {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", NULL};
  const int n = launched(names);
  return n > 1 ? n : 1;
}

int sph_procs_rank(void) { return rank; }
int sph_procs_count(void) { return count; }

#ifdef SPH_MPI

static int started = 0;
/* this job's processes on this machine (set at the start) */
static int here = 1;
/* whether some machine of the job runs more of its threads than it has
 * cores: then a process that waits for the others naps (-1: not known
 * yet, crowded() finds it at the first collective step) */
static int crowded_job = -1;

/* Whether this machine's processes of the job, times their threads, are
 * more than its cores, on any machine of the job: one answer for all, at
 * the first collective step (all make it, after the threads are set:
 * cli_run.c sets them before any), since a collective started without
 * blocking does not match a blocking one. */
static int crowded(void) {
  if (crowded_job >= 0) return crowded_job;
  int threads = 1;
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif
  const long cores = sysconf(_SC_NPROCESSORS_ONLN);
  int mine = cores > 0 && (long)here * threads > cores;
  MPI_Allreduce(&mine, &crowded_job, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
#ifdef PR_SET_TIMERSLACK
  /* a nap of 10 us, not Linux's default slack of 50 us more */
  if (crowded_job) prctl(PR_SET_TIMERSLACK, 1000UL, 0UL, 0UL, 0UL);
#endif
  return crowded_job;
}

/* Seconds this process has spent in the collectives' waits (sph_procs_waited):
 * each blocking call timed on sph_seconds, core/parallel.h). */
static double waited = 0.0;

/* Waits for the collective r, started without blocking, on a crowded
 * machine: tests it and naps between tests, 10 us at first and twice as
 * long each time up to 160 us, so that the processes still at their pass
 * get the cores that a polling wait (Open MPI's, with mpi_yield_when_idle
 * or without) takes from them, while a collective of several rounds,
 * which moves only inside MPI's calls, is not held a long nap a round.
 * The results do not depend on how a process waits. */
static void wait_for(MPI_Request *r) {
  int done = 0;
  MPI_Test(r, &done, MPI_STATUS_IGNORE);
  for (long nap = 10000; !done; nap = nap < 160000 ? 2 * nap : nap) {
    const struct timespec t = {0, nap};
    nanosleep(&t, NULL);
    MPI_Test(r, &done, MPI_STATUS_IGNORE);
  }
}

int sph_procs_crowded(void) { return count > 1 && crowded(); }

double sph_procs_waited(void) { return waited; }

int sph_procs_start(sph_error *err) {
  if (started) return 0;
  static const char *const names[] = {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", NULL};
  if (launched(names) < 0) return 0; /* not under a launcher: one process, no MPI at all */
  int provided = 0;
  if (MPI_Init_thread(NULL, NULL, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
    return sph_error_set(err, "MPI_Init_thread failed");
  started = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &count);
  MPI_Comm local;
  if (MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &local) ==
      MPI_SUCCESS) {
    MPI_Comm_size(local, &here);
    MPI_Comm_free(&local);
  }
  if (provided < MPI_THREAD_FUNNELED)
    return sph_error_set(err,
                         "the MPI library gives no thread support (%d); threads need "
                         "MPI_THREAD_FUNNELED",
                         provided);
  return 0;
}

void sph_procs_end(void) {
  if (started) MPI_Finalize();
  started = 0;
}

/* all[k] = the largest mine[k] over the processes, k < n: one collective. */
static void max_ints(int *mine, int *all, int n) {
  MPI_Request r;
  const double t0 = sph_seconds();
  if (!crowded())
    MPI_Allreduce(mine, all, n, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  else {
    MPI_Iallreduce(mine, all, n, MPI_INT, MPI_MAX, MPI_COMM_WORLD, &r);
    wait_for(&r);
  }
  waited += sph_seconds() - t0;
}

int sph_procs_any(int flag) {
  if (count == 1) return flag != 0;
  int mine = flag != 0, any = 0;
  max_ints(&mine, &any, 1);
  return any;
}

/* The message of process `first` into err on every other process. */
static void tell(int first, sph_error *err) {
  char msg[sizeof err->msg];
  memcpy(msg, err->msg, sizeof msg);
  MPI_Request r;
  const double t0 = sph_seconds();
  if (!crowded())
    MPI_Bcast(msg, (int)sizeof msg, MPI_CHAR, first, MPI_COMM_WORLD);
  else {
    MPI_Ibcast(msg, (int)sizeof msg, MPI_CHAR, first, MPI_COMM_WORLD, &r);
    wait_for(&r);
  }
  waited += sph_seconds() - t0;
  msg[sizeof msg - 1] = '\0';
  if (first != rank) sph_error_set(err, "process %d of %d: %s", first, count, msg);
}

int sph_procs_agree(int rc, sph_error *err) {
  int flag = 0;
  return sph_procs_agree_any(rc, &flag, err);
}

int sph_procs_agree_any(int rc, int *flag, sph_error *err) {
  return sph_procs_agree_flags(rc, flag, 1, err);
}

int sph_procs_agree_flags(int rc, int *flags, int n, sph_error *err) {
  if (count == 1) return rc ? -1 : 0;
  /* one reduction: the lowest failing rank (as -rank's max) and the flags */
  int mine[1 + SPH_PROCS_FLAGS], all[1 + SPH_PROCS_FLAGS];
  mine[0] = rc ? -rank : -count;
  for (int k = 0; k < n; k++)
    mine[1 + k] = flags[k] != 0;
  max_ints(mine, all, 1 + n);
  for (int k = 0; k < n; k++)
    flags[k] = all[1 + k];
  if (-all[0] == count) return 0;
  tell(-all[0], err);
  return -1;
}

int sph_procs_failed(int first, sph_error *err) {
  if (count > 1) tell(first, err);
  return -1;
}

void sph_procs_gather(const void *mine, size_t len, void *all) {
  if (count == 1) {
    memcpy(all, mine, len);
    return;
  }
  MPI_Request r;
  const double t0 = sph_seconds();
  if (!crowded())
    MPI_Allgather(mine, (int)len, MPI_BYTE, all, (int)len, MPI_BYTE, MPI_COMM_WORLD);
  else {
    MPI_Iallgather(mine, (int)len, MPI_BYTE, all, (int)len, MPI_BYTE, MPI_COMM_WORLD, &r);
    wait_for(&r);
  }
  waited += sph_seconds() - t0;
}

void sph_procs_share(void *buf, size_t len) { sph_procs_share_from(buf, len, 0); }

void sph_procs_share_from(void *buf, size_t len, int root) {
  if (count == 1) return;
  MPI_Request r;
  const double t0 = sph_seconds();
  if (!crowded())
    MPI_Bcast(buf, (int)len, MPI_BYTE, root, MPI_COMM_WORLD);
  else {
    MPI_Ibcast(buf, (int)len, MPI_BYTE, root, MPI_COMM_WORLD, &r);
    wait_for(&r);
  }
  waited += sph_seconds() - t0;
}

int sph_procs_records_fit(const size_t *counts, size_t rec) {
  if (count > SPH_PROCS_MAX || rec > INT_MAX) return 0;
  size_t total = 0;
  for (int r = 0; r < count; r++)
    total += counts[r];
  return total <= INT_MAX;
}

/* The counts and offsets of a gather of records (each process's counts[r]
 * of rec bytes, in rank order) and their datatype, committed. */
static void records_layout(const size_t *counts, size_t rec, int *n, int *at, MPI_Datatype *t) {
  int total = 0;
  for (int r = 0; r < count; r++) {
    n[r] = (int)counts[r];
    at[r] = total;
    total += n[r];
  }
  MPI_Type_contiguous((int)rec, MPI_BYTE, t);
  MPI_Type_commit(t);
}

void sph_procs_gather_records(const void *mine, const size_t *counts, size_t rec, void *all) {
  if (count == 1) {
    memcpy(all, mine, counts[0] * rec);
    return;
  }
  int n[SPH_PROCS_MAX], at[SPH_PROCS_MAX];
  MPI_Datatype t;
  records_layout(counts, rec, n, at, &t);
  /* an MPI error ends the job (MPI_ERRORS_ARE_FATAL, the default) */
  MPI_Request r;
  const double t0 = sph_seconds();
  if (!crowded())
    MPI_Allgatherv(mine, n[rank], t, all, n, at, t, MPI_COMM_WORLD);
  else {
    MPI_Iallgatherv(mine, n[rank], t, all, n, at, t, MPI_COMM_WORLD, &r);
    wait_for(&r);
  }
  waited += sph_seconds() - t0;
  MPI_Type_free(&t);
}

/* The gather that sph_procs_gather_records_start left running. */
static MPI_Request pending;
static MPI_Datatype pending_type;

void sph_procs_gather_records_start(const void *mine, const size_t *counts, size_t rec, void *all) {
  int n[SPH_PROCS_MAX], at[SPH_PROCS_MAX];
  records_layout(counts, rec, n, at, &pending_type);
  MPI_Iallgatherv(mine, n[rank], pending_type, all, n, at, pending_type, MPI_COMM_WORLD, &pending);
}

void sph_procs_gather_records_progress(void) {
  int done;
  MPI_Test(&pending, &done, MPI_STATUS_IGNORE);
}

void sph_procs_gather_records_wait(void) {
  const double t0 = sph_seconds();
  if (!crowded())
    MPI_Wait(&pending, MPI_STATUS_IGNORE);
  else
    wait_for(&pending);
  waited += sph_seconds() - t0;
  MPI_Type_free(&pending_type);
}

#else /* one process */

int sph_procs_start(sph_error *err) {
  (void)err;
  return 0;
}
void sph_procs_end(void) {}
int sph_procs_any(int flag) { return flag != 0; }
int sph_procs_crowded(void) { return 0; }
double sph_procs_waited(void) { return 0.0; }
int sph_procs_agree(int rc, sph_error *err) {
  (void)err;
  return rc ? -1 : 0;
}
int sph_procs_agree_any(int rc, int *flag, sph_error *err) {
  (void)flag, (void)err;
  return rc ? -1 : 0;
}
int sph_procs_agree_flags(int rc, int *flags, int n, sph_error *err) {
  (void)flags, (void)n, (void)err;
  return rc ? -1 : 0;
}
int sph_procs_failed(int first, sph_error *err) {
  (void)first, (void)err;
  return -1;
}
void sph_procs_gather(const void *mine, size_t len, void *all) { memcpy(all, mine, len); }
void sph_procs_share(void *buf, size_t len) { (void)buf, (void)len; }
void sph_procs_share_from(void *buf, size_t len, int root) { (void)buf, (void)len, (void)root; }
int sph_procs_records_fit(const size_t *counts, size_t rec) {
  return rec <= INT_MAX && counts[0] <= INT_MAX;
}
void sph_procs_gather_records(const void *mine, const size_t *counts, size_t rec, void *all) {
  memcpy(all, mine, counts[0] * rec);
}
void sph_procs_gather_records_start(const void *mine, const size_t *counts, size_t rec, void *all) {
  memcpy(all, mine, counts[0] * rec);
}
void sph_procs_gather_records_progress(void) {}
void sph_procs_gather_records_wait(void) {}
#endif
