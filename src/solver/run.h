/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * run.h - running a case to its end: the output schedule (snapshots, the
 * XDMF index, diagnostics.csv), the stop condition, interruption and
 * blow-up handling.
 *
 * Output times are k * output_interval (k = 0, 1, ...), the listed
 * time.output_times, and the end time; steps are shortened to land on them
 * exactly. Snapshot k is
 * <outdir>/snap_NNNN.h5 (N = k), indexed by <outdir>/snapshots.xmf; one
 * diagnostics row per output time, and with wave gauges (output.gauges) a
 * row of <outdir>/gauges.csv: each gauge's surface elevation above its level
 * at t = 0. After a blow-up the snapshots already
 * written stay as they are, and the last state that passed the check is
 * written to <outdir>/last_good.h5.
 */
#ifndef SPH_RUN_H
#define SPH_RUN_H

#include <signal.h>

#include "core/error.h"
#include "solver/sim.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
  SPH_RUN_END = 0,         /* reached time.end */
  SPH_RUN_STOPPED = 1,     /* the case's stop condition was met */
  SPH_RUN_INTERRUPTED = 2, /* *interrupt became non-zero */
  SPH_RUN_BLOWUP = 3,      /* the blow-up check failed (err says where) */
  SPH_RUN_ERROR = 4        /* I/O or other failure (err says what) */
} sph_run_status;

typedef struct sph_run_options {
  const char *outdir; /* must exist; NULL writes nothing */
  /* called after every step (and once at the start) */
  void (*progress)(void *ctx, const sph_sim *s);
  void *progress_ctx;
  volatile sig_atomic_t *interrupt; /* may be NULL */
  /* called with every row written to diagnostics.csv (at t = 0 and at each
   * output time), or that would be without an outdir; may be NULL */
  void (*row)(void *ctx, const sph_diag_row *r);
  void *row_ctx;
} sph_run_options;

typedef struct sph_run_result {
  sph_run_status status;
  long steps;
  size_t outputs;           /* snapshots (or output times) written */
  char last_snapshot[4096]; /* path of the last snapshot written, "" if none */
} sph_run_result;

/* Runs s until time.end, the stop condition, an interrupt or a blow-up.
 * Returns 0 for END, STOPPED and INTERRUPTED, non-zero otherwise (with err). */
int sph_run(sph_sim *s, const sph_run_options *o, sph_run_result *r, sph_error *err);

/* The same for a sim restored from a snapshot (sph_sim_restore), rd its
 * restart record: the output numbering, gauge levels and CSV files carry
 * on from there (see run.c); rd NULL is sph_run. */
int sph_run_resume(sph_sim *s, const sph_run_options *o, const sph_snapshot_restart_data *rd,
                   sph_run_result *r, sph_error *err);

const char *sph_run_status_name(sph_run_status st);

/* The case's stop condition: the quantity it watches now, and the value at
 * which it stops the run. front_at_wall: the surge front (sph_diag_front)
 * and the right wall less dx. 0 (and nothing set) when the case has no stop
 * condition. A progress display measures the run's progress by it
 * between where it stood at the start and *stop. */
int sph_run_stop_measure(const sph_sim *s, double *now, double *stop);

#ifdef __cplusplus
}
#endif

#endif
