/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * shifting.c - particle shifting (see shifting.h).
 */
#include "config.h"

#include "core/parallel.h"

#include "physics/shifting.h"

#include <math.h>

#include "physics/kernel.h"

void sph_shifting_sums_of(const sph_particles *p, const sph_nlist *l, const sph_shifting_params *sp,
                          size_t i, sph_shifting_sums *s) {
  const double h = sp->h, inv_h = 1.0 / h, support = SPH_CUBIC_SUPPORT * h;
  double w_dx, dw_dx;
  sph_kernel_w_dw(sp->kernel, sp->dx, h, &w_dx, &dw_dx);
  const double inv_wdx = 1.0 / w_dx;
  size_t cnt;
  const uint32_t *row = sph_nlist_row(l, i, &cnt);
  double g[SPH_DIM] = {0.0}, tg[SPH_DIM] = {0.0}, div = 0.0;
  for (size_t k = 0; k < cnt; k++) {
    const size_t j = row[k];
    double d[SPH_DIM];
    for (int a = 0; a < SPH_DIM; a++)
      d[a] = sph_nlist_sep(l, a, p->pos[a][i], p->pos[a][j]);
    const double r2 = SPH_NORM2(d[0], d[1], d[2]);
    if (r2 == 0.0 || r2 >= support * support) continue;
    const double r = sqrt(r2);
    double w, f; /* f = (1/r) dW/dr: grad_i W_ij = f r_ij */
    sph_kernel_w_f(sp->kernel, r, 1.0 / r, inv_h, &w, &f);
    const double vf = p->mass[j] / p->rho[j] * f;
    const double q = w * inv_wdx, q2 = q * q;
    const double t = 1.0 + SPH_SHIFTING_TENSILE * (q2 * q2); /* n = SPH_SHIFTING_EXPONENT = 4 */
    for (int a = 0; a < SPH_DIM; a++) {
      g[a] += vf * d[a];
      tg[a] += t * vf * d[a];
    }
    div -= vf * r2;
  }
  for (int a = 0; a < SPH_DIM; a++) {
    s->g[a] = g[a];
    s->tg[a] = tg[a];
  }
  s->div = div;
}

void sph_shifting_displacement(const sph_shifting_sums *s, double diffusivity, double d[SPH_DIM]) {
  for (int a = 0; a < SPH_DIM; a++)
    d[a] = -diffusivity * s->tg[a];
  const double g = sqrt(SPH_NORM2(s->g[0], s->g[1], s->g[2]));
  if (s->div < SPH_SHIFTING_SURFACE_DIV && g > 0.0) {
    double n[SPH_DIM];
    for (int a = 0; a < SPH_DIM; a++)
      n[a] = -s->g[a] / g;
    double along = d[0] * n[0];
    for (int a = 1; a < SPH_DIM; a++)
      along += d[a] * n[a];
    for (int a = 0; a < SPH_DIM; a++)
      d[a] -= along * n[a];
  }
}

void sph_shifting_compute(const sph_particles *p, const sph_nlist *l, const sph_shifting_params *sp,
                          double dt, double *const d[SPH_DIM]) {
  const long n = (long)p->n;
  const double ahdt = sp->coefficient * sp->h * dt;
#pragma omp parallel if (n > SPH_OMP_MIN)
  {
    size_t lo, hi;
    sph_slice(l->cost, p->n, &lo, &hi);
    for (size_t i = lo; i < hi; i++) {
      for (int a = 0; a < SPH_DIM; a++)
        d[a][i] = 0.0;
      if (p->kind[i] != SPH_KIND_FLUID) continue;
      sph_shifting_sums s;
      sph_shifting_sums_of(p, l, sp, i, &s);
      const double speed = sqrt(SPH_NORM2(p->vx[i], p->vy[i], p->vz[i]));
      double di[SPH_DIM];
      sph_shifting_displacement(&s, ahdt * speed, di);
      for (int a = 0; a < SPH_DIM; a++)
        d[a][i] = di[a];
    }
  }
}
