/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * sim.c - the step: interaction passes, integrator stages, wall motion,
 * filters, the blow-up check, and what the state reports (diagnostics,
 * snapshots). Set-up is in setup.c, restart in restart.c, the energy
 * ledger in ledger.c.
 *
 * One step is paper B's predictor-corrector (integrate.h) with an
 * interaction pass at the mid-step state and one at the new state. The
 * passes walk a neighbour list (grid.h) that is kept, with a skin, for as
 * long as it provably holds every pair within the support (see
 * neighbours()), so the grid is not rebuilt at every pass; every pair
 * inside the support is evaluated at every pass, exactly as with a fresh
 * grid. The time step comes from the first pass (the state
 * at t^n). After the step every particle is checked: finite state, density
 * within density_limit of rho0, inside the domain. The first offender in id
 * order is reported, so the message is the same for any thread count.
 */
#include "config.h"

#include "core/check.h"
#include "core/exact_sum.h"
#include "core/parallel.h"

#include "solver/sim_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "io/snapshot.h"
#include "neighbours/grid.h"
#include "physics/eos.h"
#include "physics/filter.h"
#include "physics/freesurface.h"
#include "physics/kernel.h"
#include "physics/shifting.h"
#include "solver/diag_sums.h"
#include "solver/forces.h"
#include "solver/integrate.h"
#include "solver/procs.h"
#include "solver/surface_tension.h"
#include "walls/adami.h"
#include "walls/boundary.h"
#include "walls/dbc.h"
#include "walls/wall_velocity.h"

/* The largest smoothing length: k h with h* = k h on the free surface. */
static double h_max(const sph_sim *s) {
  if (!s->c->variable_h) return s->fp.var_h ? s->c->fs_h_factor * s->c->h : s->c->h;
  if (s->hmax_all > 0.0) return s->hmax_all; /* a rank's store: the whole store's (ranks.c) */
  double h = 0.0;
  for (size_t i = 0; i < s->p.n; i++)
    if (s->p.h[i] > h) h = s->p.h[i];
  return h;
}

/* Paper B §2.1: h = h0 (rho0/rho)^(1/d) at every particle (d = SPH_DIM). */
static void update_h(sph_sim *s) {
  if (!s->c->variable_h) return;
  const double h0 = s->c->h, rho0 = s->c->rho0;
  for (size_t i = 0; i < s->p.n; i++)
#if SPH_DIM == 2
    s->p.h[i] = h0 * sqrt(rho0 / s->p.rho[i]);
#else
    s->p.h[i] = h0 * cbrt(rho0 / s->p.rho[i]);
#endif
}

/* Paper A §7: flag the free surface (circles of radius factor * h_i), then
 * with h* = k h give surface particles the smoothing length k h0. Without
 * h* the smoothing lengths are left alone (constant, or paper B's
 * variable h). */
static int free_surface(sph_sim *s, sph_error *err) {
  const sph_case *c = s->c;
  const sph_freesurface_params fp = {
      .radius_factor = c->fs_radius_factor,
      .period = c->periodic ? c->periodic_range[1] - c->periodic_range[0] : 0.0,
      .exact_only = 0,
      .scalar = sph_force_loop_narrow(s->fp.loop), /* (no AVX2 scan either) */
      .paxis = s->fp.paxis};
  const int hstar = c->fs_h_factor > 0.0;
  if (hstar) sph_freesurface_apply_h(&s->p, c->h, 1.0);
  if (sph_freesurface_detect_list(&s->p, &s->nl, &fp, &s->n_surface, err)) return -1;
  if (hstar) sph_freesurface_apply_h(&s->p, c->h, c->fs_h_factor);
  return 0;
}

/* The interaction support: 2 max h, and the Lennard-Jones range if larger. */
static double support(const sph_sim *s) {
  double r = SPH_CUBIC_SUPPORT * h_max(s);
  if (s->fp.repulsive && s->fp.lj_r0 > r) r = s->fp.lj_r0;
  return r * SPH_CELL_MARGIN;
}

/* The cell list of the current positions (periodic along the case's
 * periodic axis), cells fitting the support plus the list's skin. At most ~64 cells
 * per particle: far more than any sane domain needs. */
static int build_grid(sph_sim *s, double cell, sph_error *err) {
  const sph_case *c = s->c;
  const size_t max_cells = 64 * s->p.n + 1024 * 1024;
  return c->periodic
             ? sph_grid_build_periodic(&s->grid, &s->p, cell, c->periodic_axis,
                                       c->periodic_range[0], c->periodic_range[1], max_cells, err)
             : sph_grid_build(&s->grid, &s->p, cell, max_cells, err);
}

/* The cells the store is sorted by: they fit the support, plus the
 * default skin when the case keeps its list (below). */
static double sort_cell(const sph_sim *s) {
  return (support(s) + (s->skin > 0.0 ? SPH_SKIN_DEFAULT * SPH_CUBIC_SUPPORT * s->c->h : 0.0)) *
         SPH_CELL_MARGIN;
}

int sph_sim_sort(sph_sim *s, sph_error *err) { return build_grid(s, sort_cell(s), err); }

/* Steps between sorts of the store when the neighbour list is kept. */
#define SPH_RESORT_EVERY 40

/* The neighbour list of the current state.
 *
 * Without a skin (cases whose passes need a fresh grid or change the
 * store: mirror particles, variable h) the store is
 * sorted by cell and the list rebuilt at every pass.
 *
 * With a skin, a list built earlier is kept while sph_nlist_fresh proves it
 * complete (no particle moved more than skin/2 since); otherwise the
 * particles are binned without reordering the store and the list rebuilt.
 * The store is sorted (for memory locality) only at the end-of-step pass
 * of every SPH_RESORT_EVERY-th step: a function of the step count, not of
 * when lists happened to be rebuilt. Since the rows of a list are in
 * storage order, every sum of a pass then depends only on the state, the
 * storage order and the step count, so a run restarted from any snapshot
 * (which records the storage order) repeats the uninterrupted run bit for
 * bit, whatever the skin. */
static int neighbours(sph_sim *s, sph_error *err) {
  const sph_case *c = s->c;
  const int resort = s->resort;
  s->resort = 0;
  if (s->skin > 0.0 && !resort && sph_nlist_fresh(&s->nl, &s->p)) return 0;
  const double cell = (support(s) + s->skin) * SPH_CELL_MARGIN;
  const double px0 = c->periodic ? c->periodic_range[0] : 0.0;
  const double px1 = c->periodic ? c->periodic_range[1] : 0.0;
  /* Without a skin the cells fit the support. With one, the store is
   * sorted by cells that fit the support plus the default skin, whatever
   * the skin in effect: the storage order (and with it every result) does
   * not depend on the skin, and with the default skin the list's cells are
   * the sort's. A particle then stays in the cell it was sorted by until
   * it crosses a cell edge, so the cells' contents, walked in the grid's
   * order, come out nearly in storage order and the rows' insertion sort
   * (sph_nlist_build) has little to do; with smaller sort cells every row
   * interleaves several cells' runs of indices. */
  if ((s->skin == 0.0 || resort) && sph_sim_sort(s, err)) return -1;
  if (s->skin > 0.0 && sph_grid_bin(&s->grid, &s->p, cell, c->periodic ? 1 + c->periodic_axis : 0,
                                    px0, px1, 64 * s->p.n + 1024 * 1024, err))
    return -1;
  return sph_nlist_build(&s->nl, &s->grid, &s->p, support(s), s->skin, px1 - px0, err);
}

/* The density bounds of dynamic walls (dbc.h). With variable h the
 * particles they changed get the h of their new density, and where that
 * reaches beyond the list's support the list is built again. */
static int dbc_bound(sph_sim *s, sph_error *err) {
  const sph_case *c = s->c;
  const long changed = sph_dbc_bound(&s->p, &s->nl, SPH_CUBIC_SUPPORT * h_max(s), c->rho0,
                                     c->integrator == SPH_INTEGRATOR_LEAPFROG);
  if (!changed || !c->variable_h) return 0;
  update_h(s);
  return SPH_CUBIC_SUPPORT * h_max(s) > s->nl.radius - s->nl.skin ? neighbours(s, err) : 0;
}

/* mDBC wall particles (wall_velocity.h): density from the fluid through
 * their mirror points, pressure from the equation of state. */
static int mdbc_walls(sph_sim *s, sph_error *err) {
  const sph_case *c = s->c;
  sph_particles *p = &s->p;
  double head[SPH_DIM]; /* the density's hydrostatic gradient, rho0 g / c0^2 */
  for (int a = 0; a < SPH_DIM; a++)
    head[a] = c->rho0 * c->gravity[a] / (s->fp.eos.c0 * s->fp.eos.c0);
  s->mdbc_work.narrow = sph_force_loop_narrow(s->fp.loop);
  if (sph_wall_mdbc_density(p, SPH_CUBIC_SUPPORT * h_max(s), s->fp.px0,
                            c->periodic ? s->fp.period : 0.0, s->fp.paxis, c->rho0, head,
                            &s->mdbc_work, err))
    return -1;
  for (size_t i = 0; i < p->n; i++)
    if (p->flags[i] & SPH_FLAG_MDBC) p->p[i] = sph_eos_pressure(&s->fp.eos, p->rho[i]);
  return 0;
}

/* Adami walls (walls/adami.h): pressure and density from the fluid near
 * them, with the hydrostatic term and their walls' accelerations at the
 * time they stand at, and their no-slip velocity into the work's gv for
 * the viscous terms. */
void sph_sim_adami_params(const sph_sim *s, sph_adami_params *ap) {
  const sph_case *c = s->c;
  *ap = (sph_adami_params){.kernel = c->kernel,
                           .h = c->h,
                           .var_h = s->fp.var_h,
                           .eos = s->fp.eos,
                           .walls = s->walls.moving ? &s->walls : NULL,
                           .t = s->t_walls};
  for (int d = 0; d < SPH_DIM; d++)
    ap->g[d] = c->gravity[d];
}

static int adami_walls(sph_sim *s, sph_error *err) {
  if (sph_force_work_reserve(&s->work, s->p.n, err)) return -1;
  sph_adami_params ap;
  sph_sim_adami_params(s, &ap);
  sph_wall_adami(&s->p, &s->nl, &ap, s->work.gv);
  return 0;
}

/* The moving walls at time t (walls.h), which the adami walls' pass reads. */
void sph_sim_move_walls(sph_sim *s, double t) {
  sph_walls_move(&s->walls, &s->p, t);
  s->t_walls = t;
}

/* A rank's store (ranks.c): the pass's reductions over the particles it
 * owns (and their mirror particles), before the mirror particles go: the
 * step rule's max of c + sigma (the interaction loop's over the rows it
 * made: it skips the ghosts, loops.h), paper A's max of c + |v| over the
 * store's particles (no mirror particle: sph_dt_cfl reads the whole store
 * between passes), and the ledger's exact sums. */
static void rank_reductions(sph_sim *s, int diffusion) {
  const sph_particles *p = &s->p;
  double vmax = 0.0;
  if (s->c->dt_rule == SPH_DT_CFL)
    for (size_t i = 0; i < p->n; i++) {
      if ((p->flags[i] & SPH_FLAG_GHOST) || p->kind[i] == SPH_KIND_MIRROR) continue;
      const double v = sph_cfl_speed(p, s->fp.phase_eos, i);
      if (v > vmax) vmax = v;
    }
  s->own_cs_max = s->work.cs_sigma_max;
  s->own_cfl_max = vmax;
  if (!s->fp.ledger) return;
  sph_ledger_sums_init(&s->own_ledger);
  sph_ledger_sums_add(&s->own_ledger, &s->ledger, p, &s->work, s->c->gravity, s->c->xsph != 0.0,
                      diffusion, SPH_FLAG_GHOST);
}

/* Mirror particles, grid build, free-surface flags and one interaction
 * pass on the current state; the mirror particles are gone again when it
 * returns. */
int sph_sim_pass(sph_sim *s, sph_error *err) {
  const sph_case *c = s->c;
  update_h(s);
  if (s->ranks > 1) return sph_sim_ranks_pass(s, h_max(s), err); /* ranks.c */
#if SPH_DIM == 2
  if (s->walls.n_mirror && sph_mirror_add(&s->p, s->walls.mirror, s->walls.n_mirror,
                                          s->walls.mirror_reach, c->rho0, err) < 0)
    return -1;
#else
  if (s->walls.n_mirror && sph_mirror_add_planes(&s->p, s->walls.plane, s->walls.n_plane,
                                                 s->walls.mirror_reach, c->rho0, err) < 0)
    return -1;
#endif
  int rc = neighbours(s, err);
  if (rc == 0 && s->walls.dbc) rc = dbc_bound(s, err);
  if (rc == 0 && s->detect) rc = free_surface(s, err);
  if (rc == 0 && s->walls.mdbc) rc = mdbc_walls(s, err);
  if (s->adami_stages) /* a process's rank store: with the other processes (ranks.c) */
    rc = s->adami_stages(s, s->adami_ctx, rc, err);
  else if (rc == 0 && s->walls.adami)
    rc = adami_walls(s, err);
  s->fp.h_reach = s->fp.var_h ? h_max(s) : 0.0; /* the whole store's (a rank's too) */
  if (rc == 0) rc = sph_forces_evaluate(&s->p, &s->nl, &s->fp, &s->work, err);
  if (s->adami_stages_end) s->adami_stages_end(s, s->adami_ctx);
  s->step_pass = s->steps; /* the state w->hot now holds */
  /* everything that reads the pass's per-particle work arrays, before
   * removing the mirror particles reorders the store under them */
  if (rc == 0) {
    s->dt_paper_b = sph_dt_paper_b(&s->work, c->h, c->dt_factor);
    const int diffusion = c->diffusion != SPH_DIFFUSION_NONE || c->riemann;
    if (s->rank_store) /* a rank's store: its own particles' part (ranks.c) */
      rank_reductions(s, diffusion);
    else if (s->fp.ledger)
      sph_ledger_rates(&s->ledger, &s->p, &s->work, c->gravity, c->xsph != 0.0, diffusion);
  }
  if (s->walls.n_mirror) sph_mirror_remove(&s->p, s->grid.perm, sph_grid_scratch(&s->grid));
  return rc;
}

/* Density re-initialisation (paper B §2.8) on a grid of the new positions;
 * with the leap-frog the half-step density is reset to the filtered one. */
static int apply_filter(sph_sim *s, sph_error *err) {
  const sph_case *c = s->c;
  sph_nlist_invalidate(&s->nl); /* the grid build reorders the store */
  if (build_grid(s, SPH_CUBIC_SUPPORT * h_max(s) * SPH_CELL_MARGIN, err)) return -1;
  sph_filter_params fp;
  sph_filter_params_default(&fp, s->fp.var_h ? 0.0 : c->h);
  fp.kernel = c->kernel;
  if (sph_filter_apply(c->density_filter, &s->p, &s->grid, &fp, s->work.prho2, NULL, err))
    return -1;
  const int floored = s->fp.eos.rho_min > 0.0, leapfrog = c->integrator == SPH_INTEGRATOR_LEAPFROG;
  if (floored || leapfrog)
    for (size_t i = 0; i < s->p.n; i++) {
      /* the floor (eos.h) holds for the filtered density too */
      if (floored && s->p.kind[i] == SPH_KIND_FLUID)
        s->p.rho[i] =
            sph_eos_floor(sph_eos_of(s->fp.phase_eos, sph_particles_phases(&s->p), i), s->p.rho[i]);
      if (leapfrog) s->p.rhoh[i] = s->p.rho[i];
    }
  sph_forces_pressure(&s->p, s->fp.phase_eos);
  return 0;
}

/* Periodic: particles that crossed a side re-enter at the other. */
static void wrap_periodic(sph_sim *s) {
  if (!s->c->periodic) return;
  const double x0 = s->c->periodic_range[0], x1 = s->c->periodic_range[1], L = x1 - x0;
  double *restrict x = s->p.pos[s->c->periodic_axis];
  for (size_t i = 0; i < s->p.n; i++) {
    if (x[i] >= x1)
      x[i] -= L;
    else if (x[i] < x0)
      x[i] += L;
  }
}

/* How the loops over the store split it among threads: by the neighbour
 * list's rows while the list covers the store (parallel.h). */
static const size_t *slices(const sph_sim *s) {
  return s->nl.cost && s->nl.n == s->p.n ? s->nl.cost : NULL;
}

/* Whether the sim is a process's under mpirun (a rank's own store is not:
 * sph_sim_ranks_init sets self, ranks.c). */
static int in_team(const sph_sim *s) { return s->self >= 0 && s->ranks > 1 && !s->rank_store; }

/* Why particle i fails the blow-up check, or NULL. */
static inline const char *bad_particle(const sph_particles *p, size_t i, double lim, double rho0,
                                       const double *d) {
  if (!isfinite(p->x[i]) || !isfinite(p->y[i]) || !isfinite(p->vx[i]) || !isfinite(p->vy[i]) ||
      !isfinite(p->rho[i]) || !isfinite(p->p[i]))
    return "state is not finite (NaN or Inf)";
  if (fabs(p->rho[i] / rho0 - 1.0) > lim) return "density outside the allowed band";
  if (p->kind[i] == SPH_KIND_FLUID &&
      (p->x[i] < d[0] || p->x[i] > d[1] || p->y[i] < d[2] || p->y[i] > d[3]))
    return "particle left the domain";
#if SPH_DIM == 3
  if (!isfinite(p->z[i]) || !isfinite(p->vz[i])) return "state is not finite (NaN or Inf)";
  if (p->kind[i] == SPH_KIND_FLUID && (p->z[i] < d[4] || p->z[i] > d[5]))
    return "particle left the domain";
#endif
  return NULL;
}

/* Whether particle i surely passes the blow-up check, without a division:
 * v - v is 0 for every finite v and NaN otherwise; the density band is
 * narrowed by a relative 1e-9, far more than the rounding of
 * |rho / rho0 - 1| (bad_particle decides every particle this does not
 * pass, so the check names the same particles). */
static inline int surely_good(const sph_particles *p, size_t i, double rlo, double rhi,
                              const double *d) {
  const double x = p->x[i], y = p->y[i], rho = p->rho[i];
  const double z = (x - x) + (y - y) + (p->vx[i] - p->vx[i]) + (p->vy[i] - p->vy[i]) + (rho - rho) +
                   (p->p[i] - p->p[i]);
#if SPH_DIM == 3
  const double zz = p->z[i], vz = p->vz[i];
  if (!((zz - zz) + (vz - vz) == 0.0) || (p->kind[i] == SPH_KIND_FLUID && (zz < d[4] || zz > d[5])))
    return 0;
#endif
  return z == 0.0 && rho > rlo && rho < rhi &&
         (p->kind[i] != SPH_KIND_FLUID || !(x < d[0] || x > d[1] || y < d[2] || y > d[3]));
}

/* Whether particle i fails the blow-up check and comes before `first` in id
 * order: surely_good decides most particles, bad_particle the rest (each
 * phase's band: the arrays by phase, ph NULL for one). */
static inline __attribute__((always_inline)) int
offends_before(const sph_particles *p, size_t i, int64_t first, const uint8_t *ph,
               const double *rlo, const double *rhi, const double *lim, const double *r0,
               const double *d) {
  const int k = ph ? ph[i] : 0;
  return !surely_good(p, i, rlo[k], rhi[k], d) && p->id[i] < first &&
         bad_particle(p, i, lim[k], r0[k], d);
}

/* The blow-up check; the first offender in id order is named (a min
 * reduction over ids, exact in any order, then a serial look-up). Shared
 * (under mpirun, every process making this call at once: each holds the
 * same store, sim_internal.h), each process checks its share of the store
 * and the processes take the least id in one collective step. */
static int check_state(sph_sim *s, int shared, sph_error *err) {
  const sph_particles *p = &s->p;
  /* each phase's band about its own rho0 (two phases: physics.air, whose band is its own) */
  const uint8_t *ph = sph_particles_phases(p);
  double r0[SPH_PHASES_MAX], lim[SPH_PHASES_MAX], rlo[SPH_PHASES_MAX], rhi[SPH_PHASES_MAX];
  for (int k = 0; k < s->fp.phases; k++) {
    r0[k] = s->fp.phase_eos[k].rho0; /* (phase 0's the case's rho0) */
    lim[k] = s->fp.phase_mat[k].density_limit;
    rlo[k] = r0[k] * (1.0 - lim[k]) * (1.0 + 1e-9), rhi[k] = r0[k] * (1.0 + lim[k]) * (1.0 - 1e-9);
  }
  /* with geometry.leaving: remove, a particle outside is taken out after the check */
  static const double everywhere[2 * SPH_DIM] = {-INFINITY, INFINITY, -INFINITY,
                                                 INFINITY SPH_IF3(, -INFINITY, INFINITY)};
  const double *d = s->c->leaving == SPH_LEAVING_REMOVE ? everywhere : s->domain;
  const long n = (long)p->n;
  /* this process's share: a range of the store; where each process's walls' values are its
   * own to hold (ranks.c, sph_sim_ranks_own_walls), the fluid of that range and its own walls */
  size_t from = 0, to = p->n, n_walls = 0;
  if (shared) sph_sim_span(s, &from, &to);
  const size_t *walls = shared ? sph_sim_ranks_own_walls(s, &n_walls) : NULL;
  int64_t first = INT64_MAX;
#pragma omp parallel if (n > SPH_OMP_MIN) reduction(min : first)
  {
    size_t lo, hi;
    sph_slice(shared ? NULL : slices(s), to - from, &lo, &hi);
    for (size_t i = from + lo; i < from + hi; i++)
      if (!(walls && p->kind[i] != SPH_KIND_FLUID) &&
          offends_before(p, i, first, ph, rlo, rhi, lim, r0, d))
        first = p->id[i];
    sph_slice(NULL, n_walls, &lo, &hi);
    for (size_t k = lo; k < hi; k++)
      if (offends_before(p, walls[k], first, ph, rlo, rhi, lim, r0, d)) first = p->id[walls[k]];
  }
  /* shared: the process whose share holds the first offender makes the message, which the
   * others take from it (the distributed store's way: no process need hold the particle) */
  int maker = -1;
  if (shared) {
    int64_t all[SPH_PROCS_MAX];
    sph_procs_gather(&first, sizeof first, all);
    for (int q = 0; q < s->ranks; q++)
      if (all[q] < first) first = all[q];
    for (int q = 0; q < s->ranks && maker < 0; q++)
      if (all[q] == first) maker = q;
  }
  if (first == INT64_MAX) return 0;
  if (shared && maker != s->self) {
    sph_procs_share_from(err->msg, sizeof err->msg, maker);
    return SPH_BLOWUP;
  }
  long worst = -1;
  for (size_t i = from; i < to && worst < 0; i++)
    if (p->id[i] == first && !(walls && p->kind[i] != SPH_KIND_FLUID)) worst = (long)i;
  for (size_t k = 0; k < n_walls && worst < 0; k++)
    if (p->id[walls[k]] == first) worst = (long)walls[k];
  if (worst < 0) { /* (cannot be: the share found it) */
    sph_error_set(err, "blow-up at step %ld, t = %.9g s: particle %lld", s->steps, s->t,
                  (long long)first);
    if (shared) sph_procs_share_from(err->msg, sizeof err->msg, maker);
    return SPH_BLOWUP;
  }
  const size_t i = (size_t)worst;
  const double rho0 = r0[ph ? ph[i] : 0], band = lim[ph ? ph[i] : 0];
  const char *why = bad_particle(p, i, band, rho0, d);
  /* with a fixed step, what the step rule would have allowed (the last
   * pass's state: the one the failed step started from) */
  char hint[256] = "";
  const sph_case *c = s->c;
  if (c->dt_rule == SPH_DT_FIXED && c->dt_fixed > s->dt_paper_b)
    snprintf(hint, sizeof hint,
             "; the fixed time step %.6g s is %.3g times the stable step %.6g s that paper B's "
             "rule (time_step.rule: paper_b, factor %g) gives for that state",
             c->dt_fixed, c->dt_fixed / s->dt_paper_b, s->dt_paper_b, c->dt_factor);
  /* the state and the domain in every component (issue 61, E12) */
  char state[256], box[160];
#if SPH_DIM == 3
  snprintf(state, sizeof state, "x = %.6g, y = %.6g, z = %.6g, vx = %.6g, vy = %.6g, vz = %.6g",
           p->x[i], p->y[i], p->z[i], p->vx[i], p->vy[i], p->vz[i]);
  snprintf(box, sizeof box, "x [%.6g, %.6g] y [%.6g, %.6g] z [%.6g, %.6g]", d[0], d[1], d[2], d[3],
           d[4], d[5]);
#else
  snprintf(state, sizeof state, "x = %.6g, y = %.6g, vx = %.6g, vy = %.6g", p->x[i], p->y[i],
           p->vx[i], p->vy[i]);
  snprintf(box, sizeof box, "x [%.6g, %.6g] y [%.6g, %.6g]", d[0], d[1], d[2], d[3]);
#endif
  sph_error_set(err,
                "blow-up at step %ld, t = %.9g s: %s particle %lld: %s "
                "(%s, rho = %.6g; allowed rho in [%.6g, %.6g], domain %s)%s",
                s->steps, s->t, p->kind[i] == SPH_KIND_FLUID ? "fluid" : "wall",
                (long long)p->id[i], why, state, p->rho[i], rho0 * (1.0 - band),
                rho0 * (1.0 + band), box, hint);
  if (shared) sph_procs_share_from(err->msg, sizeof err->msg, maker);
  return SPH_BLOWUP;
}

int sph_sim_check_state(sph_sim *s, sph_error *err) { return check_state(s, in_team(s), err); }

/* Mirror lines and tank faces keep the fluid off (walls.h), and the
 * ledger books what that did to it. Only the step's result is kept off, not the mid-step
 * state of the predictor-corrector: a reflection there would move the
 * step's end (which is X^n + dt F(X^{n+1/2})) without being booked,
 * and the pass does not need it (a particle across a line has no image,
 * one exactly on it skips the coincident pair). */
static void keep_off_mirrors(sph_sim *s, int half_step) {
  double kick[2 * SPH_DIM] = {0.0};
  const double d_min = SPH_MIRROR_MIN_DISTANCE * s->c->dx;
  if (sph_walls_keep_off(&s->walls, &s->p, d_min, half_step, kick) && s->fp.ledger)
    sph_ledger_add_kick(&s->ledger, kick, s->c->gravity);
}

/* Particle shifting (physics/shifting.h) of the step's end state, on a
 * neighbour list of it; then the mirror lines and tank faces keep the
 * fluid off again (a shift toward a face is reflected as a step's move
 * would be), and periodic particles wrap. */
static int shift_particles(sph_sim *s, double dt, sph_error *err) {
  const sph_case *c = s->c;
  sph_particles *p = &s->p;
  if (neighbours(s, err)) return -1;
  const sph_shifting_params sp = {c->shifting_coefficient, c->h, c->dx, c->kernel};
  sph_shifting_compute(p, &s->nl, &sp, dt, s->shift);
  sph_xsum sum[SPH_DIM]; /* exact (exact_sum.h): the same bits in any order */
  for (int a = 0; a < SPH_DIM; a++)
    sph_xsum_init(&sum[a]);
  for (size_t i = 0; i < p->n; i++) {
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    for (int a = 0; a < SPH_DIM; a++) {
      p->pos[a][i] += s->shift[a][i];
      sph_xsum_add(&sum[a], p->mass[i] * s->shift[a][i]);
    }
  }
  double moved[SPH_DIM];
  for (int a = 0; a < SPH_DIM; a++)
    moved[a] = sph_xsum_round(&sum[a]);
  if (s->fp.ledger) sph_ledger_add_shift(&s->ledger, moved, c->gravity);
  keep_off_mirrors(s, c->integrator == SPH_INTEGRATOR_LEAPFROG);
  wrap_periodic(s);
  return 0;
}

/* Whether the pass's packed copy (w->hot) holds the state of the last
 * pass, particle for particle in storage order: what the leap-frog keeps
 * instead of X0 (setup.c). Checked at every leap-frog step in a debug
 * build. */
static int hot_is_state(const sph_sim *s) {
  const sph_particles *p = &s->p;
  if (s->hot_in_sub) return 1; /* the processes' rank stores hold it (tests/test_mpi: a blow-up) */
  if (s->work.cap < p->n) return 0;
  for (size_t i = 0; i < p->n; i++) {
    const sph_force_hot *h = &s->work.hot[i];
    if (h->x != p->x[i] || h->y != p->y[i] || h->vx != p->vx[i] || h->vy != p->vy[i] ||
        h->rho != p->rho[i] SPH_IF3(|| h->z != p->z[i] || h->vz != p->vz[i]))
      return 0;
  }
  return 1;
}

/* The step's floor, a fraction of the case's acoustic step factor h / c0,
 * and how many steps in a row may stay below it: a run whose step stays
 * that small is stalling, not resolving its flow (a motion of period
 * 1e-300 s, a fixed step of 1e-300 s; issue 61, E5). Paper B's rule dips
 * far below it when two particles pass very close (to 1e-9 in the 3-D
 * energy box and a dropped column) and recovers within a hundred steps;
 * such an episode goes on. */
#define SPH_DT_FLOOR 1e-6
#define SPH_DT_FLOOR_STEPS 1000

/* The message of a step below the floor: the rule, and the particle that
 * moves fastest (what the acoustic rule reads). SPH_BLOWUP. */
static int step_collapse(const sph_sim *s, double dt, double acoustic, sph_error *err) {
  static const char *const rule[] = {"paper_b", "cfl", "fixed"};
  const sph_particles *p = &s->p;
  const sph_case *c = s->c;
  size_t from, to, fast = 0;
  sph_sim_span(s, &from, &to);
  double vmax = -1.0;
  for (size_t i = from; i < to; i++) { /* serial: the first of equals, any thread count */
    const double w2 = SPH_NORM2(p->vx[i], p->vy[i], p->vz[i]);
    if (w2 > vmax) vmax = w2, fast = i;
  }
  /* under mpirun each process looks at its share; the first process with the largest speed
   * holds the first of equals in storage order (the shares are ranges in rank order), and it
   * makes the message for all */
  int maker = -1;
  if (in_team(s)) {
    double all[SPH_PROCS_MAX];
    sph_procs_gather(&vmax, sizeof vmax, all);
    double best = -1.0;
    maker = 0; /* (a store with particles: some share holds one) */
    for (int q = 0; q < s->ranks; q++)
      if (all[q] > best) best = all[q], maker = q;
    if (maker != s->self) {
      sph_procs_share_from(err->msg, sizeof err->msg, maker);
      return SPH_BLOWUP;
    }
  }
  const int r = c->dt_rule == SPH_DT_CFL ? 1 : c->dt_rule == SPH_DT_FIXED ? 2 : 0;
  sph_error_set(err,
                "time step collapse at step %ld, t = %.9g s: the step (numerics.time_step.rule: "
                "%s) has stayed below %g of the case's acoustic step factor h / c0 = %.3g s for "
                "%d steps (now %.3g s); the fastest particle, %s particle %lld, moves at %.3g m/s "
                "(c0 = %.3g m/s): look for a motion, a fixed step or an output interval far "
                "shorter than the flow's time",
                s->steps, s->t, rule[r], SPH_DT_FLOOR, acoustic, SPH_DT_FLOOR_STEPS, dt,
                p->kind[fast] == SPH_KIND_FLUID ? "fluid" : "wall", (long long)p->id[fast],
                vmax > 0.0 ? sqrt(vmax) : 0.0, c->sound_speed);
  if (maker >= 0) sph_procs_share_from(err->msg, sizeof err->msg, maker);
  return SPH_BLOWUP;
}

int sph_sim_step(sph_sim *s, double t_target, sph_error *err) {
  const sph_case *c = s->c;
  const int xsph = c->xsph != 0.0;
  double dt; /* from the rates of the current state, computed by the last pass */
  switch (c->dt_rule) {
  case SPH_DT_FIXED: dt = c->dt_fixed; break;
  case SPH_DT_CFL: /* the ranks' last pass found the max (ranks.c) */
    dt = s->cfl_max > 0.0 ? sph_dt_cfl_of(s->cfl_max, c->h, c->dt_factor)
                          : sph_dt_cfl(&s->p, s->fp.phase_eos, c->h, c->dt_factor);
    break;
  case SPH_DT_PAPER_B:
  default: dt = s->dt_paper_b; break;
  }
  if (s->fp.sigma > 0.0 && c->dt_rule != SPH_DT_FIXED) /* the capillary bound */
    dt = fmin(dt, sph_surface_dt(&s->fp, c->h));
  if (!(dt > 0.0) || !isfinite(dt))
    return sph_error_set(err, "blow-up at step %ld, t = %.9g s: time step is %g", s->steps, s->t,
                         dt),
           SPH_BLOWUP;
  const double acoustic = c->dt_factor * c->h / c->sound_speed;
  /* (a restart counts afresh: the count decides only whether the run stops) */
  s->below_floor = dt < SPH_DT_FLOOR * acoustic ? s->below_floor + 1 : 0;
  if (s->below_floor >= SPH_DT_FLOOR_STEPS) return step_collapse(s, dt, acoustic, err);
  if (!(s->dt_first > 0.0)) s->dt_first = s->dt_smallest = dt, s->t_smallest = s->t;
  if (dt < s->dt_smallest) s->dt_smallest = dt, s->t_smallest = s->t;
  int land = 0;
  if (s->t + dt >= t_target) {
    dt = t_target - s->t;
    land = 1;
  }
  /* the stage (or the leap-frog) saves X^n in X0; a leap-frog without the
   * SAVED group finds it in the last pass's packed copy */
  s->t_saved = s->t;
  const double t_new = land ? t_target : s->t + dt;
  if (c->integrator == SPH_INTEGRATOR_LEAPFROG) {
    if (SPH_DEBUG && !(s->p.live & SPH_ARRAYS_SAVED))
      SPH_INVARIANT(hot_is_state(s),
                    "leap-frog: the pass's packed copy is not the state at t = %.9g "
                    "s (the last good state after a blow-up is read from it)",
                    s->t);
    /* the rates of t^n drive the whole step: so do the ledger's powers */
    sph_ledger_advance(&s->ledger, dt);
    sph_leapfrog_step(&s->p, dt, s->last_dt, s->first_step, xsph, s->fp.phase_eos, slices(s));
    s->first_step = 0;
    sph_sim_move_walls(s, t_new);
    keep_off_mirrors(s, 1);
  } else {
    sph_pc_half(&s->p, dt, xsph, s->fp.phase_eos, slices(s));
    sph_sim_move_walls(s, s->t + 0.5 * dt);

    if (sph_sim_pass(s, err)) return -1;
    /* X^{n+1} = X^n + dt F(X^{n+1/2}): the mid-step powers drive the step */
    sph_ledger_advance(&s->ledger, dt);
    sph_pc_finish(&s->p, dt, xsph, s->fp.phase_eos, slices(s));
    sph_sim_move_walls(s, t_new);
    keep_off_mirrors(s, 0);
  }
  wrap_periodic(s);
  s->t = t_new;
  s->last_dt = dt;
  s->steps++;
  if (c->density_filter != SPH_FILTER_NONE && s->steps % c->filter_every == 0 &&
      apply_filter(s, err))
    return -1;
  const int st = check_state(s, s->self >= 0, err);
  if (st == SPH_BLOWUP) sph_sim_ranks_saved_state(s); /* (a leap-frog's last good state) */
  if (st) return st;
  if (c->leaving == SPH_LEAVING_REMOVE && sph_outflow_count(&s->p, s->domain) > 0) {
    /* (the store reordered: first the walls' values the processes kept to themselves, every
     * process's at once, the fluid being the same on each: ranks.c) */
    sph_sim_catch_up(s);
    if (sph_outflow_remove(&s->out, &s->p, s->domain, c->gravity, s->floor_y, err) < 0) return -1;
  }
  /* rates (and flags) of the new state: the next step starts from them,
   * and a snapshot of this state carries flags that belong to it */
  s->resort = s->steps % SPH_RESORT_EVERY == 0;
  if (c->shifting && shift_particles(s, dt, err)) return -1;
  return sph_sim_pass(s, err);
}

double sph_sim_time(const sph_sim *s) { return s->t; }
long sph_sim_steps(const sph_sim *s) { return s->steps; }
int sph_sim_step_range(const sph_sim *s, double *first, double *smallest, double *t) {
  if (!(s->dt_first > 0.0)) return 0;
  *first = s->dt_first;
  *smallest = s->dt_smallest;
  *t = s->t_smallest;
  return 1;
}
const sph_case *sph_sim_case(const sph_sim *s) { return s->c; }
const char *sph_sim_loop(const sph_sim *s, double *ratio) {
  *ratio = s->lane_ratio;
  return sph_force_loop_name(&s->fp);
}
sph_particles *sph_sim_particles(sph_sim *s) { return &s->p; }
double sph_sim_floor(const sph_sim *s) { return s->floor_y; }
size_t sph_sim_fluid_removed(const sph_sim *s) { return s->fluid_removed; }
size_t sph_sim_fluid_left(const sph_sim *s, double *mass) {
  if (mass) *mass = s->out.mass;
  return s->out.count;
}
size_t sph_sim_fluid_in_obstacles(const sph_sim *s) { return s->fluid_in_obstacles; }
size_t sph_sim_walls_dropped(const sph_sim *s) { return s->walls.n_dropped; }
void sph_sim_domain(const sph_sim *s, double box[2 * SPH_DIM]) {
  memcpy(box, s->domain, 2 * SPH_DIM * sizeof *box);
}

void sph_sim_span(const sph_sim *s, size_t *from, size_t *to) {
  const size_t n = s->p.n;
  *from = in_team(s) ? n * (size_t)s->self / (size_t)s->ranks : 0;
  *to = in_team(s) ? n * (size_t)(s->self + 1) / (size_t)s->ranks : n;
}

/* The diagnostics row and the fluid's stored heat (the ledger's start). */
static void diag_row(const sph_sim *s, sph_diag_row *row, double *u_fluid) {
  /* this process's share, then (under mpirun) every process's merged in
   * rank order: exact sums, a count and a max, the bits of one sum */
  size_t from, to;
  sph_sim_span(s, &from, &to);
  sph_diag_sums t;
  sph_diag_sums_init(&t);
  sph_diag_sums_add(&t, &s->p, from, to, s->floor_y, 2.0 * s->c->dx, s->c->gravity, s->c->energy);
  if (in_team(s)) {
    sph_procs_gather(&t, sizeof t, s->diag_all);
    sph_diag_sums_init(&t);
    for (int q = 0; q < s->ranks; q++)
      sph_diag_sums_merge(&t, &s->diag_all[q]);
    if (s->rank_order_sums == 2) /* test hook: each process's sums rounded, then added in order */
      for (int k = 0; k < SPH_DS_COUNT; k++) {
        double sum = 0.0;
        for (int q = 0; q < s->ranks; q++)
          sum += sph_xsum_round(&s->diag_all[q].s[k]);
        sph_xsum_init(&t.s[k]);
        sph_xsum_add(&t.s[k], sum);
      }
  }
  sph_diag_sums_row(&t, row);
  row->n_surface = s->detect ? (long)s->n_surface : -1;
  if (s->c->leaving == SPH_LEAVING_REMOVE) {
    row->outflow = 1;
    row->n_removed = s->out.count;
    row->mass_removed = s->out.mass;
  }
  if (s->c->energy) {
    *u_fluid = sph_xsum_round(&t.s[SPH_DS_HEAT_FLUID]);
    sph_ledger_fill(&s->ledger, sph_xsum_round(&t.s[SPH_DS_HEAT]), *u_fluid, &s->out, row);
    row->diffusion = s->c->diffusion != SPH_DIFFUSION_NONE || s->c->riemann;
    row->shifting = s->c->shifting;
  }
  row->time = s->t;
  row->step = s->steps;
  row->dt = s->last_dt;
}

void sph_sim_diag(const sph_sim *s, sph_diag_row *row) {
  double u_fluid = 0.0;
  diag_row(s, row, &u_fluid);
}

void sph_sim_ledger_start(sph_sim *s) {
  sph_diag_row row;
  double u_fluid = 0.0;
  diag_row(s, &row, &u_fluid);
  sph_ledger_start(&s->ledger, u_fluid, &row);
}

void sph_sim_fill_meta(const sph_sim *s, sph_snapshot_meta *m, double t, long step) {
  memset(m, 0, sizeof *m);
  m->time = t;
  m->dt = s->last_dt;
  m->step = step;
  m->case_name = s->c->name;
  m->case_text = s->c->text;
  m->overrides = s->c->overrides;
  m->parameters = s->parameters;
  m->kernel = sph_kernel_name(s->c->kernel);
  m->dx = s->c->dx;
  m->h = s->c->h;
  m->rho0 = s->c->rho0;
  memcpy(m->view, s->view, sizeof m->view);
  m->free_surface = s->detect;
  m->geometry = &s->geometry;
}

int sph_sim_write_snapshot(const sph_sim *s, const char *path, sph_error *err) {
  sph_snapshot_meta m;
  sph_sim_fill_meta(s, &m, s->t, s->steps);
  return sph_snapshot_write(path, &m, &s->p, err);
}

int sph_sim_write_saved_snapshot(sph_sim *s, const char *path, sph_error *err) {
  if (!(s->p.live & SPH_ARRAYS_SAVED) && s->step_pass == s->steps) {
    /* the leap-frog stopped before its step (a step that is not finite):
     * the store is still the state of the last pass */
    sph_snapshot_meta m;
    sph_sim_fill_meta(s, &m, s->t, s->steps);
    return sph_snapshot_write(path, &m, &s->p, err);
  }
  /* a view of the store whose state arrays are the saved ones */
  sph_particles v = s->p;
  const size_t n = v.n;
  double *tmp = NULL;
  if (s->p.live & SPH_ARRAYS_SAVED) {
    for (int d = 0; d < SPH_STORE_DIM; d++) {
      v.pos[d] = s->p.pos0[d];
      v.vel[d] = s->p.vel0[d];
    }
    v.rho = s->p.rho0;
  } else { /* the leap-frog: the state of the last pass (at t_saved), from its packed copy */
    if (!(tmp = malloc((2 * SPH_DIM + 1) * (n ? n : 1) * sizeof *tmp)))
      return sph_error_set(err, "out of memory for the last good state");
    for (int d = 0; d < SPH_STORE_DIM; d++) {
      v.pos[d] = tmp + (size_t)d * n;
      v.vel[d] = tmp + (size_t)(SPH_DIM + d) * n;
    }
    v.rho = tmp + (size_t)(2 * SPH_DIM) * n;
    for (size_t i = 0; i < n; i++) {
      const sph_force_hot *h = &s->work.hot[i];
      v.x[i] = h->x, v.y[i] = h->y, v.vx[i] = h->vx, v.vy[i] = h->vy, v.rho[i] = h->rho;
      SPH_IF3(v.z[i] = h->z, v.vz[i] = h->vz;)
    }
  }
  v.u = s->p.u0;
  v.p = s->work.prho2; /* scratch: pressure of the saved state */
  for (size_t i = 0; i < n; i++)
    v.p[i] = sph_eos_pressure(&s->fp.eos, v.rho[i]);
  sph_snapshot_meta m;
  sph_sim_fill_meta(s, &m, s->t_saved, s->steps - 1);
  const int rc = sph_snapshot_write(path, &m, &v, err);
  free(tmp);
  return rc;
}
