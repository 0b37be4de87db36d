/*
 * forces.c - the interaction passes (see forces.h for the equations).
 *
 * Loops are written once as always-inline functions taking a bit set F of
 * the terms in use; every call site passes a constant F, so each of the 128
 * combinations compiles to a loop without the terms it does not use
 * (DESIGN rule 4: a case pays only for what it switches on). Particles are
 * processed in parallel, each writing only its own rates; each sum runs
 * over neighbours in the grid's fixed order, so results are bitwise
 * independent of the thread count and the schedule.
 *
 * The viscous stress needs the strain rate of both particles of a pair, so
 * with that model a first pass computes eps_i at every particle (paper A
 * eq. 13-14) and stores tau_i / rho_i^2; the main pass then reads it.
 */
#include "config.h"

#include "parallel.h"

#include "forces.h"

#include <math.h>
#include <stdlib.h>

#include "kernel.h"
#include "turbulence.h"

/* The terms, as bits of F. */
enum {
  F_AV = 1,        /* artificial viscosity */
  F_XSPH = 2,      /* XSPH velocity correction */
  F_STRESS = 4,    /* viscous stress tensor, paper A */
  F_MORRIS = 8,    /* Morris laminar viscosity, paper B */
  F_PERIODIC = 16, /* minimum image in x */
  F_VARH = 32,     /* per-particle smoothing length */
  F_LEDGER = 64    /* energy ledger: du/dt and the power of moving walls */
};

void sph_force_work_free(sph_force_work *w) {
  free(w->prho2);
  free(w->cs);
  free(w->sigma);
  free(w->sxx);
  free(w->sxy);
  free(w->syy);
  free(w->wpow);
  free(w->wfx);
  free(w->wfy);
  *w = (sph_force_work){0};
}

static int work_reserve(sph_force_work *w, size_t n, sph_error *err) {
  if (n <= w->cap) return 0;
  const size_t cap = n + n / 4 + 16;
  double **arrays[] = {&w->prho2, &w->cs,   &w->sigma, &w->sxx, &w->sxy,
                       &w->syy,   &w->wpow, &w->wfx,   &w->wfy};
  for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; k++) {
    double *a = realloc(*arrays[k], cap * sizeof *a);
    if (!a) return sph_error_set(err, "forces: out of memory for %zu particles", n);
    *arrays[k] = a;
  }
  w->cap = cap;
  return 0;
}

void sph_forces_pressure(sph_particles *p, const sph_eos *eos) {
  const long n = (long)p->n;
#pragma omp parallel for schedule(static) if (n > SPH_OMP_MIN)
  for (long i = 0; i < n; i++) p->p[i] = sph_eos_pressure(eos, p->rho[i]);
}

/* Neighbour candidate ranges of i: three (plain grid) or six (periodic). */
#define RANGES(F, g, i, lo, hi, nr)                                                          \
  size_t lo[SPH_GRID_RANGES], hi[SPH_GRID_RANGES];                                           \
  int nr;                                                                                    \
  if ((F)&F_PERIODIC) {                                                                      \
    sph_grid_ranges_all(g, i, lo, hi);                                                       \
    nr = SPH_GRID_RANGES;                                                                    \
  } else {                                                                                   \
    sph_grid_ranges(g, i, lo, hi);                                                           \
    nr = 3;                                                                                  \
  }

/* x_i - x_j with the minimum image when periodic. */
static inline __attribute__((always_inline)) double sep_x(double xi, double xj, double period,
                                                          double half, const unsigned F) {
  double d = xi - xj;
  if (F & F_PERIODIC) {
    if (d > half)
      d -= period;
    else if (d < -half)
      d += period;
  }
  return d;
}

/* ---- the strain-rate pass (paper A eq. 13-14) ------------------------------------ */

static inline __attribute__((always_inline)) void
strain_one(const sph_particles *restrict p, const sph_grid *restrict g,
           const sph_force_params *restrict fp, size_t i, double *exx, double *exy, double *eyy,
           const unsigned F) {
  const double *restrict x = p->x, *restrict y = p->y, *restrict h = p->h;
  const double *restrict vx = p->vx, *restrict vy = p->vy;
  const double *restrict m = p->mass, *restrict rho = p->rho;
  const double period = fp->period, half = 0.5 * fp->period;
  const double xi = x[i], yi = y[i], vxi = vx[i], vyi = vy[i];
  double sxx = 0.0, sxy = 0.0, syy = 0.0, div = 0.0;
  RANGES(F, g, i, lo, hi, nr)
  for (int k = 0; k < nr; k++)
    for (size_t j = lo[k]; j < hi[k]; j++) {
      const double dx = sep_x(xi, x[j], period, half, F), dy = yi - y[j];
      const double r2 = dx * dx + dy * dy;
      const double hij = (F & F_VARH) ? 0.5 * (h[i] + h[j]) : fp->h;
      if (r2 >= 4.0 * hij * hij || r2 == 0.0) continue;
      const double r = sqrt(r2);
      double wij, dw;
      sph_cubic_w_dw(r, hij, &wij, &dw);
      const double f = dw / r * (m[j] / rho[j]);
      const double gx = f * dx, gy = f * dy;       /* V_j grad_i W_ij */
      const double ux = vx[j] - vxi, uy = vy[j] - vyi; /* v_ji */
      sxx += 2.0 * ux * gx;
      syy += 2.0 * uy * gy;
      sxy += uy * gx + ux * gy;
      div += ux * gx + uy * gy;
    }
  /* the deviatoric part as the paper writes it (its 2/3 is the 3-D factor) */
  exx[i] = sxx - (2.0 / 3.0) * div;
  eyy[i] = syy - (2.0 / 3.0) * div;
  exy[i] = sxy;
}

/* One function per variant, with F a literal inside the parallel region
 * (OpenMP outlines the region before inlining, so a constant must be
 * spelled out there to reach the loop). */
#define STRAIN_VARIANT(k)                                                                    \
  static void strain_all_##k(const sph_particles *p, const sph_grid *g,                       \
                             const sph_force_params *fp, double *exx, double *exy,            \
                             double *eyy) {                                                   \
    const long n = (long)p->n;                                                               \
    _Pragma("omp parallel for schedule(dynamic, 256) if (n > SPH_OMP_MIN)") for (long i = 0; i < n; i++)          \
        strain_one(p, g, fp, (size_t)i, exx, exy, eyy, k);                                   \
  }
STRAIN_VARIANT(0)
STRAIN_VARIANT(16)
STRAIN_VARIANT(32)
STRAIN_VARIANT(48)

int sph_forces_strain_rate(const sph_particles *p, const sph_grid *g, const sph_force_params *fp,
                           double *exx, double *exy, double *eyy, sph_error *err) {
  (void)err;
  const unsigned F = (fp->periodic ? F_PERIODIC : 0) | (fp->var_h ? F_VARH : 0);
  switch (F) {
  case 0: strain_all_0(p, g, fp, exx, exy, eyy); break;
  case F_PERIODIC: strain_all_16(p, g, fp, exx, exy, eyy); break;
  case F_VARH: strain_all_32(p, g, fp, exx, exy, eyy); break;
  default: strain_all_48(p, g, fp, exx, exy, eyy); break;
  }
  return 0;
}

/* ---- the main pass ----------------------------------------------------------------- */

static inline __attribute__((always_inline)) void
interact_one(sph_particles *restrict p, const sph_grid *restrict g,
             const sph_force_params *restrict fp, sph_force_work *restrict w, size_t i,
             const unsigned F) {
  const double *restrict x = p->x, *restrict y = p->y, *restrict h = p->h;
  const double *restrict vx = p->vx, *restrict vy = p->vy;
  const double *restrict m = p->mass, *restrict rho = p->rho;
  const double *restrict prho2 = w->prho2, *restrict cs = w->cs;
  const double *restrict sxx = w->sxx, *restrict sxy = w->sxy, *restrict syy = w->syy;
  const int32_t *restrict kind = p->kind;
  const double period = fp->period, half = 0.5 * fp->period;
  const double nu4 = 4.0 * fp->mu / fp->eos.rho0;
  if (kind[i] == SPH_KIND_MIRROR || (p->flags[i] & SPH_FLAG_REPULSIVE)) {
    p->drho[i] = p->ax[i] = p->ay[i] = 0.0;
    w->sigma[i] = 0.0;
    if (F & F_LEDGER) p->du[i] = w->wpow[i] = w->wfx[i] = w->wfy[i] = 0.0;
    return;
  }
  const double xi = x[i], yi = y[i], vxi = vx[i], vyi = vy[i];
  const double rhoi = rho[i], pri = prho2[i], ci = cs[i];
  const int fluid = kind[i] == SPH_KIND_FLUID;
  double drho = 0.0, ax = 0.0, ay = 0.0, xs = 0.0, ys = 0.0, sig = 0.0;
  double du = 0.0, wpow = 0.0, wfx = 0.0, wfy = 0.0; /* energy and momentum ledger */
  RANGES(F, g, i, lo, hi, nr)
  for (int k = 0; k < nr; k++) {
    for (size_t j = lo[k]; j < hi[k]; j++) {
      const double dx = sep_x(xi, x[j], period, half, F), dy = yi - y[j];
      const double r2 = dx * dx + dy * dy;
      const double hij = (F & F_VARH) ? 0.5 * (h[i] + h[j]) : fp->h;
      if (r2 >= 4.0 * hij * hij || r2 == 0.0) continue; /* j == i, or coincident */
      const double r = sqrt(r2);
      double wij, dw;
      sph_cubic_w_dw(r, hij, &wij, &dw);
      const double f = dw / r;
      const double gx = f * dx, gy = f * dy;
      const double dvx = vxi - vx[j], dvy = vyi - vy[j];
      drho += m[j] * (dvx * gx + dvy * gy);
      const double vdotr = dvx * dx + dvy * dy;
      const double s = fabs(hij * vdotr / r2);
      if (s > sig) sig = s;
      /* a wall particle needs the pair terms only for its share of the heat */
      if (!fluid && !((F & F_LEDGER) && kind[j] == SPH_KIND_FLUID)) continue;
      double pij = pri + prho2[j];
      if ((F & F_AV) && vdotr < 0.0) {
        const double eta = fp->eta * hij;
        const double mu = hij * vdotr / (r2 + eta * eta);
        const double cbar = 0.5 * (ci + cs[j]);
        const double rhobar = 0.5 * (rhoi + rho[j]);
        pij += (-fp->alpha * cbar * mu + fp->beta * mu * mu) / rhobar;
      }
      /* the pair's acceleration of i (momentum, paper A eq. 11) */
      double pax = -m[j] * pij * gx, pay = -m[j] * pij * gy;
      if (F & F_LEDGER) du += 0.5 * m[j] * pij * (dvx * gx + dvy * gy); /* A eq. 28 */
      if (F & F_STRESS) {
        const double txx = sxx[i] + sxx[j], txy = sxy[i] + sxy[j], tyy = syy[i] + syy[j];
        pax += m[j] * (txx * gx + txy * gy);
        pay += m[j] * (txy * gx + tyy * gy);
        /* viscous dissipation, the discrete form of A eq. 29 that balances
         * the pair's work exactly */
        if (F & F_LEDGER)
          du -= 0.5 * m[j] * (txx * dvx * gx + txy * (dvx * gy + dvy * gx) + tyy * dvy * gy);
      }
      if (F & F_MORRIS) {
        const double eta = fp->eta * hij;
        const double c = m[j] * nu4 * (f * r2) / ((rhoi + rho[j]) * (r2 + eta * eta));
        pax += c * dvx;
        pay += c * dvy;
        if (F & F_LEDGER) du -= 0.5 * c * (dvx * dvx + dvy * dvy);
      }
      if (!fluid) continue;
      ax += pax;
      ay += pay;
      /* power of a (moving) wall particle's force on i, per unit mass of i */
      if ((F & F_LEDGER) && kind[j] == SPH_KIND_WALL) wpow += pax * vx[j] + pay * vy[j];
      /* force of walls and mirror particles on i: external to the fluid */
      if ((F & F_LEDGER) && kind[j] != SPH_KIND_FLUID) {
        wfx += pax;
        wfy += pay;
      }
      if ((F & F_XSPH) && kind[j] == SPH_KIND_FLUID) {
        const double c = m[j] / (0.5 * (rhoi + rho[j])) * wij;
        xs -= c * dvx;
        ys -= c * dvy;
      }
    }
  }
  p->drho[i] = drho;
  w->sigma[i] = sig;
  if (F & F_LEDGER) {
    p->du[i] = du;
    w->wpow[i] = wpow;
    w->wfx[i] = wfx;
    w->wfy[i] = wfy;
  }
  if (fluid) {
    p->ax[i] = ax + fp->gx;
    p->ay[i] = ay + fp->gy;
    if (F & F_XSPH) {
      p->xsx[i] = fp->xsph * xs;
      p->xsy[i] = fp->xsph * ys;
    }
  } else {
    p->ax[i] = p->ay[i] = 0.0;
  }
}

/* One function per combination of terms, F a literal in its parallel
 * region (see STRAIN_VARIANT). */
#define VARIANT(k)                                                                           \
  static void interact_all_##k(sph_particles *p, const sph_grid *g,                          \
                               const sph_force_params *fp, sph_force_work *w) {               \
    const long n = (long)p->n;                                                               \
    _Pragma("omp parallel for schedule(dynamic, 256) if (n > SPH_OMP_MIN)") for (long i = 0; i < n; i++)          \
        interact_one(p, g, fp, w, (size_t)i, k);                                             \
  }
#define VARIANTS8(a, b, c, d, e, f, g, h)                                                    \
  VARIANT(a) VARIANT(b) VARIANT(c) VARIANT(d) VARIANT(e) VARIANT(f) VARIANT(g) VARIANT(h)
VARIANTS8(0, 1, 2, 3, 4, 5, 6, 7)
VARIANTS8(8, 9, 10, 11, 12, 13, 14, 15)
VARIANTS8(16, 17, 18, 19, 20, 21, 22, 23)
VARIANTS8(24, 25, 26, 27, 28, 29, 30, 31)
VARIANTS8(32, 33, 34, 35, 36, 37, 38, 39)
VARIANTS8(40, 41, 42, 43, 44, 45, 46, 47)
VARIANTS8(48, 49, 50, 51, 52, 53, 54, 55)
VARIANTS8(56, 57, 58, 59, 60, 61, 62, 63)
VARIANTS8(64, 65, 66, 67, 68, 69, 70, 71)
VARIANTS8(72, 73, 74, 75, 76, 77, 78, 79)
VARIANTS8(80, 81, 82, 83, 84, 85, 86, 87)
VARIANTS8(88, 89, 90, 91, 92, 93, 94, 95)
VARIANTS8(96, 97, 98, 99, 100, 101, 102, 103)
VARIANTS8(104, 105, 106, 107, 108, 109, 110, 111)
VARIANTS8(112, 113, 114, 115, 116, 117, 118, 119)
VARIANTS8(120, 121, 122, 123, 124, 125, 126, 127)

typedef void (*interact_fn)(sph_particles *, const sph_grid *, const sph_force_params *,
                            sph_force_work *);
#define FN8(a, b, c, d, e, f, g, h)                                                          \
  interact_all_##a, interact_all_##b, interact_all_##c, interact_all_##d, interact_all_##e,   \
      interact_all_##f, interact_all_##g, interact_all_##h
static const interact_fn VARIANT_TABLE[128] = {
    FN8(0, 1, 2, 3, 4, 5, 6, 7),         FN8(8, 9, 10, 11, 12, 13, 14, 15),
    FN8(16, 17, 18, 19, 20, 21, 22, 23), FN8(24, 25, 26, 27, 28, 29, 30, 31),
    FN8(32, 33, 34, 35, 36, 37, 38, 39), FN8(40, 41, 42, 43, 44, 45, 46, 47),
    FN8(48, 49, 50, 51, 52, 53, 54, 55), FN8(56, 57, 58, 59, 60, 61, 62, 63),
    FN8(64, 65, 66, 67, 68, 69, 70, 71), FN8(72, 73, 74, 75, 76, 77, 78, 79),
    FN8(80, 81, 82, 83, 84, 85, 86, 87), FN8(88, 89, 90, 91, 92, 93, 94, 95),
    FN8(96, 97, 98, 99, 100, 101, 102, 103), FN8(104, 105, 106, 107, 108, 109, 110, 111),
    FN8(112, 113, 114, 115, 116, 117, 118, 119), FN8(120, 121, 122, 123, 124, 125, 126, 127)};

/* ---- repulsive walls (paper A eq. 21-22) ------------------------------------------- */

static void lennard_jones(sph_particles *p, const sph_grid *g, const sph_force_params *fp) {
  const long n = (long)p->n;
  const double r0 = fp->lj_r0, d = fp->lj_d;
  const double period = fp->period, half = 0.5 * fp->period;
#pragma omp parallel for schedule(dynamic, 256) if (n > SPH_OMP_MIN)
  for (long li = 0; li < n; li++) {
    const size_t i = (size_t)li;
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    size_t lo[SPH_GRID_RANGES], hi[SPH_GRID_RANGES];
    sph_grid_ranges_all(g, i, lo, hi);
    double ax = 0.0, ay = 0.0;
    for (int k = 0; k < SPH_GRID_RANGES; k++)
      for (size_t j = lo[k]; j < hi[k]; j++) {
        if (!(p->flags[j] & SPH_FLAG_REPULSIVE)) continue;
        double dx = p->x[i] - p->x[j];
        if (fp->periodic) {
          if (dx > half)
            dx -= period;
          else if (dx < -half)
            dx += period;
        }
        const double dy = p->y[i] - p->y[j];
        const double r2 = dx * dx + dy * dy;
        if (r2 >= r0 * r0 || r2 == 0.0) continue;
        const double q2 = r0 * r0 / r2, q4 = q2 * q2, q12 = q4 * q4 * q4;
        const double f = d * (q12 - q4) / r2;
        ax += f * dx;
        ay += f * dy;
      }
    p->ax[i] += ax;
    p->ay[i] += ay;
  }
}

int sph_forces_evaluate(sph_particles *p, const sph_grid *g, const sph_force_params *fp,
                        sph_force_work *w, sph_error *err) {
  const long n = (long)p->n;
  if (work_reserve(w, p->n, err)) return -1;
#pragma omp parallel for schedule(static) if (n > SPH_OMP_MIN)
  for (long i = 0; i < n; i++) {
    const double rho = p->rho[i];
    w->prho2[i] = p->p[i] / (rho * rho);
    w->cs[i] = sph_eos_sound_speed(&fp->eos, rho);
  }
  unsigned F = 0;
  if (fp->alpha != 0.0 || fp->beta != 0.0) F |= F_AV;
  if (fp->xsph != 0.0) F |= F_XSPH;
  if (fp->viscosity == SPH_VISCOSITY_STRESS_TENSOR || fp->sps) F |= F_STRESS;
  if (fp->viscosity == SPH_VISCOSITY_MORRIS) F |= F_MORRIS;
  if (fp->periodic) F |= F_PERIODIC;
  if (fp->var_h) F |= F_VARH;
  if (fp->ledger) F |= F_LEDGER;
  if (F & F_STRESS) {
    if (sph_forces_strain_rate(p, g, fp, w->sxx, w->sxy, w->syy, err)) return -1;
#pragma omp parallel for schedule(static) if (n > SPH_OMP_MIN)
    for (long i = 0; i < n; i++) { /* tau / rho^2: laminar mu eps, plus the SPS stress */
      const double rho = p->rho[i];
      const double exx = w->sxx[i], exy = w->sxy[i], eyy = w->syy[i];
      const double lam = fp->viscosity == SPH_VISCOSITY_STRESS_TENSOR ? fp->mu / (rho * rho) : 0.0;
      double txx = lam * exx, txy = lam * exy, tyy = lam * eyy;
      if (fp->sps) {
        /* S from eps (eps_xx = 2 S_xx - (2/3) div, div = S_xx + S_yy) */
        double a, b, c;
        sph_sps_stress(0.5 * (2.0 * exx + eyy), 0.5 * exy, 0.5 * (2.0 * eyy + exx), fp->sps_cs,
                       fp->sps_ci, fp->sps_delta, &a, &b, &c);
        txx += a / rho;
        txy += b / rho;
        tyy += c / rho;
      }
      w->sxx[i] = txx;
      w->sxy[i] = txy;
      w->syy[i] = tyy;
    }
  }
  VARIANT_TABLE[F](p, g, fp, w);
  if (fp->repulsive) lennard_jones(p, g, fp);
  return 0;
}
