/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * ledger.h - the energy and momentum ledger of a run (output.energy).
 *
 * Paper A §5 (eq. 28-29) checks a run by its energy: kinetic + potential
 * + internal (the heat of the pressure, artificial-viscosity and viscous
 * pair terms) stays constant, less the work that moving walls do on the
 * fluid. The ledger keeps, besides the state's own sums (diag.h):
 *   power_wall   sum over fluid i of m_i sum_{wall j} a_ij . v_j   (W)
 *   power_xsph   -sum over fluid i of m_i g . xs_i: the rate at which the
 *                XSPH correction (a displacement no force pays for)
 *                changes the potential energy                         (W)
 *   force        the external force on the fluid: walls, mirror
 *                particles and the body force                         (N)
 *   power_diffusion  sum over fluid i of m_i (p_i / rho_i^2) D_i, D_i the
 *                density diffusion's share of drho_i/dt               (W)
 *   wall_potential  sum over fluid i of m_i phi_i, the potential energy
 *                of the Lennard-Jones force of repulsive walls
 *                (repulsion.h; a state, not a rate)                   (J)
 * at the last interaction pass, and their time integrals work_wall,
 * drift_xsph, the impulse and work_diffusion. With these
 *   total     = kinetic + potential + internal + wall_potential
 *               - work_wall - drift_xsph - drift_shifting + energy_removed
 * (energy_removed: what the fluid that left the domain carried, outflow.h)
 *   deviation = (total - total_0) / total_0
 * closes to round-off for a conservative scheme, and the momentum residual
 * p - p_0 - impulse closes to round-off. The density diffusion moves no
 * particle, so it leaves that balance closed (internal is the work of the
 * pair forces, not the equation of state's elastic energy); work_diffusion
 * (the diagnostics' diffusion_energy column) is the elastic energy it adds
 * beyond that work, negative where it damps the density's noise. Sums run serially in storage
 * order: the same bits for any thread count.
 *
 * The per-pair parts (heat, a_ij . v_j, a_ij from walls) are pair terms
 * (src/physics/pair_terms.h) summed by the interaction loop into du and
 * the pass's wpow, wfx, wfy; this file sums them over the particles,
 * integrates them in time (one call for both integrators: the rates that
 * drive the step drive the ledger), and writes them to the diagnostics
 * row and the restart record.
 */
#ifndef SPH_LEDGER_H
#define SPH_LEDGER_H

#include "core/exact_sum.h"
#include "core/particles.h"
#include "solver/diag.h"
#include "solver/forces.h"
#include "solver/outflow.h"

/* The number of doubles a restart record keeps (sph_ledger_save). */
#define SPH_LEDGER_SAVED (2 + SPH_DIM) /* wall work, XSPH drift, an impulse per axis */

typedef struct sph_ledger {
  /* rates at the last pass */
  double power_wall, power_xsph, power_diffusion;
  int repulsion;         /* repulsive walls: wall_potential is part of the total */
  double wall_potential; /* their Lennard-Jones potential energy at the last pass */
  double force_x, force_y;
#if SPH_DIM == 3
  double force_z;
#endif
  /* their time integrals */
  double work_wall, drift_xsph, work_diffusion;
  double drift_shifting; /* potential energy of particle shifting's moves (physics/shifting.h) */
  double impulse_x, impulse_y;
#if SPH_DIM == 3
  double impulse_z;
#endif
  /* the initial state */
  double e0, e0_fluid; /* total, and the fluid's own kinetic + potential + internal */
  double p0x, p0y;     /* fluid momentum */
#if SPH_DIM == 3
  double p0z;
#endif
  double m0; /* fluid mass (exact: it never changes) */
} sph_ledger;

/* The rates of the pass just run (w holds its wpow, wfx, wfy, and dd with
 * density diffusion; p its xsx, xsy when XSPH is on), over the fluid
 * particles of p. */
void sph_ledger_rates(sph_ledger *lg, const sph_particles *p, const sph_force_work *w,
                      const double gravity[SPH_DIM], int xsph, int diffusion);

/* The same in parts, for a store split among ranks (solver/ranks.c): the
 * rates' exact sums (exact_sum.h) over the fluid particles whose flags
 * hold none of the bits `skip`, added into t; sums of several ranks merged
 * (exactly, in any order); then rounded once into lg. */
#define SPH_LEDGER_SUMS 8
typedef struct sph_ledger_sums {
  sph_xsum s[SPH_LEDGER_SUMS];
} sph_ledger_sums;
void sph_ledger_sums_init(sph_ledger_sums *t);
void sph_ledger_sums_add(sph_ledger_sums *t, const sph_ledger *lg, const sph_particles *p,
                         const sph_force_work *w, const double gravity[SPH_DIM], int xsph,
                         int diffusion, unsigned skip);
void sph_ledger_sums_merge(sph_ledger_sums *t, const sph_ledger_sums *u);
void sph_ledger_finish(sph_ledger *lg, sph_ledger_sums *t, const double gravity[SPH_DIM]);

/* Integrates the rates over a step of dt (the rates of the pass that
 * drives the step: t^n for the leap-frog, the mid-step for the
 * predictor-corrector). */
void sph_ledger_advance(sph_ledger *lg, double dt);

/* What the mirror lines and tank faces did to the fluid in a step by
 * moving particles off them (walls.h, sph_walls_keep_off: kick = sum m dr
 * by axis, then sum m dv by axis): the lift's potential energy -g . sum m dr is the walls' work,
 * the velocity change their impulse. */
void sph_ledger_add_kick(sph_ledger *lg, const double kick[2 * SPH_DIM],
                         const double gravity[SPH_DIM]);

/* What particle shifting did to the fluid in a step (physics/shifting.h:
 * moved = sum m dr over the fluid, by axis): a move no force pays for,
 * whose potential energy -g . moved is booked as drift_shifting (the
 * diagnostics' shifting_drift column), as the XSPH correction's is. */
void sph_ledger_add_shift(sph_ledger *lg, const double moved[SPH_DIM],
                          const double gravity[SPH_DIM]);

/* Completes a diagnostics row (row->kinetic, potential and momentum
 * already filled by sph_diag_compute) with the ledger's columns, given the
 * stored heat sum m_i u_i of every particle (u: dynamic walls take half a
 * pair's) and of the fluid alone (u_fluid; diag_sums.h sums both); out (or
 * NULL) is the fluid that left the domain (outflow.h): its energy joins
 * the totals (the energy_removed column) and its momentum the balance. */
void sph_ledger_fill(const sph_ledger *lg, double u, double u_fluid, const sph_outflow *out,
                     sph_diag_row *row);

/* Takes the initial totals from the first row (filled by
 * sph_ledger_fill with zero integrals) and the fluid's stored heat. */
void sph_ledger_start(sph_ledger *lg, double u_fluid, const sph_diag_row *row);

/* The time integrals for a restart record, and back. */
void sph_ledger_save(const sph_ledger *lg, double out[SPH_LEDGER_SAVED]);
void sph_ledger_restore(sph_ledger *lg, const double in[SPH_LEDGER_SAVED]);

#endif
