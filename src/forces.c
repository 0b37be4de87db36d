/*
 * forces.c - the interaction pass (see forces.h for the equations).
 *
 * The loop body is one always-inline function whose switches (artificial
 * viscosity on/off, XSPH on/off) are compile-time constants at each call
 * site, so each case runs a loop without the terms it does not use
 * (DESIGN rule 4). Particles are processed in parallel, each writing only
 * its own rates; each sum runs over neighbours in the grid's fixed order,
 * so results are bitwise independent of the thread count and schedule.
 */
#include "config.h"

#include "forces.h"

#include <math.h>
#include <stdlib.h>

#include "kernel.h"

void sph_force_work_free(sph_force_work *w) {
  free(w->prho2);
  free(w->cs);
  free(w->sigma);
  w->prho2 = w->cs = w->sigma = NULL;
  w->cap = 0;
}

static int work_reserve(sph_force_work *w, size_t n, sph_error *err) {
  if (n <= w->cap) return 0;
  size_t cap = n + n / 4 + 16;
  double *a = realloc(w->prho2, cap * sizeof *a);
  if (a) w->prho2 = a;
  double *b = realloc(w->cs, cap * sizeof *b);
  if (b) w->cs = b;
  double *c = realloc(w->sigma, cap * sizeof *c);
  if (c) w->sigma = c;
  if (!a || !b || !c) return sph_error_set(err, "forces: out of memory for %zu particles", n);
  w->cap = cap;
  return 0;
}

void sph_forces_pressure(sph_particles *p, const sph_eos *eos) {
  const long n = (long)p->n;
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; i++) p->p[i] = sph_eos_pressure(eos, p->rho[i]);
}

/* The rates of particle i: AV and XSPH are constants at each call site. */
static inline __attribute__((always_inline)) void
interact_one(sph_particles *restrict p, const sph_grid *restrict g,
             const sph_force_params *restrict fp, sph_force_work *restrict w, size_t i,
             const int AV, const int XSPH) {
  const double *restrict x = p->x, *restrict y = p->y;
  const double *restrict vx = p->vx, *restrict vy = p->vy;
  const double *restrict m = p->mass, *restrict rho = p->rho;
  const double *restrict prho2 = w->prho2, *restrict cs = w->cs;
  const int32_t *restrict kind = p->kind;
  const double h = fp->h;
  const double support2 = (SPH_CUBIC_SUPPORT * h) * (SPH_CUBIC_SUPPORT * h);
  const double eta2 = (fp->eta * h) * (fp->eta * h);
  const double xi = x[i], yi = y[i], vxi = vx[i], vyi = vy[i];
  const double rhoi = rho[i], pri = prho2[i], ci = cs[i];
  const int fluid = kind[i] == SPH_KIND_FLUID;
  double drho = 0.0, ax = 0.0, ay = 0.0, xs = 0.0, ys = 0.0, sig = 0.0;
  size_t lo[3], hi[3];
  sph_grid_ranges(g, i, lo, hi);
  for (int k = 0; k < 3; k++) {
    for (size_t j = lo[k]; j < hi[k]; j++) {
      const double dx = xi - x[j], dy = yi - y[j];
      const double r2 = dx * dx + dy * dy;
      if (r2 >= support2 || r2 == 0.0) continue; /* j == i, or coincident */
      const double r = sqrt(r2);
      double wij, dw;
      sph_cubic_w_dw(r, h, &wij, &dw);
      const double f = dw / r;
      const double gx = f * dx, gy = f * dy;
      const double dvx = vxi - vx[j], dvy = vyi - vy[j];
      drho += m[j] * (dvx * gx + dvy * gy);
      const double vdotr = dvx * dx + dvy * dy;
      const double s = fabs(h * vdotr / r2);
      if (s > sig) sig = s;
      if (!fluid) continue;
      double pij = pri + prho2[j];
      if (AV && vdotr < 0.0) {
        const double mu = h * vdotr / (r2 + eta2);
        const double cbar = 0.5 * (ci + cs[j]);
        const double rhobar = 0.5 * (rhoi + rho[j]);
        pij += (-fp->alpha * cbar * mu + fp->beta * mu * mu) / rhobar;
      }
      ax -= m[j] * pij * gx;
      ay -= m[j] * pij * gy;
      if (XSPH && kind[j] == SPH_KIND_FLUID) {
        const double c = m[j] / (0.5 * (rhoi + rho[j])) * wij;
        xs -= c * dvx;
        ys -= c * dvy;
      }
    }
  }
  p->drho[i] = drho;
  w->sigma[i] = sig;
  if (fluid) {
    p->ax[i] = ax + fp->gx;
    p->ay[i] = ay + fp->gy;
    if (XSPH) {
      p->xsx[i] = fp->xsph * xs;
      p->xsy[i] = fp->xsph * ys;
    }
  } else {
    p->ax[i] = p->ay[i] = 0.0;
  }
}

static void interact_all(sph_particles *p, const sph_grid *g, const sph_force_params *fp,
                         sph_force_work *w, const int AV, const int XSPH) {
  const long n = (long)p->n;
#pragma omp parallel for schedule(dynamic, 256)
  for (long i = 0; i < n; i++) interact_one(p, g, fp, w, (size_t)i, AV, XSPH);
}

int sph_forces_evaluate(sph_particles *p, const sph_grid *g, const sph_force_params *fp,
                        sph_force_work *w, sph_error *err) {
  const long n = (long)p->n;
  if (work_reserve(w, p->n, err)) return -1;
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; i++) {
    const double rho = p->rho[i];
    w->prho2[i] = p->p[i] / (rho * rho);
    w->cs[i] = sph_eos_sound_speed(&fp->eos, rho);
  }
  const int av = fp->alpha != 0.0 || fp->beta != 0.0;
  const int xsph = fp->xsph != 0.0;
  if (av && xsph)
    interact_all(p, g, fp, w, 1, 1);
  else if (av)
    interact_all(p, g, fp, w, 1, 0);
  else if (xsph)
    interact_all(p, g, fp, w, 0, 1);
  else
    interact_all(p, g, fp, w, 0, 0);
  return 0;
}
