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
#include "solver/interact.h"

/* Half the renormalised density gradient at fluid particle i, Antuono et
 * al. (2010) eq. (6): <grad rho>^L_i = L_i sum_j (rho_j - rho_i) grad_i W_ij V_j,
 * L_i = [sum_j r_ji (x) grad_i W_ij V_j]^-1 over every neighbour (walls and
 * mirror particles complete the support as they do for the strain rate),
 * L_i = I where det L_i^-1 <= SPH_GRADIENT_CORRECTION_MIN_DET. */
static void half_gradient(const sph_particles *restrict p, const sph_nlist *restrict l,
                          const sph_force_params *restrict fp, size_t i, double *cx, double *cy) {
  const double *restrict x = p->x, *restrict y = p->y, *restrict h = p->h;
  const double *restrict m = p->mass, *restrict rho = p->rho;
  const double period = fp->periodic ? fp->period : 0.0, half = 0.5 * period;
  const unsigned F = fp->periodic ? F_PERIODIC : 0u;
  const double xi = x[i], yi = y[i], rhoi = rho[i];
  double gx = 0.0, gy = 0.0, mxx = 0.0, mxy = 0.0, myy = 0.0;
  ROW(l, i, nb, cnt)
  for (size_t k = 0; k < cnt; k++) {
    const size_t j = nb[k];
    const double dx = sep_x(xi, x[j], period, half, F), dy = yi - y[j];
    const double r2 = dx * dx + dy * dy;
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
  }
  double axx, axy, ayy;
  sph_gradient_correction(mxx, mxy, myy, &axx, &axy, &ayy);
  *cx = 0.5 * (axx * gx + axy * gy);
  *cy = 0.5 * (axy * gx + ayy * gy);
}

int sph_diffusion_wall_takes_part(int32_t kind, uint8_t flags) {
  return kind == SPH_KIND_WALL && !(flags & (SPH_FLAG_MDBC | SPH_FLAG_REPULSIVE));
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
  const double period = fp->periodic ? fp->period : 0.0, half = 0.5 * period;
  const unsigned F = fp->periodic ? F_PERIODIC : 0u;
  ROW(l, i, nb, cnt)
  for (size_t k = 0; k < cnt; k++) {
    const size_t j = nb[k];
    if (!(p->flags[j] & SPH_FLAG_MDBC)) continue;
    const double dx = sep_x(p->x[i], p->x[j], period, half, F), dy = p->y[i] - p->y[j];
    const double hij = fp->var_h ? 0.5 * (p->h[i] + p->h[j]) : fp->h;
    if (dx * dx + dy * dy < 4.0 * hij * hij) return 0.0;
  }
  return p->mass[i];
}

void sph_diffusion_prepare(const sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                           sph_force_work *w) {
  const long n = (long)p->n;
  double cx = 0.0,
         cy = 0.0; /* the same c_i everywhere but for antuono (the lane loops rely on it) */
  if (fp->diffusion == SPH_DIFFUSION_NONE) return;
#pragma omp parallel for schedule(dynamic, 256) if (n > SPH_OMP_MIN)
  for (long i = 0; i < n; i++)
    w->ddm[i] = diffusion_mass(p, l, fp, (size_t)i);
  switch (fp->diffusion) {
  case SPH_DIFFUSION_NONE: return;
  case SPH_DIFFUSION_FOURTAKAS: {
    const double k = 0.5 * fp->eos.rho0 / (fp->eos.c0 * fp->eos.c0);
    cx = k * fp->gx;
    cy = k * fp->gy;
    break;
  }
  case SPH_DIFFUSION_ANTUONO:
#pragma omp parallel for schedule(dynamic, 256) if (n > SPH_OMP_MIN)
    for (long i = 0; i < n; i++) {
      if (p->kind[i] == SPH_KIND_FLUID)
        half_gradient(p, l, fp, (size_t)i, &w->ddcx[i], &w->ddcy[i]);
      else
        w->ddcx[i] = w->ddcy[i] = 0.0;
    }
    return;
  case SPH_DIFFUSION_MOLTENI: break;
  }
#pragma omp parallel for schedule(static) if (n > SPH_OMP_MIN)
  for (long i = 0; i < n; i++) {
    w->ddcx[i] = cx;
    w->ddcy[i] = cy;
  }
}
