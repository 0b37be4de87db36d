/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * adami.c - Adami, Hu and Adams' (2012) generalized wall boundary
 * condition (see adami.h): one loop over the adami wall particles, each
 * summing over the fluid particles of its own neighbour row.
 */
#include "config.h"

#include "walls/adami.h"

#include <math.h>

#include "core/parallel.h"
#include "physics/kernel.h"
#include "walls/motion.h"

/* g - a_w of wall particle i: its moving wall's acceleration by its law. */
static void resulting_acceleration(const sph_particles *p, const sph_adami_params *ap, size_t i,
                                   double ga[SPH_DIM]) {
  for (int d = 0; d < SPH_DIM; d++)
    ga[d] = ap->g[d];
  if (!ap->walls || !(p->live & SPH_ARRAYS_REST) || p->body[i] < 0) return;
  const sph_motion *m = &ap->walls->segments[p->body[i]].motion;
  const double r[SPH_DIM] = {SPH_XYZ(p->xr[i], p->yr[i], p->zr[i])};
  double a[SPH_DIM];
  sph_motion_accel(m, ap->t, r, a);
  for (int d = 0; d < SPH_DIM; d++)
    ga[d] -= a[d];
}

/* Whether a rank's ghost wall particle i is read by no row of the pass:
 * a row that reads its p, rho or no-slip velocity pairs it within the
 * support, so the list (complete, symmetric) names that row's particle in
 * i's row; here every particle of i's row is a ghost with an empty row. */
static int read_by_none(const sph_particles *p, const sph_nlist *l, size_t i, const uint32_t *row,
                        size_t cnt) {
  if (!l->no_row || !(p->flags[i] & SPH_FLAG_GHOST)) return 0;
  for (size_t k = 0; k < cnt; k++)
    if (!(p->flags[row[k]] & SPH_FLAG_GHOST) || !sph_nlist_empty_row(l, p, row[k])) return 0;
  return 1;
}

/* Wall particle i's pressure, density and no-slip velocity from its row;
 * 1 if it had fluid within reach. `phased` (a literal at each call: one
 * phase pays no test per pair) says the store has phases. */
static inline __attribute__((always_inline)) int adami_row(sph_particles *p, const sph_nlist *l,
                                                           const sph_adami_params *ap,
                                                           double *const *gv, size_t i,
                                                           const int phased) {
  size_t cnt;
  const uint32_t *row = sph_nlist_row(l, i, &cnt);
  if (read_by_none(p, l, i, row, cnt)) {
    if (gv)
      for (int d = 0; d < SPH_DIM; d++)
        gv[d][i] = p->vel[d][i];
    return 0;
  }
  double ga[SPH_DIM];
  resulting_acceleration(p, ap, i, ga);
  /* AHA12 eq. (27): sum_f (p_f + rho_f (g - a_w) . r_wf) W_wf and sum_f W_wf; eq. (24): sum_f
   * v_f W_wf; with two phases the air's sums apart (swa, spa), and the fluid particle nearest
   * the wall particle's mirror point x_w + m_w (the first by id of equals): the wall takes its
   * phase and that phase's extrapolation (adami.h) */
  const uint8_t *ph = phased ? p->phase : NULL;
  double sw = 0.0, sp = 0.0, sv[SPH_DIM] = {0.0}, swa = 0.0, spa = 0.0;
  double near2 = INFINITY;
  int64_t near_id = INT64_MAX;
  int mirror_phase = 0;
  for (size_t k = 0; k < cnt; k++) {
    const size_t j = row[k];
    if (p->kind[j] != SPH_KIND_FLUID) continue;
    const double dx = sph_nlist_sep(l, 0, p->x[i], p->x[j]);
    const double dy = sph_nlist_sep(l, 1, p->y[i], p->y[j]);
    SPH_IF3(const double dz = sph_nlist_sep(l, 2, p->z[i], p->z[j]);)
    const double r2 = SPH_NORM2(dx, dy, dz);
    const double hij = ap->var_h ? 0.5 * (p->h[i] + p->h[j]) : ap->h;
    if (r2 >= SPH_CUBIC_SUPPORT * SPH_CUBIC_SUPPORT * hij * hij || r2 == 0.0) continue;
    double wij, dwij; /* the static inline form, as the interaction loops use (kernel.c) */
    sph_kernel_w_dw(ap->kernel, sqrt(r2), hij, &wij, &dwij);
#if SPH_DIM == 2
    const double gr = ga[0] * dx + ga[1] * dy;
#else
    const double gr = ga[0] * dx + ga[1] * dy + ga[2] * dz;
#endif
    if (phased) { /* (j - (x_w + m_w) = -(r_wf + m_w)) */
      const double mx = dx + p->mx[i], my = dy + p->my[i];
      SPH_IF3(const double mz = dz + p->mz[i];)
      const double e2 = SPH_NORM2(mx, my, mz);
      if (e2 < near2 || (e2 == near2 && p->id[j] < near_id))
        near2 = e2, near_id = p->id[j], mirror_phase = ph[j];
    }
    if (phased && ph[j])
      swa += wij, spa += (p->p[j] + p->rho[j] * gr) * wij;
    else
      sw += wij, sp += (p->p[j] + p->rho[j] * gr) * wij;
    for (int d = 0; d < SPH_DIM; d++)
      sv[d] += p->vel[d][j] * wij;
  }
  const double st = sw + swa; /* every fluid neighbour's weight: the no-slip velocity's */
  if (phased) {               /* two phases: the mirror point's phase */
    p->wphase[i] = (uint8_t)mirror_phase;
    if (mirror_phase) sw = swa, sp = spa;
  }
  double pw = 0.0;
  if (sw > 0.0) {
    pw = sp / sw;
    /* a wall pushes the liquid, never pulls it (adami.h); the air's gauge pressure may fall
     * below 0 (it has no floor), and the wall that mirrors it takes it as it is */
    if (!(pw > 0.0) && !(phased && p->wphase[i])) pw = 0.0;
  }
  p->p[i] = pw;
  p->rho[i] = pw > 0.0 ? sph_eos_density(&ap->eos, pw) : ap->eos.rho0; /* AHA12 eq. (28) */
  if (gv)
    for (int d = 0; d < SPH_DIM; d++)
      gv[d][i] = st > 0.0 ? 2.0 * p->vel[d][i] - sv[d] / st : p->vel[d][i];
  return st > 0.0;
}

static int adami_one(sph_particles *p, const sph_nlist *l, const sph_adami_params *ap,
                     double *const *gv, size_t i) {
  return sph_particles_phases(p) ? adami_row(p, l, ap, gv, i, 1) : adami_row(p, l, ap, gv, i, 0);
}

size_t sph_wall_adami(sph_particles *p, const sph_nlist *l, const sph_adami_params *ap,
                      double *const *gv) {
  const long n = (long)p->n;
  size_t wet = 0;
#pragma omp parallel for schedule(dynamic, 256) if (n > SPH_OMP_MIN) reduction(+ : wet)
  for (long li = 0; li < n; li++) {
    const size_t i = (size_t)li;
    if (p->kind[i] != SPH_KIND_WALL || !(p->flags[i] & SPH_FLAG_ADAMI)) continue;
    if (ap->skip && ap->skip[i]) continue;
    wet += (size_t)adami_one(p, l, ap, gv, i);
  }
  return wet;
}

size_t sph_wall_adami_list(sph_particles *p, const sph_nlist *l, const sph_adami_params *ap,
                           double *const *gv, const size_t *which, size_t k) {
  const long n = (long)k;
  size_t wet = 0;
#pragma omp parallel for schedule(dynamic, 256) if (n > SPH_OMP_MIN) reduction(+ : wet)
  for (long q = 0; q < n; q++)
    wet += (size_t)adami_one(p, l, ap, gv, which[q]);
  return wet;
}
