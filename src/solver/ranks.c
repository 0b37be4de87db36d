/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * ranks.c - a pass made as ranks make it (sim_internal.h; doc/method.md,
 * Ranks).
 *
 * The whole store is cut into ranks along the Hilbert curve of its cells
 * (neighbours/decomp.h). For each rank in turn, a second sim (`sub`) takes
 * the rank's own particles and its ghosts, in the whole store's order, and
 * makes the pass on them alone; its own particles (their rates, and what
 * the pass wrote into them: wall densities and pressures, flags) go back
 * into the whole store. The reductions of the pass (the step rule's max of
 * c + sigma, the flagged particles' count, the energy ledger's rates) are
 * taken over each rank's own particles (SPH_FLAG_GHOST marks the others,
 * and their mirror particles) and combined: a max, a count and exact sums
 * (exact_sum.h) are the same in any order and for any split. The
 * integration, the blow-up check and the outputs then run on the whole
 * store as they always do.
 *
 * Under mpirun (procs.h) each process makes its own rank's part, then the
 * processes share what their passes changed in their own particles and
 * combine the reductions (doc/parallel.md). With SPH_TEST_RANKS=R one
 * process makes every rank's part in turn, each from the store as it was
 * before any (as separate processes do): every output of a run must be
 * the same bytes as the run's on one rank (tests/test_ranks, and
 * tests/test_mpi under mpirun). Particle shifting runs on the whole store,
 * over a neighbour list of its own (sim.c).
 */
#include "config.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/exact_sum.h"
#include "core/lanes.h"
#include "core/parallel.h"
#include "neighbours/decomp.h"
#include "physics/kernel.h"
#include "solver/diag_sums.h"
#include "solver/integrate.h"
#include "solver/procs.h"
#include "solver/sim_internal.h"

/* Ghosts at least this many decomposition cells deep, the cells one
 * support wide: two supports, the reach of a pass's chains (a neighbour's
 * value that needs its own neighbours: the Adami walls' extrapolation, the
 * strain rate, the free-surface flags; tests/test_decomp measures the least
 * depth on every scheme, tests/test_ranks the bytes with these); mirror
 * points add their reach, and the walls made in stages leave one support
 * (ghost_depth). */
#define SPH_RANKS_DEPTH 2
#define SPH_RANKS_CELL 1.0

/* Whether a pass before the main one makes a fluid row's result that a
 * neighbour's row reads (the strain rate, the capillary stress and the moments, with their
 * volumes m/rho; Antuono's density gradient); the free-surface scan is the
 * callers' to add. */
static int fluid_rows_read(const sph_sim *s) {
  const sph_force_params *fp = &s->fp;
  return fp->viscosity == SPH_VISCOSITY_STRESS_TENSOR || fp->sps || fp->sigma > 0.0 ||
         fp->gradient_correction || fp->corrected_gradient ||
         fp->diffusion == SPH_DIFFUSION_ANTUONO;
}

int sph_sim_ranks_row_depth(const sph_sim *s, int depth) {
  /* passes before the main one that write a value from a row (a dynamic
   * wall's bounded density, an Adami wall's pressure, free-surface flags) */
  const int writes = s->walls.dbc || s->walls.adami || s->detect;
  /* passes before the main one that read a neighbour's such value in a row
   * of their own (the strain rate's and the moments' volumes, Antuono's
   * density gradient, the free-surface scan) */
  const int reads = fluid_rows_read(s) || s->detect;
  return writes && reads ? depth : 1;
}

unsigned sph_sim_ranks_row_kinds(const sph_sim *s) {
  const unsigned all = 1u << SPH_KIND_FLUID | 1u << SPH_KIND_WALL | 1u << SPH_KIND_MIRROR;
  /* a fluid row's result read by a neighbour: a free-surface flag (and the
   * smoothing length it sets), a strain rate, the moments, Antuono's density
   * gradient */
  const int fluid = s->detect || fluid_rows_read(s);
  /* else only a wall's row gives one (a dynamic wall's bounded density, an
   * Adami wall's pressure and velocity) */
  return fluid || !(s->walls.dbc || s->walls.adami) ? all : 1u << SPH_KIND_WALL;
}

/* The cut's weights: a particle's cost in a pass, in ns, from the pairs its
 * rows make: a fluid particle's row in the interaction loop holds its every
 * neighbour within the support, a wall particle's (its Adami, dynamic or
 * mdbc row) its fluid ones; each estimated from the particles in the 3^D
 * cells one support wide around it (decomp.h, sph_decomp_block_counts)
 * times the support's ball over that block (SPH_RANKS_BALL). Per pair and
 * per particle, timed with perf on SPHERIC Test 2 in 3-D (dx = 0.02 m, 2
 * processes of one thread, each process's rows counted): the interaction
 * loop and the list 4.4 + 0.5 ns a row entry, an Adami row 7 ns a fluid
 * entry, and every particle about 50 ns (taking the store, putting it
 * back, the step), which keeps a store of dry walls alone cut. (Weights of
 * the kinds alone, a fluid particle 45, a wall with fluid within a cell
 * 12, a dry one 1, left one process's fluid rows with 3 % more entries:
 * its fluid more often beside the walls, the other's at the free surface;
 * with the walls made in stages the other waited 0.6 s.) */
#define SPH_RANKS_NS_PARTICLE 50.0
#define SPH_RANKS_NS_FLUID_PAIR 4.9
#define SPH_RANKS_NS_WALL_PAIR 7.0
#if SPH_DIM == 2
#define SPH_RANKS_BALL (3.14159265358979323846 / 9.0) /* the unit disc over 3 x 3 cells */
#else
#define SPH_RANKS_BALL (4.18879020478639098461 / 27.0) /* the unit ball over 3 x 3 x 3 cells */
#endif

/* A particle's weight in the cut (above) from its block's counts. */
static uint32_t cut_weight(int32_t kind, uint32_t all, uint32_t fluid) {
  const double pairs = SPH_RANKS_BALL * (kind == SPH_KIND_FLUID ? all : fluid);
  const double ns =
      SPH_RANKS_NS_PARTICLE +
      (kind == SPH_KIND_FLUID ? SPH_RANKS_NS_FLUID_PAIR : SPH_RANKS_NS_WALL_PAIR) * pairs;
  return ns < 4e9 ? (uint32_t)ns : 4000000000u;
}

/* What a rank's pass adds up over its own particles. */
typedef struct rank_sums {
  double cs_max;  /* the step rule's max of c + sigma */
  double cfl_max; /* paper A's max of c + |v| (sph_dt_cfl) */
  size_t surface; /* free-surface particles */
  sph_ledger_sums ledger;
} rank_sums;

/* What a process tells every other after its pass, in one gather. */
typedef struct pass_report {
  int64_t failed; /* 1: its pass (or its exchange's buffer) failed */
  double work;    /* the process's seconds since its last report less its waits (-1: none yet) */
  unsigned long long arrays[2]; /* the arrays its pass changed in a bit of some particle: of
                                   the fluid, of the walls */
  rank_sums sums;
} pass_report;

/* The processes' lane loop: each timed both on its own (setup.c), and a
 * busy core can make one process take the slower loop (SPHERIC Test 2, 2
 * processes: one took the AVX2 loop, its interaction loop 10 % slower, the
 * other waited); where every process timed them, all take the loop for the
 * mean of their ratios (the same bits on each: the same ratios in rank
 * order). The loops give the same bits: only the time moves. */
int sph_sim_ranks_agree_loop(sph_sim *s, int rc, sph_error *err) {
  const sph_force_loop l = s->fp.loop;
  const double mine[3] = {rc ? 1.0 : 0.0,
                          l == SPH_LOOP_LANES_AVX || l == SPH_LOOP_LANES_AVX512 ? 1.0 : 0.0,
                          s->lane_ratio};
  double all[3 * SPH_PROCS_MAX], sum = 0.0;
  int chose = 1;
  sph_procs_gather(mine, sizeof mine, all);
  for (int q = 0; q < s->ranks; q++) {
    if (all[3 * q] != 0.0) return sph_procs_failed(q, err);
    if (!(all[3 * q + 1] == 1.0) || !(all[3 * q + 2] != 1.0)) chose = 0; /* one did not choose */
    sum += all[3 * q + 2];
  }
  if (!chose) return 0;
  s->lane_ratio = sum / s->ranks;
  s->fp.loop = sph_forces_loop_for_ratio(s->lane_ratio);
  return 0;
}

/* Whether the processes make their Adami walls in stages (stage_walls):
 * where the Adami walls' pass is the only one before the main pass that
 * makes a value from a row (no dynamic, mdbc or no-slip walls, no mirror
 * walls, no free-surface flags, nothing that reads such a value in a row of
 * its own; no moving walls: not tested with them), each process makes its
 * own walls alone and its ghost walls get their own processes' values,
 * instead of making them again from their rows (which stay: forces.c marks
 * the Riemann rows that meet a wall from the walls' rows). */
static int staged(const sph_sim *s) {
  const sph_walls *w = &s->walls;
  return s->self >= 0 && w->adami && !w->dbc && !w->mdbc && !w->no_slip && !w->n_mirror &&
         !w->moving && !s->detect && !fluid_rows_read(s) && s->fp.phases < 2;
}

static int stage_walls(sph_sim *r, void *ctx, int rc, sph_error *err);
static void stages_end(sph_sim *r, void *ctx);

int sph_sim_ranks_init(sph_sim *s, int ranks, int self, sph_error *err) {
  const sph_case *c = s->c;
  s->self = -1;
  if (ranks < 2) return 0;
  if (ranks > SPH_PROCS_MAX)
    return sph_error_set(err, "%s: at most %d ranks, got %d",
                         self < 0 ? "SPH_TEST_RANKS" : "mpirun -n", SPH_PROCS_MAX, ranks);
  s->ranks = ranks;
  if (sph_sim_create_rank_store(c, &s->sub, err)) return -1;
  s->sub->rank_store = 1;
  s->sub->work.skip_ghosts = 1;
  s->self = self;
  sph_sim_set_balance(s, 1); /* (processes only: self >= 0) */
  s->staged = staged(s);
  if (s->staged)
    s->sub->adami_stages = stage_walls, s->sub->adami_stages_end = stages_end,
    s->sub->adami_ctx = s;
  /* what a pass reads: all but the integrator's saved state, the rates and the leap-frog's half
   * step (a mirror particle's is made in the pass from its image's velocity), but for a dynamic
   * wall's half-step density; what it writes, kind by kind: the rates, the walls' densities and
   * pressures (and that half-step density: dbc.h, adami.h, wall_velocity.h; no pass writes a
   * fluid particle's), and with free-surface flags (freesurface.h) the flags and the smoothing
   * lengths they set */
  const unsigned long long half = s->walls.dbc ? 0 : sph_particles_array_bits("rhoh");
  s->pass_in =
      SPH_PARTICLES_ALL &
      ~sph_particles_array_bits("x0 y0 z0 vx0 vy0 vz0 rho0 u0 ax ay az drho du xsx xsy xsz "
                                "vxh vyh vzh uh") &
      ~half;
  const unsigned long long flagged = s->detect ? sph_particles_array_bits("h flags") : 0;
  const unsigned long long rates = sph_particles_array_bits("ax ay az drho du xsx xsy xsz");
  s->pass_out[0] = rates | flagged;
  /* (a wall's rates are zero at every pass where it is an Adami or a
   * repulsive wall: interact_row.h) */
  int rated = 0;
  for (size_t i = 0; i < s->p.n && !rated; i++)
    rated =
        s->p.kind[i] == SPH_KIND_WALL && !(s->p.flags[i] & (SPH_FLAG_ADAMI | SPH_FLAG_REPULSIVE));
  s->pass_out[1] = (rated ? rates : 0) | (sph_particles_array_bits("rho p rhoh") & ~half) |
                   flagged |
                   (s->fp.phases > 1 ? sph_particles_array_bits("wphase") : 0); /* (adami.h) */
  /* what a kept store does not take again of a wall: its position and velocity where no wall
   * moves (walls.h: the fluid alone is kept off walls, shifted and integrated), and with the
   * walls in stages and a constant h its density and pressure (the pass makes its own walls'
   * before any row reads them, and its rows read only those ghost walls whose values their own
   * processes send: stage_walls; a variable h is made from them before) */
  const int h_static = !c->variable_h && !s->fp.var_h;
  s->wall_not_taken = (s->walls.moving ? 0 : sph_particles_array_bits("x y z vx vy vz")) |
                      (s->staged && h_static ? sph_particles_array_bits("rho p") : 0);
  /* the walls' values kept by their own processes between the outputs (sph_sim_catch_up):
   * where a pass writes only a wall's density and pressure, no other process's pass takes
   * them from the store (above), and no step reads them but the blow-up check (each
   * process checks its own walls, sim.c) and the leap-frog's copy of the density (its own
   * walls' right, the others' shared with them); not with particle shifting or a density
   * filter (their neighbours' volumes) */
  s->lazy_walls = s->staged && h_static && !(s->pass_out[1] & ~sph_particles_array_bits("rho p")) &&
                  !c->shifting && c->density_filter == SPH_FILTER_NONE;
  s->walls_behind = 0;
  /* what no step changes: a store kept from the last pass keeps them (the smoothing lengths
   * without paper B's variable h or a free surface's h*) */
  s->pass_static = sph_particles_array_bits("mass mx my mz xr yr zr kind body id phase") |
                   (c->variable_h || s->fp.var_h ? 0 : sph_particles_array_bits("h"));
  /* SPH_TEST_RANK_ORDER_SUMS=1 (doc/testing.md): the ledger's sums made the
   * way that depends on the rank count, for the test that must see it; =2 the
   * diagnostics' sums (sim.c) */
  const char *e = getenv("SPH_TEST_RANK_ORDER_SUMS");
  s->rank_order_sums = e && (*e == '1' || *e == '2') ? *e - '0' : 0;
  /* SPH_TEST_FAIL_PASS=R:K (doc/testing.md): process R's K-th pass fails
   * before it starts, for the test that the others are not left waiting */
  const char *fe = getenv("SPH_TEST_FAIL_PASS");
  if (fe && sscanf(fe, "%d:%ld", &s->fail_rank, &s->fail_pass) != 2) s->fail_pass = 0;
  /* SPH_TEST_SLOW_PROCESS=R:F (doc/testing.md): process R naps F times its pass's time after
   * each pass, a core 1 + F times slower, for the test of the cut by measured work */
  const char *se = getenv("SPH_TEST_SLOW_PROCESS");
  s->slow_rank = -1;
  if (se && (sscanf(se, "%d:%lf", &s->slow_rank, &s->slow_factor) != 2 ||
             !(s->slow_factor >= 0.0 && s->slow_factor <= 100.0)))
    s->slow_rank = -1;
  if (self >= 0 && (!(s->reports = malloc((size_t)ranks * sizeof(pass_report))) ||
                    !(s->diag_all = malloc((size_t)ranks * sizeof(sph_diag_sums)))))
    return sph_error_set(err, "out of memory for the ranks' sums");
  return 0;
}

void sph_sim_ranks_free(sph_sim *s) {
  if (s->sub) sph_sim_free(s->sub);
  sph_particles_free(&s->before);
  free(s->keys);
  free(s->mark);
  free(s->from);
  free(s->own_sub);
  free(s->own_whole);
  s->own_sub = s->own_whole = NULL;
  free(s->kind_sub);
  free(s->kind_whole);
  s->kind_sub = s->kind_whole = NULL;
  free(s->owner);
  free(s->by_owner);
  s->by_owner = NULL;
  free(s->send_whole);
  free(s->send_sub);
  free(s->to_sub);
  free(s->made_first);
  free(s->send_pos);
  free(s->wall_buf);
  s->send_whole = s->send_sub = s->to_sub = NULL, s->made_first = NULL, s->send_pos = NULL;
  s->wall_buf = NULL, s->n_send = s->n_send_pos = s->cap_made_first = s->cap_wall_buf = 0;
  free(s->records);
  free(s->reports);
  free(s->diag_all);
  s->diag_all = NULL;
  free(s->mark_last);
  free(s->take_pos);
  s->take_pos = NULL;
  free(s->late);
  s->late = NULL, s->cap_late = 0;
  free(s->weight);
  free(s->fluid_near);
  s->fluid_near = NULL;
  free(s->no_row);
  s->no_row = NULL;
  s->weight = NULL;
  s->reports = NULL, s->mark_last = NULL, s->n_mark_last = 0;
  s->sub = NULL, s->keys = NULL, s->mark = NULL, s->from = NULL, s->cap_ranks = 0;
  s->owner = NULL, s->records = NULL, s->cap_records = 0;
}

void sph_sim_ranks_forget(sph_sim *s) {
  if (!s->sub) return;
  sph_nlist_release(&s->sub->nl);
  sph_force_work_free(&s->sub->work);
  s->sub->work.skip_ghosts = 1; /* (as sph_sim_ranks_init set it) */
  s->hot_in_sub = 0;
  s->n_mark_last = 0, s->n_send_pos = 0, s->n_cut = 0; /* taken, sent and cut anew */
  s->walls_behind = 0;                                 /* (the store is the whole state) */
  s->late_n = 0;
  s->work_clock = 0.0, s->work_passes = 0; /* (the restore's time is no pass's work) */
  for (int q = 0; q < s->ranks; q++)
    s->work_sum[q] = 0.0;
}

static int reserve(sph_sim *s, size_t n, sph_error *err) {
  if (n <= s->cap_ranks) return 0;
  uint64_t *k = realloc(s->keys, n * sizeof *k);
  if (k) s->keys = k;
  unsigned char *m = realloc(s->mark, n);
  if (m) s->mark = m;
  unsigned char *nr = realloc(s->no_row, n); /* by id: ids are 0..n-1 (particles.h) */
  if (nr) s->no_row = nr;
  size_t *f = realloc(s->from, n * sizeof *f);
  if (f) s->from = f;
  size_t *os = realloc(s->own_sub, n * sizeof *os);
  if (os) s->own_sub = os;
  size_t *ow = realloc(s->own_whole, n * sizeof *ow);
  if (ow) s->own_whole = ow;
  size_t *ks = s->self >= 0 ? realloc(s->kind_sub, n * sizeof *ks) : s->kind_sub;
  if (ks) s->kind_sub = ks;
  size_t *kw = s->self >= 0 ? realloc(s->kind_whole, n * sizeof *kw) : s->kind_whole;
  if (kw) s->kind_whole = kw;
  unsigned char *o = s->self >= 0 ? realloc(s->owner, n) : s->owner;
  if (o) s->owner = o;
  size_t *bo = s->self >= 0 ? realloc(s->by_owner, n * sizeof *bo) : s->by_owner;
  if (bo) s->by_owner = bo;
  unsigned char *l = s->self >= 0 ? realloc(s->mark_last, n) : s->mark_last;
  if (l) s->mark_last = l;
  double *tp = s->self >= 0 ? realloc(s->take_pos, SPH_DIM * n * sizeof *tp) : s->take_pos;
  if (tp) s->take_pos = tp;
  uint32_t *w = realloc(s->weight, n * sizeof *w);
  if (w) s->weight = w;
  uint32_t *fn = realloc(s->fluid_near, n * sizeof *fn);
  if (fn) s->fluid_near = fn;
  int staged_ok = 1;
  if (s->staged) {
    size_t *sw = realloc(s->send_whole, n * sizeof *sw);
    if (sw) s->send_whole = sw;
    size_t *ss = realloc(s->send_sub, n * sizeof *ss);
    if (ss) s->send_sub = ss;
    size_t *ts = realloc(s->to_sub, n * sizeof *ts);
    if (ts) s->to_sub = ts;
    double *sp = realloc(s->send_pos, SPH_DIM * n * sizeof *sp);
    if (sp) s->send_pos = sp;
    staged_ok = sw && ss && ts && sp;
    s->n_send_pos = 0; /* (the walls to send chosen anew) */
  }
  if (!k || !m || !nr || !f || !os || !ow || !w || !fn || !staged_ok ||
      (s->self >= 0 && (!o || !bo || !l || !tp || !ks || !kw)))
    return sph_error_set(err, "out of memory for the ranks' cut");
  s->cap_ranks = n;
  return 0;
}

/* The ghosts' depth in cells of width `cell`: one support where the walls
 * are made in stages; else the two supports of a pass's chains, and beyond
 * them the farthest mirror point of an mdbc or no-slip wall particle (its
 * density and velocity are fits over the fluid around that point, and that
 * fluid's smoothing lengths follow its free-surface flags: a chain two
 * supports long from the point, not from the particle; free_surface.h_factor
 * with mdbc walls needed 3 cells where 2 were taken). */
static int ghost_depth(const sph_sim *s, const sph_particles *p, double cell) {
  /* the walls in stages (staged, above): a ghost wall takes its own process's values, and no
   * other pass before the main one makes a value from a row, so a pass reads its ghosts' state
   * alone, within one support of its own particles (without density diffusion, whose pass
   * before the loop is not made in stages) */
  if (s->staged && s->fp.diffusion == SPH_DIFFUSION_NONE) return 1;
  if (!(p->live & SPH_ARRAYS_OFFSET)) return SPH_RANKS_DEPTH; /* no wall with a mirror point */
  double far = 0.0;
  for (size_t i = 0; i < p->n; i++)
    if (p->kind[i] == SPH_KIND_WALL && (p->flags[i] & (SPH_FLAG_MDBC | SPH_FLAG_NO_SLIP))) {
      double m2 = 0.0;
      for (int a = 0; a < SPH_DIM; a++)
        m2 += p->mirror_offset[a][i] * p->mirror_offset[a][i];
      if (m2 > far) far = m2;
    }
  return SPH_RANKS_DEPTH + (int)ceil(sqrt(far) / cell);
}

/* A process's store (s->self) keeps the particles of its last pass while
 * they cover what it needs now (s->mark; never once the store was sorted
 * or reordered since: may_cover): the same own particles, every
 * ghost it needs among them, the store in the same order (extra ghosts
 * change no own particle's bits: decomp.h, the depth). Its neighbour list
 * then still names them, and is kept while its skin allows (sim.c: every
 * sum depends on the state, the order and the step count alone, not on
 * when lists are built). 1 with s->mark the last pass's marks, else 0. */
static int may_cover(const sph_sim *s, int resort) {
  return !resort && s->n_mark_last == s->p.n && s->order_last == s->p.order;
}

static int covered(sph_sim *s, int resort) {
  const sph_particles *p = &s->p;
  int cover = may_cover(s, resort);
  for (size_t i = 0; cover && i < p->n; i++) {
    /* own the same; a ghost that needs a row had one, a ghost that is a
     * neighbour only was there */
    const unsigned char now = s->mark[i], was = s->mark_last[i];
    cover = (now == 1) == (was == 1) && (now != 2 || was == 2) && (now != 3 || was >= 2);
  }
  if (cover) memcpy(s->mark, s->mark_last, p->n);
  return cover;
}

/* How many of x[lo, hi) lie l or more from x0 (a NaN does): a count in
 * doubles, so that the loop runs in lanes (four with AVX2, where the
 * processor has it: the same count). */
SPH_AVX2_TWIN(double, count_far,
              (const double *x, const double *x0, size_t lo, size_t hi, double l),
              (x, x0, lo, hi, l), {
                double far = 0.0;
                _Pragma("omp simd reduction(+ : far)") for (size_t i = lo; i < hi; i++) far +=
                    fabs(x[i] - x0[i]) < l ? 0.0 : 1.0;
                return far;
              })

/* Whether no particle of p moved lim[k] or more along any axis from where
 * ref[k] (SPH_DIM arrays of p->n) holds it (a NaN has moved), for each
 * k < refs (at most 2): bit k of the result. One reading of the positions,
 * a block of particles at a time in lanes. */
static unsigned moved_under(const sph_particles *p, const double *const *ref, const double *lim,
                            int refs) {
  const size_t n = p->n, block = 4096;
  unsigned ok = (1u << refs) - 1u;
  for (int a = 0; a < SPH_DIM; a++) {
    const double *x = p->pos[a];
    for (size_t lo = 0; lo < n; lo += block) {
      const size_t hi = n - lo > block ? lo + block : n;
      for (int k = 0; k < refs; k++) {
        if (!(ok >> k & 1u)) continue;
        if (count_far(x, ref[k] + (size_t)a * n, lo, hi, lim[k]) != 0.0) ok &= ~(1u << k);
      }
      if (!ok) return 0;
    }
  }
  return ok;
}

/* The conditions of still_covered (below) but the particles' moves. */
static int take_refs_good(const sph_sim *s, int resort, double side) {
  return may_cover(s, resort) && side <= s->side_last;
}

/* The conditions of send_still_good (below) but the particles' moves. */
static int send_refs_good(const sph_sim *s, double side) {
  const sph_particles *p = &s->p;
  return s->n_send_pos == p->n && p->n > 0 && s->order_send == p->order && s->cut_send == s->cuts &&
         side <= s->side_send;
}

/* Both checks of the particles' moves in one reading (process_pass), where
 * both are to be made this pass: moved_known then holds their bits. */
static void moved_both(sph_sim *s, int resort, double side) {
  s->moved_known = 0;
  if (!take_refs_good(s, resort, side) || !send_refs_good(s, side)) return;
  const double *ref[2] = {s->take_pos, s->send_pos};
  const double lim[2] = {0.49 * s->side_last, 0.49 * s->side_send};
  s->moved_ok = moved_under(&s->p, ref, lim, 2);
  s->moved_known = 1;
}

/* Whether the store this process took last still holds what its pass
 * needs, without finding the ghosts again: the same cut over the store in
 * the same order, cells no wider than then, and no particle of the whole
 * store moved half a cell along any axis since. It was taken one cell
 * deeper than it needs, in ghosts and in rows: two particles now within k
 * cells' side of each other along every axis (a chain of k supports) were
 * within k + 1 then, so every ghost needed now, and every row, is in it
 * (the argument covered() makes cell by cell, made by distance, at the
 * price of a subtraction a particle). */
static int still_covered(const sph_sim *s, int resort, double side) {
  if (!take_refs_good(s, resort, side)) return 0;
  if (s->moved_known) return s->moved_ok & 1u;
  const double lim = 0.49 * s->side_last; /* half a cell, less a margin */
  return moved_under(&s->p, (const double *const[]){s->take_pos}, &lim, 1) != 0;
}

/* A process's store, kept from its last pass, takes the values a step
 * changed: the fluid's, and the walls' but those it does not need again
 * (wall_not_taken). */
static void take_by_kind(sph_sim *s, const sph_particles *in) {
  sph_particles *q = &s->sub->p;
  const unsigned long long arrays = s->pass_in & ~s->pass_static;
  const size_t nf = s->n_kind_fluid;
  sph_particles_put(q, s->kind_sub, in, s->kind_whole, nf, arrays, 0);
  sph_particles_put(q, s->kind_sub + nf, in, s->kind_whole + nf, s->n_from - nf,
                    arrays & ~s->wall_not_taken, 0);
}

/* Rank `rank`'s part of the pass: its own particles and its ghosts into
 * sub, in the whole store's order; the pass; its own particles' results
 * back into the whole store, its reductions into t. */
static int rank_pass(sph_sim *s, const sph_particles *in, const sph_decomp_grid *g,
                     const uint64_t *first, int rank, int resort, double hmax, rank_sums *t,
                     sph_error *err) {
  const sph_case *c = s->c;
  sph_particles *p = &s->p;
  sph_sim *r = s->sub;
  if (s->self >= 0 && s->self == s->fail_rank && s->fig_passes + 1 == s->fail_pass)
    return sph_error_set(err, "SPH_TEST_FAIL_PASS: pass %ld fails (a test)", s->fail_pass);
  const int rows = sph_sim_ranks_row_depth(s, s->depth);
  const unsigned kinds = sph_sim_ranks_row_kinds(s);
  int same = s->self >= 0 && still_covered(s, resort, g->side);
  if (same)
    memcpy(s->mark, s->mark_last, p->n);
  else if (s->self < 0 || may_cover(s, resort)) { /* (else the deeper halo alone, below) */
    if (sph_decomp_halo(g, p, s->keys, first, s->ranks, rank, s->depth, rows, kinds, s->mark, err) <
        0)
      return -1;
    same = s->self >= 0 && covered(s, resort);
  }
  if (s->self >= 0 && !same) {
    /* one cell more than it needs, of ghosts and of rows: a particle then
     * crosses a whole cell before the store must be taken anew */
    if (sph_decomp_halo(g, p, s->keys, first, s->ranks, rank, s->depth + 1, rows + 1, kinds,
                        s->mark, err) < 0)
      return -1;
    memcpy(s->mark_last, s->mark, p->n);
    s->n_mark_last = p->n, s->order_last = p->order, s->side_last = g->side;
    for (int a = 0; a < SPH_DIM; a++)
      memcpy(s->take_pos + (size_t)a * p->n, p->pos[a], p->n * sizeof *s->take_pos);
  }
  size_t k = 0, own = 0;
  if (same) /* the last pass's particles: its indices hold */
    k = s->n_from, own = s->n_own;
  else {
    for (size_t i = 0; i < p->n; i++)
      if (s->mark[i]) {
        s->no_row[p->id[i]] = s->mark[i] == 3;
        if (s->mark[i] == 1 && p->kind[i] == SPH_KIND_FLUID)
          s->own_sub[own] = k, s->own_whole[own++] = i;
        s->from[k++] = i;
      }
    s->n_own_fluid = own;
    for (size_t j = 0; j < k; j++) /* then the walls */
      if (s->mark[s->from[j]] == 1 && p->kind[s->from[j]] != SPH_KIND_FLUID)
        s->own_sub[own] = j, s->own_whole[own++] = s->from[j];
    if (s->self >= 0) { /* all of sub by kind, the fluid first (take_by_kind) */
      size_t m = 0;
      for (int wall = 0; wall < 2; wall++) {
        if (wall) s->n_kind_fluid = m;
        for (size_t j = 0; j < k; j++)
          if ((p->kind[s->from[j]] != SPH_KIND_FLUID) == wall)
            s->kind_sub[m] = j, s->kind_whole[m++] = s->from[j];
      }
    }
    if (s->staged) {
      memset(s->to_sub, 0xff, p->n * sizeof *s->to_sub); /* SIZE_MAX: not in sub */
      for (size_t j = 0; j < k; j++)
        s->to_sub[s->from[j]] = j;
    }
  }
  s->n_from = k;
  if (s->staged) { /* the walls sent, in sub; the walls sub does not make in the second stage:
                     those and its ghosts (their own processes' values; their rows stay, for the
                     Riemann rows that meet a wall, forces.c) */
    if (k > s->cap_made_first) {
      unsigned char *mf = realloc(s->made_first, k);
      if (!mf) return sph_error_set(err, "out of memory for the walls' stages");
      s->made_first = mf, s->cap_made_first = k;
    }
    for (size_t j = 0; j < k; j++)
      s->made_first[j] = s->mark[s->from[j]] >= 2;
    for (size_t m = 0; m < s->n_send; m++) {
      s->send_sub[m] = s->to_sub[s->send_whole[m]];
      s->made_first[s->send_sub[m]] = 1;
    }
  }
  if (same && s->wall_not_taken) /* (take_by_kind) */
    take_by_kind(s, in);
  else if (sph_particles_gather(&r->p, in, s->from, k,
                                same ? s->pass_in & ~s->pass_static : s->pass_in, err))
    return -1;
  for (size_t j = 0; j < k; j++)
    if (s->mark[s->from[j]] >= 2) r->p.flags[j] |= SPH_FLAG_GHOST;
  r->nl.no_row = s->no_row, r->nl.no_row_n = p->n;
  r->t = s->t, r->t_walls = s->t_walls, r->t_saved = s->t_saved;
  r->steps = s->steps, r->last_dt = s->last_dt, r->first_step = s->first_step;
  r->resort = resort;
  if (same)
    r->nl.order = r->p.order; /* the list's rows name the same particles */
  else
    r->nl.valid = 0;
  r->fp.loop = s->fp.loop;
  r->hmax_all = c->variable_h ? hmax : 0.0;
  if (sph_sim_pass(r, err)) return -1;
  if (r->p.n != k)
    return sph_error_set(err, "ranks: rank %d's store holds %zu particles after its pass, not %zu",
                         rank, r->p.n, k);
  if (r->own_cs_max > t->cs_max) t->cs_max = r->own_cs_max;
  if (r->own_cfl_max > t->cfl_max) t->cfl_max = r->own_cfl_max;
  if (s->fp.ledger) sph_ledger_sums_merge(&t->ledger, &r->own_ledger);
  for (size_t j = 0; j < k; j++)
    if (r->p.id[j] != p->id[s->from[j]])
      return sph_error_set(err, "ranks: rank %d's pass reordered its store", rank);
  /* its own particles back (a ghost's own rank writes it), array by array */
  const size_t nf = s->n_own_fluid;
  s->changed[0] |=
      sph_particles_put(p, s->own_whole, &r->p, s->own_sub, nf, s->pass_out[0], s->self >= 0);
  s->changed[1] |= sph_particles_put(p, s->own_whole + nf, &r->p, s->own_sub + nf, own - nf,
                                     s->pass_out[1], s->self >= 0);
  for (size_t q = 0; q < own; q++)
    t->surface += (p->flags[s->own_whole[q]] & SPH_FLAG_FREE_SURFACE) != 0;
  s->n_own = own;
  s->fig_passes++;
  s->fig_own += (double)own;
  s->fig_ghosts += (double)(k - own);
  return 0;
}

/* Each particle's process at the cut, and the store's indices by process
 * (each process's fluid, then its walls, each in storage order: the order
 * it sends them in). */
static void own_by_process(sph_sim *s, const uint64_t *first) {
  const sph_particles *p = &s->p;
  size_t at[SPH_PROCS_MAX], wall[SPH_PROCS_MAX], sum = 0;
  memset(s->owned, 0, sizeof s->owned);
  memset(s->owned_fluid, 0, sizeof s->owned_fluid);
  for (size_t i = 0; i < p->n; i++) {
    s->owner[i] = (unsigned char)sph_decomp_owner(first, s->ranks, s->keys[i]);
    s->owned[s->owner[i]]++;
    s->owned_fluid[s->owner[i]] += p->kind[i] == SPH_KIND_FLUID;
  }
  for (int q = 0; q < s->ranks; q++)
    at[q] = sum, wall[q] = sum + s->owned_fluid[q], sum += s->owned[q];
  for (size_t i = 0; i < p->n; i++)
    s->by_owner[p->kind[i] == SPH_KIND_FLUID ? at[s->owner[i]]++ : wall[s->owner[i]]++] = i;
}

/* Room for the records of the exchange, at the size of every array's
 * record (the arrays a pass changed are known only after it), reserved
 * before the pass so that its failure is told with the pass's. */
static int reserve_records(sph_sim *s, sph_error *err) {
  const sph_particles *p = &s->p;
  const size_t *counts = s->owned;
  const size_t rec = sph_particles_record_size(p), need = (p->n + counts[s->self]) * rec;
  if (!sph_procs_records_fit(counts, rec))
    return sph_error_set(err, "the processes' exchange: more than %d particles' records", INT_MAX);
  if (need <= s->cap_records) return 0;
  unsigned char *b = realloc(s->records, need);
  if (!b) return sph_error_set(err, "out of memory for the processes' exchange (%zu bytes)", need);
  s->records = b, s->cap_records = need;
  return 0;
}

/* The reports combined, the same bits on every process: the step rule's
 * max, the count, and the ledger's exact sums merged in rank order (exact:
 * any order gives the same bits). */
static void combine(sph_sim *s, const pass_report *all, rank_sums *t) {
  memset(t, 0, sizeof *t);
  sph_ledger_sums_init(&t->ledger);
  for (int q = 0; q < s->ranks; q++) {
    if (all[q].sums.cs_max > t->cs_max) t->cs_max = all[q].sums.cs_max;
    if (all[q].sums.cfl_max > t->cfl_max) t->cfl_max = all[q].sums.cfl_max;
    t->surface += all[q].sums.surface;
    if (s->fp.ledger) sph_ledger_sums_merge(&t->ledger, &all[q].sums.ledger);
  }
  if (s->fp.ledger &&
      s->rank_order_sums == 1) /* test hook: each rank's sums rounded, then added in rank order */
    for (int k = 0; k < SPH_LEDGER_SUMS; k++) {
      double sum = 0.0;
      for (int q = 0; q < s->ranks; q++)
        sum += sph_xsum_round(&all[q].sums.ledger.s[k]);
      sph_xsum_init(&t->ledger.s[k]);
      sph_xsum_add(&t->ledger.s[k], sum);
    }
}

/* ---- the Adami walls in stages (staged) ---- */

/* An Adami wall's values after its row, as its own process sends them. */
typedef struct wall_value {
  int64_t at; /* its index in the store */
  double p, rho, gv[SPH_DIM];
} wall_value;

/* Whether the walls chosen to send still cover what the other processes
 * read: the same cut and store order, cells no wider, and no particle
 * moved half a cell along any axis since (as still_covered: a wall within
 * a support of another process's fluid now was within two cells then). */
static int send_still_good(const sph_sim *s, double side) {
  if (!send_refs_good(s, side)) return 0;
  if (s->moved_known) return (s->moved_ok >> 1) & 1u;
  const double lim = 0.49 * s->side_send;
  return moved_under(&s->p, (const double *const[]){s->send_pos}, &lim, 1) != 0;
}

/* The walls this process sends in each pass's first stage: its own Adami
 * walls within two cells of another process's own particles (each such
 * process's halo, sph_decomp_halo), chosen anew when send_still_good says
 * so (at the same passes on every process: the same store and history);
 * the processes then tell each other their counts, in one collective step,
 * after making room for the exchange. 0, or -1 with err on every process. */
static int choose_send(sph_sim *s, const sph_decomp_grid *g, const uint64_t *first,
                       sph_error *err) {
  sph_particles *p = &s->p;
  const size_t n = p->n;
  if (send_still_good(s, g->side)) return 0;
  int64_t mine = 0, all[SPH_PROCS_MAX];
  unsigned char *pick = calloc(n ? n : 1, 1);
  const size_t room = 2 * (n ? n : 1) * sizeof(wall_value);
  if (room > s->cap_wall_buf) {
    void *b = realloc(s->wall_buf, room);
    if (b) s->wall_buf = b, s->cap_wall_buf = room;
  }
  if (!pick || room > s->cap_wall_buf)
    mine = -1, sph_error_set(err, "out of memory for the walls' stages");
  for (int q = 0; q < s->ranks && mine >= 0; q++) {
    if (q == s->self) continue;
    if (sph_decomp_halo(g, p, s->keys, first, s->ranks, q, 2, 0, 0u, s->mark, err) < 0) {
      mine = -1;
      break;
    }
    for (size_t i = 0; i < n; i++)
      if (s->mark[i] >= 2 && s->owner[i] == s->self && p->kind[i] == SPH_KIND_WALL &&
          (p->flags[i] & SPH_FLAG_ADAMI))
        pick[i] = 1;
  }
  size_t m = 0;
  if (mine >= 0) {
    for (size_t i = 0; i < n; i++)
      if (pick[i]) s->send_whole[m++] = i;
    mine = (int64_t)m;
  }
  free(pick);
  sph_procs_gather(&mine, sizeof mine, all);
  for (int q = 0; q < s->ranks; q++)
    if (all[q] < 0) {
      s->n_send_pos = 0;
      return sph_procs_failed(q, err);
    }
  s->n_send = m, s->send_total = 0;
  for (int q = 0; q < s->ranks; q++)
    s->send_counts[q] = (size_t)all[q], s->send_total += s->send_counts[q];
  for (int a = 0; a < SPH_DIM; a++)
    memcpy(s->send_pos + (size_t)a * n, p->pos[a], n * sizeof *s->send_pos);
  s->n_send_pos = n, s->order_send = p->order, s->cut_send = s->cuts, s->side_send = g->side;
  return 0;
}

/* The rows of a process's rank store that read a ghost wall (late 2; the
 * others 1): its own fluid particles in a ghost wall's row (the list is
 * symmetric; a ghost wall within a support of an own particle has its row:
 * sph_sim_ranks_row_depth), found again when the list was built again. */
static int late_rows(sph_sim *s, sph_sim *r, sph_error *err) {
  const sph_particles *q = &r->p;
  if (s->late && r->nl.builds == s->late_builds && s->late_n == q->n) return 0;
  if (q->n > s->cap_late) {
    unsigned char *l = realloc(s->late, q->n);
    if (!l) return sph_error_set(err, "out of memory for the late rows");
    s->late = l, s->cap_late = q->n;
  }
  memset(s->late, 1, q->n);
  for (size_t j = 0; j < q->n; j++) {
    if (q->kind[j] != SPH_KIND_WALL || !(q->flags[j] & SPH_FLAG_GHOST)) continue;
    size_t cnt;
    const uint32_t *row = sph_nlist_row(&r->nl, j, &cnt);
    for (size_t k = 0; k < cnt; k++)
      if (q->kind[row[k]] == SPH_KIND_FLUID && !(q->flags[row[k]] & SPH_FLAG_GHOST))
        s->late[row[k]] = 2;
  }
  s->late_builds = r->nl.builds, s->late_n = q->n;
  return 0;
}

/* The second half of the walls' stages: the wait for the other processes'
 * values, and (after a pass that has not failed) those values in this
 * process's ghost walls, with their packed copies made again where the
 * pass's preparation had made them (repack). Once a pass. */
static void stage_finish(sph_sim *s, int repack) {
  sph_sim *r = s->sub;
  sph_particles *q = &r->p;
  if (s->stage_waited) return;
  sph_procs_gather_records_wait();
  s->stage_waited = 1;
  if (s->stage_failed) return;
  const wall_value *every = s->wall_buf;
  size_t at = 0;
  for (int k = 0; k < s->ranks; k++) {
    if (k != s->self)
      for (size_t m = at; m < at + s->send_counts[k]; m++) {
        const wall_value *v = &every[m];
        const size_t j = s->to_sub[v->at];
        if (j == SIZE_MAX) continue; /* not in this process's store */
        q->p[j] = v->p, q->rho[j] = v->rho;
        for (int d = 0; d < SPH_DIM; d++)
          r->work.gv[d][j] = v->gv[d];
        if (repack) sph_force_work_repack(q, &r->fp, &r->work, j);
      }
    at += s->send_counts[k];
  }
}

static void stage_late(void *ctx) { stage_finish(ctx, 1); }
static void stage_progress(void *ctx) {
  (void)ctx;
  sph_procs_gather_records_progress();
}

/* A process's rank store's Adami walls (sim.c's adami_stages), in two
 * stages around one collective step: the walls other processes read
 * (send_sub) first, their values sent without waiting; the rest of its
 * own walls while they travel (made_first skips those and its ghost walls).
 * Where nothing before the interaction loop reads a ghost wall (no density
 * diffusion: the pre-passes that read a neighbour's row value are not
 * staged), the loop makes the rows that read no ghost wall first and only
 * then waits and gives the ghost walls the other processes' values
 * (late_rows, stage_late); else it waits now. A ghost wall then holds the
 * bits its own process made from its whole row, which a row of its own
 * here would give (tests/test_mpi). A pass that failed before (rc) still
 * joins the step (sph_sim_pass ends it: adami_stages_end, stages_end).
 * Returns rc, or -1. */
static int stage_walls(sph_sim *r, void *ctx, int rc, sph_error *err) {
  sph_sim *s = ctx;
  sph_particles *q = &r->p;
  wall_value *every = s->wall_buf, *mine = every + s->send_total;
  sph_adami_params ap;
  if (rc == 0 && sph_force_work_reserve(&r->work, q->n, err)) rc = -1;
  if (rc == 0) {
    sph_sim_adami_params(r, &ap);
    sph_wall_adami_list(q, &r->nl, &ap, r->work.gv, s->send_sub, s->n_send);
    for (size_t m = 0; m < s->n_send; m++) {
      const size_t j = s->send_sub[m];
      wall_value *v = &mine[m];
      v->at = (int64_t)s->send_whole[m], v->p = q->p[j], v->rho = q->rho[j];
      for (int d = 0; d < SPH_DIM; d++)
        v->gv[d] = r->work.gv[d][j];
    }
  }
  sph_procs_gather_records_start(mine, s->send_counts, sizeof *mine, every);
  s->stage_joined = 1, s->stage_waited = 0;
  if (rc == 0) {
    ap.skip = s->made_first;
    sph_wall_adami(q, &r->nl, &ap, r->work.gv);
  }
  const int late = r->fp.diffusion == SPH_DIFFUSION_NONE; /* (no pre-pass reads the walls) */
  if (rc == 0 && late && late_rows(s, r, err)) rc = -1;
  s->stage_failed = rc != 0;
  if (rc == 0 && late)
    r->work.late = s->late, r->work.late_hook = stage_late, r->work.late_progress = stage_progress,
    r->work.late_ctx = s;
  else
    stage_finish(s, 0);
  return rc;
}

static void stages_end(sph_sim *r, void *ctx) {
  stage_finish(ctx, 0); /* (after a pass that made its late rows: nothing left) */
  r->work.late = NULL, r->work.late_hook = NULL, r->work.late_progress = NULL;
}

/* Every process's own particles of one kind (0: the fluid, 1: the walls)
 * into every process's store, in one collective step: of the arrays in
 * `arrays`, a block of each array's values in turn (by_owner's order), in
 * buf; returns the bytes of buf it took. */
static size_t share_kind(sph_sim *s, int kind, unsigned long long arrays, unsigned char *buf) {
  sph_particles *p = &s->p;
  const size_t rec = sph_particles_record_size_of(p, arrays);
  size_t counts[SPH_PROCS_MAX], first[SPH_PROCS_MAX], at[SPH_PROCS_MAX], sum = 0, whole = 0;
  for (int q = 0; q < s->ranks; q++) {
    counts[q] = kind ? s->owned[q] - s->owned_fluid[q] : s->owned_fluid[q];
    first[q] = whole + (kind ? s->owned_fluid[q] : 0); /* in by_owner */
    at[q] = sum, sum += counts[q], whole += s->owned[q];
  }
  if (!rec) return 0;
  unsigned char *own = buf + sum * rec;
  sph_particles_pack_block(p, s->by_owner + first[s->self], counts[s->self], arrays, own);
  sph_procs_gather_records(own, counts, rec, buf);
  s->fig_bytes += (double)(counts[s->self] * rec) * (double)(s->ranks - 1); /* to each other */
  for (int q = 0; q < s->ranks; q++)
    if (q != s->self)
      sph_particles_unpack_block(p, s->by_owner + first[q], counts[q], arrays, buf + rec * at[q]);
  return (sum + counts[s->self]) * rec;
}

/* This process's rank's pass, then collective steps (procs.h): every
 * process's report (failure, the arrays changed, the reductions) to every
 * other, and each particle's record, as its own process left it, into
 * every process's store: the arrays some process's pass changed in a
 * particle of its kind (the fluid's rates, the walls' pressures), the
 * others being the same on every process before and after. Every process
 * holds the same store in the same order, so a rank's particles are sent
 * in storage order, kind by kind, and placed by their owner alone. */
static int process_pass(sph_sim *s, const sph_decomp_grid *g, const uint64_t *first, int resort,
                        double hmax, rank_sums *t, sph_error *err) {
  sph_particles *p = &s->p;
  pass_report mine;
  memset(&mine, 0, sizeof mine);
  sph_ledger_sums_init(&mine.sums.ledger);
  if (s->staged) moved_both(s, resort, g->side);
  if (s->staged && choose_send(s, g, first, err)) return -1;
  s->stage_joined = 0;
  const double t0 = sph_seconds();
  mine.failed =
      reserve_records(s, err) || rank_pass(s, p, g, first, s->self, resort, hmax, &mine.sums, err);
  if (s->self == s->slow_rank && s->slow_factor > 0.0) { /* (the test hook) */
    const double nap = s->slow_factor * (sph_seconds() - t0);
    const struct timespec ts = {(time_t)nap, (long)(1e9 * (nap - floor(nap)))};
    nanosleep(&ts, NULL);
  }
  s->moved_known = 0;                  /* (the next step moves the particles) */
  if (s->staged && !s->stage_joined) { /* it stopped before its walls: the others wait there */
    wall_value *every = s->wall_buf; /* (what it sends is not read: its report tells the failure) */
    sph_procs_gather_records_start(every + s->send_total, s->send_counts, sizeof *every, every);
    sph_procs_gather_records_wait();
  }
  mine.arrays[0] = s->changed[0], mine.arrays[1] = s->changed[1];
  s->changed[0] = s->changed[1] = 0;
  /* its work since its last report: the wall time less its waits (balance) */
  const double now = sph_seconds();
  mine.work =
      s->work_clock > 0.0 ? now - s->work_clock - (sph_procs_waited() - s->work_waited) : -1.0;
  pass_report *all = s->reports;
  sph_procs_gather(&mine, sizeof mine, all);
  s->work_clock = sph_seconds(), s->work_waited = sph_procs_waited();
  for (int q = 0; q < s->ranks; q++)
    if (all[q].failed) return sph_procs_failed(q, err);
  int timed = 1;
  for (int q = 0; q < s->ranks; q++)
    timed = timed && all[q].work >= 0.0;
  if (timed) {
    for (int q = 0; q < s->ranks; q++)
      s->work_sum[q] += all[q].work;
    s->work_passes++;
  }
  combine(s, all, t);
  unsigned long long arrays[2] = {0, 0};
  for (int q = 0; q < s->ranks; q++)
    arrays[0] |= all[q].arrays[0], arrays[1] |= all[q].arrays[1];
  /* (the buffer holds every particle's whole record and this process's
   * again: reserve_records) */
  const size_t used = share_kind(s, 0, arrays[0], s->records);
  if (s->lazy_walls) /* (kept to their own processes until sph_sim_catch_up) */
    s->walls_behind |= arrays[1];
  else
    share_kind(s, 1, arrays[1], s->records + used);
  return 0;
}

/* Every process's own walls' values into every process's store, where
 * the passes left them with their own processes (lazy_walls): the arrays
 * those passes changed, and the leap-frog's half-step density, which each
 * process's steps copied from those values (integrate.c: an Adami wall's
 * is its density at the step's start) and are right only in its own
 * walls. One collective step, over the cut of those passes. */
static void walls_catch_up(sph_sim *s) {
  if (!s->walls_behind) return;
  /* (what reorders the store, a sort or fluid taken out, comes here first: the cut is over
   * this order, its owners those of the passes) */
  share_kind(s, 1, s->walls_behind | sph_particles_array_bits("rhoh"), s->records);
  s->walls_behind = 0;
}

void sph_sim_catch_up(sph_sim *s) {
  if (s->self >= 0 && s->ranks > 1 && !s->rank_store) walls_catch_up(s);
}

const size_t *sph_sim_ranks_own_walls(const sph_sim *s, size_t *n) {
  /* (the whole store is the state: its ranges; a cut over another order names other
   * particles, and the walls are never behind then: walls_catch_up) */
  if (!s->walls_behind || s->n_cut != s->p.n || s->order_cut != s->p.order) return NULL;
  size_t at = 0;
  for (int q = 0; q < s->self; q++)
    at += s->owned[q];
  *n = s->owned[s->self] - s->owned_fluid[s->self];
  return s->by_owner + at + s->owned_fluid[s->self];
}

/* The cut by measured work. A process's particles cost what the cut's
 * weights say only on a core as fast as the others': a core shared with
 * another job, or slowed by the machine's other tenants, takes longer
 * (measured here: one of two cores 1.48 times slower for minutes), and the
 * others wait for it at every pass. At each cut, when the processes' work
 * since the last one (their wall time less their waits, gathered with the
 * passes' reports: the same numbers on every process) differs by more than
 * SPH_RANKS_BALANCE_SLACK, each process's share of the weights is scaled
 * by the mean work over its own (by at most a factor of 2 either way): the
 * step that evens out a work proportional to the share, and short of it
 * when a part of the work (the whole store's) is the same on every
 * process, so that it does not overshoot; no share falls below half of an
 * even one (a process too slow for any share, its work mostly the whole
 * store's, would otherwise be left none). Every process computes the same
 * shares from the same numbers, and the cut moves no bit of the results
 * (each rank's own rates are the whole store's, whatever the cut). */
#define SPH_RANKS_BALANCE_SLACK 1.03
#define SPH_RANKS_BALANCE_PASSES 8 /* the least passes measured for a move */

static void balance(sph_sim *s) {
  const int n = s->ranks;
  double mean = 0.0, most = 0.0;
  for (int q = 0; q < n; q++) {
    mean += s->work_sum[q] / n;
    if (s->work_sum[q] > most) most = s->work_sum[q];
  }
  if (s->work_passes >= SPH_RANKS_BALANCE_PASSES && mean > 0.0 &&
      most > SPH_RANKS_BALANCE_SLACK * mean) {
    double total = 0.0;
    for (int q = 0; q < n; q++) {
      const double f = s->work_sum[q] > 0.5 * mean ? mean / s->work_sum[q] : 2.0;
      s->share[q] *= f > 0.5 ? f : 0.5;
      total += s->share[q];
    }
    for (int q = 0; q < n; q++)
      s->share[q] /= total;
    sph_shares_at_least_half(s->share, n); /* (as the threads' learned split: core/parallel.h) */
    s->balanced++;
  }
  for (int q = 0; q < n; q++)
    s->work_sum[q] = 0.0;
  s->work_passes = 0;
}

int sph_sim_ranks_pass(sph_sim *s, double hmax, sph_error *err) {
  const sph_case *c = s->c;
  sph_particles *p = &s->p;
  /* the whole store sorted when its own pass would sort it */
  const int resort = s->resort || s->skin == 0.0;
  s->resort = 0;
  if (resort) walls_catch_up(s); /* (by the cut over this order, before the sort moves them) */
  if (resort && sph_sim_sort(s, err)) return -1;
  if (reserve(s, p->n, err)) return -1;
  const double reach = SPH_CUBIC_SUPPORT * hmax;
  /* a periodic axis: whole cells over the period (a last, narrower strip
   * joins cell 0); a period shorter than the ghosts' reach puts its every
   * cell in every rank's halo */
  const long cells =
      c->periodic
          ? (long)floor((c->periodic_range[1] - c->periodic_range[0]) / (SPH_RANKS_CELL * reach))
          : 0;
  const sph_decomp_grid g = {SPH_RANKS_CELL * reach, c->periodic ? 1 + c->periodic_axis : 0,
                             c->periodic ? c->periodic_range[0] : 0.0, cells > 0 ? cells : 1};
  /* The cut moves no bit (each rank's own rates are the whole store's), so
   * it is made again only when the store was sorted or reordered: between
   * sorts a particle's rank is that of its cell at the last cut, and its
   * ghosts are found from where the particles are now. */
  uint64_t *first = s->first;
  if (resort || s->n_cut != p->n || s->order_cut != p->order) {
    if (sph_decomp_block_counts(&g, p, SPH_KIND_FLUID, s->weight, s->fluid_near, err)) return -1;
    for (size_t i = 0; i < p->n; i++)
      s->weight[i] = cut_weight(p->kind[i], s->weight[i], s->fluid_near[i]);
    if (s->balance) balance(s);
    if (sph_decomp_keys(&g, p, s->keys, err) ||
        sph_decomp_cut_shares(s->keys, s->weight, p->n, s->ranks, s->balance ? s->share : NULL,
                              first, err))
      return -1;
    s->n_cut = p->n, s->order_cut = p->order, s->cuts++;
    s->depth = ghost_depth(s, p, g.side);
    if (s->self >= 0) own_by_process(s, first); /* for the exchange (process_pass) */
  }
  rank_sums t;
  memset(&t, 0, sizeof t);
  sph_ledger_sums_init(&t.ledger);
  if (s->self < 0) { /* every rank, one after the other, each from the state before any */
    memset(s->mark, 1, p->n);
    if (sph_particles_take(&s->before, p, s->mark, err)) return -1;
    for (int rank = 0; rank < s->ranks; rank++)
      if (rank_pass(s, &s->before, &g, first, rank, resort, hmax, &t, err)) return -1;
  } else if (process_pass(s, &g, first, resort, hmax, &t, err)) /* this process's rank */
    return -1;
  s->work.cs_sigma_max = t.cs_max;
  s->cfl_max = t.cfl_max;
  s->dt_paper_b = sph_dt_paper_b(&s->work, c->h, c->dt_factor);
  s->n_surface = s->detect ? t.surface : 0;
  if (s->fp.ledger) sph_ledger_finish(&s->ledger, &t.ledger, c->gravity);
  s->step_pass = s->steps;
  /* the state the pass saw, as the whole store's pass packs it: the
   * leap-frog's last good state (sim.c); under mpirun each process's rank
   * store holds it for its own particles, gathered only if a step blows up
   * (room reserved now: that gather cannot fail on one process alone) */
  if (sph_force_work_reserve(&s->work, p->n, err)) return -1;
  s->hot_in_sub = s->self >= 0;
  if (s->hot_in_sub) return 0;
  for (size_t i = 0; i < p->n; i++) {
    sph_force_hot *h = &s->work.hot[i];
    h->x = p->x[i], h->y = p->y[i], h->vx = p->vx[i], h->vy = p->vy[i], h->rho = p->rho[i];
    SPH_IF3(h->z = p->z[i], h->vz = p->vz[i];)
  }
  return 0;
}

/* The state record of the leap-frog's last good state: the fields of a
 * packed copy (sph_force_hot) that the pass read from the store. */
enum { STATE_DOUBLES = 2 * SPH_DIM + 1 };

static void state_pack(const sph_force_hot *h, double *d) {
  d[0] = h->x, d[1] = h->y, d[2] = h->vx, d[3] = h->vy, d[4] = h->rho;
  SPH_IF3(d[5] = h->z, d[6] = h->vz;)
}

static void state_unpack(const double *d, sph_force_hot *h) {
  h->x = d[0], h->y = d[1], h->vx = d[2], h->vy = d[3], h->rho = d[4];
  SPH_IF3(h->z = d[5], h->vz = d[6];)
}

void sph_sim_ranks_saved_state(sph_sim *s) {
  walls_catch_up(s); /* (the walls' pressures of the last good state: the last pass's) */
  if (!s->hot_in_sub) return;
  const sph_particles *p = &s->p;
  const sph_force_hot *hot = s->sub->work.hot;
  const size_t rec = STATE_DOUBLES * sizeof(double);
  /* the exchange's buffer holds every particle's whole record and this
   * process's again (reserve_records): more than these; this process's
   * own particles in by_owner's order (own_sub's: the fluid first) */
  unsigned char *every = s->records, *own = s->records + p->n * rec;
  for (size_t q = 0; q < s->n_own; q++) {
    double d[STATE_DOUBLES];
    state_pack(&hot[s->own_sub[q]], d);
    memcpy(own + q * rec, d, rec);
  }
  sph_procs_gather_records(own, s->owned, rec, every);
  for (size_t k = 0; k < p->n; k++) { /* every process's in turn */
    double d[STATE_DOUBLES];
    memcpy(d, every + rec * k, rec);
    state_unpack(d, &s->work.hot[s->by_owner[k]]);
  }
  s->hot_in_sub = 0;
}

void sph_sim_set_balance(sph_sim *s, int measured) {
  if (s->self < 0) return;
  s->balance = measured != 0;
  for (int q = 0; q < s->ranks; q++)
    s->share[q] = 1.0 / s->ranks;
}

int sph_sim_procs_figures(const sph_sim *s, sph_procs_figures *f) {
  memset(f, 0, sizeof *f);
  if (s->self < 0) return 0;
  const double mine[5] = {(double)s->fig_passes, s->fig_own, s->fig_ghosts, s->fig_bytes,
                          sph_procs_waited() - s->fig_waited0};
  double all[5 * SPH_PROCS_MAX];
  sph_procs_gather(mine, sizeof mine, all);
  f->processes = s->ranks;
  f->crowded = sph_procs_crowded();
  f->balance = s->balance;
  f->balanced = s->balanced;
  f->share_min = f->share_max = s->share[0];
  for (int q = 1; q < s->ranks; q++) {
    if (s->share[q] < f->share_min) f->share_min = s->share[q];
    if (s->share[q] > f->share_max) f->share_max = s->share[q];
  }
  f->waited_min = f->waited_max = all[4];
  for (int q = 0; q < s->ranks; q++) {
    const double *a = all + 5 * q;
    if (q == 0) f->passes = (long)a[0];
    f->own += a[1], f->ghosts += a[2], f->bytes += a[3];
    if (a[4] < f->waited_min) f->waited_min = a[4];
    if (a[4] > f->waited_max) f->waited_max = a[4];
  }
  return 0;
}
