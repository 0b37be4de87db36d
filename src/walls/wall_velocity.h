/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * wall_velocity.h - the extrapolated (no-slip) velocity of wall particles.
 *
 * Morris, Fox and Zhu (1997) give the wall particles, in the viscous terms
 * only, a velocity extrapolated from the fluid so that the velocity
 * vanishes on the wall face itself rather than somewhere inside the wall
 * layers: with the face at distance d_B behind wall particle B and d_A in
 * front of fluid particle A, v_B = -(d_B/d_A) v_A. Paper A (§6 b) calls
 * such walls "Morris particles". Here the extrapolation is done once per
 * wall particle, through its mirror point across the face: a wall particle
 * at depth d carries
 *
 *     v_ghost = 2 v_wall - v_fluid(x + m),   m = 2 d n
 *
 * with n the face's normal into the fluid, v_wall its own (prescribed)
 * velocity and v_fluid the fluid's velocity at the mirror point: the value
 * at that point of the linear moving-least-squares fit to the fluid
 * particles j within reach (weights W(x + m - x_j, h_j)), exact for a
 * linear field even though the wall cuts the kernel there (the Shepard
 * average sum_j v_j W / sum_j W, biased into the fluid, doubled the film's
 * error next to the bed); the Shepard average only where the fit's moment
 * matrix is near singular. For a velocity field linear in the distance
 * from a straight face the ghost is v(x) continued through the face,
 * exactly; the same ghost velocity serves every fluid
 * neighbour, so the wall particles' own strain rates (paper A eq. 13),
 * which enter the stress divergence, are those of the continued field too.
 * A mirror point with no fluid within reach leaves the wall velocity.
 *
 * The mirror offset m of each wall particle (particles.h: mx, my, and mz in
 * 3-D) is set when the wall is built (boundary.h); SPH_FLAG_NO_SLIP marks
 * the particles of walls with `extrapolated_velocity: true`. The fit has
 * SPH_DIM + 1 unknowns (value and gradient): a 3 x 3 system in 2-D (by
 * Cramer's rule), 4 x 4 in 3-D (core/linsolve.h).
 */
#ifndef SPH_WALL_VELOCITY_H
#define SPH_WALL_VELOCITY_H

#include <stddef.h>
#include <stdint.h>

#include "core/error.h"
#include "core/particles.h"

/* Scratch of the interpolation: the fluid particles binned in cells of
 * side >= the largest support (kept between calls). */
typedef struct sph_wall_velocity_work {
  size_t *start; /* cell offsets into idx */
  uint32_t *idx; /* fluid storage indices by cell, in storage order within a cell */
  size_t *key;   /* cell of each particle (scratch) */
  double *pack;  /* the coordinates and h of the particles of idx, slot by slot: SPH_DIM + 1
                    arrays of cap_n, so that a fit reads its candidates in a row */
  size_t cap_cells, cap_n;
  /* 1: the fits test and weigh their candidates two at a time even where
   * the processor has AVX-512 (eight at a time, the default); the same
   * bits either way (the sums take them one by one in the same order).
   * The tests' SPH_TEST_LANES=portable or scalar sets it. */
  int narrow;
} sph_wall_velocity_work;

void sph_wall_velocity_work_free(sph_wall_velocity_work *w);

/* gv[a] (SPH_DIM arrays of n values) = the velocity of every particle in
 * the viscous terms: the ghost velocity above for particles flagged
 * SPH_FLAG_NO_SLIP, the particle's own velocity for all others but adami
 * wall particles, whose entries are left as they are (walls/adami.h sets
 * them). `support`
 * is the kernel's reach (2 max h); period > 0: the domain is periodic
 * along axis paxis over [px0, px0 + period). Deterministic: each sum runs
 * in cell order, storage order within a cell, whatever the thread count. */
int sph_wall_velocity(const sph_particles *p, double support, double px0, double period, int paxis,
                      double *const *gv, sph_wall_velocity_work *w, sph_error *err);

/* The modified dynamic boundary condition (mDBC; English, Dominguez,
 * Vacondio, Crespo, Stansby, Lind, Chiapponi and Gomez-Gesteira,
 * Computational Particle Mechanics 9, 2022) for the wall particles flagged
 * SPH_FLAG_MDBC: instead of evolving by continuity, a wall particle takes
 * the density of the fluid extrapolated to it through its mirror point
 * x + m across the wall face: the linear MLS fit of the fluid density at
 * x + m (the same fit as the ghost velocity above), evaluated at the wall
 * particle, rho = rho_g - m . grad rho_g, limited to the largest density
 * among the fluid particles of the fit plus the weight of the fluid
 * between the particle that holds it, x_j, and the wall particle x:
 * head . (x - x_j), where head = rho0 g / c0^2 is the density's
 * hydrostatic gradient, so that a hydrostatic density passes the limit
 * exactly. Without the limit the extrapolation over up to 2 dx overshot at
 * an impact (1.3 rho0 in a corner of the coarse dam break) and an ill-posed
 * fit fed on itself (1.9e14 kg/m^3 in the 3-D energy box); without the
 * weight it cut every hydrostatic extrapolation to the fit's densest
 * particle, and on a 3-D cylinder's top the walls over its axis, whose fits
 * see only the water above, took the first row's density where those
 * nearer its rim, whose fits reach the deeper water beside it, took the
 * hydrostatic one: the water over the axis sank into the cylinder.
 * Where no fluid reaches the mirror point, rho0; and never below rho0, so
 * a wall pushes the fluid but never pulls it (a wall particle left with a negative pressure held
 * a film of fluid on the dam break's back wall). Sets p->rho of those
 * particles; the caller sets their pressure from the equation of state. */
int sph_wall_mdbc_density(sph_particles *p, double support, double px0, double period, int paxis,
                          double rho0, const double head[SPH_DIM], sph_wall_velocity_work *w,
                          sph_error *err);

#endif
