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

/* Whether flag is set on any process (the same answer on every one); the
 * flag itself on one process. A collective step: every process calls it at
 * the same point of the run. */
int sph_procs_any(int flag);

/* After a step every process made: 0 when rc is 0 on every process, else
 * -1 on every one, err holding the message of the lowest rank that failed
 * (prefixed with its rank when it is not this process's own). */
int sph_procs_agree(int rc, sph_error *err);

/* Reductions over the processes, the same bits on every one: the largest
 * of each process's x, and the sum of each one's n. */
double sph_procs_max(double x);
size_t sph_procs_sum(size_t n);

/* The bits set on any process. */
unsigned long long sph_procs_or(unsigned long long bits);

/* Every process's `len` bytes at `mine`, in rank order, into all
 * (count x len bytes). */
void sph_procs_gather(const void *mine, size_t len, void *all);

/* The records (rec bytes each) of every process's own items: process r
 * holds counts[r] of them at its `mine`; all receives every process's in
 * rank order. 0, or -1 with err. */
int sph_procs_gather_records(const void *mine, const size_t *counts, size_t rec, void *all,
                             sph_error *err);

#ifdef __cplusplus
}
#endif

#endif
