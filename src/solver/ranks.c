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
 * This is the pass of the MPI decomposition run in one process: each rank
 * here stands for a process, `sub` for its store. With SPH_TEST_RANKS=R
 * every output of a run must be the same bytes as the run's on one rank
 * (tests/test_ranks): the proof that the cut, the ghosts and the order of
 * every sum are right before any message is sent. Particle shifting runs on
 * the whole store, over a neighbour list of its own (sim.c).
 */
#include "config.h"

#include <math.h>
#include <stdlib.h>

#include "neighbours/decomp.h"
#include "physics/kernel.h"
#include "solver/integrate.h"
#include "solver/sim_internal.h"

/* Ghosts this many decomposition cells deep; the cells 1.25 supports wide
 * (tests/test_decomp: 2 cells give the same bits on every scheme). */
#define SPH_RANKS_DEPTH 3
#define SPH_RANKS_CELL 1.25

int sph_sim_ranks_init(sph_sim *s, int ranks, sph_error *err) {
  const sph_case *c = s->c;
  if (ranks < 2) return 0;
  if (ranks > 64) return sph_error_set(err, "SPH_TEST_RANKS: at most 64 ranks, got %d", ranks);
  if (sph_sim_create_rank_store(c, &s->sub, err)) return -1;
  s->sub->rank_store = 1;
  s->sub->work.keep_sigma = 1;
  s->ranks = ranks;
  return 0;
}

void sph_sim_ranks_free(sph_sim *s) {
  if (s->sub) sph_sim_free(s->sub);
  free(s->keys);
  free(s->mark);
  free(s->from);
  s->sub = NULL, s->keys = NULL, s->mark = NULL, s->from = NULL, s->cap_ranks = 0;
}

static int reserve(sph_sim *s, size_t n, sph_error *err) {
  if (n <= s->cap_ranks) return 0;
  uint64_t *k = realloc(s->keys, n * sizeof *k);
  if (k) s->keys = k;
  unsigned char *m = realloc(s->mark, n);
  if (m) s->mark = m;
  size_t *f = realloc(s->from, n * sizeof *f);
  if (f) s->from = f;
  if (!k || !m || !f) return sph_error_set(err, "out of memory for the ranks' cut");
  s->cap_ranks = n;
  return 0;
}

int sph_sim_ranks_pass(sph_sim *s, double hmax, sph_error *err) {
  const sph_case *c = s->c;
  sph_particles *p = &s->p;
  sph_sim *r = s->sub;
  /* the whole store sorted when its own pass would sort it */
  const int resort = s->resort || s->skin == 0.0;
  s->resort = 0;
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
  uint64_t first[64];
  if (sph_decomp_keys(&g, p, s->keys, err) || sph_decomp_cut(s->keys, p->n, s->ranks, first, err))
    return -1;
  double cs_max = 0.0;
  size_t surface = 0;
  sph_ledger_sums ledger;
  sph_ledger_sums_init(&ledger);
  for (int rank = 0; rank < s->ranks; rank++) {
    if (sph_decomp_halo(&g, p, s->keys, first, s->ranks, rank, SPH_RANKS_DEPTH, s->mark, err) < 0 ||
        sph_particles_take(&r->p, p, s->mark, err))
      return -1;
    size_t k = 0;
    for (size_t i = 0; i < p->n; i++)
      if (s->mark[i]) {
        if (s->mark[i] == 2) r->p.flags[k] |= SPH_FLAG_GHOST;
        s->from[k++] = i;
      }
    r->t = s->t, r->t_walls = s->t_walls, r->t_saved = s->t_saved;
    r->steps = s->steps, r->last_dt = s->last_dt, r->first_step = s->first_step;
    r->resort = resort;
    r->nl.valid = 0;
    r->fp.loop = s->fp.loop;
    r->hmax_all = c->variable_h ? hmax : 0.0;
    if (sph_sim_pass(r, err)) return -1;
    if (r->p.n != k)
      return sph_error_set(err,
                           "ranks: rank %d's store holds %zu particles after its pass, not %zu",
                           rank, r->p.n, k);
    if (r->own_cs_max > cs_max) cs_max = r->own_cs_max;
    if (s->fp.ledger) sph_ledger_sums_merge(&ledger, &r->own_ledger);
    for (size_t j = 0; j < k; j++) {
      const size_t i = s->from[j];
      if (r->p.id[j] != p->id[i])
        return sph_error_set(err, "ranks: rank %d's pass reordered its store", rank);
      if (s->mark[i] != 1) continue; /* a ghost: its own rank writes it */
      sph_particles_copy_one(p, i, &r->p, j);
      surface += (r->p.flags[j] & SPH_FLAG_FREE_SURFACE) != 0;
    }
  }
  s->work.cs_sigma_max = cs_max;
  s->dt_paper_b = sph_dt_paper_b(&s->work, c->h, c->dt_factor);
  s->n_surface = s->detect ? surface : 0;
  if (s->fp.ledger) sph_ledger_finish(&s->ledger, &ledger, c->gravity);
  s->step_pass = s->steps;
  /* the state the pass saw, as the whole store's pass packs it: the
   * leap-frog's last good state (sim.c) */
  if (sph_force_work_reserve(&s->work, p->n, err)) return -1;
  for (size_t i = 0; i < p->n; i++) {
    sph_force_hot *h = &s->work.hot[i];
    h->x = p->x[i], h->y = p->y[i], h->vx = p->vx[i], h->vy = p->vy[i], h->rho = p->rho[i];
    SPH_IF3(h->z = p->z[i], h->vz = p->vz[i];)
  }
  return 0;
}
