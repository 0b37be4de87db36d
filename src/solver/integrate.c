/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * integrate.c - predictor-corrector stages and time-step rules (see
 * integrate.h). Every loop is per particle (no sums), and the step rules use
 * min/max reductions only, which are exact in any order, so the results do
 * not depend on the number of threads.
 */
#include "config.h"

#include "core/parallel.h"

#include "solver/integrate.h"

#include <math.h>

/* X0 <- X for particle i: position, velocity, density (group SAVED). */
static inline __attribute__((always_inline)) void save_start(sph_particles *p, size_t i) {
  p->x0[i] = p->x[i];
  p->y0[i] = p->y[i];
  p->vx0[i] = p->vx[i];
  p->vy0[i] = p->vy[i];
  SPH_IF3(p->z0[i] = p->z[i]; p->vz0[i] = p->vz[i];)
  p->rho0[i] = p->rho[i];
}

/* The shared update: X <- X0 + dt/2 F, then doubled-and-shifted when
 * `finish`: X <- 2 X - X0; the predictor first saves X0 <- X (`save`).
 * The pressure follows from the new density in the same loop, so a stage
 * is one pass over the store (and one parallel region). */
static inline __attribute__((always_inline)) void stage(sph_particles *p, double dt, int xsph,
                                                        const sph_eos *eos, const size_t *cost,
                                                        const int save, const int finish) {
  const long n = (long)p->n;
  const double hdt = 0.5 * dt;
  const int heat = (p->live & SPH_ARRAYS_HEAT) != 0; /* without the ledger u stays 0 */
  const uint8_t *ph = sph_particles_phases(p);
#pragma omp parallel if (n > SPH_OMP_MIN)
  {
    size_t lo, hi;
    sph_slice(cost, p->n, &lo, &hi);
    for (size_t i = lo; i < hi; i++) {
      const sph_eos *e = sph_eos_of(eos, ph, i);
      if (save) {
        save_start(p, i);
        if (heat) p->u0[i] = p->u[i];
      }
      double rho = p->rho0[i] + hdt * p->drho[i];
      if (finish) rho = 2.0 * rho - p->rho0[i];
      if (p->kind[i] == SPH_KIND_FLUID) rho = sph_eos_floor(e, rho);
      p->rho[i] = rho;
      if (heat) {
        double u = p->u0[i] + hdt * p->du[i];
        if (finish) u = 2.0 * u - p->u0[i];
        p->u[i] = u;
      }
      p->p[i] = sph_eos_pressure(e, rho);
      if (p->kind[i] != SPH_KIND_FLUID) continue;
      double ux = p->vx[i], uy = p->vy[i]; /* dr/dt uses the velocity of the evaluated state */
      SPH_IF3(double uz = p->vz[i];)
      if (xsph) {
        ux += p->xsx[i];
        uy += p->xsy[i];
        SPH_IF3(uz += p->xsz[i];)
      }
      double x = p->x0[i] + hdt * ux, y = p->y0[i] + hdt * uy;
      double vx = p->vx0[i] + hdt * p->ax[i], vy = p->vy0[i] + hdt * p->ay[i];
      SPH_IF3(double z = p->z0[i] + hdt * uz, vz = p->vz0[i] + hdt * p->az[i];)
      if (finish) {
        x = 2.0 * x - p->x0[i];
        y = 2.0 * y - p->y0[i];
        vx = 2.0 * vx - p->vx0[i];
        vy = 2.0 * vy - p->vy0[i];
        SPH_IF3(z = 2.0 * z - p->z0[i]; vz = 2.0 * vz - p->vz0[i];)
      }
      p->x[i] = x;
      p->y[i] = y;
      p->vx[i] = vx;
      p->vy[i] = vy;
      SPH_IF3(p->z[i] = z; p->vz[i] = vz;)
    }
  }
}

void sph_pc_half(sph_particles *p, double dt, int xsph, const sph_eos *eos, const size_t *cost) {
  stage(p, dt, xsph, eos, cost, 1, 0);
}
void sph_pc_finish(sph_particles *p, double dt, int xsph, const sph_eos *eos, const size_t *cost) {
  stage(p, dt, xsph, eos, cost, 0, 1);
}

void sph_leapfrog_step(sph_particles *p, double dt, double dt_prev, int first, int xsph,
                       const sph_eos *eos, const size_t *cost) {
  const long n = (long)p->n;
  /* the kick spans t^{n-1/2} to t^{n+1/2}: half the last step and half this one (a kick of a
   * whole dt gained or lost (dt - dt_prev)/2 of every rate at each change of step, for good:
   * the energy box's ledger drifted by 7e-5 of E0, first order in the step) */
  const double kick = first ? 0.5 * dt : 0.5 * (dt_prev + dt), hdt = 0.5 * dt;
  const int heat = (p->live & SPH_ARRAYS_HEAT) != 0; /* without the ledger u stays 0 */
  /* the saved state (the last good state after a blow-up), unless the
   * pass's packed copy holds it (solver/sim.c) */
  const int save = (p->live & SPH_ARRAYS_SAVED) != 0;
  const uint8_t *ph = sph_particles_phases(p);
#pragma omp parallel if (n > SPH_OMP_MIN)
  {
    size_t lo, hi;
    sph_slice(cost, p->n, &lo, &hi);
    for (size_t i = lo; i < hi; i++) {
      if (save) save_start(p, i);
      if (p->flags[i] & (SPH_FLAG_MDBC | SPH_FLAG_ADAMI)) {
        /* an mdbc wall's density is the fluid's, extrapolated at every pass
         * (wall_velocity.h), not a state: integrated from t = 0 its half-step
         * value drifted to 1.3 rho0 on the Lobovsky floor and stopped the run
         * as a blow-up although the pass never used it */
        p->rhoh[i] = p->rho[i];
      } else {
        const sph_eos *e = sph_eos_of(eos, ph, i);
        double rh = (first ? p->rho[i] : p->rhoh[i]) + kick * p->drho[i],
               rho = rh + hdt * p->drho[i];
        if (p->kind[i] == SPH_KIND_FLUID) /* the floor (eos.h), on both the state and its value */
          rh = sph_eos_floor(e, rh), rho = sph_eos_floor(e, rho);
        p->rhoh[i] = rh;
        p->rho[i] = rho;
        p->p[i] = sph_eos_pressure(e, p->rho[i]);
      }
      if (heat) {
        p->u0[i] = p->u[i];
        const double uh = (first ? p->u[i] : p->uh[i]) + kick * p->du[i];
        p->uh[i] = uh;
        p->u[i] = uh + hdt * p->du[i];
      }
      if (p->kind[i] != SPH_KIND_FLUID) continue;
      const double vxh = (first ? p->vx[i] : p->vxh[i]) + kick * p->ax[i];
      const double vyh = (first ? p->vy[i] : p->vyh[i]) + kick * p->ay[i];
      double ux = vxh, uy = vyh;
      SPH_IF3(const double vzh = (first ? p->vz[i] : p->vzh[i]) + kick * p->az[i]; double uz = vzh;)
      if (xsph) {
        ux += p->xsx[i];
        uy += p->xsy[i];
        SPH_IF3(uz += p->xsz[i];)
      }
      p->x[i] += dt * ux;
      p->y[i] += dt * uy;
      p->vxh[i] = vxh;
      p->vyh[i] = vyh;
      p->vx[i] = vxh + hdt * p->ax[i];
      p->vy[i] = vyh + hdt * p->ay[i];
      SPH_IF3(p->z[i] += dt * uz; p->vzh[i] = vzh; p->vz[i] = vzh + hdt * p->az[i];)
    }
  }
}

double sph_dt_paper_b(const sph_force_work *w, double h, double factor) {
  /* min_a (factor h) / x_a = (factor h) / max_a x_a exactly: a correctly
   * rounded division is monotone in its divisor */
  return factor * h / w->cs_sigma_max;
}

double sph_dt_cfl(const sph_particles *p, const sph_eos *eos, double h, double factor) {
  const long n = (long)p->n;
  double vmax = 0.0;
#pragma omp parallel for schedule(static) if (n > SPH_OMP_MIN) reduction(max : vmax)
  for (long i = 0; i < n; i++) {
    const double v = sph_cfl_speed(p, eos, (size_t)i);
    if (v > vmax) vmax = v;
  }
  return sph_dt_cfl_of(vmax, h, factor);
}
