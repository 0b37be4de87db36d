/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * forces.h - the interaction passes: rates of change of every particle from
 * its neighbours (gather form: each particle sums over its own neighbours
 * into its own accumulators, so no two threads write the same memory and
 * the summation order is fixed by the sorted store).
 *
 * Terms (paper A = dam-break paper, paper B = breaking-wave paper):
 *   continuity       drho_i/dt = sum_j m_j (v_i - v_j) . grad_i W_ij      (B eq. 2, A eq. 12),
 *                    over fluid neighbours only for a wall particle i
 *   momentum         dv_i/dt = -sum_j m_j (p_i/rho_i^2 + p_j/rho_j^2 + Pi_ij) grad_i W_ij + g
 *                                                                         (A eq. 11, B eq. 3)
 *   art. viscosity   Pi_ij = (-alpha c_ij mu_ij + beta mu_ij^2)/rho_ij if v_ij.r_ij < 0, else 0
 *                    mu_ij = h_ij v_ij.r_ij / (r_ij^2 + eta^2), eta = eta_f h_ij (A eq. 15-16)
 *   viscous stress   + sum_j m_j sum_d (tau_i^ad/rho_i^2 + tau_j^ad/rho_j^2) dW_ij/dx_i^d,
 *                    tau = mu eps, eps from the strain-rate pass          (A eq. 11, 13, 14)
 *   Morris viscosity + sum_j m_j 4 nu0 r_ij.grad_i W_ij / ((rho_i + rho_j)(r_ij^2 + eta^2)) v_ij
 *                    nu0 = mu / rho0                                       (B eq. 4, laminar)
 *   XSPH             dr_i/dt = v_i + eps sum_j (m_j/rho_ij) (v_j - v_i) W_ij  (B eq. 6),
 *                    over fluid neighbours only (a wall at rest would drag
 *                    the fluid otherwise)
 *   SPS turbulence   + sum_j m_j (tau*_i/rho_i^2 + tau*_j/rho_j^2) . grad_i W_ij, tau* the
 *                    Smagorinsky SPS stress of src/physics/turbulence.h       (B eq. 4)
 *   Lennard-Jones    + D [(r0/r)^12 - (r0/r)^4] r_ij / r^2 from repulsive wall particles
 *                    closer than r0                                        (A eq. 21-22)
 *   density diff.    + delta h c0 sum_j psi_ij (r_ji . grad_i W_ij) / r_ij^2 V_j on drho_i/dt,
 *                    fluid pairs only (physics/density_diffusion.h: Molteni &
 *                    Colagrossi 2009, Antuono et al. 2010, Fourtakas et al. 2019)
 *   time-step data   sigma_i = max_j |h v_ij.r_ij / r_ij^2|                 (B §2.6)
 *   energy ledger    du_i/dt = 1/2 sum_j m_j (p_i/rho_i^2 + p_j/rho_j^2 + Pi_ij) v_ij.grad_i W_ij
 *                    (A eq. 28-29, with the artificial-viscosity share) plus the
 *                    viscous dissipation in the pairwise form that balances
 *                    the viscous force's work exactly, for fluid and dynamic
 *                    wall particles (each takes half of a pair's heat); and
 *                    the power sum_j a_ij . v_j of wall particles j on fluid i
 * Dynamic wall particles (GOST R 57700.6 3.4.7) get drho/dt (and du/dt with
 * the ledger); repulsive wall particles and mirror particles get no rates. Walls and mirrors act on
 * fluid through their pressure and the viscous terms.
 *
 * Kernel-gradient correction of the pressure (numerics.gradient_correction;
 * Bonet and Lok 1999, CMAME 180:97, their symmetric form): the pressure
 * force, its artificial viscosity, their heat and the continuity term take
 * L_ij grad_i W_ij in place of grad_i W_ij, L_ij = (L_i + L_j) / 2, with
 * L = M^-1 of every particle from the strain-rate pass's moment M (below;
 * forces.c, moment_pass). L_ij is the same for both particles of a pair,
 * so the force stays antisymmetric (momentum conserved) and the
 * continuity term matches the pressure's work (the ledger closes). A
 * linear pressure field then balances exactly inside the water, which the
 * cubic spline's lattice sum at h = 1.3 dx misses by 0.65 % in 3-D
 * (M_zz = 0.9935; 1.0105 in 2-D), enough to leave a still tank's floor
 * 1.8 % over rho0 g H (doc/dimensions.md). The viscous terms keep
 * grad_i W_ij.
 *
 * Kernel-gradient correction of the stress tensor (physics.viscosity.
 * gradient_correction; Bonet and Lok 1999): the strain-rate pass sums
 * G_ab = sum_j V_j (v_j - v_i)_a dW_ij/dx_i^b and the moment
 * M_ab = sum_j V_j (x_j - x_i)_a dW_ij/dx_i^b, and takes grad v = G M^-1
 * (exact for a linear field whatever the neighbours); the stress divergence
 * then uses sym(tau L_i), L = M^-1, in place of tau_i, so that a linear
 * stress has its exact divergence while the pair terms stay antisymmetric
 * (momentum conserved). On a square lattice at h = 1.3 dx M = 1.0105 I,
 * so without it the nested gradients make the Laplacian 2.1 % too large.
 * Where det M <= SPH_GRADIENT_CORRECTION_MIN_DET (the free surface, the
 * outer layers of a wall) L = I: inverting a truncated moment there
 * amplifies noise (at 4900 particles the film blew up at 0.05 s with 0.25).
 * With extrapolated wall velocities (wall_velocity.h) the strain-rate pass
 * reads the wall particles' ghost velocities.
 *
 * The term sets the shipped cases run have loops of their own, the terms
 * they do not use compiled out (DESIGN rule 4); every other set runs a
 * loop compiled for its heaviest terms that tests the others per pair
 * (interact.h, LANE_LOOPS and SCALAR_LOOPS).
 */
#ifndef SPH_FORCES_H
#define SPH_FORCES_H

#include "core/particles.h"
#include "neighbours/grid.h"
#include "solver/force_pass.h"

/* Whether the loop can run on this build and processor. */
int sph_force_loop_available(sph_force_loop loop);

/* Whether the loop asked for is the portable lanes or the scalar loop: the
 * passes beside the interaction loop (the free-surface scan, the walls'
 * fits) then take no wider lanes either (the same bits whichever they take;
 * SPH_TEST_LANES=portable or scalar asks for it). */
static inline int sph_force_loop_narrow(sph_force_loop loop) {
  return loop == SPH_LOOP_SCALAR || loop == SPH_LOOP_LANES;
}

void sph_force_work_free(sph_force_work *w);

/* Room in w for n particles (the contents carried over): for a caller
 * that fills one of its arrays before the pass (adami walls' gv). */
int sph_force_work_reserve(sph_force_work *w, size_t n, sph_error *err);
/* Particle i's packed copy made again from the store (after a pass's
 * preparation gave it its own: a value that came later, force_pass.h's
 * late rows). */
void sph_force_work_repack(const sph_particles *p, const sph_force_params *fp, sph_force_work *w,
                           size_t i);

/* Sets p->p from the equation of state for every particle. */
void sph_forces_pressure(sph_particles *p, const sph_eos *eos);

/* One interaction pass over the neighbour list l (complete for the
 * support 2 h, 2 max h with var_h, and for the Lennard-Jones range r0 on
 * p's current positions: see sph_nlist_fresh): fills p->drho, p->ax, p->ay
 * (and p->xsx, p->xsy when XSPH is on), w->hot (its cs the sound speed),
 * w->cs_sigma_max and, with w->keep_sigma, w->sigma. Needs p->p current. */
int sph_forces_evaluate(sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                        sph_force_work *w, sph_error *err);

/* The loop the main pass runs with fp, as the run reports it: "scalar"
 * (asked for, per-particle h, mirror walls), "portable lanes", "AVX2
 * lanes" or "AVX-512 lanes" (SPH_LOOP_AUTO: the widest the processor has). */
const char *sph_force_loop_name(const sph_force_params *fp);

/* Rounds of the start-up choice of lane loop, and the margin by which the
 * AVX2 loop must be faster to be chosen over the AVX-512 one. */
#define SPH_FASTEST_ROUNDS 3
#define SPH_FASTEST_MARGIN 0.03

/* The lane loop (*loop) a run with fp->loop = SPH_LOOP_AUTO should use on
 * this processor: where both the AVX2 and the AVX-512 loops can run, each
 * evaluates the pass on p SPH_FASTEST_ROUNDS times, interleaved, and the
 * AVX2 loop is chosen if its fastest time is under (1 - margin) times the
 * AVX-512 loop's (some processors run AVX-512 divisions and square roots
 * at half the rate, or lower their clock for it). *ratio gets AVX2 time /
 * AVX-512 time (1 where nothing was measured). Both loops give the same
 * bits, so the choice moves run time only; the pass's rates are left as
 * one evaluation leaves them. Otherwise *loop = fp->loop (SPH_LOOP_AUTO
 * where a single lane loop can run, or for per-particle h and mirror
 * walls). Non-zero if an evaluation failed. */
int sph_forces_fastest_loop(sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                            sph_force_work *w, sph_force_loop *loop, double *ratio, sph_error *err);
/* The lane loop sph_forces_fastest_loop takes for a ratio of AVX2 time to
 * AVX-512 time (the processes of a run agree on one: solver/ranks.c). */
sph_force_loop sph_forces_loop_for_ratio(double ratio);

/* The strain-rate tensor of paper A eq. (13)-(14) at every particle, for
 * tests and output: eps[SPH_XX], eps[SPH_XY], ... (each n values,
 * core/tensor.h); with fp's gradient correction and extrapolated wall
 * velocities when set. */
int sph_forces_strain_rate(const sph_particles *p, const sph_grid *g, const sph_force_params *fp,
                           double *const eps[SPH_SYM], sph_error *err);

#endif
