/* SPDX-License-Identifier: BSD-3-Clause */
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
 * particles only, wall and mirror particles get 0); and w->ddm with the
 * mass each particle diffuses with: m_i for a fluid particle whose support
 * holds no mdbc wall particle, 0 for the others. Pairs diffuse only where
 * both masses are not zero, so the fluid next to an mdbc wall keeps the
 * density the continuity equation gives it, as DualSPHysics' Fourtakas
 * term does next to any boundary (its DensityDT 2): a particle pressed
 * onto an mdbc floor is held off it by its own compression, which the
 * diffusion would otherwise spread into the fluid above, while the wall's
 * density, taken from the fluid, does not rise either (the bottom row of
 * the coarse dam break sank from 0.5 dx to 0.25 dx above the floor's face
 * within 2 s, held there by the walls' guard, walls.h). Next to dynamic
 * walls, whose density rises as the fluid comes near, the diffusion stays
 * on: off there, the coarse dam break's largest isolated pressure spike
 * went from 1.1 to 6.5 rho0 g 2a (tests/test_pressure_noise). The pairs
 * left still move density only within the fluid (sum_i V_i D_i = 0). w must have room for p->n
 * particles. Each particle writes only its own entries: the same bits for any thread count. Nothing
 * to do when the diffusion is off. */
void sph_diffusion_prepare(const sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                           sph_force_work *w);

#endif
