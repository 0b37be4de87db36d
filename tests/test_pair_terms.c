/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_pair_terms.c - the pair terms are written once and every loop that
 * sums them agrees (src/physics/pair_terms.h, src/solver/interact.h).
 *
 * 1. Oracle: for each of the 512 term sets F (artificial viscosity, XSPH,
 *    stress tensor, Morris, periodic, per-particle h, energy ledger,
 *    density diffusion: Molteni-Colagrossi, Antuono, Fourtakas by set;
 *    the Riemann-solver pressure and continuity term;
 *    the cubic spline and the Wendland C2 kernel alternating; the
 *    corrected gradient of the pressure and continuity in one of the
 *    three sets, the oracle inverting each particle's moment itself) and
 *    three random particle sets (fluid on a jittered lattice with random
 *    velocities and densities; dynamic, moving, repulsive and mirror wall
 *    particles below it; periodic in x when F says so, per-particle h
 *    when F says so; in the second set the moving wall is free-slip, in
 *    the third the mirror particles carry their own no-slip velocity), the
 *    main pass is run with the scalar loop, the
 *    portable lane loop and, where the processor has them, the AVX2 lane
 *    loop and the AVX-512 eight-lane loop, and compared with a naive all-pairs loop written here
 * from the papers' equations (piecewise kernel, no neighbour list). Every rate (drho/dt, dv/dt with
 * gravity and the Lennard-Jones force, XSPH, du/dt, the step rule's sigma, the ledger's wall power
 * and wall force) agrees to 1e-12 of the largest magnitude of that rate over the set. The lane
 * flavours (four lanes, portable and AVX2; eight lanes into four- lane sums, AVX-512) agree
 * bitwise, and so do the lane and scalar loops where the lane loop defers to the scalar one
 * (per-particle h, ledger).
 * 2. Symmetry: each force term evaluated for the pair (i, j) and for
 *    (j, i), with the inputs formed as a loop forms them (x_j - x_i, ...),
 *    is exactly antisymmetric (equal masses), and each scalar term (the
 *    continuity sum, signal, heats, kernel) exactly symmetric; a free-slip
 *    wall's normal part of the gradient is antisymmetric and along the
 *    normal; the Lennard-Jones potential is zero at r0 and its slope is
 *    minus the force (central differences, 1e-5); and each
 *    term gives the same bits in every lane of v4e as in v1 (v4x and v8z
 *    are held to v4e bitwise through the loops in 1).
 * 3. The AVX-512 operations themselves (where the processor has AVX-512):
 *    every v8z operation gives v1's bits in each of its eight lanes, on
 *    values that include signed zeros, infinities, ties of min and max and
 *    subnormals; the record transposes (v8z and, with AVX2, v4x) put field f
 *    of record q in lane q of vector f; v8z_lo / v8z_hi are lanes 0-3 and
 *    4-7.
 */
#include "config.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "core/particles.h"
#include "neighbours/grid.h"
#include "physics/eos.h"
#include "physics/kernel.h"
#include "physics/pair_terms.h"
#include "physics/turbulence.h"
#include "solver/forces.h"
#include "testutil.h"

#define DX 0.02
#define NXL 12 /* lattice columns */
#define NYL 10 /* lattice rows: 3 wall rows, then fluid */
#define RHO0 1000.0
#define TOL 1e-12

/* a small counter-based generator: uniform in [0, 1) */
static uint64_t rng_state;
static double uniform(void) {
  rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(rng_state >> 11) * 0x1.0p-53;
}
static double between(double a, double b) { return a + (b - a) * uniform(); }

/* The random set: walls in rows 0-2 (row 0 repulsive, row 1 every third a
 * mirror particle with a no-slip velocity of its own in vxh, vyh, row 2
 * dynamic and moving, every other one flagged mdbc, free-slip when `slip`,
 * its normal (0, -1) as a mirror offset (0, -DX)), fluid above. */
static void make_set(sph_particles *p, unsigned seed, int periodic, int varh, int slip,
                     const sph_eos *eos) {
  sph_error err;
  rng_state = 0x9e3779b97f4a7c15ULL * (seed + 1);
  CU_ASSERT_FATAL(sph_particles_init(p, NXL * NYL, &err) == 0);
  const double h0 = 1.3 * DX;
  for (int j = 0; j < NYL; j++)
    for (int i = 0; i < NXL; i++) {
      double x = (i + 0.5) * DX + between(-0.2, 0.2) * DX;
      const double y = (j + 0.5) * DX + between(-0.2, 0.2) * DX;
      if (periodic) x = fmod(x + NXL * DX, NXL * DX);
      const double rho = RHO0 * between(0.98, 1.02);
      int32_t kind = j < 3 ? SPH_KIND_WALL : SPH_KIND_FLUID;
      if (j == 1 && i % 3 == 0) kind = SPH_KIND_MIRROR;
      double vx = 0.0, vy = 0.0;
      if (kind == SPH_KIND_FLUID || j == 2) {
        vx = between(-1.0, 1.0);
        vy = between(-1.0, 1.0);
      }
      const double h = varh ? h0 * between(0.9, 1.1) : h0;
      const long k = sph_particles_add(p, x, y, vx, vy, rho, rho * DX * DX, h, kind, &err);
      CU_ASSERT_FATAL(k >= 0);
      if (j == 0) p->flags[k] |= SPH_FLAG_REPULSIVE;
      if (j == 2 && slip) p->flags[k] |= SPH_FLAG_FREE_SLIP;
      if (j == 2 && i % 2 == 0) p->flags[k] |= SPH_FLAG_MDBC; /* no diffusion near them */
      if (j == 2) p->my[k] = -DX;
      p->vxh[k] = p->vyh[k] = 0.0;
      if (kind == SPH_KIND_MIRROR) {
        p->vxh[k] = between(-1.0, 1.0);
        p->vyh[k] = between(-1.0, 1.0);
      }
      p->p[k] = sph_eos_pressure(eos, rho);
    }
}

/* F & 128 (density diffusion) takes the model by the set's seed. */
static const sph_diffusion_kind DIFFUSION[3] = {SPH_DIFFUSION_MOLTENI, SPH_DIFFUSION_ANTUONO,
                                                SPH_DIFFUSION_FOURTAKAS};

static void params_for(unsigned F, unsigned seed, sph_force_params *fp) {
  memset(fp, 0, sizeof *fp);
  fp->eos = sph_eos_tait(RHO0, 20.0);
  fp->h = 1.3 * DX;
  fp->eta = 0.1;
  fp->gx = 0.3;
  fp->gy = -9.81;
  if (F & 1) fp->alpha = 0.08, fp->beta = 0.5;
  if (F & 2) fp->xsph = 0.5;
  if (F & 4) fp->viscosity = SPH_VISCOSITY_STRESS_TENSOR, fp->mu = 0.05;
  if (F & 8) fp->viscosity = SPH_VISCOSITY_MORRIS, fp->mu = 0.03;
  if ((F & 12) == 12) fp->viscosity = SPH_VISCOSITY_STRESS_TENSOR, fp->sps = 1; /* both bits */
  fp->sps_cs = 0.12;
  fp->sps_ci = 0.00066;
  fp->sps_delta = DX;
  if (F & 16) fp->periodic = 1, fp->period = NXL * DX, fp->px0 = 0.0;
  if (F & 32) fp->var_h = 1;
  if (F & 64) fp->ledger = 1;
  if (F & 128) fp->diffusion = DIFFUSION[seed % 3], fp->diffusion_delta = 0.1;
  if (F & 256) fp->riemann = 1, fp->riemann_limiter = 3.0;
  /* the corrected gradient in one set of each term set's three (the others without) */
  fp->corrected_gradient = (F + seed) % 3 == 0;
  /* the kernel alternates with the set: both in every term set */
  fp->kernel = ((F + seed) & 1) ? SPH_KERNEL_WENDLAND_C2 : SPH_KERNEL_CUBIC_SPLINE;
  fp->repulsive = 1;
  fp->lj_d = 5.0;
  fp->lj_r0 = DX;
  fp->moving_walls = 1; /* row 2 moves */
  fp->free_slip = seed % 3 == 1;
  fp->mirror = seed % 3 == 2;
}

typedef struct rates {
  double *f[10]; /* drho ax ay xsx xsy du sigma wpow wfx wfy */
} rates;
static const char *const FIELD[10] = {"drho", "ax",    "ay",   "xsx", "xsy",
                                      "du",   "sigma", "wpow", "wfx", "wfy"};

static void rates_alloc(rates *r, size_t n) {
  for (int k = 0; k < 10; k++)
    r->f[k] = calloc(n, sizeof(double));
}
static void rates_free(rates *r) {
  for (int k = 0; k < 10; k++)
    free(r->f[k]);
}

/* ---- the naive oracle, from the equations ---------------------------------------- */

static double min_image(double d, const sph_force_params *fp) {
  if (!fp->periodic) return d;
  if (d > 0.5 * fp->period) return d - fp->period;
  if (d < -0.5 * fp->period) return d + fp->period;
  return d;
}

/* the pair (i, j): separation, h_ij, gradient of the piecewise kernel */
static int pair(const sph_particles *p, const sph_force_params *fp, size_t i, size_t j, double *dx,
                double *dy, double *r, double *hij, double *w, double *gx, double *gy) {
  *dx = min_image(p->x[i] - p->x[j], fp);
  *dy = p->y[i] - p->y[j];
  *r = sqrt(*dx * *dx + *dy * *dy);
  *hij = fp->var_h ? 0.5 * (p->h[i] + p->h[j]) : fp->h;
  if (*r >= 2.0 * *hij || *r == 0.0) return 0;
  double dw;
  sph_kernel_w_dw(fp->kernel, *r, *hij, w, &dw);
  *gx = dw * *dx / *r;
  *gy = dw * *dy / *r;
  return 1;
}

/* tau / rho^2 at every particle: paper A eq. (13)-(14) (3-D 2/3 factor as
 * the code and the paper), plus the SPS stress when on */
static void oracle_stress(const sph_particles *p, const sph_force_params *fp, double *txx,
                          double *txy, double *tyy) {
  for (size_t i = 0; i < p->n; i++) {
    double gxx = 0, gxy = 0, gyx = 0, gyy = 0;
    for (size_t j = 0; j < p->n; j++) {
      double dx, dy, r, hij, w, gx, gy;
      if (j == i || !pair(p, fp, i, j, &dx, &dy, &r, &hij, &w, &gx, &gy)) continue;
      const double vj = p->mass[j] / p->rho[j];
      /* mirror particles: their no-slip velocity (boundary.h) */
      const int mi = fp->mirror && p->kind[i] == SPH_KIND_MIRROR;
      const int mj = fp->mirror && p->kind[j] == SPH_KIND_MIRROR;
      const double ux = (mj ? p->vxh[j] : p->vx[j]) - (mi ? p->vxh[i] : p->vx[i]);
      const double uy = (mj ? p->vyh[j] : p->vy[j]) - (mi ? p->vyh[i] : p->vy[i]);
      gxx += vj * ux * gx;
      gxy += vj * ux * gy;
      gyx += vj * uy * gx;
      gyy += vj * uy * gy;
    }
    const double div = gxx + gyy;
    const double exx = 2 * gxx - 2.0 / 3.0 * div, eyy = 2 * gyy - 2.0 / 3.0 * div;
    const double exy = gxy + gyx, rho = p->rho[i];
    const double lam = fp->viscosity == SPH_VISCOSITY_STRESS_TENSOR ? fp->mu / (rho * rho) : 0;
    txx[i] = lam * exx;
    txy[i] = lam * exy;
    tyy[i] = lam * eyy;
    if (fp->sps) {
      double a, b, c;
      sph_sps_stress(0.5 * (2 * exx + eyy), 0.5 * exy, 0.5 * (2 * eyy + exx), fp->sps_cs,
                     fp->sps_ci, fp->sps_delta, &a, &b, &c);
      txx[i] += a / rho;
      txy[i] += b / rho;
      tyy[i] += c / rho;
    }
  }
}

/* The corrected gradient's L_i = M_i^-1 (Bonet and Lok 1999), M_i = sum_j V_j r_ji (x)
 * grad_i W_ij over every neighbour, as (xx, xy, yy): the identity where M is not positive
 * definite with det M > 0.8 (forces.h). */
static void oracle_l(const sph_particles *p, const sph_force_params *fp, double *l) {
  for (size_t i = 0; i < p->n; i++) {
    double mxx = 0, mxy = 0, myy = 0;
    for (size_t j = 0; j < p->n; j++) {
      double dx, dy, r, hij, w, gx, gy;
      if (j == i || !pair(p, fp, i, j, &dx, &dy, &r, &hij, &w, &gx, &gy)) continue;
      const double vj = p->mass[j] / p->rho[j];
      mxx -= vj * dx * gx;
      mxy -= vj * dx * gy;
      myy -= vj * dy * gy;
    }
    const double det = mxx * myy - mxy * mxy;
    const int ok = det > 0.8 && mxx > 0.0;
    l[3 * i] = ok ? myy / det : 1.0;
    l[3 * i + 1] = ok ? -mxy / det : 0.0;
    l[3 * i + 2] = ok ? mxx / det : 1.0;
  }
}

static int oracle_diffuses(const sph_particles *p, const sph_force_params *fp, size_t i);

/* The density diffusion's c_i (physics/density_diffusion.h): 0, half the
 * renormalised density gradient over every neighbour, or rho0 g / (2 c0^2). */
static void oracle_diffusion_c(const sph_particles *p, const sph_force_params *fp, double *cx,
                               double *cy) {
  for (size_t i = 0; i < p->n; i++) {
    cx[i] = cy[i] = 0.0;
    if (fp->diffusion == SPH_DIFFUSION_FOURTAKAS) {
      cx[i] = 0.5 * fp->eos.rho0 * fp->gx / (fp->eos.c0 * fp->eos.c0);
      cy[i] = 0.5 * fp->eos.rho0 * fp->gy / (fp->eos.c0 * fp->eos.c0);
    }
    if (fp->diffusion != SPH_DIFFUSION_ANTUONO || !oracle_diffuses(p, fp, i)) continue;
    double g[2] = {0, 0}, M[2][2] = {{0, 0}, {0, 0}}; /* Antuono et al. 2010 eq. (6) */
    for (size_t j = 0; j < p->n; j++) {
      double dx, dy, r, hij, w, gx, gy;
      if (j == i || !pair(p, fp, i, j, &dx, &dy, &r, &hij, &w, &gx, &gy)) continue;
      const double V = p->mass[j] / p->rho[j], d[2] = {-dx, -dy}, gw[2] = {gx * V, gy * V};
      for (int a = 0; a < 2; a++) {
        g[a] += (p->rho[j] - p->rho[i]) * gw[a];
        for (int b = 0; b < 2; b++)
          M[a][b] += d[a] * gw[b];
      }
    }
    const double det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
    double gx = g[0], gy = g[1];
    if (det > SPH_GRADIENT_CORRECTION_MIN_DET && M[0][0] > 0) {
      gx = (M[1][1] * g[0] - M[0][1] * g[1]) / det;
      gy = (-M[1][0] * g[0] + M[0][0] * g[1]) / det;
    }
    cx[i] = 0.5 * gx;
    cy[i] = 0.5 * gy;
  }
}

/* Whether particle i diffuses (solver/diffusion.h): fluid with no mdbc wall
 * particle in its support; with fp->wall_diffusion a wall particle that is
 * neither mdbc nor repulsive (a dynamic one; it diffuses with fluid only). */
static int oracle_diffuses(const sph_particles *p, const sph_force_params *fp, size_t i) {
  if (p->kind[i] == SPH_KIND_WALL)
    return fp->wall_diffusion && !(p->flags[i] & (SPH_FLAG_MDBC | SPH_FLAG_REPULSIVE));
  if (p->kind[i] != SPH_KIND_FLUID) return 0;
  for (size_t j = 0; j < p->n; j++) {
    double dx, dy, r, hij, w, gx, gy;
    if (j != i && (p->flags[j] & SPH_FLAG_MDBC) &&
        pair(p, fp, i, j, &dx, &dy, &r, &hij, &w, &gx, &gy))
      return 0;
  }
  return 1;
}

static void oracle(const sph_particles *p, const sph_force_params *fp, rates *o) {
  const size_t n = p->n;
  double *dcx = calloc(n, sizeof *dcx), *dcy = calloc(n, sizeof *dcy);
  int *dif = calloc(n, sizeof *dif);
  oracle_diffusion_c(p, fp, dcx, dcy);
  for (size_t i = 0; i < n; i++)
    dif[i] = oracle_diffuses(p, fp, i);
  double *txx = calloc(n, sizeof *txx), *txy = calloc(n, sizeof *txy),
         *tyy = calloc(n, sizeof *tyy);
  const int stress = fp->viscosity == SPH_VISCOSITY_STRESS_TENSOR || fp->sps;
  if (stress) oracle_stress(p, fp, txx, txy, tyy);
  double *lc = calloc(3 * n, sizeof *lc);
  if (fp->corrected_gradient) oracle_l(p, fp, lc);
  for (size_t i = 0; i < n; i++) {
    for (int k = 0; k < 10; k++)
      o->f[k][i] = 0.0;
    if (p->kind[i] == SPH_KIND_MIRROR || (p->flags[i] & SPH_FLAG_REPULSIVE)) continue;
    const int fluid = p->kind[i] == SPH_KIND_FLUID;
    const double rhoi = p->rho[i], ci = sph_eos_sound_speed(&fp->eos, rhoi);
    double ax = 0, ay = 0, xs = 0, ys = 0, du = 0, sig = 0, drho = 0, wpow = 0, wfx = 0, wfy = 0;
    for (size_t j = 0; j < n; j++) {
      double dx, dy, r, hij, w, gx, gy;
      if (j == i || !pair(p, fp, i, j, &dx, &dy, &r, &hij, &w, &gx, &gy)) continue;
      const double du_before_pair = du;
      const double mj = p->mass[j], rhoj = p->rho[j];
      const double vx = p->vx[i] - p->vx[j], vy = p->vy[i] - p->vy[j];
      /* the pressure's, its Pi_ij's and the continuity's gradient: with the correction
       * (L_i + L_j) / 2 grad_i W_ij (forces.h); the viscous terms keep grad_i W_ij */
      double cgx = gx, cgy = gy;
      if (fp->corrected_gradient) {
        const double lxx = 0.5 * (lc[3 * i] + lc[3 * j]),
                     lxy = 0.5 * (lc[3 * i + 1] + lc[3 * j + 1]);
        const double lyy = 0.5 * (lc[3 * i + 2] + lc[3 * j + 2]);
        cgx = lxx * gx + lxy * gy;
        cgy = lxy * gx + lyy * gy;
      }
      const double vg = vx * cgx + vy * cgy, vr = vx * dx + vy * dy;
      if (fluid || p->kind[j] == SPH_KIND_FLUID) drho += mj * vg; /* B eq. 2; a wall: fluid j */
      sig = fmax(sig, fabs(hij * vr) / (r * r));                  /* B §2.6 */
      /* density_diffusion.h, diffusion.h: fluid with fluid, a dynamic wall
       * with fluid */
      if (fp->diffusion && dif[i] && dif[j] && (fluid || p->kind[j] == SPH_KIND_FLUID)) {
        const double psi = 2.0 * ((rhoj - rhoi) + (dcx[i] + dcx[j]) * dx + (dcy[i] + dcy[j]) * dy);
        const double rji_gw = -(dx * gx + dy * gy); /* r_ji . grad_i W_ij */
        drho += fp->diffusion_delta * hij * fp->eos.c0 * psi * rji_gw / (r * r) * mj / rhoj;
      }
      /* the Riemann scheme's continuity term (pair_terms.h), between fluid particles */
      if (fp->riemann && fluid && p->kind[j] == SPH_KIND_FLUID) {
        const double jump = (p->p[i] - p->p[j]) - fp->eos.rho0 * (fp->gx * dx + fp->gy * dy);
        const double dwdr = (gx * dx + gy * dy) / r;
        drho += rhoi * mj / rhoj * jump * dwdr / (fp->eos.rho0 * fp->eos.c0);
      }
      if (!fluid && !(fp->ledger && p->kind[j] == SPH_KIND_FLUID)) continue;
      /* a mirror particle's no-slip velocity in the viscous terms */
      const int img = fp->mirror && p->kind[j] == SPH_KIND_MIRROR;
      const double ux = img ? p->vx[i] - p->vxh[j] : vx, uy = img ? p->vy[i] - p->vyh[j] : vy;
      /* a free-slip wall: the pressure and Pi_ij along its normal (here the y
       * axis), Pi_ij of the normal relative velocity */
      const size_t b = fluid ? j : i;
      const int slip =
          fp->free_slip && p->kind[b] == SPH_KIND_WALL && (p->flags[b] & SPH_FLAG_FREE_SLIP);
      const double ur = slip ? uy * dy : ux * dx + uy * dy;
      double P = p->p[i] / (rhoi * rhoi) + p->p[j] / (rhoj * rhoj);
      if (fp->riemann) { /* Zhang et al. 2017: the interface pressure, the closing speed along
                          * the line of centres (a wall with a normal: the normal one) */
        const int nrm = p->kind[b] == SPH_KIND_WALL && (p->flags[b] & SPH_WALL_NORMAL);
        const double closing = -(nrm ? vy * dy : vr) / r, c0 = fp->eos.c0;
        const double beta = fmin(fp->riemann_limiter * fmax(closing, 0.0) / c0, 1.0);
        P = (p->p[i] + p->p[j] + beta * fp->eos.rho0 * c0 * closing) / (rhoi * rhoj);
      }
      if ((fp->alpha != 0 || fp->beta != 0) && ur < 0) { /* A eq. 15-16 */
        const double eta = fp->eta * hij, mu = hij * ur / (r * r + eta * eta);
        const double cbar = 0.5 * (ci + sph_eos_sound_speed(&fp->eos, rhoj));
        P += (-fp->alpha * cbar * mu + fp->beta * mu * mu) / (0.5 * (rhoi + rhoj));
      }
      const double px = slip ? 0.0 : cgx;
      double fx = -mj * P * px, fy = -mj * P * cgy; /* A eq. 11 */
      du += 0.5 * mj * P * (vx * px + vy * cgy);    /* A eq. 28 */
      if (stress) {
        const double sxx = txx[i] + txx[j], sxy = txy[i] + txy[j], syy = tyy[i] + tyy[j];
        fx += mj * (sxx * gx + sxy * gy);
        fy += mj * (sxy * gx + syy * gy);
        du -= 0.5 * mj * (sxx * vx * gx + sxy * (vx * gy + vy * gx) + syy * vy * gy);
      }
      if (fp->viscosity == SPH_VISCOSITY_MORRIS) { /* B eq. 4 */
        const double eta = fp->eta * hij;
        const double c = mj * 4.0 * fp->mu / fp->eos.rho0 * (dx * gx + dy * gy) /
                         ((rhoi + rhoj) * (r * r + eta * eta));
        fx += c * ux;
        fy += c * uy;
        du -= 0.5 * c * (vx * vx + vy * vy);
      }
      if (p->kind[j] == SPH_KIND_MIRROR || (p->flags[j] & SPH_FLAG_REPULSIVE)) {
        /* a neighbour that takes no heat: i takes all of it (pair_terms.h) */
        const int wall = p->kind[j] == SPH_KIND_WALL;
        const double wx = wall ? p->vx[j] : 0.0, wy = wall ? p->vy[j] : 0.0;
        du = du_before_pair - (fx * (p->vx[i] - wx) + fy * (p->vy[i] - wy));
      }
      if (!fluid) continue;
      ax += fx;
      ay += fy;
      if (p->kind[j] == SPH_KIND_WALL) wpow += fx * p->vx[j] + fy * p->vy[j];
      if (p->kind[j] != SPH_KIND_FLUID) wfx += fx, wfy += fy;
      if (p->kind[j] == SPH_KIND_FLUID) { /* B eq. 6 */
        xs -= mj / (0.5 * (rhoi + rhoj)) * vx * w;
        ys -= mj / (0.5 * (rhoi + rhoj)) * vy * w;
      }
    }
    if (fluid) {
      ax += fp->gx;
      ay += fp->gy;
      for (size_t j = 0; j < n; j++) { /* A eq. 21-22 */
        if (!(p->flags[j] & SPH_FLAG_REPULSIVE)) continue;
        const double dx = min_image(p->x[i] - p->x[j], fp), dy = p->y[i] - p->y[j];
        const double r2 = dx * dx + dy * dy, r0 = fp->lj_r0;
        if (r2 >= r0 * r0 || r2 == 0) continue;
        const double f = fp->lj_d * (pow(r0 * r0 / r2, 6) - pow(r0 * r0 / r2, 2)) / r2;
        ax += f * dx;
        ay += f * dy;
        if (fp->ledger) { /* its power and force, as the other wall forces' */
          wpow += f * (dx * p->vx[j] + dy * p->vy[j]);
          wfx += f * dx;
          wfy += f * dy;
        }
      }
    }
    const double v[10] = {drho, ax, ay, fp->xsph * xs, fp->xsph * ys, du, sig, wpow, wfx, wfy};
    for (int k = 0; k < 10; k++)
      o->f[k][i] = v[k];
  }
  free(lc);
  free(txx);
  free(txy);
  free(tyy);
  free(dcx);
  free(dcy);
  free(dif);
}

/* ---- the library's loops ------------------------------------------------------------ */

/* One main pass with the loop asked for; the rates by particle id. */
/* One pass of the loop asked for over a copy of p0 into o (and tau / rho^2
 * and L into tau); with `choose`, the start-up choice of lane loop first
 * (sph_forces_fastest_loop: *chosen, *ratio): the rates are those of its
 * last evaluation, or where it chose nothing (and evaluated nothing), of
 * one evaluation after it. */
static void run_pass(const sph_particles *p0, const sph_force_params *fp0, sph_force_loop loop,
                     rates *o, double *tau[6], int choose, sph_force_loop *chosen, double *ratio) {
  sph_error err;
  sph_particles p;
  CU_ASSERT_FATAL(sph_particles_init(&p, p0->n, &err) == 0);
  for (size_t i = 0; i < p0->n; i++) {
    const long k = sph_particles_add(&p, p0->x[i], p0->y[i], p0->vx[i], p0->vy[i], p0->rho[i],
                                     p0->mass[i], p0->h[i], p0->kind[i], &err);
    p.flags[k] = p0->flags[i];
    p.p[k] = p0->p[i];
    p.mx[k] = p0->mx[i];
    p.my[k] = p0->my[i];
    p.vxh[k] = p0->vxh[i];
    p.vyh[k] = p0->vyh[i];
  }
  sph_force_params fp = *fp0;
  fp.loop = loop;
  double hmax = fp.h;
  for (size_t i = 0; i < p.n; i++)
    hmax = fmax(hmax, p.h[i]);
  const double support = 2.0 * (fp.var_h ? hmax : fp.h);
  sph_grid g;
  sph_grid_init(&g);
  const double cell = support * (1.0 + 1e-9);
  int rc = fp.periodic
               ? sph_grid_build_periodic(&g, &p, cell, SPH_AXIS_X, 0.0, fp.period, 1u << 16, &err)
               : sph_grid_build(&g, &p, cell, 1u << 16, &err);
  CU_ASSERT_FATAL(rc == 0);
  sph_nlist l;
  sph_nlist_init(&l);
  CU_ASSERT_FATAL(sph_nlist_build(&l, &g, &p, support, 0.0, fp.periodic ? fp.period : 0.0, &err) ==
                  0);
  sph_force_work w;
  memset(&w, 0, sizeof w);
  w.keep_sigma = 1; /* sigma per particle, compared below */
  int rc_pass = choose ? sph_forces_fastest_loop(&p, &l, &fp, &w, chosen, ratio, &err) : 0;
  /* nothing measured: no evaluation either */
  if (rc_pass == 0 && (!choose || *chosen == fp.loop))
    rc_pass = sph_forces_evaluate(&p, &l, &fp, &w, &err);
  CU_ASSERT_FATAL(rc_pass == 0);
  for (size_t i = 0; i < p.n; i++) {
    const size_t id = (size_t)p.id[i];
    const double v[10] = {p.drho[i], p.ax[i],    p.ay[i],   p.xsx[i], p.xsy[i],
                          p.du[i],   w.sigma[i], w.wpow[i], w.wfx[i], w.wfy[i]};
    for (int k = 0; k < 10; k++)
      o->f[k][id] = v[k];
    if (tau) { /* tau / rho^2 of the strain-rate pass, and L with the correction */
      const double t[6] = {w.sxx[i], w.sxy[i], w.syy[i], w.lxx[i], w.lxy[i], w.lyy[i]};
      for (int k = 0; k < 6; k++)
        tau[k][id] = (k < 3 || fp.gradient_correction) ? t[k] : 0.0;
    }
  }
  sph_force_work_free(&w);
  sph_nlist_free(&l);
  sph_grid_free(&g);
  sph_particles_free(&p);
}

static void run_loop_tau(const sph_particles *p0, const sph_force_params *fp0, sph_force_loop loop,
                         rates *o, double *tau[6]) {
  run_pass(p0, fp0, loop, o, tau, 0, NULL, NULL);
}

static void run_loop(const sph_particles *p0, const sph_force_params *fp0, sph_force_loop loop,
                     rates *o) {
  run_loop_tau(p0, fp0, loop, o, NULL);
}

/* Whether field k is an output of the term set F. */
static int field_used(int k, unsigned F) {
  if (k == 3 || k == 4) return (F & 2) != 0;
  if (k == 5 || k >= 7) return (F & 64) != 0;
  return 1;
}

/* max_i |a_i - b_i| / max_i |b_i| over field k */
static double rel_err(const rates *a, const rates *b, int k, size_t n) {
  double d = 0.0, s = 0.0;
  for (size_t i = 0; i < n; i++) {
    d = fmax(d, fabs(a->f[k][i] - b->f[k][i]));
    s = fmax(s, fabs(b->f[k][i]));
  }
  return s > 0.0 ? d / s : d;
}

static void test_oracle_every_term_set(void) {
  const int avx = sph_force_loop_available(SPH_LOOP_LANES_AVX);
  const int avx512 = sph_force_loop_available(SPH_LOOP_LANES_AVX512);
  if (!avx) printf("\n  (no AVX2 on this processor: the AVX2 lane loop is not compared)");
  if (!avx512) printf("\n  (no AVX-512F on this processor: the eight-lane loop is not compared)");
  double worst[4] = {0, 0, 0, 0}; /* scalar, lanes, avx, avx512 against the oracle */
  unsigned bad = 0;
  for (unsigned F = 0; F < 512; F++)
    for (unsigned seed = 0; seed < 3; seed++) {
      sph_force_params fp;
      params_for(F, seed, &fp);
      sph_particles p;
      make_set(&p, F * 3 + seed, (F & 16) != 0, (F & 32) != 0, fp.free_slip, &fp.eos);
      for (size_t k = 0; k < p.n; k++) { /* as the set-up does: some walls are mdbc, */
        if (p.flags[k] & SPH_FLAG_MDBC) fp.mdbc = 1;
        /* and some dynamic walls take part in the diffusion */
        if (fp.diffusion && fp.diffusion != SPH_DIFFUSION_ANTUONO && p.kind[k] == SPH_KIND_WALL &&
            !(p.flags[k] & (SPH_FLAG_MDBC | SPH_FLAG_REPULSIVE)))
          fp.wall_diffusion = 1;
      }
      const size_t n = p.n;
      rates o, r[4];
      rates_alloc(&o, n);
      oracle(&p, &fp, &o);
      const sph_force_loop loops[4] = {SPH_LOOP_SCALAR, SPH_LOOP_LANES, SPH_LOOP_LANES_AVX,
                                       SPH_LOOP_LANES_AVX512};
      for (int m = 0; m < 4; m++) {
        rates_alloc(&r[m], n);
        if ((m == 2 && !avx) || (m == 3 && !avx512)) continue;
        run_loop(&p, &fp, loops[m], &r[m]);
        /* the flavour's run-time loop: the bytes of the loop compiled for F */
        rates rt;
        rates_alloc(&rt, n);
        sph_force_params fr = fp;
        fr.runtime_terms = 1;
        run_loop(&p, &fr, loops[m], &rt);
        for (int k = 0; k < 10; k++)
          if (field_used(k, F) && memcmp(rt.f[k], r[m].f[k], n * sizeof(double)) != 0 && bad++ < 10)
            printf("\n  F = %u, set %u, loop %d: the run-time loop's %s differs", F, seed, m,
                   FIELD[k]);
        rates_free(&rt);
        for (int k = 0; k < 10; k++) {
          if (!field_used(k, F)) continue;
          const double e = rel_err(&r[m], &o, k, n);
          worst[m] = fmax(worst[m], e);
          if (!(e <= TOL) && bad++ < 10)
            printf("\n  F = %u, set %u, loop %d: %s off by %.3g relative", F, seed, m, FIELD[k], e);
        }
      }
      for (int k = 0; k < 10; k++) {
        if (!field_used(k, F)) continue;
        const size_t bytes = n * sizeof(double);
        if (avx) CU_ASSERT(memcmp(r[1].f[k], r[2].f[k], bytes) == 0);    /* lane flavours */
        if (avx512) CU_ASSERT(memcmp(r[1].f[k], r[3].f[k], bytes) == 0); /* 8 lanes as 4 */
        /* where the lanes defer to the scalar loop (but for the strain-rate pass of the
         * stress and the corrected gradient's moment, which run in lanes unless h is per
         * particle) */
        const int strain_in_lanes = ((F & 4) || fp.corrected_gradient) && !(F & 32);
        if (((F & 32) || fp.mirror) && !strain_in_lanes)
          CU_ASSERT(memcmp(r[0].f[k], r[1].f[k], bytes) == 0);
      }
      for (int m = 0; m < 4; m++)
        rates_free(&r[m]);
      rates_free(&o);
      sph_particles_free(&p);
    }
  printf("\n  512 term sets x 3 sets (density diffusion: the three models by set; the corrected "
         "gradient in one): worst relative difference from the all-pairs oracle: "
         "scalar %.2e, lanes %.2e, AVX2 lanes %.2e, AVX-512 lanes %.2e (tolerance %.0e)",
         worst[0], worst[1], worst[2], worst[3], TOL);
  CU_ASSERT(bad == 0);
}

/* The strain-rate pass (tau / rho^2 and the correction's L) in every lane
 * flavour bitwise, and within TOL of the scalar pass, with and without the
 * kernel-gradient correction, the wall particles' extrapolated velocities,
 * periodicity, for both kernels, the stress tensor and SPS. */
static void test_strain_rate_lanes(void) {
  const int avx = sph_force_loop_available(SPH_LOOP_LANES_AVX);
  const int avx512 = sph_force_loop_available(SPH_LOOP_LANES_AVX512);
  const sph_force_loop loops[4] = {SPH_LOOP_SCALAR, SPH_LOOP_LANES, SPH_LOOP_LANES_AVX,
                                   SPH_LOOP_LANES_AVX512};
  double worst = 0.0;
  unsigned cases = 0, bad = 0;
  for (unsigned c = 0; c < 32; c++) {
    const unsigned F = 4u | ((c & 1) ? 16u : 0u) | ((c & 16) ? 8u : 0u); /* 12: SPS */
    sph_force_params fp;
    params_for(F, c, &fp);
    fp.free_slip = fp.mirror = 0;
    fp.kernel = (c & 2) ? SPH_KERNEL_WENDLAND_C2 : SPH_KERNEL_CUBIC_SPLINE;
    fp.gradient_correction = (c & 4) != 0;
    fp.no_slip = (c & 8) != 0; /* the walls' extrapolated velocities (wall_velocity.h) */
    sph_particles p;
    make_set(&p, 1000 + c, fp.periodic, 0, 0, &fp.eos);
    for (size_t k = 0; k < p.n; k++) /* no mirror particles without mirror walls */
      if (p.kind[k] == SPH_KIND_MIRROR) p.kind[k] = SPH_KIND_WALL;
    for (size_t k = 0; k < p.n; k++)
      if (fp.no_slip && p.kind[k] == SPH_KIND_WALL) p.flags[k] |= SPH_FLAG_NO_SLIP;
    const size_t n = p.n;
    double *tau[4][6];
    rates r[4];
    for (int m = 0; m < 4; m++) {
      rates_alloc(&r[m], n);
      for (int k = 0; k < 6; k++)
        tau[m][k] = calloc(n, sizeof(double));
      if ((m == 2 && !avx) || (m == 3 && !avx512)) continue;
      run_loop_tau(&p, &fp, loops[m], &r[m], tau[m]);
    }
    for (int k = 0; k < 6; k++) {
      double d = 0.0, s = 0.0;
      for (size_t i = 0; i < n; i++) {
        d = fmax(d, fabs(tau[1][k][i] - tau[0][k][i]));
        s = fmax(s, fabs(tau[0][k][i]));
      }
      const double e = s > 0.0 ? d / s : d;
      worst = fmax(worst, e);
      if (!(e <= TOL) && bad++ < 10) printf("\n  strain case %u: field %d off by %.3g", c, k, e);
      const size_t bytes = n * sizeof(double);
      if (avx) CU_ASSERT(memcmp(tau[1][k], tau[2][k], bytes) == 0);
      if (avx512) CU_ASSERT(memcmp(tau[1][k], tau[3][k], bytes) == 0);
    }
    for (int m = 0; m < 4; m++) {
      rates_free(&r[m]);
      for (int k = 0; k < 6; k++)
        free(tau[m][k]);
    }
    sph_particles_free(&p);
    cases++;
  }
  printf("\n  %u strain-rate cases (correction, extrapolated wall velocities, periodic, both "
         "kernels, SPS): lane flavours bitwise, worst relative difference from the scalar pass "
         "%.2e (tolerance %.0e)",
         cases, worst, TOL);
  CU_ASSERT(bad == 0);
  CU_ASSERT(worst > 0.0); /* the lane pass is not the scalar one */
}

/* ---- symmetry and flavour agreement of each term -------------------------------- */

static int same(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* v4e and (if present) v4x give the bits of v1 in every lane: each term is
 * evaluated on four different argument sets at once. */
#define LANES_AGREE(call1, callv)                                                                  \
  do {                                                                                             \
    double want[4], got[4];                                                                        \
    for (int q = 0; q < 4; q++)                                                                    \
      want[q] = call1;                                                                             \
    v4e_store(got, callv);                                                                         \
    for (int q = 0; q < 4; q++)                                                                    \
      CU_ASSERT(same(got[q], want[q]));                                                            \
  } while (0)

static void test_pair_symmetry(void) {
  rng_state = 12345;
  unsigned checked = 0;
  for (int t = 0; t < 2000; t++) {
    const double h = DX * between(1.0, 1.5), m = between(0.3, 0.5);
    const double xi = between(0, 1), yi = between(0, 1);
    const double xj = xi + between(-1.9, 1.9) * h, yj = yi + between(-1.9, 1.9) * h;
    const double vxi = between(-2, 2), vyi = between(-2, 2), vxj = between(-2, 2),
                 vyj = between(-2, 2);
    const double rhoi = between(990, 1010), rhoj = between(990, 1010);
    const double ci = between(19, 21), cj = between(19, 21);
    const double s[6] = {between(-1, 1), between(-1, 1), between(-1, 1),
                         between(-1, 1), between(-1, 1), between(-1, 1)};
    /* as a loop forms them, from i's side and from j's */
    const double dx = xi - xj, dy = yi - yj, ex = xj - xi, ey = yj - yi;
    const double r2 = dx * dx + dy * dy, q2 = ex * ex + ey * ey;
    if (!(r2 < 4 * h * h) || r2 == 0) continue;
    CU_ASSERT(same(r2, q2));
    const double inv_r2 = 1 / r2, r = sqrt(r2), inv_r = r * inv_r2, inv_h = 1 / h;
    const double sigma = 10 / (7 * SPH_PI) * inv_h * inv_h;
    double w, f;
    cubic_w_f_v1(r, inv_r, inv_h, sigma, sigma * inv_h, &w, &f);
    const double gx = f * dx, gy = f * dy, hx = f * ex, hy = f * ey;
    const double dvx = vxi - vxj, dvy = vyi - vyj, evx = vxj - vxi, evy = vyj - vyi;
    const double vr = dvx * dx + dvy * dy, ur = evx * ex + evy * ey;
    CU_ASSERT(same(vr, ur));
    /* the pair terms' vectors and tensors, from i's side and from j's */
    const vec_v1 gv = {{gx, gy}}, hv = {{hx, hy}}, dv = {{dvx, dvy}}, ev = {{evx, evy}};
    const vec_v1 rv = {{dx, dy}}, qv = {{ex, ey}};
    CU_ASSERT(same(continuity_v1(m, dv, gv), continuity_v1(m, ev, hv)));
    CU_ASSERT(same(signal_v1(h, vr, inv_r2), signal_v1(h, ur, inv_r2)));
    const double eta2 = 0.01 * h * h, irb = inv_rho_mean_v1(rhoi, rhoj);
    CU_ASSERT(same(irb, inv_rho_mean_v1(rhoj, rhoi)));
    const double pi_ij = artificial_viscosity_v1(vr, h, r2, eta2, ci, cj, -0.08, 0.5, irb);
    const double pi_ji = artificial_viscosity_v1(ur, h, q2, eta2, cj, ci, -0.08, 0.5, irb);
    CU_ASSERT(same(pi_ij, pi_ji));
    const double mp = m * ((s[0] + s[1]) + pi_ij), mq = m * ((s[1] + s[0]) + pi_ji);
    vec_v1 a = pressure_force_v1(mp, gv), b = pressure_force_v1(mq, hv);
    CU_ASSERT(same(a.c[0], -b.c[0]) && same(a.c[1], -b.c[1]));
    CU_ASSERT(same(pressure_heat_v1(mp, dv, gv), pressure_heat_v1(mq, ev, hv)));
    const double txx = s[0] + s[3], txy = s[1] + s[4], tyy = s[2] + s[5];
    const double uxx = s[3] + s[0], uxy = s[4] + s[1], uyy = s[5] + s[2];
    const sym_v1 tv = {{txx, txy, tyy}}, uv = {{uxx, uxy, uyy}};
    a = stress_force_v1(m, tv, gv);
    b = stress_force_v1(m, uv, hv);
    CU_ASSERT(same(a.c[0], -b.c[0]) && same(a.c[1], -b.c[1]));
    CU_ASSERT(same(stress_heat_v1(m, tv, dv, gv), stress_heat_v1(m, uv, ev, hv)));
    const double c = morris_factor_v1(m, 2e-4, f, r2, rhoi, rhoj, eta2);
    CU_ASSERT(same(c, morris_factor_v1(m, 2e-4, f, q2, rhoj, rhoi, eta2)));
    CU_ASSERT(same(c * dvx, -(c * evx)) && same(c * dvy, -(c * evy)));
    CU_ASSERT(same(morris_heat_v1(c, dv), morris_heat_v1(c, ev)));
    const double xf = xsph_factor_v1(m, irb, w);
    CU_ASSERT(same(xf * dvx, -(xf * evx)));
    const double ljf = lennard_jones_v1(5.0, 1.2 * h, r2);
    CU_ASSERT(same(ljf * dx, -(ljf * ex)) && same(ljf, lennard_jones_v1(5.0, 1.2 * h, q2)));
    { /* the corrected gradient: the same L_ij from either side, so antisymmetric, and each
       * term built on it keeps its symmetry */
      const sym_v1 li = {{1.0 + 0.1 * s[0], 0.05 * s[1], 1.0 + 0.1 * s[2]}};
      const sym_v1 lj = {{1.0 + 0.1 * s[3], 0.05 * s[4], 1.0 + 0.1 * s[5]}};
      const vec_v1 cg = corrected_gradient_v1(li, lj, gv), ch = corrected_gradient_v1(lj, li, hv);
      CU_ASSERT(same(cg.c[0], -ch.c[0]) && same(cg.c[1], -ch.c[1]));
      const vec_v1 ca = pressure_force_v1(mp, cg), cb = pressure_force_v1(mq, ch);
      CU_ASSERT(same(ca.c[0], -cb.c[0]) && same(ca.c[1], -cb.c[1]));
      CU_ASSERT(same(continuity_v1(m, dv, cg), continuity_v1(m, ev, ch)));
      CU_ASSERT(same(pressure_heat_v1(mp, dv, cg), pressure_heat_v1(mq, ev, ch)));
      /* (L_i + L_j) / 2 times g, by hand */
      const double lxx = 0.5 * (li.c[0] + lj.c[0]), lxy = 0.5 * (li.c[1] + lj.c[1]);
      const double lyy = 0.5 * (li.c[2] + lj.c[2]);
      CU_ASSERT(fabs(cg.c[0] - (lxx * gx + lxy * gy)) <= 1e-15 * (fabs(gx) + fabs(gy)));
      CU_ASSERT(fabs(cg.c[1] - (lxy * gx + lyy * gy)) <= 1e-15 * (fabs(gx) + fabs(gy)));
      /* L = I leaves the gradient as it is */
      const sym_v1 id = {{1.0, 0.0, 1.0}};
      const vec_v1 gi = corrected_gradient_v1(id, id, gv);
      CU_ASSERT(same(gi.c[0], gx) && same(gi.c[1], gy));
      for (int k = 0; k < 2; k++) { /* the lanes: four pairs at once */
        double want[4], got[4];
        const double k4c[4] = {1.0, 0.9, 0.8, 0.7};
        vec_v4e g4;
        for (int e = 0; e < 2; e++)
          g4.c[e] = v4e_set(gv.c[e] * k4c[0], gv.c[e] * k4c[1], gv.c[e] * k4c[2], gv.c[e] * k4c[3]);
        sym_v4e l4i, l4j;
        for (int e = 0; e < 3; e++) {
          l4i.c[e] = v4e_all(li.c[e]);
          l4j.c[e] = v4e_all(lj.c[e]);
        }
        v4e_store(got, corrected_gradient_v4e(l4i, l4j, g4).c[k]);
        for (int q = 0; q < 4; q++) {
          const vec_v1 gq = {{gv.c[0] * k4c[q], gv.c[1] * k4c[q]}};
          want[q] = corrected_gradient_v1(li, lj, gq).c[k];
          CU_ASSERT(same(got[q], want[q]));
        }
      }
    }
    { /* a free-slip wall's normal part: antisymmetric, and along the normal */
      const double mx = s[2] * DX, my = s[3] * DX;
      const vec_v1 mv = {{mx, my}}, slide = {{-my, mx}};
      const vec_v1 n = normal_part_v1(gv, mv), o = normal_part_v1(hv, mv);
      const double nx = n.c[0], ny = n.c[1];
      CU_ASSERT(same(nx, -o.c[0]) && same(ny, -o.c[1]));
      CU_ASSERT(fabs(nx * my - ny * mx) <= 1e-12 * (fabs(gx) + fabs(gy)) * (fabs(mx) + fabs(my)));
      /* the normal relative velocity's v . r: symmetric, and blind to a slide along the wall */
      CU_ASSERT(same(normal_vdotr_v1(dv, rv, mv), normal_vdotr_v1(ev, qv, mv)));
      CU_ASSERT(fabs(normal_vdotr_v1(slide, rv, mv)) <=
                1e-15 * (fabs(mx) + fabs(my)) * (fabs(dx) + fabs(dy)));
    }
    { /* the Lennard-Jones potential: zero at r0, its slope minus the force */
      const double r0 = 1.2 * h, e = 1e-6 * r;
      CU_ASSERT(fabs(lennard_jones_potential_v1(5.0, r0, r0 * r0)) <= 1e-15 * 5.0);
      if (r < r0 - e) {
        const double up = lennard_jones_potential_v1(5.0, r0, (r + e) * (r + e));
        const double dn = lennard_jones_potential_v1(5.0, r0, (r - e) * (r - e));
        const double slope = (up - dn) / (2 * e), force = lennard_jones_v1(5.0, r0, r2) * r;
        CU_ASSERT(fabs(slope + force) <= 1e-5 * fabs(force) + 1e-9);
      }
    }
    { /* the Riemann pressure: symmetric; dissipative only for a closing pair, and then
       * quadratic in the closing speed below c0 / eta (Zhang et al. 2017) */
      const double z0 = 1000.0 * 20.0, kc = 3.0 / 20.0, pi_ = s[4] * 1e4, pj_ = s[5] * 1e4;
      const double cl = -vr * inv_r, cm = -ur * inv_r;
      const double P = riemann_pressure_v1(pi_, pj_, rhoi, rhoj, cl, z0, kc);
      CU_ASSERT(same(P, riemann_pressure_v1(pj_, pi_, rhoj, rhoi, cm, z0, kc)));
      const double central = (pi_ + pj_) / (rhoi * rhoj), extra = P - central;
      if (cl <= 0) CU_ASSERT(extra == 0.0);
      if (cl > 0)
        CU_ASSERT(fabs(extra - 3.0 * 1000.0 * cl * cl / (rhoi * rhoj)) <=
                  1e-9 * fabs(central) + 1e-12 * extra);
      /* its continuity term: antisymmetric where the densities are equal, zero for a
       * hydrostatic jump */
      const double d = riemann_density_v1(rhoi, m, rhoi, pi_ - pj_, f, r, 1 / z0);
      CU_ASSERT(same(d, -riemann_density_v1(rhoi, m, rhoi, pj_ - pi_, f, r, 1 / z0)));
      CU_ASSERT(riemann_density_v1(rhoi, m, rhoj, 0.0, f, r, 1 / z0) == 0.0);
      if (pi_ > pj_) CU_ASSERT(d < 0); /* density moves down the jump */
    }
    const double ccx = s[0] * 1e3, ccy = s[1] * 1e3; /* c_i + c_j of the diffusion */
    const vec_v1 cc = {{ccx, ccy}};
    const double psi = diffusion_psi_v1(rhoi, rhoj, rv, cc);
    CU_ASSERT(same(psi, -diffusion_psi_v1(rhoj, rhoi, qv, cc)));
    checked++;

    /* the lane flavours: four different pairs at once (scaled copies) */
    const double k4[4] = {1.0, 0.9, 0.8, 0.7};
#define V4(e) v4e_set((e)*k4[0], (e)*k4[1], (e)*k4[2], (e)*k4[3])
#define S(e) ((e)*k4[q])
#define S2(a, b) ((vec_v1){{S(a), S(b)}})
#define V42(a, b) ((vec_v4e){{V4(a), V4(b)}})
    LANES_AGREE(continuity_v1(S(m), S2(dvx, dvy), S2(gx, gy)),
                continuity_v4e(V4(m), V42(dvx, dvy), V42(gx, gy)));
    LANES_AGREE(signal_v1(S(h), S(vr), S(inv_r2)), signal_v4e(V4(h), V4(vr), V4(inv_r2)));
    LANES_AGREE(
        artificial_viscosity_v1(S(vr), S(h), S(r2), S(eta2), S(ci), S(cj), -0.08, 0.5, S(irb)),
        artificial_viscosity_v4e(V4(vr), V4(h), V4(r2), V4(eta2), V4(ci), V4(cj), v4e_all(-0.08),
                                 v4e_all(0.5), V4(irb)));
    LANES_AGREE(
        morris_factor_v1(S(m), 2e-4, S(f), S(r2), S(rhoi), S(rhoj), S(eta2)),
        morris_factor_v4e(V4(m), v4e_all(2e-4), V4(f), V4(r2), V4(rhoi), V4(rhoj), V4(eta2)));
    LANES_AGREE(
        stress_heat_v1(S(m), ((sym_v1){{S(txx), S(txy), S(tyy)}}), S2(dvx, dvy), S2(gx, gy)),
        stress_heat_v4e(V4(m), ((sym_v4e){{V4(txx), V4(txy), V4(tyy)}}), V42(dvx, dvy),
                        V42(gx, gy)));
    LANES_AGREE(diffusion_psi_v1(S(rhoi), S(rhoj), S2(dx, dy), S2(ccx, ccy)),
                diffusion_psi_v4e(V4(rhoi), V4(rhoj), V42(dx, dy), V42(ccx, ccy)));
    LANES_AGREE(riemann_pressure_v1(S(s[4] * 1e4), S(s[5] * 1e4), S(rhoi), S(rhoj), S(-vr * inv_r),
                                    2e4, 0.15),
                riemann_pressure_v4e(V4(s[4] * 1e4), V4(s[5] * 1e4), V4(rhoi), V4(rhoj),
                                     V4(-vr * inv_r), v4e_all(2e4), v4e_all(0.15)));
    LANES_AGREE(riemann_density_v1(S(rhoi), S(m), S(rhoj), S(s[4] * 1e4), S(f), S(r), 5e-5),
                riemann_density_v4e(V4(rhoi), V4(m), V4(rhoj), V4(s[4] * 1e4), V4(f), V4(r),
                                    v4e_all(5e-5)));
    LANES_AGREE(diffusion_v1(S(psi), S(f), S(m), S(rhoj)),
                diffusion_v4e(V4(psi), V4(f), V4(m), V4(rhoj)));
    { /* the Wendland kernel at four radii */
      double rq[4], wq[4], fq[4], wl[4], fl[4];
      const double sw = 7 / (4 * SPH_PI) * inv_h * inv_h;
      for (int q = 0; q < 4; q++) {
        rq[q] = S(r);
        wendland_w_f_v1(rq[q], 1 / rq[q], inv_h, sw, sw * inv_h, &wq[q], &fq[q]);
      }
      v4e W, Fv;
      wendland_w_f_v4e(v4e_set(rq[0], rq[1], rq[2], rq[3]),
                       v4e_set(1 / rq[0], 1 / rq[1], 1 / rq[2], 1 / rq[3]), v4e_all(inv_h),
                       v4e_all(sw), v4e_all(sw * inv_h), &W, &Fv);
      v4e_store(wl, W);
      v4e_store(fl, Fv);
      for (int q = 0; q < 4; q++)
        CU_ASSERT(same(wl[q], wq[q]) && same(fl[q], fq[q]));
    }
    { /* the kernel at four radii */
      double rq[4], iq[4], wq[4], fq[4], wl[4], fl[4];
      for (int q = 0; q < 4; q++) {
        rq[q] = S(r);
        iq[q] = 1 / rq[q];
        cubic_w_f_v1(rq[q], iq[q], inv_h, sigma, sigma * inv_h, &wq[q], &fq[q]);
      }
      v4e W, Fv;
      cubic_w_f_v4e(v4e_set(rq[0], rq[1], rq[2], rq[3]), v4e_set(iq[0], iq[1], iq[2], iq[3]),
                    v4e_all(inv_h), v4e_all(sigma), v4e_all(sigma * inv_h), &W, &Fv);
      v4e_store(wl, W);
      v4e_store(fl, Fv);
      for (int q = 0; q < 4; q++)
        CU_ASSERT(same(wl[q], wq[q]) && same(fl[q], fq[q]));
    }
#undef V42
#undef S2
#undef S
#undef V4
  }
  printf("\n  %u random pairs: every force term exactly antisymmetric, every scalar term "
         "symmetric, v4e lanes bitwise v1",
         checked);
  CU_ASSERT(checked > 1000);
}

/* ---- the AVX-512 operations ------------------------------------------------------- */

#ifdef SPH_LANES_AVX512
static double bits_of(uint64_t u) {
  double d;
  memcpy(&d, &u, sizeof d);
  return d;
}

/* Mismatches of every v8z operation against v1, lane by lane, over the
 * values v (eight at a time, each against its neighbour in the list). */
static __attribute__((target("avx512f"))) unsigned v8z_mismatches(const double *v, size_t nv) {
  unsigned bad = 0;
  for (size_t s = 0; s + 16 <= nv; s++) {
    double a[8], b[8], o[8];
    for (int q = 0; q < 8; q++) {
      a[q] = v[s + (size_t)q];
      b[q] = v[s + 8 + (size_t)q];
    }
    const v8z A = v8z_set(a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7]);
    const v8z B = _mm512_loadu_pd(b);
    const v8z_mask lt = v8z_lt(A, B);
#define CHECK(expr, want)                                                                          \
  do {                                                                                             \
    _mm512_storeu_pd(o, expr);                                                                     \
    for (int q = 0; q < 8; q++) {                                                                  \
      const double w_ = (want);                                                                    \
      if (memcmp(&o[q], &w_, sizeof w_) != 0) bad++;                                               \
    }                                                                                              \
  } while (0)
    CHECK(v8z_add(A, B), v1_add(a[q], b[q]));
    CHECK(v8z_sub(A, B), v1_sub(a[q], b[q]));
    CHECK(v8z_mul(A, B), v1_mul(a[q], b[q]));
    CHECK(v8z_div(A, B), v1_div(a[q], b[q]));
    CHECK(v8z_sqrt(A), isnan(v1_sqrt(a[q])) ? o[q] : v1_sqrt(a[q])); /* NaN's payload aside */
    CHECK(v8z_min(A, B), v1_min(a[q], b[q]));
    CHECK(v8z_max(A, B), v1_max(a[q], b[q]));
    CHECK(v8z_abs(A), v1_abs(a[q]));
    CHECK(v8z_neg(A), v1_neg(a[q]));
    CHECK(v8z_and(lt, A), v1_and(v1_lt(a[q], b[q]), a[q]));
    CHECK(v8z_sel(lt, A, B), v1_sel(v1_lt(a[q], b[q]), a[q], b[q]));
    CHECK(v8z_all(a[3]), a[3]);
    double lo[4], hi[4];
    v4x_store(lo, v8z_lo(A));
    v4x_store(hi, v8z_hi(A));
    if (memcmp(lo, a, sizeof lo) != 0 || memcmp(hi, a + 4, sizeof hi) != 0) bad++;
#undef CHECK
  }
  /* the transpose of eight records */
  double rec[8][8];
  const double *r[8];
  for (int q = 0; q < 8; q++) {
    for (int f = 0; f < 8; f++)
      rec[q][f] = v[(size_t)(q * 8 + f) % nv] + (double)(q * 8 + f);
    r[q] = rec[q];
  }
  v8z out[8];
  v8z_transpose8(r, out);
  for (int f = 0; f < 8; f++) {
    double lanes[8];
    _mm512_storeu_pd(lanes, out[f]);
    for (int q = 0; q < 8; q++)
      if (memcmp(&lanes[q], &rec[q][f], sizeof lanes[q]) != 0) bad++;
  }
  return bad;
}
#endif

#ifdef SPH_LANES_AVX
/* Mismatches of the AVX2 record transpose (four records, eight fields). */
static __attribute__((target("avx2"))) unsigned v4x_transpose_mismatches(void) {
  double rec[4][8];
  const double *r[4];
  for (int q = 0; q < 4; q++) {
    for (int f = 0; f < 8; f++)
      rec[q][f] = 10.0 * q + f + 0.125;
    r[q] = rec[q];
  }
  v4x out[8];
  v4x_transpose8(r, out);
  unsigned bad = 0;
  for (int f = 0; f < 8; f++) {
    double lanes[4];
    v4x_store(lanes, out[f]);
    for (int q = 0; q < 4; q++)
      if (memcmp(&lanes[q], &rec[q][f], sizeof lanes[q]) != 0) bad++;
  }
  return bad;
}
#endif

/* Two phases' wall floor (wall_pressure_floor): a wall particle of the other phase below fluid
 * particle i presses it with max(p_w, p_i + rho0_i g . (x_w - x_i)); in a column at rest,
 * p_i = rho0 g (H - y_i), the floor is the column's pressure at the wall particle's height. */
static void test_wall_pressure_floor(void) {
  const double rho0 = 1000.0, g = 9.81, H = 0.3, yi = 0.0525, yw = -0.0075;
  const double pi = rho0 * g * (H - yi), hg = rho0 * -g * (yi - yw); /* rho0 g . r_iw */
  const double column = rho0 * g * (H - yw);
  const double floor = wall_pressure_floor_v1(1.0, pi, hg); /* a wall reading the air: ~0 */
  printf("\n  the floor %.6f Pa, the column at the wall %.6f Pa", floor, column);
  CU_ASSERT(fabs(floor - column) <= 1e-12 * column);
  CU_ASSERT(same(wall_pressure_floor_v1(2.0 * column, pi, hg), 2.0 * column)); /* above it */
}

/* Two phases' Morris viscosity (physics.air with physics.viscosity): the
 * harmonic mean of the materials' viscosities, and a pair force whose
 * momentum m_i c_ij v_ij is the negative of m_j c_ji v_ji between materials
 * 1000 apart in density; within one material Morris' (mu_i + mu_j) /
 * (rho_i rho_j). */
static void test_phase_viscosity(void) {
  rng_state = 777;
  const double mu_w = 1.0e-3, mu_a = 1.8e-5;
  const double mu2 = phase_viscosity_v1(mu_w, mu_a);
  CU_ASSERT(same(mu2, phase_viscosity_v1(mu_a, mu_w)));
  CU_ASSERT(fabs(mu2 - 2.0 * (2.0 * mu_w * mu_a / (mu_w + mu_a))) <= 1e-15 * mu2);
  CU_ASSERT(mu2 < 2.0 * (2.0 * mu_a)); /* the weaker material sets it: mu_ij < 2 mu_a */
  CU_ASSERT(fabs(phase_viscosity_v1(mu_w, mu_w) - 2.0 * mu_w) <= 1e-15 * mu_w);
  unsigned checked = 0;
  for (int t = 0; t < 1000; t++) {
    const double h = 2.0 * DX, vol = DX * DX;
    const double rhoi = between(995, 1005), rhoj = between(1.19, 1.21); /* water, air */
    const double mi = 1000.0 * vol, mj = 1.2 * vol;
    const double dx = between(-1.9, 1.9) * h, dy = between(-1.9, 1.9) * h;
    const double r2 = dx * dx + dy * dy;
    if (!(r2 < 4 * h * h) || r2 == 0) continue;
    const double r = sqrt(r2), inv_r = 1 / r, inv_h = 1 / h;
    const double sigma = 10 / (7 * SPH_PI) * inv_h * inv_h;
    double w, f;
    cubic_w_f_v1(r, inv_r, inv_h, sigma, sigma * inv_h, &w, &f);
    const double eta2 = 0.01 * h * h;
    const double cij = morris_phases_factor_v1(mj, rhoj, mu2, f, r2, rhoi, eta2);
    const double cji =
        morris_phases_factor_v1(mi, rhoi, phase_viscosity_v1(mu_a, mu_w), f, r2, rhoj, eta2);
    CU_ASSERT(cij < 0.0 || f == 0.0); /* dW/dr < 0: c v_ij drags i toward j's velocity */
    CU_ASSERT(fabs(mi * cij - mj * cji) <= 1e-14 * fabs(mi * cij));
    /* one material: Morris' m_j (mu_i + mu_j) F r^2 / (rho_i rho_j (r^2 + eta^2)) */
    const double one =
        morris_phases_factor_v1(mi, rhoj, phase_viscosity_v1(mu_w, mu_w), f, r2, rhoi, eta2);
    const double want = mi * (2.0 * mu_w) * f * r2 / (rhoi * rhoj * (r2 + eta2));
    CU_ASSERT(fabs(one - want) <= 1e-14 * fabs(want));
    checked++;
  }
  CU_ASSERT(checked > 500);
}

static void test_v8z_operations(void) {
#ifdef SPH_LANES_AVX
  if (sph_force_loop_available(SPH_LOOP_LANES_AVX)) {
    const unsigned tb = v4x_transpose_mismatches();
    printf("\n  v4x: %u mismatches in the record transpose", tb);
    CU_ASSERT(tb == 0);
  }
#endif
  if (!sph_force_loop_available(SPH_LOOP_LANES_AVX512)) {
    printf("\n  (no AVX-512F on this processor: its operations are not checked)");
    return;
  }
#ifdef SPH_LANES_AVX512
  enum { NV = 400 };
  double v[NV];
  const double special[] = {
      0.0, -0.0, 1.0,  -1.0, INFINITY, -INFINITY, 1e-310, -1e-310,    DBL_MAX, -DBL_MAX, 3.0,
      3.0, 0.1,  -0.0, 0.0,  2.0,      1e300,     1e-300, bits_of(1), -2.5,    -2.5,     7.0};
  const size_t ns = sizeof special / sizeof special[0];
  rng_state = 777;
  for (size_t k = 0; k < NV; k++)
    v[k] = k < ns ? special[k] : (k % 5 == 0 ? special[k % ns] : between(-1e3, 1e3));
  const unsigned bad = v8z_mismatches(v, NV);
  printf("\n  v8z: %u mismatches against v1 over %d value sets (signed zeros, infinities, "
         "subnormals, ties), transpose and halves included",
         bad, NV - 15);
  CU_ASSERT(bad == 0);
#endif
}

/* The start-up choice of lane loop: an available loop, the same rates as
 * the default loop's to the bit, nothing chosen where there is nothing to
 * choose from (one lane loop, per-particle h, mirror walls). */
static void test_fastest_loop(void) {
  const unsigned sets[3] = {1 | 2 | 128, 1 | 4 | 64, 1 | 32};
  for (int c = 0; c < 3; c++) {
    sph_force_params fp;
    params_for(sets[c], 3 * (unsigned)c, &fp); /* seed 0, 3, 6: no mirror walls */
    sph_particles p0;
    make_set(&p0, 3 * (unsigned)c, 0, (sets[c] & 32) != 0, 0, &fp.eos);
    rates a, b;
    rates_alloc(&a, p0.n);
    rates_alloc(&b, p0.n);
    sph_force_loop chosen = SPH_LOOP_SCALAR;
    double ratio = 0.0;
    run_pass(&p0, &fp, SPH_LOOP_AUTO, &a, NULL, 1, &chosen, &ratio);
    run_loop(&p0, &fp, SPH_LOOP_AUTO, &b);
    const int both = sph_force_loop_available(SPH_LOOP_LANES_AVX) &&
                     sph_force_loop_available(SPH_LOOP_LANES_AVX512);
    if (both && !fp.var_h) {
      CU_ASSERT(chosen == SPH_LOOP_LANES_AVX || chosen == SPH_LOOP_LANES_AVX512);
      CU_ASSERT(ratio > 0.0 && isfinite(ratio));
      printf("\n  term set %u: %s chosen, AVX2 / AVX-512 time %.2f", sets[c],
             chosen == SPH_LOOP_LANES_AVX ? "AVX2" : "AVX-512", ratio);
    } else {
      CU_ASSERT_EQUAL(chosen, SPH_LOOP_AUTO);
      CU_ASSERT_EQUAL(ratio, 1.0);
    }
    for (int k = 0; k < 10; k++)
      CU_ASSERT(memcmp(a.f[k], b.f[k], p0.n * sizeof(double)) == 0);
    rates_free(&a);
    rates_free(&b);
    sph_particles_free(&p0);
  }
}

int main(void) {
  CU_TestInfo tests[] = {
      {"the 512 term sets: scalar, lane, AVX2 and AVX-512 loops against the all-pairs oracle, "
       "the run-time loops bitwise the compiled ones",
       test_oracle_every_term_set},
      {"the strain-rate pass: lane flavours bitwise, the scalar pass within tolerance",
       test_strain_rate_lanes},
      {"each term antisymmetric or symmetric in the pair, and bitwise in every lane",
       test_pair_symmetry},
      {"two phases' wall floor: the column at rest continued", test_wall_pressure_floor},
      {"two phases' Morris viscosity: the harmonic mean, momentum across a density ratio of "
       "1000, Morris' form within one material",
       test_phase_viscosity},
      {"the AVX-512 operations bitwise v1 in every lane; the record transpose",
       test_v8z_operations},
      {"the start-up choice of lane loop: available, the same bits", test_fastest_loop},
      CU_TEST_INFO_NULL,
  };
  return sph_test_main("pair terms", tests);
}
