/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * diffusion.c - the per-particle vector c_i of the density diffusion (see
 * diffusion.h and src/physics/density_diffusion.h).
 */
#include "config.h"

#include "solver/diffusion.h"

#include <math.h>

#include "core/parallel.h"
#include "physics/kernel.h"
#include "solver/row_walk.h"

/* Half the renormalised density gradient at fluid particle i, Antuono et
 * al. (2010) eq. (6): <grad rho>^L_i = L_i sum_j (rho_j - rho_i) grad_i W_ij V_j,
 * L_i = [sum_j r_ji (x) grad_i W_ij V_j]^-1 over every neighbour (walls and
 * mirror particles complete the support as they do for the strain rate),
 * L_i = I where det L_i^-1 <= SPH_GRADIENT_CORRECTION_MIN_DET. */
static void half_gradient(const sph_particles *restrict p, const sph_nlist *restrict l,
                          const sph_force_params *restrict fp, size_t i, double c[SPH_DIM]) {
  const double *restrict x = p->x, *restrict y = p->y, *restrict h = p->h;
  const double *restrict m = p->mass, *restrict rho = p->rho;
  const unsigned F = fp->periodic ? SPH_ROW_PERIODIC : 0u;
  const double xi = x[i], yi = y[i], rhoi = rho[i];
  double gx = 0.0, gy = 0.0, mxx = 0.0, mxy = 0.0, myy = 0.0;
  SPH_IF3(const double *restrict z = p->z; const double zi = z[i];
          double gz = 0.0, mxz = 0.0, myz = 0.0, mzz = 0.0;)
  ROW(l, i, nb, cnt)
  for (size_t k = 0; k < cnt; k++) {
    const size_t j = nb[k];
    const double dx = SEP(fp, 0, xi, x[j], F), dy = SEP(fp, 1, yi, y[j], F);
    SPH_IF3(const double dz = SEP(fp, 2, zi, z[j], F);)
    const double r2 = SPH_NORM2(dx, dy, dz);
    const double hij = fp->var_h ? 0.5 * (h[i] + h[j]) : fp->h;
    if (r2 >= 4.0 * hij * hij || r2 == 0.0) continue;
    const double r = sqrt(r2);
    double wij, f;
    sph_kernel_w_f(fp->kernel, r, r / r2, 1.0 / hij, &wij, &f);
    const double fv = f * (m[j] / rho[j]); /* V_j grad_i W_ij = fv (dx, dy) */
    const double drho = rho[j] - rhoi;
    gx += drho * fv * dx;
    gy += drho * fv * dy;
    mxx -= dx * fv * dx; /* r_ji = -(dx, dy) */
    mxy -= dx * fv * dy;
    myy -= dy * fv * dy;
    SPH_IF3(gz += drho * fv * dz; mxz -= dx * fv * dz; myz -= dy * fv * dz; mzz -= dz * fv * dz;)
  }
#if SPH_DIM == 2
  const double mm[SPH_SYM] = {mxx, mxy, myy};
  double a[SPH_SYM];
  sph_gradient_correction(mm, a);
  const double axx = a[SPH_XX], axy = a[SPH_XY], ayy = a[SPH_YY];
  c[0] = 0.5 * (axx * gx + axy * gy);
  c[1] = 0.5 * (axy * gx + ayy * gy);
#else
  const double mm[SPH_SYM] = {mxx, mxy, mxz, myy, myz, mzz}, gg[3] = {gx, gy, gz};
  double a[SPH_SYM];
  sph_gradient_correction(mm, a);
  for (int r = 0; r < 3; r++)
    c[r] = 0.5 * ((a[sph_sym_index(r, 0)] * gg[0] + a[sph_sym_index(r, 1)] * gg[1]) +
                  a[sph_sym_index(r, 2)] * gg[2]);
#endif
}

int sph_diffusion_wall_takes_part(int32_t kind, uint8_t flags) {
  return kind == SPH_KIND_WALL && !(flags & (SPH_FLAG_MDBC | SPH_FLAG_REPULSIVE | SPH_FLAG_ADAMI));
}

int sph_diffusion_walls(const sph_particles *p, const sph_force_params *fp) {
  /* antuono's c_i is a density gradient, which a wall particle has no
   * fluid-side estimate of: its walls keep out (diffusion.h) */
  if (fp->diffusion == SPH_DIFFUSION_NONE || fp->diffusion == SPH_DIFFUSION_ANTUONO) return 0;
  for (size_t i = 0; i < p->n; i++)
    if (sph_diffusion_wall_takes_part(p->kind[i], p->flags[i])) return 1;
  return 0;
}

/* The mass with which particle i takes part in the diffusion: a fluid
 * particle m_i where no mdbc wall particle lies inside its support, 0
 * where one does; a dynamic or fixed_layers wall particle m_i (its pairs
 * with fluid diffuse, diffusion.h); every other particle 0. */
static double diffusion_mass(const sph_particles *restrict p, const sph_nlist *restrict l,
                             const sph_force_params *restrict fp, size_t i) {
  if (p->kind[i] != SPH_KIND_FLUID)
    return fp->wall_diffusion && sph_diffusion_wall_takes_part(p->kind[i], p->flags[i]) ? p->mass[i]
                                                                                        : 0.0;
  if (!fp->mdbc) return p->mass[i]; /* no mdbc wall: no scan (a term that is off costs nothing) */
  const unsigned F = fp->periodic ? SPH_ROW_PERIODIC : 0u;
  ROW(l, i, nb, cnt)
  for (size_t k = 0; k < cnt; k++) {
    const size_t j = nb[k];
    if (!(p->flags[j] & SPH_FLAG_MDBC)) continue;
    const double dx = SEP(fp, 0, p->x[i], p->x[j], F), dy = SEP(fp, 1, p->y[i], p->y[j], F);
    const double hij = fp->var_h ? 0.5 * (p->h[i] + p->h[j]) : fp->h;
    SPH_IF3(const double dz = SEP(fp, 2, p->z[i], p->z[j], F);)
    if (SPH_NORM2(dx, dy, dz) < 4.0 * hij * hij) return 0.0;
  }
  return p->mass[i];
}

void sph_diffusion_prepare(const sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                           sph_force_work *w, int mass_is_fm) {
  const long n = (long)p->n;
  double c[SPH_DIM] = {0.0}; /* the same c_i everywhere but for antuono */
  if (fp->diffusion == SPH_DIFFUSION_NONE) return;
  if (!mass_is_fm) {
#pragma omp parallel for schedule(dynamic, 256) if (n > SPH_OMP_MIN)
    for (long i = 0; i < n; i++)
      w->ddm[i] = diffusion_mass(p, l, fp, (size_t)i);
  }
  switch (fp->diffusion) {
  case SPH_DIFFUSION_NONE: return;
  case SPH_DIFFUSION_FOURTAKAS: {
    const double k = 0.5 * fp->eos.rho0 / (fp->eos.c0 * fp->eos.c0);
#pragma GCC unroll 3
    for (int d = 0; d < SPH_DIM; d++)
      c[d] = k * fp->g[d];
    break;
  }
  case SPH_DIFFUSION_ANTUONO:
#pragma omp parallel for schedule(dynamic, 256) if (n > SPH_OMP_MIN)
    for (long i = 0; i < n; i++) {
      double ci[SPH_DIM] = {0.0};
      if (p->kind[i] == SPH_KIND_FLUID) half_gradient(p, l, fp, (size_t)i, ci);
#pragma GCC unroll 3
      for (int d = 0; d < SPH_DIM; d++)
        w->ddc[d][i] = ci[d];
    }
    return;
  case SPH_DIFFUSION_MOLTENI: break;
  }
#pragma GCC unroll 3
  for (int d = 0; d < SPH_DIM; d++)
    w->ddc0[d] = c[d];
}
