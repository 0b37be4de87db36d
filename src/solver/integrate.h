/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * integrate.h - time integration: the predictor-corrector of paper B
 * (eq. 7-8) and the time-step rules.
 *
 *   X^{n+1/2} = X^n + dt/2 F(X^n)          (predictor)
 *   X^{n+1/2} = X^n + dt/2 F(X^{n+1/2})    (corrector)
 *   X^{n+1}   = 2 X^{n+1/2} - X^n
 * with X = (r, v, rho, u) for fluid particles (dr/dt = v + XSPH correction)
 * and X = (rho, u) for wall particles (u: thermal energy per unit mass,
 * integrated like the density, paper A §9); the pressure follows from the EOS
 * in each stage's loop. The state before the step is saved in X0 (x0, y0,
 * vx0, vy0, rho0, u0) by the predictor (and by the leap-frog when the
 * store keeps the SAVED group: core/particles.h).
 */
#ifndef SPH_INTEGRATE_H
#define SPH_INTEGRATE_H

#include <math.h>

#include "core/particles.h"
#include "physics/eos.h"
#include "solver/forces.h"

/* Every update below is per particle; `cost` (n + 1 entries, or NULL)
 * splits the store among the threads as the neighbour loops do
 * (sph_slice in parallel.h), which changes only the time. */

/* X0 <- X, then X <- X0 + dt/2 F (the predictor), and the pressure. */
void sph_pc_half(sph_particles *p, double dt, int xsph, const sph_eos *eos, const size_t *cost);
/* X <- 2 (X0 + dt/2 F) - X0: the corrector half step and the final
 * update, and the pressure. */
void sph_pc_finish(sph_particles *p, double dt, int xsph, const sph_eos *eos, const size_t *cost);

/* The leap-frog of paper A eq. (17)-(19), one force evaluation per step.
 * Between steps the store holds x^n, the half-step values (vxh, vyh, rhoh)
 * = (v, rho)^{n-1/2}, and the values at t^n predicted from them,
 * (v, rho)^n = (v, rho)^{n-1/2} + dt/2 (dv, drho)/dt^{n-1}, at which the
 * rates are evaluated. After the rates at t^n are known:
 *   (v, rho)^{n+1/2} = (v, rho)^{n-1/2} + (dt_prev + dt)/2 (dv, drho)/dt^n
 *                      (first step: (v, rho)^0 + dt/2 (dv, drho)/dt^0)
 *   x^{n+1} = x^n + dt (v^{n+1/2} + XSPH correction)
 *   (v, rho)^{n+1} predicted = (v, rho)^{n+1/2} + dt/2 (dv, drho)/dt^n,
 * dt = t^{n+1} - t^n and dt_prev = t^n - t^{n-1}: with a step that changes
 * (the CFL rule, a step landing on an output time) the kick is the
 * velocity Verlet's half of each, and the scheme stays second order. */
void sph_leapfrog_step(sph_particles *p, double dt, double dt_prev, int first, int xsph,
                       const sph_eos *eos, const size_t *cost);

/* Paper B §2.6: dt = min_a factor h / (c_a + sigma_a), from the maximum of
 * c_a + sigma_a that the last interaction pass found (w->cs_sigma_max). */
double sph_dt_paper_b(const sph_force_work *w, double h, double factor);
/* Paper A eq. (20): dt = factor min h / max_a (c_a + |v_a|). */
double sph_dt_cfl(const sph_particles *p, const sph_eos *eos, double h, double factor);
/* c_a + |v_a| of particle i, what sph_dt_cfl takes the maximum of. */
static inline double sph_cfl_speed(const sph_particles *p, const sph_eos *eos, size_t i) {
  const double w2 = SPH_NORM2(p->vx[i], p->vy[i], p->vz[i]);
  return sph_eos_sound_speed(sph_eos_of(eos, sph_particles_phases(p), i), p->rho[i]) + sqrt(w2);
}
/* sph_dt_cfl from that maximum, vmax (a rank's pass finds it: solver/ranks.c). */
static inline double sph_dt_cfl_of(double vmax, double h, double factor) {
  return factor * h / vmax;
}

#endif
