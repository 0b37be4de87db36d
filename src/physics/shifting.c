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
  const uint32_t *row = l->nb + l->start[i];
  double gx = 0.0, gy = 0.0, tgx = 0.0, tgy = 0.0, div = 0.0;
  for (size_t k = 0; k < l->count[i]; k++) {
    const size_t j = row[k];
    const double dx = sph_grid_min_image(p->x[i] - p->x[j], sp->period);
    const double dy = p->y[i] - p->y[j];
    const double r2 = dx * dx + dy * dy;
    if (r2 == 0.0 || r2 >= support * support) continue;
    const double r = sqrt(r2);
    double w, f; /* f = (1/r) dW/dr: grad_i W_ij = f r_ij */
    sph_kernel_w_f(sp->kernel, r, 1.0 / r, inv_h, &w, &f);
    const double vf = p->mass[j] / p->rho[j] * f;
    const double q = w * inv_wdx, q2 = q * q;
    const double t = 1.0 + SPH_SHIFTING_TENSILE * (q2 * q2); /* n = SPH_SHIFTING_EXPONENT = 4 */
    gx += vf * dx;
    gy += vf * dy;
    tgx += t * vf * dx;
    tgy += t * vf * dy;
    div -= vf * r2;
  }
  s->gx = gx;
  s->gy = gy;
  s->tgx = tgx;
  s->tgy = tgy;
  s->div = div;
}

void sph_shifting_displacement(const sph_shifting_sums *s, double diffusivity, double *dx,
                               double *dy) {
  double sx = -diffusivity * s->tgx, sy = -diffusivity * s->tgy;
  const double g = sqrt(s->gx * s->gx + s->gy * s->gy);
  if (s->div < SPH_SHIFTING_SURFACE_DIV && g > 0.0) {
    const double nx = -s->gx / g, ny = -s->gy / g, along = sx * nx + sy * ny;
    sx -= along * nx;
    sy -= along * ny;
  }
  *dx = sx;
  *dy = sy;
}

void sph_shifting_compute(const sph_particles *p, const sph_nlist *l, const sph_shifting_params *sp,
                          double dt, double *dx, double *dy) {
  const long n = (long)p->n;
  const double ahdt = sp->coefficient * sp->h * dt;
#pragma omp parallel if (n > SPH_OMP_MIN)
  {
    size_t lo, hi;
    sph_slice(l->cost, p->n, &lo, &hi);
    for (size_t i = lo; i < hi; i++) {
      dx[i] = dy[i] = 0.0;
      if (p->kind[i] != SPH_KIND_FLUID) continue;
      sph_shifting_sums s;
      sph_shifting_sums_of(p, l, sp, i, &s);
      const double speed = sqrt(p->vx[i] * p->vx[i] + p->vy[i] * p->vy[i]);
      sph_shifting_displacement(&s, ahdt * speed, &dx[i], &dy[i]);
    }
  }
}
