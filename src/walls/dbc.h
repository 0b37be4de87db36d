/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * dbc.h - the bounds on the density of dynamic boundary particles.
 *
 * Dynamic particles (paper B §2.7; GOST R 57700.6 3.4.7) and Morris' fixed
 * layers (paper A §6 b) carry a density from the continuity equation and a
 * pressure from the equation of state. Left to that alone, a wall particle
 * the fluid moves away from drops below rho0, and its negative pressure
 * pulls the fluid onto the wall: a film of one or two particles hung on the
 * Martin & Moyce back wall at 0.97-0.996 of the column height for the whole
 * run, and a lifted gate carried the water beside it upwards. A wall
 * particle the fluid has left keeps whatever density it last had, and
 * pushes the next fluid that comes near with that stale pressure.
 *
 * The two bounds, applied to the state every interaction pass reads:
 *   - rho >= rho0: a wall pushes the fluid, it never pulls it (the
 *     correction SPHysics applies to its dynamic boundaries, after Hughes
 *     and Graham 2010; DualSPHysics' DBC does the same);
 *   - rho = rho0 where no fluid particle is within the kernel's support:
 *     with no fluid near, the wall carries the ambient pressure, and fluid
 *     that comes back meets a wall at rest, not the pressure of an earlier
 *     impact.
 * Neither changes the energy ledger's balance: a pair's heat is booked with
 * the pressures the pass used, whatever they are (method.md, Energy ledger).
 */
#ifndef SPH_DBC_H
#define SPH_DBC_H

#include "core/particles.h"
#include "neighbours/grid.h"

/* Applies both bounds to every wall particle of a dynamic or fixed_layers
 * wall (kind SPH_KIND_WALL, none of SPH_FLAG_REPULSIVE, _MDBC, _ADAMI):
 * its density (and, when half_step is set, its leap-frog half-step density
 * rhoh) is raised to rho0 where below, and set to rho0 where no fluid
 * particle of the list l is closer than `support` (the minimum image along
 * the list's periodic axis); its pressure is then the equation of state's at
 * rho0, 0. Per particle, so bitwise the same for any thread count.
 * Returns the number of particles changed. */
long sph_dbc_bound(sph_particles *p, const sph_nlist *l, double support, double rho0,
                   int half_step);

#endif
