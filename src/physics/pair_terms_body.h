/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * pair_terms_body.h - the pair terms for one arithmetic flavour FL (v1,
 * v4e, v4x, v8z of src/core/lanes.h), with PT_ATTR their attributes. Not a
 * header to include directly: src/physics/pair_terms.h includes it once
 * per flavour, and each function below becomes name_FL (continuity_v1,
 * continuity_v4e, ...). No include guard on purpose.
 *
 * Each function is one term of one pair and returns its contribution; the
 * loops add them up (src/solver/interact.h). The order of the operations
 * inside each function is the order of the results' bits: change it and
 * the golden files move.
 */

#define T FL
#define PT(name) SPH_PT_XGLUE(name, FL)
#define OP(name) SPH_PT_XGLUE(FL, name)
#define ALL OP(all)
#define ADD OP(add)
#define SUB OP(sub)
#define MUL OP(mul)
#define DIV OP(div)
#define NEG OP(neg)
#define ABS OP(abs)
#define MIN OP(min)
#define MAX OP(max)
#define VEC PT(vec)
#define SYM PT(sym)

/* A vector (a separation, a velocity, a kernel gradient) and a symmetric
 * tensor (xx, xy, yy in 2-D; xx, xy, xz, yy, yz, zz in 3-D) of the
 * flavour's numbers, SPH_DIM components (src/core/dim.h). */
typedef struct {
  T c[SPH_DIM];
} VEC;
typedef struct {
  T c[SPH_SYM];
} SYM;

/* The helpers below spell their components out (no loop over the axes:
 * the compiler then keeps a vector's components in registers). */

/* a . b, the components added in axis order. */
PT_ATTR T PT(dot)(VEC a, VEC b) {
#if SPH_DIM == 2
  return ADD(MUL(a.c[0], b.c[0]), MUL(a.c[1], b.c[1]));
#else
  return ADD(ADD(MUL(a.c[0], b.c[0]), MUL(a.c[1], b.c[1])), MUL(a.c[2], b.c[2]));
#endif
}

/* s a. */
PT_ATTR VEC PT(scale)(T s, VEC a) {
#if SPH_DIM == 2
  const VEC r = {{MUL(s, a.c[0]), MUL(s, a.c[1])}};
#else
  const VEC r = {{MUL(s, a.c[0]), MUL(s, a.c[1]), MUL(s, a.c[2])}};
#endif
  return r;
}

/* a - b. */
PT_ATTR VEC PT(minus)(VEC a, VEC b) {
#if SPH_DIM == 2
  const VEC r = {{SUB(a.c[0], b.c[0]), SUB(a.c[1], b.c[1])}};
#else
  const VEC r = {{SUB(a.c[0], b.c[0]), SUB(a.c[1], b.c[1]), SUB(a.c[2], b.c[2])}};
#endif
  return r;
}

/* t g, t symmetric: row d is sum_e t_de g_e, e in axis order. */
PT_ATTR VEC PT(sym_times)(SYM t, VEC g) {
#if SPH_DIM == 2 /* t = (xx, xy, yy) */
  const VEC r = {{ADD(MUL(t.c[0], g.c[0]), MUL(t.c[1], g.c[1])),
                  ADD(MUL(t.c[1], g.c[0]), MUL(t.c[2], g.c[1]))}};
#else /* t = (xx, xy, xz, yy, yz, zz) */
  const VEC r = {{ADD(ADD(MUL(t.c[0], g.c[0]), MUL(t.c[1], g.c[1])), MUL(t.c[2], g.c[2])),
                  ADD(ADD(MUL(t.c[1], g.c[0]), MUL(t.c[3], g.c[1])), MUL(t.c[4], g.c[2])),
                  ADD(ADD(MUL(t.c[2], g.c[0]), MUL(t.c[4], g.c[1])), MUL(t.c[5], g.c[2]))}};
#endif
  return r;
}

/* t : sym(u v^T) (twice its off-diagonal part): in storage order,
 * t_aa u_a v_a and t_ab (u_a v_b + u_b v_a), added left to right. */
PT_ATTR T PT(sym_contract)(SYM t, VEC u, VEC v) {
#define SPH_PT_DIAG(k, a) MUL(MUL(t.c[k], u.c[a]), v.c[a])
#define SPH_PT_OFF(k, a, b) MUL(t.c[k], ADD(MUL(u.c[a], v.c[b]), MUL(u.c[b], v.c[a])))
#if SPH_DIM == 2
  const T s = ADD(ADD(SPH_PT_DIAG(0, 0), SPH_PT_OFF(1, 0, 1)), SPH_PT_DIAG(2, 1));
#else
  const T s = ADD(ADD(ADD(ADD(ADD(SPH_PT_DIAG(0, 0), SPH_PT_OFF(1, 0, 1)), SPH_PT_OFF(2, 0, 2)),
                          SPH_PT_DIAG(3, 1)),
                      SPH_PT_OFF(4, 1, 2)),
                  SPH_PT_DIAG(5, 2));
#endif
#undef SPH_PT_OFF
#undef SPH_PT_DIAG
  return s;
}

/* The cubic spline (paper A eq. 8, paper B §2.1; src/core/kernel_shape.h)
 * in the loops' form: W_ij and F_ij = (1/r) dW/dr for 0 < r < 2h, from
 * 1/r, 1/h, the normalisation sigma (sph_kernel_norm: 10/(7 pi h^2) in 2-D)
 * and sigma/h. Both branches of the spline
 * are one expression (no unpredictable branch): with t = 2 - q and
 * a = max(1 - q, 0), W = sigma [t^3/4 - a^3], dW/dq = sigma [3 a^2 - 3/4 t^2]. */
PT_ATTR void PT(cubic_w_f)(T r, T inv_r, T inv_h, T sigma, T sigma_h, T *w, T *f) {
  const T q = MUL(r, inv_h), t = SUB(ALL(2.0), q);
  const T a = MAX(SUB(ALL(1.0), q), ALL(0.0));
  *w = MUL(sigma, SUB(MUL(ALL(0.25), MUL(MUL(t, t), t)), MUL(MUL(a, a), a)));
  *f = MUL(MUL(sigma_h, SUB(MUL(ALL(3.0), MUL(a, a)), MUL(ALL(0.75), MUL(t, t)))), inv_r);
}

/* The Wendland C2 kernel (Wendland 1995; src/core/kernel_shape.h) in the
 * loops' form, the same arguments as cubic_w_f with its sigma (7/(4 pi h^2)
 * in 2-D):
 * with t = 1 - q/2 (0 < q < 2), W = sigma t^4 (2q + 1) and
 * dW/dq = -5 sigma q t^3, so F = (1/r) dW/dr = -5 (sigma/h) (1/h) t^3 (no 1/r). */
PT_ATTR void PT(wendland_w_f)(T r, T inv_r, T inv_h, T sigma, T sigma_h, T *w, T *f) {
  (void)inv_r;
  const T q = MUL(r, inv_h), t = SUB(ALL(1.0), MUL(ALL(0.5), q));
  const T t3 = MUL(MUL(t, t), t);
  *w = MUL(sigma, MUL(MUL(t3, t), ADD(MUL(ALL(2.0), q), ALL(1.0))));
  *f = MUL(MUL(ALL(-5.0), sigma_h), MUL(inv_h, t3));
}

/* Continuity, paper B eq. (2), paper A eq. (12): m_j v_ij . grad_i W_ij. */
PT_ATTR T PT(continuity)(T mj, VEC dv, VEC g) { return MUL(mj, PT(dot)(dv, g)); }

/* Density diffusion (src/physics/density_diffusion.h): the bracket of
 * psi_ij / 2 = (rho_j - rho_i) + c_ij . r_ij, given c_ij = c_i + c_j. */
PT_ATTR T PT(diffusion_psi)(T rhoi, T rhoj, VEC r, VEC c) {
  return ADD(SUB(rhoj, rhoi), PT(dot)(c, r));
}

/* Its pair sum F_ij psi_ij m_j / rho_j; the loop scales the sum by
 * -2 delta h c0 (r_ji . grad_i W_ij / r^2 = -F_ij). */
PT_ATTR T PT(diffusion)(T psi, T f, T mj, T rhoj) { return DIV(MUL(MUL(f, psi), mj), rhoj); }

/* A free-slip wall (walls.h, SPH_FLAG_FREE_SLIP): the part of the kernel
 * gradient g of a fluid-wall pair along the wall's normal, given the wall
 * particle's mirror offset m = (mx, my) (boundary.h: twice its depth, along
 * the normal): g' = (g . m) m / |m|^2. The pair's pressure and artificial-
 * viscosity force -mp g' and their heat then act along the normal only,
 * so the wall neither drags the fluid along its face nor, moving along
 * it, does work on it; the continuity term keeps g. */
PT_ATTR VEC PT(normal_part)(VEC g, VEC m) {
  return PT(scale)(DIV(PT(dot)(g, m), PT(dot)(m, m)), m);
}

/* v_ij . r_ij as the artificial viscosity of a fluid-wall pair on a
 * free-slip wall reads it: with v_ij's normal part only, (v' . r_ij) with
 * v' = normal_part(v_ij). Its switch (mu_ij = 0 unless approaching) then
 * answers whether the pair closes along the normal: the fluid sliding
 * along the wall is neither pushed off it (the pairs ahead, approaching
 * along the slide, would take Pi_ij > 0 and those behind none) nor braked. */
PT_ATTR T PT(normal_vdotr)(VEC v, VEC r, VEC m) { return PT(dot)(PT(normal_part)(v, m), r); }

/* The time-step rule's signal term, paper B §2.6: |h_ij v_ij . r_ij| / r^2. */
PT_ATTR T PT(signal)(T hij, T vdotr, T inv_r2) { return MUL(ABS(MUL(hij, vdotr)), inv_r2); }

/* 1 / rho_ij with rho_ij = (rho_i + rho_j) / 2 (artificial viscosity, XSPH). */
PT_ATTR T PT(inv_rho_mean)(T rhoi, T rhoj) { return DIV(ALL(2.0), ADD(rhoi, rhoj)); }

/* Artificial viscosity Pi_ij, paper A eq. (15)-(16):
 *   mu_ij = h_ij min(v_ij . r_ij, 0) / (r^2 + eta^2)   (0 unless approaching)
 *   Pi_ij = (-alpha c_ij mu_ij + beta mu_ij^2) / rho_ij, c_ij = (c_i + c_j) / 2,
 * with nalpha = -alpha and eta2 = (eta_f h_ij)^2. */
PT_ATTR T PT(artificial_viscosity)(T vdotr, T hij, T r2, T eta2, T ci, T cj, T nalpha, T beta,
                                   T inv_rb) {
  const T mu = DIV(MUL(hij, MIN(vdotr, ALL(0.0))), ADD(r2, eta2));
  const T cbar = MUL(ALL(0.5), ADD(ci, cj));
  return MUL(ADD(MUL(MUL(nalpha, cbar), mu), MUL(MUL(beta, mu), mu)), inv_rb);
}

/* The pressure term of the Riemann-solver scheme, Zhang, Hu & Adams (2017)
 * (ZH17 in doc/method.md): the pair's interface pressure from the
 * linearised (acoustic) Riemann problem along the line of centres,
 *   p* = (p_i + p_j)/2 + 1/2 beta rho0 c0 dU,  beta = min(eta max(dU, 0)/c0, 1),
 * dU = U_L - U_R = -v_ij . r_ij / r the speed at which the pair closes
 * (positive approaching), as the momentum equation's pair factor
 * P_ij = 2 p* / (rho_i rho_j) of dv_i/dt = -sum_j m_j P_ij grad_i W_ij.
 * The limiter beta keeps the dissipation to closing pairs and makes it
 * quadratic in dU below c0/eta (3 rho0 dU^2 / 2 at eta = 3), so that slow
 * flow sees almost none and an impact the acoustic impedance's; given
 * z0 = rho0 c0 and kc = eta / c0. Symmetric in the pair (the force
 * antisymmetric), and its work on the pair is the ledger's heat through
 * pressure_heat like any P_ij. */
PT_ATTR T PT(riemann_pressure)(T pi, T pj, T rhoi, T rhoj, T du, T z0, T kc) {
  const T beta = MIN(MUL(kc, MAX(du, ALL(0.0))), ALL(1.0));
  return DIV(ADD(ADD(pi, pj), MUL(MUL(beta, z0), du)), MUL(rhoi, rhoj));
}

/* The continuity term of the Riemann-solver scheme, Zhang, Hu & Adams
 * (2017): the share of 2 rho_i V_j (v_i - v*) . grad_i W_ij
 * that the pressure jump puts in the interface velocity v* (its part
 * (p_i - p_j) / (2 rho0 c0) along the line of centres), with the hydrostatic
 * jump rho0 g . r_ij taken out, as Fourtakas et al. (2019) take it out of
 * the density difference, so that water at rest feels none:
 *   rho_i (m_j / rho_j) [(p_i - p_j) - rho0 g . r_ij] (dW/dr) / (rho0 c0),
 * given jump = the bracket, f = F_ij (dW/dr = F_ij r) and
 * inv_z0 = 1 / (rho0 c0). dW/dr < 0: density moves down the jump. */
PT_ATTR T PT(riemann_density)(T rhoi, T mj, T rhoj, T jump, T f, T r, T inv_z0) {
  return MUL(DIV(MUL(rhoi, mj), rhoj), MUL(MUL(jump, MUL(f, r)), inv_z0));
}

/* Two phases (physics.air; Rezavand, Zhang & Hu 2020, RZH20 in
 * doc/method.md, Two phases): the acoustic Riemann problem between
 * materials of impedances z_i = rho0_i c_i and z_j (a wall particle takes
 * i's own). Its interface pressure and velocity are the impedance-weighted
 * means p* = (z_j p_i + z_i p_j) / (z_i + z_j) and
 * v* = (z_i v_i + z_j v_j) / (z_i + z_j), its dissipation acts with
 * z_ij = 2 z_i z_j / (z_i + z_j): across the water's surface the air reads
 * the water as a moving wall (v* ~ v_water) and the water reads the air's
 * pressure (p* ~ p_air). Given z_i and z_j: wi = 2 z_j / (z_i + z_j),
 * wj = 2 z_i / (z_i + z_j) (p* = (wi p_i + wj p_j) / 2) and z_ij = wi z_i.
 * One material: wi = wj = 1, z_ij = z_i. */
PT_ATTR void PT(phase_weights)(T zi, T zj, T *wi, T *wj, T *zij) {
  const T s = DIV(ALL(1.0), ADD(zi, zj));
  *wi = MUL(ALL(2.0), MUL(zj, s));
  *wj = MUL(ALL(2.0), MUL(zi, s));
  *zij = MUL(*wi, zi);
}

/* riemann_pressure between two materials (phase_weights): the momentum's
 * pair factor 2 p* / (rho_i rho_j) with p* = (wi p_i + wj p_j) / 2 +
 * 1/2 beta z_ij dU. Symmetric in the pair, as riemann_pressure. */
PT_ATTR T PT(riemann_pressure_phases)(T pi, T pj, T rhoi, T rhoj, T du, T wi, T wj, T zij, T kc) {
  const T beta = MIN(MUL(kc, MAX(du, ALL(0.0))), ALL(1.0));
  return DIV(ADD(ADD(MUL(wi, pi), MUL(wj, pj)), MUL(MUL(beta, zij), du)), MUL(rhoi, rhoj));
}

/* Two phases: the pressure a wall particle j of the other phase presses
 * fluid particle i with, at least i's own pressure continued to it through
 * i's material at rest, p_i + rho0_i g . (x_j - x_i) (given hg =
 * rho0_i g . r_ij, r_ij = x_i - x_j): the wall stands for the phase at its
 * mirror point (walls/adami.h), and a layer deep under a film one particle
 * thick stands for the air above the film, which held the film up by its
 * own mirror image alone; it still pushes i no less than i's own column
 * would (as Zhang, Hu and Adams' wall state takes p_i + rho_i g . r, the
 * walls of SPHinXsys' two-phase cases). */
PT_ATTR T PT(wall_pressure_floor)(T pj, T pi, T hg) { return MAX(pj, SUB(pi, hg)); }

/* The continuity term's mass between two materials: RZH20's
 * 2 rho_i V_j (v_i - v*) . grad_i W_ij = rho_i V_j wi v_ij . grad_i W_ij
 * (V_j = m_j / rho_j, the volume form a density ratio of 1000 needs), as
 * the m_j of continuity: rho_i (m_j / rho_j) wi. */
PT_ATTR T PT(phase_continuity_mass)(T rhoi, T mj, T rhoj, T wi) {
  return MUL(MUL(rhoi, DIV(mj, rhoj)), wi);
}

/* The pair's corrected kernel gradient, Bonet and Lok (1999) in their
 * symmetric form: L_ij grad_i W_ij with L_ij = (L_i + L_j) / 2, given each
 * particle's L = M^-1 (src/solver/forces.h). L_ij is the same for both
 * particles of the pair, so the terms built on it keep their symmetry: a
 * pressure force antisymmetric, a continuity term that matches its work. */
PT_ATTR VEC PT(corrected_gradient)(SYM li, SYM lj, VEC g) {
#define SPH_PT_MEAN(k) MUL(ALL(0.5), ADD(li.c[k], lj.c[k]))
#if SPH_DIM == 2
  const SYM m = {{SPH_PT_MEAN(0), SPH_PT_MEAN(1), SPH_PT_MEAN(2)}};
#else
  const SYM m = {{SPH_PT_MEAN(0), SPH_PT_MEAN(1), SPH_PT_MEAN(2), SPH_PT_MEAN(3), SPH_PT_MEAN(4),
                  SPH_PT_MEAN(5)}};
#endif
#undef SPH_PT_MEAN
  return PT(sym_times)(m, g);
}

/* Pressure (and Pi_ij) force on i per unit mass, paper A eq. (11), paper B
 * eq. (3): -m_j (p_i/rho_i^2 + p_j/rho_j^2 + Pi_ij) grad_i W_ij, given
 * mp = m_j (prho2_i + prho2_j + Pi_ij). Antisymmetric in the pair. */
PT_ATTR VEC PT(pressure_force)(T mp, VEC g) { return PT(scale)(NEG(mp), g); }

/* The heat of the pressure pair term, paper A eq. (28) with the artificial
 * viscosity's share: du_i/dt += 1/2 mp v_ij . grad_i W_ij (energy ledger). */
PT_ATTR T PT(pressure_heat)(T mp, VEC dv, VEC g) { return MUL(MUL(ALL(0.5), mp), PT(dot)(dv, g)); }

/* Viscous stress force, paper A eq. (11) (and the SPS stress of paper B
 * eq. 4, src/physics/turbulence.h): m_j sum_b (tau_i^ab/rho_i^2 +
 * tau_j^ab/rho_j^2) dW_ij/dx_i^b, given the pair sums txx = sxx_i + sxx_j,
 * txy, tyy of tau / rho^2. */
PT_ATTR VEC PT(stress_force)(T mj, SYM t, VEC g) { return PT(scale)(mj, PT(sym_times)(t, g)); }

/* The viscous dissipation of the stress pair, the discrete form of paper A
 * eq. (29) that balances the pair's work exactly: the amount subtracted
 * from du_i/dt, 1/2 m_j tau_ij : (v_ij grad_i W_ij). */
PT_ATTR T PT(stress_heat)(T mj, SYM t, VEC dv, VEC g) {
  return MUL(MUL(ALL(0.5), mj), PT(sym_contract)(t, dv, g));
}

/* Morris' laminar viscosity, paper B eq. (4): the factor c of
 *   dv_i/dt += c v_ij,  c = m_j 4 nu0 r_ij . grad_i W_ij / ((rho_i + rho_j)(r^2 + eta^2)),
 * given nu4 = 4 mu / rho0, F_ij and eta2 = (eta_f h_ij)^2. */
PT_ATTR T PT(morris_factor)(T mj, T nu4, T f, T r2, T rhoi, T rhoj, T eta2) {
  return DIV(MUL(MUL(mj, nu4), MUL(f, r2)), MUL(ADD(rhoi, rhoj), ADD(r2, eta2)));
}

/* Two phases (physics.air): the pair's 2 mu_ij with mu_ij the harmonic
 * mean 2 mu_i mu_j / (mu_i + mu_j) of the two materials' dynamic
 * viscosities (Hu & Adams 2006, HA06 in doc/method.md: the shear stress continuous across
 * the interface, the weaker material setting it); mu_i within a material. */
PT_ATTR T PT(phase_viscosity)(T mui, T muj) {
  return DIV(MUL(ALL(4.0), MUL(mui, muj)), ADD(mui, muj));
}

/* Morris' viscosity between two materials, in the volume form of the
 * two-phase terms: dv_i/dt += c v_ij with
 *   c = (m_j / rho_j) 2 mu_ij F_ij r^2 / (rho_i (r^2 + eta^2)),
 * paper B eq. (4) (Morris et al. 1997) with (mu_i + mu_j) / (rho_i rho_j) written
 * m_j 2 mu_ij / (rho_i rho_j) = V_j 2 mu_ij / rho_i, so that a wall
 * particle (whose mass and density are the liquid's) counts by its volume
 * in an air row; given mu2 = 2 mu_ij (phase_viscosity). m_i c is symmetric
 * in the pair (V_i V_j 2 mu_ij ...): the momentum is conserved. */
PT_ATTR T PT(morris_phases_factor)(T mj, T rhoj, T mu2, T f, T r2, T rhoi, T eta2) {
  return DIV(MUL(MUL(DIV(mj, rhoj), mu2), MUL(f, r2)), MUL(rhoi, ADD(r2, eta2)));
}

/* Its dissipation, subtracted from du_i/dt: 1/2 c |v_ij|^2. */
PT_ATTR T PT(morris_heat)(T c, VEC dv) { return MUL(MUL(ALL(0.5), c), PT(dot)(dv, dv)); }

/* XSPH, paper B eq. (6): the factor m_j W_ij / rho_ij of
 * dr_i/dt = v_i + eps sum_j (m_j / rho_ij) (v_j - v_i) W_ij, with mj = 0
 * for a neighbour that is not fluid (a wall at rest would drag the fluid). */
PT_ATTR T PT(xsph_factor)(T mj, T inv_rb, T wij) { return MUL(MUL(mj, inv_rb), wij); }

/* The heat of a pair whose other particle takes none (a mirror particle or
 * a repulsive wall particle, moving at (vxj, vyj); a mirror particle's
 * counts as at rest: it is an image, not a body): the pair force's work on
 * i, less what the moving wall puts in, -a_ij . (v_i - v_j). Then the
 * fluid's kinetic energy lost to the pair is all in i's internal energy,
 * and the balance closes without a partner's half (method.md). */
PT_ATTR T PT(passive_heat)(VEC a, VEC vi, VEC vj) { return NEG(PT(dot)(a, PT(minus)(vi, vj))); }

/* The power of a wall particle j's pair force (ax, ay) on fluid i, per unit
 * mass of i (energy ledger, the boundary work of paper A §5). */
PT_ATTR T PT(wall_power)(VEC a, VEC vj) { return PT(dot)(a, vj); }

/* Lennard-Jones wall force of a repulsive wall particle within r0, paper A
 * eq. (21)-(22): the factor D [(r0/r)^12 - (r0/r)^4] / r^2 of r_ij. */
PT_ATTR T PT(lennard_jones)(T d, T r0, T r2) {
  const T q2 = DIV(MUL(r0, r0), r2), q4 = MUL(q2, q2), q12 = MUL(MUL(q4, q4), q4);
  return DIV(MUL(d, SUB(q12, q4)), r2);
}

/* Its potential energy per unit mass, zero at r0:
 * D [(r0/r)^12 / 12 - (r0/r)^4 / 4 + 1/6]; the force above is minus its
 * gradient (energy ledger). */
PT_ATTR T PT(lennard_jones_potential)(T d, T r0, T r2) {
  const T q2 = DIV(MUL(r0, r0), r2), q4 = MUL(q2, q2), q12 = MUL(MUL(q4, q4), q4);
  return MUL(d, ADD(SUB(DIV(q12, ALL(12.0)), DIV(q4, ALL(4.0))), DIV(ALL(1.0), ALL(6.0))));
}

#undef SYM
#undef VEC
#undef MAX
#undef MIN
#undef ABS
#undef NEG
#undef DIV
#undef MUL
#undef SUB
#undef ADD
#undef ALL
#undef OP
#undef PT
#undef T
