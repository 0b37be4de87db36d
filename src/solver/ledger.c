/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * ledger.c - the energy and momentum ledger (see ledger.h).
 */
#include "config.h"

#include "solver/ledger.h"

#include <math.h>

#include "core/check.h"
#include "core/exact_sum.h"
#include "core/parallel.h"

/* The rates' sums over the fluid particles, each exact (exact_sum.h): in
 * parallel, each thread's partial sums merged, the same bits in any order
 * and for any split of the particles (threads, ranks). The walls' force on
 * the fluid and its weight apart: sum m_i f_i over the particles a wall
 * pushes (most have f_i = 0 and are not added), then g times the fluid's
 * mass, added into the same exact sum. */
enum { L_PW, L_PX, L_FX, L_FY, L_PD, L_PHI, L_FZ, L_M, L_SUMS };
typedef char sph_ledger_sums_check[L_SUMS == SPH_LEDGER_SUMS ? 1 : -1];

void sph_ledger_sums_init(sph_ledger_sums *t) {
  for (int k = 0; k < SPH_LEDGER_SUMS; k++)
    sph_xsum_init(&t->s[k]);
}

void sph_ledger_sums_merge(sph_ledger_sums *t, const sph_ledger_sums *u) {
  for (int k = 0; k < SPH_LEDGER_SUMS; k++)
    sph_xsum_merge(&t->s[k], &u->s[k]);
}

void sph_ledger_rates(sph_ledger *lg, const sph_particles *p, const sph_force_work *w,
                      const double gravity[SPH_DIM], int xsph, int diffusion) {
  sph_ledger_sums t;
  sph_ledger_sums_init(&t);
  sph_ledger_sums_add(&t, lg, p, w, gravity, xsph, diffusion, 0);
  sph_ledger_finish(lg, &t, gravity);
}

void sph_ledger_sums_add(sph_ledger_sums *t, const sph_ledger *lg, const sph_particles *p,
                         const sph_force_work *w, const double gravity[SPH_DIM], int xsph,
                         int diffusion, unsigned skip) {
  const double *g = gravity;
  const int repulsion = lg->repulsion;
  sph_xsum *sum = t->s;
  const long n = (long)p->n;
#pragma omp parallel if (n > SPH_OMP_MIN)
  {
    sph_xsum part[L_SUMS];
    for (int k = 0; k < L_SUMS; k++)
      sph_xsum_init(&part[k]);
#pragma omp for schedule(static) nowait
    for (long li = 0; li < n; li++) {
      const size_t i = (size_t)li;
      if (p->kind[i] != SPH_KIND_FLUID || (p->flags[i] & skip)) continue;
      const double m = p->mass[i];
      sph_xsum_add(&part[L_M], m);
      if (w->wpow[i] != 0.0) sph_xsum_add(&part[L_PW], m * w->wpow[i]);
#if SPH_DIM == 2
      if (xsph) sph_xsum_add(&part[L_PX], -(m * (g[0] * p->xsx[i] + g[1] * p->xsy[i])));
#else
      if (xsph)
        sph_xsum_add(&part[L_PX], -(m * (g[0] * p->xsx[i] + g[1] * p->xsy[i] + g[2] * p->xsz[i])));
      if (w->wfz[i] != 0.0) sph_xsum_add(&part[L_FZ], m * w->wfz[i]);
#endif
      if (w->wfx[i] != 0.0) sph_xsum_add(&part[L_FX], m * w->wfx[i]);
      if (w->wfy[i] != 0.0) sph_xsum_add(&part[L_FY], m * w->wfy[i]);
      if (diffusion) sph_xsum_add(&part[L_PD], m * w->hot[i].prho2 * w->dd[i]);
      if (repulsion) sph_xsum_add(&part[L_PHI], m * w->lj[i]);
    }
#pragma omp critical(sph_ledger_rates)
    for (int k = 0; k < L_SUMS; k++) /* exact: in any order */
      sph_xsum_merge(&sum[k], &part[k]);
  }
}

void sph_ledger_finish(sph_ledger *lg, sph_ledger_sums *t, const double gravity[SPH_DIM]) {
  const double *g = gravity;
  sph_xsum *sum = t->s;
  const double mass = sph_xsum_round(&sum[L_M]); /* the weight: g times it */
  sph_xsum_add(&sum[L_FX], g[0] * mass);
  sph_xsum_add(&sum[L_FY], g[1] * mass);
  SPH_IF3(sph_xsum_add(&sum[L_FZ], g[2] * mass);)
  lg->wall_potential = sph_xsum_round(&sum[L_PHI]);
  lg->power_diffusion = sph_xsum_round(&sum[L_PD]);
  lg->power_wall = sph_xsum_round(&sum[L_PW]);
  lg->power_xsph = sph_xsum_round(&sum[L_PX]);
  lg->force_x = sph_xsum_round(&sum[L_FX]);
  lg->force_y = sph_xsum_round(&sum[L_FY]);
  SPH_IF3(lg->force_z = sph_xsum_round(&sum[L_FZ]);)
}

void sph_ledger_advance(sph_ledger *lg, double dt) {
  lg->work_wall += dt * lg->power_wall;
  lg->drift_xsph += dt * lg->power_xsph;
  lg->work_diffusion += dt * lg->power_diffusion;
  lg->impulse_x += dt * lg->force_x;
  lg->impulse_y += dt * lg->force_y;
  SPH_IF3(lg->impulse_z += dt * lg->force_z;)
}

void sph_ledger_add_shift(sph_ledger *lg, const double moved[SPH_DIM],
                          const double gravity[SPH_DIM]) {
  lg->drift_shifting -=
      gravity[0] * moved[0] + gravity[1] * moved[1] SPH_IF3(+gravity[2] * moved[2]);
}

void sph_ledger_add_kick(sph_ledger *lg, const double kick[2 * SPH_DIM],
                         const double gravity[SPH_DIM]) {
#if SPH_DIM == 2
  lg->work_wall -= gravity[0] * kick[0] + gravity[1] * kick[1];
  lg->impulse_x += kick[2];
  lg->impulse_y += kick[3];
#else
  lg->work_wall -= gravity[0] * kick[0] + gravity[1] * kick[1] + gravity[2] * kick[2];
  lg->impulse_x += kick[3];
  lg->impulse_y += kick[4];
  lg->impulse_z += kick[5];
#endif
}

/* The particles' heat, sum m u (fluid only, or every particle), exact. */
void sph_ledger_fill(const sph_ledger *lg, double u, double u_fluid, const sph_outflow *out,
                     sph_diag_row *row) {
  static const sph_outflow none = {0};
  if (!out) out = &none;
  row->ledger = 1;
  row->internal = u;
  row->boundary_work = lg->work_wall;
  row->xsph_drift = lg->drift_xsph;
  row->shifting_drift = lg->drift_shifting;
  row->diffusion_energy = lg->work_diffusion;
  row->repulsion = lg->repulsion;
  row->wall_potential = lg->repulsion ? lg->wall_potential : 0.0;
  row->energy_removed = out->energy;
  row->total = row->kinetic + row->potential + u + row->wall_potential - lg->work_wall -
               lg->drift_xsph - lg->drift_shifting + out->energy;
  row->deviation = lg->e0 != 0.0 ? (row->total - lg->e0) / lg->e0 : 0.0;
  const double ef = row->kinetic + row->potential + u_fluid + out->energy;
  row->fluid_deviation = lg->e0_fluid != 0.0 ? (ef - lg->e0_fluid) / lg->e0_fluid : 0.0;
  row->momentum_residual_x = row->momentum_x + out->momentum[0] - lg->p0x - lg->impulse_x;
  row->momentum_residual_y = row->momentum_y + out->momentum[1] - lg->p0y - lg->impulse_y;
  SPH_IF3(row->momentum_residual_z = row->momentum_z + out->momentum[2] - lg->p0z - lg->impulse_z;)
  /* debug invariants: masses never change (the fluid that left and what is
   * left add up to the start, to the rounding of two sums), and every
   * total is a number */
  SPH_INVARIANT(
      lg->m0 == 0.0 || (out->count == 0 ? row->mass == lg->m0
                                        : fabs(row->mass + out->mass - lg->m0) <= 1e-12 * lg->m0),
      "fluid mass %.17g (and %.17g removed), initially %.17g", row->mass, out->mass, lg->m0);
  SPH_INVARIANT(isfinite(row->total) && isfinite(lg->work_wall) && isfinite(lg->impulse_x) &&
                    isfinite(lg->impulse_y),
                "a ledger total is not finite at t = %.9g s", row->time);
}

void sph_ledger_start(sph_ledger *lg, double u_fluid, const sph_diag_row *row) {
  lg->e0 = row->total;
  lg->e0_fluid = row->kinetic + row->potential + u_fluid;
  lg->p0x = row->momentum_x;
  lg->p0y = row->momentum_y;
  SPH_IF3(lg->p0z = row->momentum_z;)
  lg->m0 = row->mass;
}

void sph_ledger_save(const sph_ledger *lg, double out[SPH_LEDGER_SAVED]) {
  out[0] = lg->work_wall;
  out[1] = lg->drift_xsph;
  out[2] = lg->impulse_x;
  out[3] = lg->impulse_y;
  SPH_IF3(out[4] = lg->impulse_z;)
}

void sph_ledger_restore(sph_ledger *lg, const double in[SPH_LEDGER_SAVED]) {
  lg->work_wall = in[0];
  lg->drift_xsph = in[1];
  lg->impulse_x = in[2];
  lg->impulse_y = in[3];
  SPH_IF3(lg->impulse_z = in[4];)
}
