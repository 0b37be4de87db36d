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
#include "solver/force_pass.h"

/* Whether a particle of this kind and these flags takes part in the
 * diffusion as a wall: a dynamic or fixed_layers wall particle (not mdbc
 * or adami, whose density is the fluid's already; not repulsive; not a
 * mirror particle). The fluid next to adami walls diffuses among its
 * fluid neighbours, as AHA12's and TrixiParticles' fluid does. */
int sph_diffusion_wall_takes_part(int32_t kind, uint8_t flags);

/* Whether the diffusion is on and some particle of p takes part in it as a
 * wall (set-up's fp->wall_diffusion). Not with antuono: its c_i is the
 * renormalised density gradient, and at a wall particle the one its wall
 * neighbours give is not the water's (deeper layers without fluid are
 * reset to rho0, dbc.h): on the 3-layer tank at rest of
 * tests/test_density_diffusion the pressure error rose from 0.35 % to
 * 2.1 % of rho0 g H. With fourtakas (c_i the hydrostatic term, the same
 * everywhere) it is 0.26 % either way, with molteni_colagrossi 0.95 %
 * (2.03 % without the walls' pairs). */
int sph_diffusion_walls(const sph_particles *p, const sph_force_params *fp);

/* Fills w->ddc0 with the model's c_i where it is the same at every
 * particle: zero (molteni_colagrossi) or (rho0 / (2 c0^2)) g (fourtakas);
 * or w->ddc[axis] (n values each, storage order) with half the renormalised
 * density gradient (antuono: a pass over the list l, fluid particles only,
 * wall and mirror particles get 0). And, unless mass_is_fm
 * (sph_diffusion_mass_is_fm: the pass reads w->fm, the same values), w->ddm with
 * the mass each particle diffuses with: m_i for a fluid particle whose
 * support holds no mdbc wall particle and, with fp->wall_diffusion, for a
 * dynamic or fixed_layers wall particle; 0 for the others. A pair diffuses
 * where both masses are not zero and one of the two is fluid: fluid with
 * fluid, fluid with such a wall, never wall with wall. The walls' pairs
 * (issue 18): a dynamic wall particle's density follows the water next to
 * it instead of keeping what an impact left; without them the coarse dam
 * break's floor read 6.3 times the load of the settled water on it two
 * seconds later and the water stood 1.33 dx above the floor's face (with
 * them 1.0 and 0.8 dx, tests/test_walls). The fluid next to an mdbc
 * wall (mass 0) keeps the
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
 * move density only among the particles that take part (sum_i V_i D_i = 0
 * over fluid and walls; within the fluid alone where no wall takes part).
 * w must have room for p->n particles. Each particle writes only its own
 * entries: the same bits for any thread count. Nothing to do when the
 * diffusion is off. */
void sph_diffusion_prepare(const sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                           sph_force_work *w, int mass_is_fm);

/* Whether the mass each particle diffuses with is w->fm's (the fluid's
 * mass, 0 for the others), which the pass fills with XSPH on: no mdbc wall
 * takes it away from the fluid next to it and no wall diffuses. */
static inline int sph_diffusion_mass_is_fm(const sph_force_params *fp, int xsph) {
  return xsph && !fp->mdbc && !fp->wall_diffusion;
}

#endif
