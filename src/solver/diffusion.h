/*
 * diffusion.h - the per-particle part of the density diffusion
 * (src/physics/density_diffusion.h), set before each interaction pass
 * (internal to src/solver/).
 */
#ifndef SPH_DIFFUSION_H
#define SPH_DIFFUSION_H

#include "core/particles.h"
#include "neighbours/grid.h"
#include "solver/forces.h"

/* Fills w->ddcx, w->ddcy (n values, storage order) with the model's c_i:
 * zero (molteni_colagrossi), (rho0 / (2 c0^2)) g (fourtakas), or half the
 * renormalised density gradient (antuono: a pass over the list l, fluid
 * particles only, wall and mirror particles get 0). w must have room for
 * p->n particles. Each particle writes only its own entries: the same bits
 * for any thread count. Nothing to do when the diffusion is off. */
void sph_diffusion_prepare(const sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                           sph_force_work *w);

#endif
