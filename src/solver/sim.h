/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * sim.h - the simulation object: the particles of a case and one time step.
 *
 * sph_sim_create builds the particles of a case (fluid blocks on a lattice,
 * tank and wall segments of wall particles or mirror lines, hydrostatic
 * start) and runs the interaction pass on that state. sph_sim_step then
 * advances them by one step of the case's integrator, predictor-corrector:
 *   time step (from the last pass) -> predictor -> pass -> corrector
 *   -> moving walls -> density filter (every N steps) -> blow-up check
 *   -> pass on the new state
 * or leap-frog (one pass per step). A pass is: mirror particles ->
 * neighbour list (kept while provably complete, else rebuilt from a grid;
 * the store is sorted by cell every 40 steps, or at every pass in cases
 * with mirror particles, free-surface detection or variable h) ->
 * free-surface flags -> interaction terms. So the rates and flags held
 * with a state always belong to it.
 * The library never prints or exits: failures come back as a status and an
 * sph_error message.
 */
#ifndef SPH_SIM_H
#define SPH_SIM_H

#include "case/case.h"
#include "core/error.h"
#include "core/particles.h"
#include "io/snapshot.h"
#include "solver/diag.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sph_sim sph_sim;

/* Status of sph_sim_step and friends: 0 = fine, SPH_BLOWUP = the new state
 * failed the blow-up check (err names step, time, particle and reason; the
 * state before the step is still held as the saved state), -1 = other error. */
#define SPH_BLOWUP 1

/* Builds the initial particles of a case. The case must outlive the sim. */
int sph_sim_create(const sph_case *c, sph_sim **out, sph_error *err);
void sph_sim_free(sph_sim *s);

/* Advances one step; the step is shortened so as not to pass t_target, and
 * when it reaches t_target the time is set to t_target exactly. */
int sph_sim_step(sph_sim *s, double t_target, sph_error *err);

double sph_sim_time(const sph_sim *s);
long sph_sim_steps(const sph_sim *s);
/* The steps of this run (since sph_sim_create or the restore) as the step rule chose them, steps
 * cut short to land on an output time left out: the first, the smallest and the time t at which
 * the smallest began. Returns 0 (and leaves the outputs alone) before the first such step. */
int sph_sim_step_range(const sph_sim *s, double *first, double *smallest, double *t);
/* The processes' figures of a run under mpirun (solver/procs.h), summed
 * over the processes since sph_sim_create: the passes each process made,
 * the particles they owned and held as ghosts (summed over the passes),
 * and the bytes each one sent. A collective step: every process calls it.
 * 0 (the figures zero) on one process. */
typedef struct sph_procs_figures {
  int processes;
  long passes;
  double own, ghosts; /* ghosts / own: the halo's share of the work */
  double bytes;       /* sent, all processes together */
  int crowded;        /* 1: the processes nap while they wait (sph_procs_crowded) */
  int balance;        /* 1: the cut follows the processes' measured work (sph_sim_set_balance) */
  long balanced;      /* cuts whose processes' shares moved */
  double share_min, share_max;   /* the processes' shares of the cut's weight now */
  double waited_min, waited_max; /* seconds a process waited for the others in the collective
                                    steps since sph_run_resume began, the least and the most
                                    (sph_procs_waited) */
} sph_procs_figures;
int sph_sim_procs_figures(const sph_sim *s, sph_procs_figures *f);
/* Under mpirun: whether the cut follows the processes' measured work
 * (1, the default: a process on a slower core gets fewer particles at the
 * next cut) or the particles' weights alone (0: the cut a pure function of
 * the state). The results are the same bits either way; only the time
 * moves. Every process must set the same; nothing on one process. */
void sph_sim_set_balance(sph_sim *s, int measured);
const sph_case *sph_sim_case(const sph_sim *s);
/* The particles (storage order changes at every step; use id for identity). */
sph_particles *sph_sim_particles(sph_sim *s);
/* The y of the floor used for the front (tank floor, or the lowest fluid
 * block bottom) and the band height (2 dx). */
double sph_sim_floor(const sph_sim *s);
/* Fluid particles of the case's blocks that were not made because a wall
 * particle lies closer than dx/2 (a wall drawn through the fluid;
 * doc/case-files.md). */
size_t sph_sim_fluid_removed(const sph_sim *s);
/* Fluid particles of the case's blocks that were not made because they lie
 * inside an obstacle box (a block drawn through a box: its inside is solid). */
size_t sph_sim_fluid_in_obstacles(const sph_sim *s);
/* Wall particles of a geometry.walls segment not made: closer than dx/2 to
 * a particle of an earlier wall (the tank or a segment before it). */
size_t sph_sim_walls_dropped(const sph_sim *s);
/* Fluid particles that left the domain and were taken out of the run
 * (geometry.leaving: remove; 0 otherwise), and their mass into *mass
 * (may be NULL). */
size_t sph_sim_fluid_left(const sph_sim *s, double *mass);
/* The domain box x0, x1, y0, y1 (, z0, z1 in 3-D): a fluid particle leaving it is
 * a blow-up, or is taken out of the run (geometry.leaving). */
void sph_sim_domain(const sph_sim *s, double box[2 * SPH_DIM]);
/* The interaction loop the run uses ("AVX-512 lanes", "AVX2 lanes",
 * "portable lanes" or "scalar"); *ratio gets the AVX2 loop's time over the AVX-512 loop's at
 * start-up, 1 where they were not both measured (forces.h). All give the
 * same results. */
const char *sph_sim_loop(const sph_sim *s, double *ratio);
/* Diagnostics of the current state. Under mpirun every process of the
 * run calls it at once (a collective step: each sums its share of the
 * store, and the exact sums merge into the bits of one process's). */
void sph_sim_diag(const sph_sim *s, sph_diag_row *row);
/* Writes the current state as a snapshot (atomically). */
int sph_sim_write_snapshot(const sph_sim *s, const char *path, sph_error *err);
/* Writes the state saved at the start of the last step (the last state that
 * passed the blow-up check) as a snapshot: used after a blow-up. */
int sph_sim_write_saved_snapshot(sph_sim *s, const char *path, sph_error *err);

/* Restart (sph run --restart). sph_sim_write_run_snapshot writes the
 * current state like sph_sim_write_snapshot plus the restart record
 * (snapshot.h: the storage order, the leap-frog's half-step values, the
 * ledger's integrals, and the run's own output_index, gauge levels and
 * probe filters: n_filters values, none when 0). Under several processes
 * (procs.h) it is a collective step: every process calls it with the same
 * arguments and the processes write the file together (snapshot.h,
 * sph_snapshot_write_team).
 * sph_sim_restore takes a sim freshly made by sph_sim_create from the same
 * case (only time.end may differ: the snapshot's "parameters" must match)
 * and puts it in the state of the snapshot at path, so that the steps that
 * follow are bitwise those of the run that wrote it. rd receives the
 * snapshot's restart record (free it with sph_snapshot_restart_free)
 * without its per-particle arrays (order and the half-step values: in the
 * store by then, and released before the state's first pass, so that a
 * restart takes no more memory than a fresh run); errors name the file
 * and what does not match. */
int sph_sim_write_run_snapshot(const sph_sim *s, const char *path, int64_t output_index,
                               const double *levels, size_t n_levels, const double *filters,
                               size_t n_filters, sph_error *err);
int sph_sim_restore(sph_sim *s, const char *path, sph_snapshot_restart_data *rd, sph_error *err);

#ifdef __cplusplus
}
#endif

#endif
