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

/* Adds the force of every repulsive wall particle within r0 to the
 * acceleration of each fluid particle, over the neighbour list l (complete
 * for r0); D = d; period > 0 takes the minimum image in x. */
void sph_repulsion_add(sph_particles *p, const sph_nlist *l, double d, double r0, double period);

#endif
