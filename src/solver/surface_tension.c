/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * surface_tension.c - the surface tension between the two phases
 * (physics.air.surface_tension; doc/method.md, Surface tension): the
 * capillary stress of Hu & Adams (2006), HA06 in doc/method.md, as a stress
 * that the interaction loop's stress term takes (w->sxx, ...).
 *
 * A pass before the main one sums at every fluid particle the gradient of
 * the colour C (1 in the liquid, phase 0; 0 in the other phase) over its
 * fluid neighbours,
 *   g_i = sum_j V_j (C_j - C_i) grad_i W_ij,   V_j = m_j / rho_j,
 * (0 away from the interface, where every neighbour is of i's phase), and
 * stores the capillary stress
 *   Pi_i = sigma (|g_i| I - g_i g_i / |g_i|),
 * sigma (I - n n) delta with n = g / |g| and delta = |g| (HA06 eq. 12-13),
 * whose divergence is the CSF force sigma kappa n delta (Brackbill, Kothe
 * and Zemach 1992): a tension along the interface and none across it. HA06
 * take its trace-free part, the isotropic rest left to the pressure; its
 * normal compression sigma |g| (1 - 1/d) then needs a pressure below the
 * ambient one at the interface, and a drop at zero ambient pressure
 * opened a gap around itself within 0.05 s (cases/laplace_drop.yaml at
 * zero gravity). The main pass adds, in the volume form of the two-phase
 * pressure (RZH20),
 *   dv_i/dt += sum_j m_j (Pi_i + Pi_j) / (rho_i rho_j) . grad_i W_ij
 * (interact_row.h; with m_j (Pi_i / rho_i^2 + Pi_j / rho_j^2) an air
 * particle beside water took a thousand times its share and the thrown
 * block of tests/data/restart_air.yaml blew up within 6 steps),
 * antisymmetric in the pair (momentum kept), with the stress's heat in the
 * ledger: the work of the capillary forces is booked with the heat, so the
 * balance closes (the surface's energy is not a column of its own). Wall
 * particles carry no stress and take no part in the colour (the wall is
 * neutral: a contact angle of 90 degrees); a free-slip wall's pairs take
 * no stress term at all (interact_row.h, the viscous lanes).
 *
 * Each row is summed in its own order by the thread that owns i: the same
 * bits for any thread count.
 */
#include "config.h"

#include "solver/surface_tension.h"

#include <math.h>
#include <string.h>

#include "core/parallel.h"
#include "core/tensor.h"
#include "physics/kernel.h"
#include "solver/row_walk.h"

/* The colour of phase ph: 1 for the liquid, 0 for the other phase. */
static inline double colour(const uint8_t *ph, size_t i) { return ph[i] ? 0.0 : 1.0; }

static void surface_one(const sph_particles *restrict p, const sph_nlist *restrict l,
                        const sph_force_params *restrict fp, const uint8_t *restrict ph, size_t i,
                        double *const *s, const unsigned F) {
  double t[SPH_SYM] = {0.0};
  if (p->kind[i] != SPH_KIND_FLUID) {
    for (int k = 0; k < SPH_SYM; k++)
      s[k][i] = 0.0;
    return;
  }
  const double *restrict x = p->x, *restrict y = p->y;
  const double *restrict m = p->mass, *restrict rho = p->rho;
  const double period = period_along(fp, 0), half = 0.5 * period_along(fp, 0);
  const double xi = x[i], yi = y[i], ci = colour(ph, i), h = fp->h;
  SPH_IF3(const double *restrict z = p->z; const double zi = z[i];)
  double g[SPH_DIM] = {0.0};
  const uint8_t phi = ph[i];
  ROW(l, i, nb, cnt)
  for (size_t k = 0; k < cnt; k++) {
    const size_t j = nb[k];
    if (ph[j] == phi || p->kind[j] != SPH_KIND_FLUID) continue; /* (most pairs: one phase) */
    const double dc = colour(ph, j) - ci;
    const double dx = sep_x(xi, x[j], period, half, F), dy = SEP(fp, 1, yi, y[j], F);
    SPH_IF3(const double dz = SEP(fp, 2, zi, z[j], F);)
    const double r2 = SPH_NORM2(dx, dy, dz);
    if (r2 >= 4.0 * h * h || r2 == 0.0) continue;
    const double r = sqrt(r2);
    double wij, dw;
    sph_kernel_w_dw(fp->kernel, r, h, &wij, &dw);
    const double f = dc * dw / r * (m[j] / rho[j]); /* V_j (C_j - C_i) dW/dr / r */
    g[0] += f * dx;
    g[1] += f * dy;
    SPH_IF3(g[2] += f * dz;)
  }
  const double g2 = SPH_NORM2(g[0], g[1], g[2]);
  if (g2 > 0.0) {
    const double gn = sqrt(g2), a = fp->sigma;
    for (int u = 0; u < SPH_DIM; u++)
      for (int v = u; v < SPH_DIM; v++)
        t[sph_sym_index(u, v)] = a * ((u == v ? gn : 0.0) - g[u] * g[v] / gn);
  }
  for (int k = 0; k < SPH_SYM; k++)
    s[k][i] = t[k];
}

void sph_surface_stress(const sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                        sph_force_work *w) {
  const long n = (long)p->n;
  const uint8_t *ph = sph_particles_phases(p);
  double *const *s = w->s;
  if (!ph) { /* (one phase: no interface) */
    for (int k = 0; k < SPH_SYM; k++)
      memset(s[k], 0, p->n * sizeof *s[k]);
    return;
  }
  if (fp->periodic) {
#pragma omp parallel for schedule(dynamic, 256) if (n > SPH_OMP_MIN)
    for (long i = 0; i < n; i++)
      surface_one(p, l, fp, ph, (size_t)i, s, SPH_ROW_PERIODIC);
  } else {
#pragma omp parallel for schedule(dynamic, 256) if (n > SPH_OMP_MIN)
    for (long i = 0; i < n; i++)
      surface_one(p, l, fp, ph, (size_t)i, s, 0u);
  }
}

double sph_surface_dt(const sph_force_params *fp, double h) {
  if (!(fp->sigma > 0.0)) return INFINITY;
  double rho = fp->phase_mat[0].rho0;
  for (int k = 1; k < fp->phases; k++)
    rho = fmin(rho, fp->phase_mat[k].rho0);
  return 0.25 * sqrt(rho * h * h * h / (2.0 * M_PI * fp->sigma));
}
