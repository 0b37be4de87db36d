/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * filter.h - density re-initialisation filters (paper B §2.8).
 *
 * Every N steps (paper B: N = 30) the density of each particle is replaced
 * by a kernel average of its neighbours' masses, which removes the
 * short-wavelength noise that the equation of state turns into pressure
 * noise. Two named choices (`density_filter: mls | shepard | none`):
 *
 *   mls      first-order moving-least-squares re-initialisation, paper B
 *            §2.8: rho_a = sum_b m_b W^MLS_ab; exact for density fields
 *            that are linear in x and y;
 *   shepard  zeroth order: rho_a = sum_b m_b W_ab / sum_b (m_b/rho_b) W_ab;
 *            exact for constant fields only; about 20 % cheaper;
 *   none     the density is left alone.
 *
 * Which particles: by default fluid particles are re-initialised and every
 * particle in the support counts as a neighbour, wall particles included
 * (the SPHysics choice: dynamic wall particles carry a density and a mass
 * like fluid ones, and a fluid particle near a wall then has a full
 * neighbourhood). `filter_walls` also re-initialises wall particles
 * (kind SPH_KIND_WALL; other fictitious kinds never are);
 * `same_kind_only` restricts the sums to particles of the filtered
 * particle's own kind (fluid from fluid, wall from wall). A particle always
 * counts itself (b = a).
 *
 * Use: between time steps, on a grid built for the current positions and
 * storage order (sph_grid_build), with cells of side >= 2h (2 max h in the
 * variable-h mode). The filters change rho only; the caller recomputes the
 * pressure from the equation of state afterwards.
 */
#ifndef SPH_FILTER_H
#define SPH_FILTER_H

#include <stddef.h>

#include "core/error.h"
#include "core/particles.h"
#include "neighbours/grid.h"
#include "physics/models.h"

/* Default fallback threshold of the MLS filter (see mls_det_min). */
#define SPH_FILTER_MLS_DET_MIN 1e-3

typedef struct sph_filter_params {
  /* Smoothing length of the pair kernel W_ab. > 0: this constant h for
   * every pair; 0: variable h, W_ab evaluated with the pair mean
   * (p->h[a] + p->h[b]) / 2 (symmetric in the pair). */
  double h;
  int filter_walls;   /* 1: re-initialise wall particles too; default 0 */
  int same_kind_only; /* 1: neighbours of the particle's own kind only; default 0 */
  /* MLS falls back to the Shepard value for a particle whose moment matrix
   * A (positions in units of h_a) has det(A) / (tr(A)/3)^3 below this
   * (det(A) / (tr(A)/4)^4 in 3-D, where A is 4x4; a number in [0, 1]: 0 for
   * a singular A, 1 for A proportional to the identity). Default
   * SPH_FILTER_MLS_DET_MIN. */
  double mls_det_min;
  sph_kernel_kind kernel; /* the case's kernel; default the cubic spline */
} sph_filter_params;

/* The defaults above, with the given constant h (0: variable h). */
void sph_filter_params_default(sph_filter_params *fp, double h);

/* First-order MLS density re-initialisation (paper B §2.8). scratch holds
 * p->n doubles. If fallbacks is not NULL it receives the number of
 * particles that got the Shepard value instead (degenerate neighbourhood).
 * Returns 0, or -1 with err on a bad argument (nothing is changed then). */
int sph_filter_mls(sph_particles *p, const sph_grid *g, const sph_filter_params *fp,
                   double *scratch, size_t *fallbacks, sph_error *err);

/* Zeroth-order (Shepard) density re-initialisation; arguments as above
 * (*fallbacks is set to 0). */
int sph_filter_shepard(sph_particles *p, const sph_grid *g, const sph_filter_params *fp,
                       double *scratch, size_t *fallbacks, sph_error *err);

/* The filter of the given kind; SPH_FILTER_NONE does nothing and returns 0. */
int sph_filter_apply(sph_filter_kind k, sph_particles *p, const sph_grid *g,
                     const sph_filter_params *fp, double *scratch, size_t *fallbacks,
                     sph_error *err);

#endif
