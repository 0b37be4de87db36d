/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * repulsion.h - repulsive walls (paper A eq. 21-22): a single layer of wall
 * particles (SPH_FLAG_REPULSIVE) pushes a fluid particle closer than r0
 * away with the Lennard-Jones force
 *   a_i += D [(r0/r)^12 - (r0/r)^4] r_ij / r^2
 * (the term itself is lennard_jones_FL of src/physics/pair_terms.h).
 */
#ifndef SPH_REPULSION_H
#define SPH_REPULSION_H

#include "core/particles.h"
#include "neighbours/grid.h"

/* What the energy ledger needs of the force (NULL arrays: not wanted):
 * per fluid particle, the sums over its repulsive neighbours of the force
 * per unit mass (added to wf[axis]), of its power a_ij . v_j (added to
 * wpow: a moving wall's work) and the potential energy per unit mass
 * D [(r0/r)^12 / 12 - (r0/r)^4 / 4 + 1/6] (set in phi, 0 at r0) whose
 * gradient the force is, so that kinetic + potential + this energy is
 * conserved by the force of walls at rest. */
typedef struct sph_repulsion_ledger {
  double *const *wf; /* wf[axis] */
  double *wpow, *phi;
} sph_repulsion_ledger;

/* Adds the force of every repulsive wall particle within r0 to the
 * acceleration of each fluid particle, over the neighbour list l (complete
 * for r0; separations as it measures them, the minimum image along its
 * periodic axis); D = d. lg: NULL, or the ledger's sums. */
void sph_repulsion_add(sph_particles *p, const sph_nlist *l, double d, double r0,
                       const sph_repulsion_ledger *lg);

#endif
