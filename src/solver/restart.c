/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * restart.c - a run's snapshot that a later run can continue from, bit for
 * bit (sph run --restart).
 */
#include "config.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <stdlib.h>
#include <string.h>

#include "solver/procs.h"
#include "solver/sim_internal.h"

/* ---- restart (sph run --restart) -------------------------------------------
 * A snapshot written by sph_sim_write_run_snapshot carries, besides the
 * fields, what the next step reads that the fields do not hold: the
 * storage order (the grid's sort is stable, so the order within a cell,
 * and with it the order of every neighbour sum, depends on the history),
 * the leap-frog's half-step values and first-step flag, the ledger's
 * time integrals, and which particles have left the domain and what they
 * carried (outflow.h). Everything else the step uses is either a function of
 * the case (set-up, rest positions and motion of walls, domain, initial
 * energies and momentum, all remade by sph_sim_create) or of the state in
 * that order (the rates, flags and step-rule inputs of the pass, which
 * sph_sim_restore reruns). So a restored sim steps bit for bit as the one
 * that wrote the snapshot. */

int sph_sim_write_run_snapshot(const sph_sim *s, const char *path, int64_t output_index,
                               const double *levels, size_t n_levels, const double *filters,
                               size_t n_filters, sph_error *err) {
  sph_snapshot_meta m;
  sph_sim_fill_meta(s, &m, s->t, s->steps);
  sph_snapshot_restart r;
  memset(&r, 0, sizeof r);
  r.output_index = output_index;
  r.first_step = s->first_step;
  sph_ledger_save(&s->ledger, r.ledger);
  r.has_diffusion = s->fp.diffusion != SPH_DIFFUSION_NONE || s->fp.riemann;
  r.ledger_diffusion = s->ledger.work_diffusion;
  r.has_shifting = s->c->shifting;
  r.ledger_shifting = s->ledger.drift_shifting;
  r.n_levels = n_levels;
  r.levels = levels;
  r.n_filters = n_filters;
  r.filters = filters;
  r.has_outflow = s->c->leaving == SPH_LEAVING_REMOVE;
  sph_outflow_save(&s->out, r.outflow);
  r.origin = s->out.origin;
  r.order = s->p.id;
  if (s->c->integrator == SPH_INTEGRATOR_LEAPFROG) {
    r.vxh = s->p.vxh;
    r.vyh = s->p.vyh;
    SPH_IF3(r.vzh = s->p.vzh;)
    r.rhoh = s->p.rhoh;
    r.uh = s->p.uh;
  }
  m.restart = &r;
  /* under several processes, all of them write it (procs.h) */
  const sph_snapshot_team team = {sph_procs_rank(), sph_procs_count(), sph_procs_agree};
  return sph_snapshot_write_team(path, &m, &s->p, &team, err);
}

/* The first line of a that differs from b, ignoring time.end (a restart
 * may run further); NULL if none. Lines are "key: value". */
static const char *first_difference(const char *a, const char *b, size_t *len) {
  for (;;) {
    while (!strncmp(a, "time.end:", 9))
      a += strcspn(a, "\n") + (a[strcspn(a, "\n")] != 0);
    while (!strncmp(b, "time.end:", 9))
      b += strcspn(b, "\n") + (b[strcspn(b, "\n")] != 0);
    if (!*a && !*b) return NULL;
    const size_t la = strcspn(a, "\n"), lb = strcspn(b, "\n");
    if (la != lb || memcmp(a, b, la)) {
      *len = la ? la : lb;
      return la ? a : b;
    }
    a += la + (a[la] != 0);
    b += lb + (b[lb] != 0);
  }
}

static int restore_state(sph_sim *s, const sph_snapshot *snap, const sph_particles *q,
                         const sph_snapshot_restart_data *rd, sph_error *err) {
  const char *path = sph_snapshot_path(snap);
  /* the fluid that had left the domain by then leaves the case's store */
  if (rd->origin) {
    if (sph_outflow_restore(&s->out, &s->p, rd->origin, rd->count, rd->outflow, path, err))
      return -1;
  } else if (rd->outflow[0] != 0.0) {
    return sph_error_set(err,
                         "%s: the restart record says %g particles left the domain but has no "
                         "/restart/origin",
                         path, rd->outflow[0]);
  }
  const size_t n = s->p.n;
  if (q->n != n)
    return sph_error_set(err,
                         "%s: holds %zu particles, the case makes %zu: not a snapshot of "
                         "this case",
                         path, q->n, n);
  const char *params = sph_snapshot_text(snap, "parameters");
  size_t dlen = 0;
  const char *diff = params ? first_difference(params, s->parameters, &dlen) : NULL;
  if (!params || diff)
    return sph_error_set(err,
                         "%s: written with other parameters than the case (%s%.*s); "
                         "only time.end may change on a restart",
                         path, params ? "first difference: " : "no parameters attribute", (int)dlen,
                         diff ? diff : "");
  /* the clock: a hand-edited or damaged header must not run from t = NaN,
   * from a negative time or step, or past time.end (which would cut the
   * output files of the run it continues before finding nothing to do) */
  const double t = sph_snapshot_time(snap), dt = sph_snapshot_dt(snap);
  const double step = (double)sph_snapshot_step(snap);
  if (!isfinite(t) || t < 0.0)
    return sph_error_set(err, "%s: its time %g is not a finite time >= 0", path, t);
  if (!(t < s->c->t_end))
    return sph_error_set(err,
                         "%s: its time %.9g s is not before time.end = %.9g s: nothing to run "
                         "(--set time.end=... past it to continue)",
                         path, t, s->c->t_end);
  /* a time that could not follow from its step (issue 61, E13): -0, a
   * subnormal time, a time of 0 after step 0 or past 0 at step 0 */
  if (signbit(t) || (t > 0.0 && t < DBL_MIN) || (t == 0.0) != (step == 0.0))
    return sph_error_set(err,
                         "%s: its time %g s does not go with its step %.0f (a run is at t = 0 at "
                         "step 0, past it after; the time a normal number)",
                         path, t, step);
  if (!(step >= 0.0) || !(isfinite(dt) && dt >= 0.0) || rd->output_index < 0 ||
      (rd->first_step != 0 && rd->first_step != 1))
    return sph_error_set(err,
                         "%s: its step %.0f, time step %g, output index %lld or first-step flag "
                         "%lld is out of range (step, dt, index >= 0; the flag 0 or 1)",
                         path, step, dt, (long long)rd->output_index, (long long)rd->first_step);
  const int leapfrog = s->c->integrator == SPH_INTEGRATOR_LEAPFROG;
  if (leapfrog && !rd->first_step && !rd->vxh)
    return sph_error_set(err,
                         "%s: a leap-frog run's snapshot without the half-step values "
                         "(/restart/vxh, vyh, rhoh, uh)",
                         path);
  size_t *pos = malloc(n * sizeof *pos), *perm = malloc(n * sizeof *perm);
  void *work = malloc(n * sizeof(double));
  if (!pos || !perm || !work) {
    free(pos);
    free(perm);
    free(work);
    return sph_error_set(err, "out of memory");
  }
  for (size_t i = 0; i < n; i++)
    pos[s->p.id[i]] = i;
  for (size_t k = 0; k < n; k++)
    perm[k] = pos[rd->order[k]];
  sph_particles_permute(&s->p, perm, work);
  free(pos);
  free(perm);
  free(work);
  sph_particles *p = &s->p;
  for (size_t k = 0; k < n; k++) {
    const size_t i = (size_t)p->id[k]; /* row of the snapshot */
    if (q->kind[i] != p->kind[k] || q->mass[i] != p->mass[k])
      return sph_error_set(
          err,
          "%s: particle %zu is a %s of mass %g, the case makes a %s of "
          "mass %g: not a snapshot of this case",
          path, i, q->kind[i] == SPH_KIND_FLUID ? "fluid particle" : "wall particle", q->mass[i],
          p->kind[k] == SPH_KIND_FLUID ? "fluid particle" : "wall particle", p->mass[k]);
    p->x[k] = q->x[i];
    p->y[k] = q->y[i];
    p->vx[k] = q->vx[i];
    p->vy[k] = q->vy[i];
    SPH_IF3(p->z[k] = q->z[i]; p->vz[k] = q->vz[i];)
    p->rho[k] = q->rho[i];
    p->p[k] = q->p[i];
    /* the smoothing length is the case's where it is constant, and near it
     * where it varies (issue 61, E13) */
    const double h0 = s->c->h, hk = q->h[i];
    const double hmax = 2.0 * h0 * (s->c->fs_h_factor > 1.0 ? s->c->fs_h_factor : 1.0);
    if (s->fp.var_h ? !(hk >= 0.5 * h0 && hk <= hmax) : hk != h0)
      return sph_error_set(err,
                           "%s: particle %zu has h = %g m, the case's h is %g m%s: not a "
                           "snapshot of this case",
                           path, i, hk, h0,
                           s->fp.var_h ? " (and varies by at most a factor 2)" : "");
    p->h[k] = hk;
    if (p->live & SPH_ARRAYS_HEAT) p->u[k] = q->u[i];
    p->flags[k] = (uint8_t)((p->flags[k] & ~SPH_FLAG_FREE_SURFACE) | (q->flags[i] & 1u));
    if (rd->vxh && (p->live & SPH_ARRAYS_HALF_STEP)) {
      p->vxh[k] = rd->vxh[k];
      p->vyh[k] = rd->vyh[k];
      SPH_IF3(p->vzh[k] = rd->vzh[k];)
      p->rhoh[k] = rd->rhoh[k];
      p->uh[k] = rd->uh[k];
    }
  }
  s->t = sph_snapshot_time(snap);
  s->t_walls = s->t; /* the snapshot's walls stand where their laws put them at t */
  s->steps = (long)sph_snapshot_step(snap);
  s->last_dt = sph_snapshot_dt(snap);
  s->first_step = (int)rd->first_step;
  sph_ledger_restore(&s->ledger, rd->ledger);
  s->ledger.work_diffusion = rd->ledger_diffusion;
  s->ledger.drift_shifting = rd->ledger_shifting;
  return sph_sim_check_state(s, err);
}

int sph_sim_restore(sph_sim *s, const char *path, sph_snapshot_restart_data *rd, sph_error *err) {
  memset(rd, 0, sizeof *rd);
  sph_snapshot *snap;
  if (sph_snapshot_open(path, &snap, err)) return -1;
  /* the list and the pass's arrays of the set-up's pass, stale once the
   * store takes the snapshot's order, go before the snapshot's copy of the
   * particles comes in (the pass below makes them anew) */
  sph_nlist_release(&s->nl);
  sph_force_work_free(&s->work);
  sph_sim_ranks_forget(s); /* (and those of a rank's store) */
  sph_particles q;
  int rc = sph_snapshot_read_particles(snap, &q, err);
  if (rc == 0) {
    rc = sph_snapshot_read_restart(snap, rd, err);
    if (rc == 0) rc = restore_state(s, snap, &q, rd, err);
    /* the snapshot's copy of the particles goes before the pass builds its
     * list and work arrays: until 2026-11-28 both stores, the list and the
     * work arrays were held at once, a restart's peak 1.4 times a fresh
     * run's (SPHERIC at dx = 0.02 m: 123 MB against 85) */
    sph_particles_free(&q);
    /* and rd's per-particle arrays, in the store by then (the run reads
     * only rd's gauges, filters and output index) */
    sph_snapshot_restart_free_particles(rd);
#ifdef __GLIBC__
    /* and its pages back to the system: blocks freed below glibc's
     * dynamic mmap threshold stay resident otherwise */
    malloc_trim(0);
#endif
  }
  sph_snapshot_close(snap);
  /* the rates, flags and step-rule inputs of this state */
  if (rc == 0) rc = sph_sim_pass(s, err);
  if (rc) sph_snapshot_restart_free(rd);
  return rc;
}
