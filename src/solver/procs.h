/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * procs.h - the processes of a run under an MPI launcher (doc/parallel.md).
 *
 * A build configured --with-mpi runs `sph run` under `mpirun -n N` as N
 * processes. Each holds the whole store and makes its state the same bits
 * as every other's: the passes are cut into ranks (neighbours/decomp.h,
 * solver/ranks.c), each process makes its own rank's part and the parts
 * are shared (every process's own particles, as records, to every other);
 * the reductions of a pass are a max, a count and exact sums, the same for
 * any split and order. Everything else (the integration, the outputs'
 * readings) each process makes on the same state, so one process (rank 0)
 * writes the files and the others follow. Without MPI, or not under a
 * launcher, the run is one process and none of this costs anything.
 */
#ifndef SPH_PROCS_H
#define SPH_PROCS_H

#include <stddef.h>

#include "core/error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* 1 when the library was built with MPI (./configure --with-mpi). */
int sph_procs_built(void);

/* The rank and the process count an MPI launcher gave this process in its
 * environment (Open MPI's OMPI_COMM_WORLD_RANK and _SIZE, or PMIx's and
 * PMI's), readable before sph_procs_start: 0 and 1 when not launched. */
int sph_procs_launched_rank(void);
int sph_procs_launched_count(void);

/* Joins the launcher's processes (MPI_Init) when launched by one and built
 * with MPI; otherwise nothing. 0, or -1 with err. Once per program. */
int sph_procs_start(sph_error *err);
/* Leaves them (MPI_Finalize), after the last collective step. */
void sph_procs_end(void);

/* This process's rank and the number of processes (0 and 1 when not
 * started). */
int sph_procs_rank(void);
int sph_procs_count(void);
/* 1 when the processes nap between looks at each other while they wait
 * (some machine of the job runs more of its processes' threads than it
 * has cores, counted with the threads set now), 0 when they block in MPI's
 * own waits (and on one process). The first call before any collective
 * step is one: every process makes it. */
int sph_procs_crowded(void);

/* Seconds of wall time this process has spent waiting in the collective
 * steps so far (each blocking call and wait timed on the monotonic clock;
 * 0 on one process): a
 * process's work is the wall time less this (solver/ranks.c weighs the
 * cut by it). */
double sph_procs_waited(void);

/* Whether flag is set on any process (the same answer on every one); the
 * flag itself on one process. A collective step: every process calls it at
 * the same point of the run. */
int sph_procs_any(int flag);

/* At most this many processes (a run's cut names a particle's process in
 * a byte). */
#define SPH_PROCS_MAX 64
/* After a step every process made: 0 when rc is 0 on every process, else
 * -1 on every one, err holding the message of the lowest rank that failed
 * (prefixed with its rank when it is not this process's own). */
int sph_procs_agree(int rc, sph_error *err);
/* sph_procs_agree, and *flag set on every process to whether it was set
 * on any: one collective step for both. */
int sph_procs_agree_any(int rc, int *flag, sph_error *err);
/* The same with n flags (n <= SPH_PROCS_FLAGS), each set on every process
 * to whether it was set on any: one collective step. */
#define SPH_PROCS_FLAGS 4
int sph_procs_agree_flags(int rc, int *flags, int n, sph_error *err);
/* After a gather that showed every process that process `first` failed
 * (the lowest rank that did): its message into err on every process
 * (prefixed with its rank on the others). -1. A collective step. */
int sph_procs_failed(int first, sph_error *err);
/* Every process's `len` bytes at `mine`, in rank order, into all
 * (count x len bytes). */
void sph_procs_gather(const void *mine, size_t len, void *all);
/* Rank 0's `len` bytes at buf, into every process's buf (len fits an
 * int). A collective step. */
void sph_procs_share(void *buf, size_t len);
/* The same from process `root`'s buf. A collective step. */
void sph_procs_share_from(void *buf, size_t len, int root);
/* Whether sph_procs_gather_records can carry these counts of rec-byte
 * records (MPI counts are ints); local, no collective. */
int sph_procs_records_fit(const size_t *counts, size_t rec);
/* The records (rec bytes each) of every process's own items: process r
 * holds counts[r] of them at its `mine`; all receives every process's in
 * rank order. The counts must fit (sph_procs_records_fit, checked and
 * agreed before); an MPI failure ends the job. */
void sph_procs_gather_records(const void *mine, const size_t *counts, size_t rec, void *all);
/* The same started without waiting (one at a time): the caller works on
 * and waits with sph_procs_gather_records_wait, touching neither mine nor
 * all in between. */
void sph_procs_gather_records_start(const void *mine, const size_t *counts, size_t rec, void *all);
/* Moves the gather that sph_procs_gather_records_start left running
 * (Open MPI moves a collective step only inside its calls; without them the
 * others wait at theirs for this process's records): from the thread that
 * calls MPI. */
void sph_procs_gather_records_progress(void);
void sph_procs_gather_records_wait(void);
#ifdef __cplusplus
}
#endif

#endif
