/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * dbc.c - the density bounds of dynamic boundary particles (see dbc.h).
 *
 * One loop over the wall particles; each reads only its own neighbour row
 * (in storage order, stopping at the first fluid particle inside the
 * support) and writes only itself, so the result does not depend on the
 * thread count or the schedule.
 */
#include "config.h"

#include "walls/dbc.h"

#include "core/parallel.h"

/* Whether a fluid particle of i's row lies inside the support. */
static int fluid_near(const sph_particles *p, const sph_nlist *l, size_t i, double s2) {
  size_t cnt;
  const uint32_t *row = sph_nlist_row(l, i, &cnt);
  for (size_t k = 0; k < cnt; k++) {
    const size_t j = row[k];
    if (p->kind[j] != SPH_KIND_FLUID) continue;
    const double dx = sph_nlist_sep(l, 0, p->x[i], p->x[j]);
    const double dy = sph_nlist_sep(l, 1, p->y[i], p->y[j]);
    SPH_IF3(const double dz = sph_nlist_sep(l, 2, p->z[i], p->z[j]);)
    if (SPH_NORM2(dx, dy, dz) < s2) return 1;
  }
  return 0;
}

long sph_dbc_bound(sph_particles *p, const sph_nlist *l, double support, double rho0,
                   int half_step) {
  const long n = (long)p->n;
  const double s2 = support * support;
  long changed = 0;
#pragma omp parallel for schedule(static) if (n > SPH_OMP_MIN) reduction(+ : changed)
  for (long li = 0; li < n; li++) {
    const size_t i = (size_t)li;
    if (p->kind[i] != SPH_KIND_WALL ||
        (p->flags[i] & (SPH_FLAG_REPULSIVE | SPH_FLAG_MDBC | SPH_FLAG_ADAMI)))
      continue;
    const double rho = p->rho[i], rhoh = half_step ? p->rhoh[i] : rho0;
    if (rho == rho0 && rhoh == rho0) continue; /* at rest: nothing to bound */
    const int near = fluid_near(p, l, i, s2);
    const double b = near && rho > rho0 ? rho : rho0, bh = near && rhoh > rho0 ? rhoh : rho0;
    if (b == rho && bh == rhoh) continue;
    if (b != rho) {
      p->rho[i] = b;
      p->p[i] = 0.0; /* the Tait pressure at rho0 */
    }
    if (half_step) p->rhoh[i] = bh;
    changed++;
  }
  return changed;
}
