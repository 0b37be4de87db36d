/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * density_diffusion.h - a diffusive term in the continuity equation, which
 * removes the high-frequency noise of the density (and so of the pressure)
 * of weakly-compressible SPH (numerics.density_diffusion).
 *
 * Every model adds to drho_i/dt, for fluid i, over fluid neighbours j (and
 * the dynamic wall pairs below):
 *
 *   D_i = delta h c0 sum_j psi_ij (r_ji . grad_i W_ij) / |r_ij|^2  V_j,
 *         V_j = m_j / rho_j, r_ji = x_j - x_i,
 *
 * where psi_ij = 2 [(rho_j - rho_i) + c_ij . r_ij], r_ij = x_i - x_j, and
 * c_ij = c_i + c_j, c_i a per-particle vector that names the model:
 *
 *   molteni_colagrossi  c_i = 0: Molteni & Colagrossi (2009), eq. (9). Its
 *                       diffusion of the full density acts against the
 *                       hydrostatic density gradient: a tank at rest
 *                       drifts (tests/test_density_diffusion.c shows it).
 *   antuono             c_i = (1/2) <grad rho>^L_i, the renormalised
 *                       density gradient sum_j (rho_j - rho_i) L_i grad_i W_ij V_j,
 *                       L_i = [sum_j r_ji (x) grad_i W_ij V_j]^-1 (Antuono,
 *                       Colagrossi, Marrone & Molteni 2010, eq. (5)-(6), the
 *                       delta-SPH): exact for a linear density field, so the
 *                       hydrostatic gradient is not diffused. It needs a
 *                       pass of its own over the neighbours (its cost is in
 *                       bench/results/features.md). Where det L^-1 falls
 *                       below SPH_GRADIENT_CORRECTION_MIN_DET (the free
 *                       surface) L = I, as for the kernel-gradient correction.
 *   fourtakas           c_i = (rho0 / (2 c0^2)) g: Fourtakas, Dominguez,
 *                       Vacondio & Rogers (2019), eq. (11)-(13): only the
 *                       dynamic density rho - rho^H diffuses, rho^H_j -
 *                       rho^H_i = rho0 g . r_ji / c0^2 = -c_ij . r_ij the
 *                       hydrostatic difference of the pair, the paper's rho0 [(1 + rho0 g z_ij /
 * B)^(1/gamma) - 1] to first order (the next term is below 1e-4 of it for a pair 2h apart at c0 =
 * 10 sqrt(g H)).
 *
 * Fluid pairs diffuse, and the pairs of fluid with dynamic and
 * fixed_layers wall particles (whose continuity density would otherwise keep
 * what an impact left while water stays near them; src/solver/diffusion.h);
 * never wall with wall, nor mdbc, repulsive or mirror particles. The term
 * moves density among the particles that take part: sum_i V_i D_i = 0 to
 * round-off (the pair sum is antisymmetric).
 * It changes no velocity, so momentum is untouched; its effect on energy is
 * the ledger's diffusion_energy column, the time integral of
 * sum_i m_i (p_i / rho_i^2) D_i (src/solver/ledger.h).
 *
 * The pair parts are pair terms (src/physics/pair_terms_body.h:
 * diffusion_psi, diffusion); the per-particle c_i is set before each
 * interaction pass (src/solver/diffusion.c). delta = 0.1 is the papers'
 * value (numerics.density_diffusion.delta).
 */
#ifndef SPH_DENSITY_DIFFUSION_H
#define SPH_DENSITY_DIFFUSION_H

#include "physics/models.h"

/* delta of the papers, the default of numerics.density_diffusion.delta */
#define SPH_DIFFUSION_DELTA_DEFAULT 0.1

#endif
