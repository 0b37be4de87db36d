/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * sim_internal.h - the simulation object's insides, shared by the files
 * of src/solver/ that make it (setup.c), step it (sim.c) and restart it
 * (restart.c). Not installed: programs see the opaque sph_sim of sim.h.
 */
#ifndef SPH_SIM_INTERNAL_H
#define SPH_SIM_INTERNAL_H

#include "core/particles.h"
#include "io/snapshot.h"
#include "neighbours/grid.h"
#include "solver/forces.h"
#include "solver/ledger.h"
#include "solver/outflow.h"
#include "solver/sim.h"
#include "walls/adami.h"
#include "walls/wall_velocity.h"
#include "walls/walls.h"

/* Cells of the grid are a hair larger than the support, so rounding in the
 * cell index can never separate a pair closer than 2h by a whole cell. */
#define SPH_CELL_MARGIN (1.0 + 1e-9)

/* The neighbour list's skin as a fraction of the support 2h (the test
 * hook SPH_TEST_SKIN overrides it for a run; 0 rebuilds at every pass). */
#define SPH_SKIN_DEFAULT 0.15

/* The closest a fluid particle comes to a mirror line, in units of dx,
 * or a tank face (walls.h, sph_walls_keep_off): half the first row's distance on
 * the initial lattice. */
#define SPH_MIRROR_MIN_DISTANCE 0.25

struct sph_sim {
  const sph_case *c;
  sph_walls walls;           /* wall particles' models, mirror lines, motions */
  int first_step;            /* leap-frog: the special first half step */
  int detect;                /* free-surface detection runs at every pass */
  size_t fluid_removed;      /* fluid particles not made: inside a wall (setup.c) */
  size_t fluid_in_obstacles; /* fluid particles not made: inside an obstacle box (setup.c) */
  size_t n_surface;          /* particles flagged at the last pass */
  sph_ledger ledger;         /* energy and momentum ledger (output.energy) */
  double dt_paper_b;         /* paper B §2.6 step from the last pass */
  sph_particles p;
  sph_grid grid;
  sph_nlist nl; /* neighbour list of the interaction passes */
  double skin;  /* its skin; 0 = rebuilt at every pass */
  int resort;   /* the next pass sorts the store by cell */
  sph_force_work work;
  sph_wall_velocity_work mdbc_work; /* the mDBC walls' fits (walls/wall_velocity.h) */
  sph_force_params fp;
  double
      *shift[SPH_DIM]; /* particle shifting's displacements by axis (numerics.shifting), or NULL */
  double t, last_dt;
  double t_walls;    /* the time the moving walls stand at (sph_sim_move_walls) */
  double lane_ratio; /* AVX2 / AVX-512 time of the start-up pass (forces.h), 1 if not measured */
  double t_saved;    /* time of the state saved at the start of the last step */
  long step_pass;    /* step of the state the last pass evaluated (w->hot) */
  long steps;
  long below_floor; /* steps in a row whose step was below the floor (sim.c) */
  /* this run's steps as its rule chose them (steps cut to land on an output time left out):
   * the first, the smallest and the time it began at (sph_sim_step_range) */
  double dt_first, dt_smallest, t_smallest;
  double floor_y;             /* the floor's height (y; z in 3-D) */
  double domain[2 * SPH_DIM]; /* x0, x1, y0, y1 (, z0, z1): leaving it is a blow-up, or */
  sph_outflow out;            /* the fluid that left it, taken out (geometry.leaving: remove) */
  double view[2 * SPH_DIM];
  char *parameters;               /* sph_case_describe */
  sph_snapshot_geometry geometry; /* every snapshot's /geometry (geometry_record.c) */
  /* ranks (ranks.c): the passes split among `ranks` ranks, each holding its
   * own particles and its ghosts in `sub`; 1: the whole store's pass */
  int ranks;
  struct sph_sim *sub;
  int depth;            /* the ghosts' depth in cells (ranks.c, ghost_depth) */
  sph_particles before; /* SPH_TEST_RANKS: the store before any rank's pass, which each takes
                         * from (a pass writes what other ranks' ghosts read: mdbc densities) */
  double hmax_all;      /* > 0: the largest h of the whole store (a rank's store's h_max) */
  uint64_t *keys;
  unsigned char *mark;
  size_t *from;                /* the whole store's index of each particle of sub */
  size_t *own_sub, *own_whole; /* the rank's own particles, the fluid first (each kind in storage
                                  order): their index in sub, in the store */
  size_t n_own, n_own_fluid, n_from; /* (how many, the fluid, and in sub, at the last pass) */
  size_t *kind_sub, *kind_whole, n_kind_fluid; /* every particle of sub, the fluid first: its
                                                  index in sub, in the store (a process's) */
  unsigned long long wall_not_taken; /* the arrays a kept store does not take again of a wall
                                        (ranks.c) */
  unsigned long long pass_in;        /* the arrays a pass reads, */
  unsigned long long pass_out[2];    /* those it may write in a fluid particle, in a wall, */
  unsigned long long pass_static;    /* and those no step changes */
  size_t cap_ranks;
  unsigned char *no_row; /* by id: a ghost of sub's with an empty row (sub's list: grid.h) */
  /* the rank this process makes (procs.h), or -1: every rank, one after
   * the other (SPH_TEST_RANKS); then each particle's rank, and the records
   * the processes share */
  int self;
  unsigned char *owner;
  size_t *by_owner; /* the store's indices by owner, each owner's fluid first (each kind in
                       storage order), */
  size_t owned[64], owned_fluid[64]; /* this many each, the fluid (SPH_PROCS_MAX), from the cut */
  unsigned char *records;
  size_t cap_records;
  void *reports;                  /* every process's report of its pass, in rank order (ranks.c) */
  struct sph_diag_sums *diag_all; /* every process's diagnostics sums (sim.c, sph_sim_diag) */
  unsigned char *mark_last;       /* the marks of this process's last pass, */
  size_t n_mark_last;             /* over this many particles, */
  uint64_t order_last;            /* the store in this order (particles.h), */
  double *take_pos;     /* every particle's position then (SPH_DIM arrays of n_mark_last), */
  double side_last;     /* and the cells' side */
  uint32_t *weight;     /* each particle's weight in the cut */
  uint32_t *fluid_near; /* (the fluid in its cells' block, for the weight) */
  unsigned long long changed[2]; /* the arrays this process's pass changed: fluid, walls */
  uint64_t first[64];            /* the cut: each rank's first key (neighbours/decomp.h), */
  size_t n_cut;                  /* made over this many particles */
  int rank_order_sums; /* the test hook SPH_TEST_RANK_ORDER_SUMS (ranks.c): 1 the ledger's, 2
                          the diagnostics' sums */
  int fail_rank;       /* the test hook SPH_TEST_FAIL_PASS (ranks.c): this process's */
  long fail_pass;      /* pass of this number fails; 0: none */
  int slow_rank;       /* the test hook SPH_TEST_SLOW_PROCESS (ranks.c): this process (-1: none) */
  double slow_factor;  /* naps this many times its pass's time after each pass */
  long fig_passes;     /* this process's figures (sph_sim_procs_figures) */
  double fig_own, fig_ghosts, fig_bytes;
  double fig_waited0; /* sph_procs_waited when sph_run_resume began */
  uint64_t order_cut; /* in this order */
  long cuts;          /* cuts made */
  /* the cut by measured work (ranks.c, balance): on (processes only); each process's share of
   * the cut's weight (SPH_PROCS_MAX); each process's work, in seconds, over the passes since the
   * last cut, and those passes; this process's clock and waits at its last report; the cuts
   * whose shares moved */
  int balance;
  double share[64], work_sum[64];
  long work_passes;
  double work_clock, work_waited;
  long balanced;
  /* the Adami walls in stages (ranks.c, staged): on; this process's own Adami walls that
   * another process's halo holds (their indices in the store and in sub), n_send of them, and
   * each process's count; each particle's index in sub (SIZE_MAX: not there), the walls sub
   * made first; the store's positions, order, cells' side and cut when those walls were chosen */
  int staged, stage_joined, stage_waited, stage_failed;
  /* the walls' values kept by their own processes between outputs (ranks.c, lazy_walls): on,
   * and the arrays the passes changed since they were last shared (sph_sim_catch_up) */
  int lazy_walls;
  unsigned long long walls_behind;
  size_t *send_whole, *send_sub, n_send, send_counts[64], send_total;
  size_t *to_sub;
  unsigned char *made_first;
  size_t cap_made_first;
  double *send_pos, side_send;
  size_t n_send_pos;
  uint64_t order_send;
  long cut_send;
  void *wall_buf; /* the walls' values sent and received */
  size_t cap_wall_buf;
  unsigned char *late; /* the rank store's rows that read a ghost wall (ranks.c, late_rows) */
  size_t cap_late, late_n;
  long late_builds;
  int moved_known;   /* this pass's two checks of the particles' moves made at once (ranks.c) */
  unsigned moved_ok; /* their bits: 1 the store taken, 2 the walls sent */
  double cfl_max;    /* the last pass's max of c + |v| (sph_dt_cfl) if the ranks made it (every
                        pass after sph_sim_ranks_init's), else 0 */
  int hot_in_sub;    /* the last pass's state is in each process's rank store, for its own
                        particles, not in work.hot (sph_sim_ranks_saved_state) */
  /* a rank's store (it is some sim's sub): ghosts carry SPH_FLAG_GHOST, and
   * each pass leaves the reductions over the rank's own particles here */
  int rank_store;
  double own_cs_max, own_cfl_max;
  /* or NULL: what makes a process's rank store's Adami walls instead of its
   * own pass over them, with the other processes (ranks.c, staged walls);
   * given the pass's status so far, which it returns (it joins the others
   * even after a failure) */
  int (*adami_stages)(struct sph_sim *s, void *ctx, int rc, sph_error *err);
  void (*adami_stages_end)(struct sph_sim *s, void *ctx); /* after the interaction loop: what
                                                             adami_stages left (its wait) */
  void *adami_ctx;
  sph_ledger_sums own_ledger;
};

/* The passes on `ranks` ranks (SPH_TEST_RANKS, doc/testing.md), this
 * process making rank `self` of them (procs.h) or, with self -1, all of
 * them: 0, or -1 with err (ranks.c). */
int sph_sim_ranks_init(sph_sim *s, int ranks, int self, sph_error *err);
void sph_sim_ranks_free(sph_sim *s);
/* Before the store takes another state and order (a restart, restart.c):
 * the rank store's list and work arrays released, and what the last pass
 * kept (the store taken, the walls sent, the cut) forgotten (ranks.c). */
void sph_sim_ranks_forget(sph_sim *s);
/* Under mpirun, after each process timed the lane loops on its own rank
 * (setup.c) or failed to (rc): the loop every process takes, from the mean
 * of their ratios; 0, or -1 with err on every process if one failed; a
 * collective step (ranks.c). */
int sph_sim_ranks_agree_loop(sph_sim *s, int rc, sph_error *err);
/* How many cells deep a rank's ghosts get rows of their own in its
 * neighbour list (ranks.c; the others, within `depth` cells, are there as
 * neighbours only, their rows empty: grid.h, no_row). One cell (a support)
 * reaches every ghost whose row's result a rank's own particles read (a
 * wall's Adami pressure or bounded density, a free-surface flag, a strain
 * rate, the moments of the corrected gradient); where a pass before the
 * main one reads, in a row of its own, a value another such pass wrote
 * from a row (the strain rate's volumes m/rho of dynamic walls whose
 * density was bounded from their rows), a chain is a support longer, and
 * every ghost gets its row. tests/test_decomp measures the least depth on
 * every scheme it runs. */
int sph_sim_ranks_row_depth(const sph_sim *s, int depth);
/* The kinds (bit 1 << SPH_KIND_*) whose ghosts get those rows: every kind
 * where a fluid row's result is read by a neighbour (free-surface flags,
 * the strain rate, the moments, Antuono's density gradient) or where no
 * wall's row gives one; else the walls alone (an Adami wall's pressure, a
 * dynamic wall's bounded density: the fluid's ghosts are neighbours only,
 * as the main loop gives a ghost no rates). tests/test_decomp and
 * tests/test_ranks compare the bytes on every scheme (ranks.c). */
unsigned sph_sim_ranks_row_kinds(const sph_sim *s);
/* One pass of the whole store made as the ranks make it, hmax the store's
 * largest smoothing length (ranks.c). */
int sph_sim_ranks_pass(sph_sim *s, double hmax, sph_error *err);
/* Under mpirun, after a step whose state blew up (every process's at
 * once: the store is the same on each): the last pass's state gathered
 * from each process's rank store into work.hot, as a pass on one process
 * leaves it; a collective step (ranks.c). */
void sph_sim_ranks_saved_state(sph_sim *s);
/* Under mpirun, where each process's passes keep its own walls' values to
 * itself between outputs (ranks.c, lazy_walls): those values shared, so
 * that every process's store is the whole state again (before anything
 * reads other processes' walls: a diagnostics row, a snapshot, a sort, a
 * blow-up's last good state); a collective step, nothing where none is
 * behind (ranks.c). */
void sph_sim_catch_up(sph_sim *s);
/* While those walls' values are behind in the store (some process's pass
 * changed them since they were shared): this process's own walls (the
 * store's indices, *n of them, in storage order; the blow-up check's share
 * of the walls, sim.c), else NULL (ranks.c). */
const size_t *sph_sim_ranks_own_walls(const sph_sim *s, size_t *n);
/* A sim of the case for one rank's store: sph_sim_create on one rank (setup.c). */
int sph_sim_create_rank_store(const sph_case *c, sph_sim **out, sph_error *err);
/* The span [*from, *to) of the store whose particles this process counts
 * in a reduction over the store (the diagnostics, the gauges, the blow-up
 * check): under mpirun (self >= 0) its share, else the whole store; the
 * shares of all processes cover the store once (sim.c). */
void sph_sim_span(const sph_sim *s, size_t *from, size_t *to);

/* The energy ledger's initial totals from the current state (a collective
 * step under mpirun, as sph_sim_diag) (sim.c). */
void sph_sim_ledger_start(sph_sim *s);

/* Sorts the store by cell and id as a sorting pass does (sim.c). */
int sph_sim_sort(sph_sim *s, sph_error *err);

/* The Adami walls' parameters of the sim's pass (sim.c). */
void sph_sim_adami_params(const sph_sim *s, sph_adami_params *ap);

/* The moving walls at time t, which a pass's adami walls read (sim.c). */
void sph_sim_move_walls(sph_sim *s, double t);

/* Mirror particles, grid build, free-surface flags and one interaction
 * pass on the current state (sim.c). */
int sph_sim_pass(sph_sim *s, sph_error *err);

/* The blow-up check of the current state: SPH_BLOWUP with err naming the
 * first offender in id order, or 0 (sim.c). Under mpirun a collective step:
 * each process checks its share (sph_sim_span) and all take the least id. */
int sph_sim_check_state(sph_sim *s, sph_error *err);

/* The case's geometry as snapshots record it: 0, or -1 with err (*g then
 * empty; sph_snapshot_geometry_free frees it) (geometry_record.c). */
int sph_sim_record_geometry(const sph_case *c, sph_snapshot_geometry *g, sph_error *err);

/* The snapshot header of the sim's state at time t, step `step` (sim.c). */
void sph_sim_fill_meta(const sph_sim *s, sph_snapshot_meta *m, double t, long step);

#endif
