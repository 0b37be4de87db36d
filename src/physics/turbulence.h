/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * turbulence.h - the sub-particle-scale (SPS) stress of paper B eq. (4), a
 * Smagorinsky large-eddy closure (Dalrymple & Rogers 2006 form):
 *   tau*_ab / rho = 2 nu_t S_ab - (2/3) C_I Delta^2 |S|^2 delta_ab
 *   nu_t = (C_s Delta)^2 |S|,   |S| = (2 S_ab S_ab)^(1/2)
 * with S the strain-rate tensor S_ab = (dv_a/dx_b + dv_b/dx_a)/2 from the
 * SPH velocity gradients, C_s = 0.12, C_I = 0.00066, Delta = the initial
 * particle spacing. The -(2/3) k delta_ab term of the paper (k the SPS
 * kinetic energy) is isotropic and left to the pressure, as is usual.
 * The stress enters the momentum equation as
 *   + sum_j m_j (tau*_i/rho_i^2 + tau*_j/rho_j^2) . grad_i W_ij.
 */
#ifndef SPH_TURBULENCE_H
#define SPH_TURBULENCE_H

#include <math.h>

#include "core/dim.h"
#include "core/tensor.h"

/* |S| = (2 S:S)^(1/2) of a symmetric tensor of SPH_DIM dimensions
 * (core/tensor.h): the diagonal's squares, then twice the others'. */
static inline double sph_strain_norm_sym(const double S[SPH_SYM]) {
#if SPH_DIM == 2
  return sqrt(2.0 * (S[SPH_XX] * S[SPH_XX] + S[SPH_YY] * S[SPH_YY] + 2.0 * S[SPH_XY] * S[SPH_XY]));
#else
  const double diag = S[SPH_XX] * S[SPH_XX] + S[SPH_YY] * S[SPH_YY] + S[SPH_ZZ] * S[SPH_ZZ];
  const double off = S[SPH_XY] * S[SPH_XY] + S[SPH_XZ] * S[SPH_XZ] + S[SPH_YZ] * S[SPH_YZ];
  return sqrt(2.0 * (diag + 2.0 * off));
#endif
}

/* tau* / rho of the SPS closure above for the strain rate S, any dimension. */
static inline void sph_sps_stress_sym(const double S[SPH_SYM], double cs, double ci, double delta,
                                      double t[SPH_SYM]) {
  const double s = sph_strain_norm_sym(S);
  const double nut = cs * delta * cs * delta * s;
  const double iso = (2.0 / 3.0) * ci * delta * delta * s * s;
  t[SPH_XX] = 2.0 * nut * S[SPH_XX] - iso;
  t[SPH_YY] = 2.0 * nut * S[SPH_YY] - iso;
  t[SPH_XY] = 2.0 * nut * S[SPH_XY];
#if SPH_DIM == 3
  t[SPH_ZZ] = 2.0 * nut * S[SPH_ZZ] - iso;
  t[SPH_XZ] = 2.0 * nut * S[SPH_XZ];
  t[SPH_YZ] = 2.0 * nut * S[SPH_YZ];
#endif
}

#if SPH_DIM == 2
/* |S| = (2 S:S)^(1/2) for a 2-D symmetric tensor. */
static inline double sph_strain_norm(double sxx, double sxy, double syy) {
  return sqrt(2.0 * (sxx * sxx + syy * syy + 2.0 * sxy * sxy));
}

/* The Smagorinsky eddy viscosity nu_t = (C_s Delta)^2 |S|. */
static inline double sph_sps_eddy_viscosity(double sxx, double sxy, double syy, double cs,
                                            double delta) {
  return cs * delta * cs * delta * sph_strain_norm(sxx, sxy, syy);
}

/* tau* / rho of the SPS closure above for the strain rate S. */
static inline void sph_sps_stress(double sxx, double sxy, double syy, double cs, double ci,
                                  double delta, double *txx, double *txy, double *tyy) {
  const double s = sph_strain_norm(sxx, sxy, syy);
  const double nut = cs * delta * cs * delta * s;
  const double iso = (2.0 / 3.0) * ci * delta * delta * s * s;
  *txx = 2.0 * nut * sxx - iso;
  *tyy = 2.0 * nut * syy - iso;
  *txy = 2.0 * nut * sxy;
}
#endif

#endif
