/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * shifting.h - particle shifting (numerics.shifting): after every step each
 * fluid particle moves a small distance down the gradient of the particle
 * concentration, which keeps the particles' arrangement from clumping where
 * the pressure is negative or zero (the tensile instability): in the thin
 * sheet of a jet running up a wall, for example (tests/test_walls.c).
 *
 * For fluid particle i, over all its neighbours j (fluid and wall particles
 * alike, so that a wall counts as full of particles and the fluid's first
 * row beside it is not a free surface: DualSPHysics' "full" shifting),
 * V_j = m_j / rho_j:
 *
 *   grad C_i = sum_j [1 + R (W_ij / W(dx))^n] grad_i W_ij V_j
 *                      the concentration gradient with the term of Lind,
 *                      Xu, Stansby & Rogers (2012) that pushes apart pairs
 *                      closer than dx harder, R = 0.2 and n = 4 (theirs);
 *   dr_i     = -D_i grad C_i,  D_i = A h |v_i| dt
 *                      Fick's law as Lind et al. (2012) take it, with the
 *                      coefficient of Skillen, Lind, Stansby & Rogers
 *                      (2013); A = numerics.shifting.coefficient, 2 by
 *                      default (their range 1-6);
 *   div r_i  = -sum_j r_ij . grad_i W_ij V_j  (Lee et al. 2008: the
 *                      dimension in the bulk; on a square lattice at
 *                      h = 1.3 dx 2.02 inside, 1.28 in the top row of a flat
 *                      surface; on a cubic one 2.98 inside, 2.03 in the top
 *                      layer).
 *
 * Near the free surface (div r_i < SPH_SHIFTING_SURFACE_DIV: 1.5 in 2-D,
 * 2.75 in 3-D, the thresholds DualSPHysics documents for its ShiftTFS)
 * only dr_i's part along the surface is kept:
 * the part along n_i = -grad C_i / |grad C_i| (the plain sum, pointing out
 * of the fluid) is removed, Lind et al.'s (2012) free-surface correction;
 * a surface particle would otherwise be pushed out of the fluid.
 *
 * The displacement changes no velocity, density or heat: its only effect
 * on the energy is the potential energy of the move, -g . sum_i m_i dr_i,
 * which the ledger books (shifting_drift, src/solver/ledger.h). Each sum
 * runs over i's neighbour row in storage order, and every particle's
 * displacement is computed before any particle moves: the result does not
 * depend on the thread count.
 */
#ifndef SPH_SHIFTING_H
#define SPH_SHIFTING_H

#include <stddef.h>

#include "core/particles.h"
#include "neighbours/grid.h"
#include "physics/models.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A of Skillen et al. (2013), the default of numerics.shifting.coefficient */
#define SPH_SHIFTING_COEFFICIENT_DEFAULT 2.0
/* R and n of Lind et al. (2012) */
#define SPH_SHIFTING_TENSILE 0.2
#define SPH_SHIFTING_EXPONENT 4
/* div r below which a particle counts as near the free surface */
#if SPH_DIM == 2
#define SPH_SHIFTING_SURFACE_DIV 1.5
#else
#define SPH_SHIFTING_SURFACE_DIV 2.75
#endif

typedef struct sph_shifting_params {
  double coefficient; /* A */
  double h, dx;       /* smoothing length and particle spacing */
  sph_kernel_kind kernel;
} sph_shifting_params;

/* The sums of one particle's row. */
typedef struct sph_shifting_sums {
  SPH_COMPONENTS(double, g, gx, gy, gz);     /* grad C_i, unweighted (the normal) */
  SPH_COMPONENTS(double, tg, tgx, tgy, tgz); /* grad C_i with Lind's term (the displacement) */
  double div;                                /* div r_i */
} sph_shifting_sums;

/* The sums of fluid particle i over its row of l (pairs within 2h; the
 * separations as the list measures them, periodic along its axis). */
void sph_shifting_sums_of(const sph_particles *p, const sph_nlist *l, const sph_shifting_params *sp,
                          size_t i, sph_shifting_sums *s);

/* The displacement d of a particle from its sums and its diffusivity
 * A h |v| dt: -A h |v| dt grad C, along the surface only where
 * div r < SPH_SHIFTING_SURFACE_DIV. */
void sph_shifting_displacement(const sph_shifting_sums *s, double diffusivity, double d[SPH_DIM]);

/* The displacements d[a][i] along every axis a of every fluid particle i of
 * p for a step of dt (0 for other particles), from l (built on p's current
 * positions, radius >= 2h). */
void sph_shifting_compute(const sph_particles *p, const sph_nlist *l, const sph_shifting_params *sp,
                          double dt, double *const d[SPH_DIM]);

#ifdef __cplusplus
}
#endif

#endif
