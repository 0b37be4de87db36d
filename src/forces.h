/*
 * forces.h - the interaction pass: rates of change of every particle from
 * its neighbours (gather form: each particle sums over its own neighbours
 * into its own accumulators, so no two threads write the same memory and
 * the summation order is fixed by the sorted store).
 *
 * Terms (paper B = breaking-wave paper, paper A = dam-break paper):
 *   continuity       drho_i/dt = sum_j m_j (v_i - v_j) . grad_i W_ij      (B eq. 2, A eq. 12)
 *   momentum         dv_i/dt = -sum_j m_j (p_i/rho_i^2 + p_j/rho_j^2 + Pi_ij) grad_i W_ij + g
 *                                                                         (A eq. 11 without tau, B eq. 3)
 *   art. viscosity   Pi_ij = (-alpha c_ij mu_ij + beta mu_ij^2)/rho_ij if v_ij.r_ij < 0, else 0
 *                    mu_ij = h v_ij.r_ij / (r_ij^2 + eta^2), eta = eta_f h   (A eq. 15-16)
 *   XSPH             dr_i/dt = v_i + eps sum_j (m_j/rho_ij) (v_j - v_i) W_ij  (B eq. 6),
 *                    over fluid neighbours only (a wall at rest would drag
 *                    the fluid otherwise)
 *   time-step data   sigma_i = max_j |h v_ij.r_ij / r_ij^2|                 (B §2.6)
 * Wall particles (dynamic particles, GOST R 57700.6 3.4.7) get only drho/dt;
 * they act on fluid through their pressure and the artificial viscosity.
 */
#ifndef SPH_FORCES_H
#define SPH_FORCES_H

#include "eos.h"
#include "grid.h"
#include "particles.h"

typedef struct sph_force_params {
  sph_eos eos;
  double h;            /* smoothing length (uniform) */
  double alpha, beta;  /* artificial viscosity; both 0 = off */
  double eta;          /* eta = eta_f * h */
  double xsph;         /* XSPH epsilon; 0 = off */
  double gx, gy;       /* body force per unit mass */
} sph_force_params;

/* Per-particle quantities computed once per pass (storage order). */
typedef struct sph_force_work {
  size_t cap;
  double *prho2; /* p / rho^2 */
  double *cs;    /* sound speed */
  double *sigma; /* max_j |h v_ij.r_ij / r_ij^2| */
} sph_force_work;

void sph_force_work_free(sph_force_work *w);

/* Sets p->p from the equation of state for every particle. */
void sph_forces_pressure(sph_particles *p, const sph_eos *eos);

/* One interaction pass over the grid g (built on p's current positions):
 * fills p->drho for all particles, p->ax, p->ay (and p->xsx, p->xsy when
 * XSPH is on) for fluid particles, and w->sigma. Needs p->p current. */
int sph_forces_evaluate(sph_particles *p, const sph_grid *g, const sph_force_params *fp,
                        sph_force_work *w, sph_error *err);

#endif
