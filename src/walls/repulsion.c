/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * repulsion.c - the Lennard-Jones force of repulsive wall particles on
 * fluid particles (see repulsion.h). Each fluid particle sums over its own
 * neighbour row in storage order (gather form), so the result does not
 * depend on the thread count.
 */
#include "config.h"

#include "walls/repulsion.h"

#include "core/parallel.h"
#include "physics/pair_terms.h"

void sph_repulsion_add(sph_particles *p, const sph_nlist *l, double d, double r0,
                       const sph_repulsion_ledger *lg) {
  const long n = (long)p->n;
#pragma omp parallel for schedule(dynamic, 256) if (n > SPH_OMP_MIN)
  for (long li = 0; li < n; li++) {
    const size_t i = (size_t)li;
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    size_t cnt;
    const uint32_t *nb = sph_nlist_row(l, i, &cnt);
    double ax = 0.0, ay = 0.0, pw = 0.0, phi = 0.0;
    SPH_IF3(double az = 0.0;)
    for (size_t k = 0; k < cnt; k++) {
      const size_t j = nb[k];
      if (!(p->flags[j] & SPH_FLAG_REPULSIVE)) continue;
      const double dx = sph_nlist_sep(l, 0, p->x[i], p->x[j]);
      const double dy = sph_nlist_sep(l, 1, p->y[i], p->y[j]);
      SPH_IF3(const double dz = sph_nlist_sep(l, 2, p->z[i], p->z[j]);)
      const double r2 = SPH_NORM2(dx, dy, dz);
      if (r2 >= r0 * r0 || r2 == 0.0) continue;
      const double f = lennard_jones_v1(d, r0, r2);
      ax += f * dx;
      ay += f * dy;
      SPH_IF3(az += f * dz;)
      if (lg) {
        const vec_v1 a = {{SPH_XYZ(f * dx, f * dy, f * dz)}};
        const vec_v1 vj = {{SPH_XYZ(p->vx[j], p->vy[j], p->vz[j])}};
        pw += wall_power_v1(a, vj);
        phi += lennard_jones_potential_v1(d, r0, r2);
      }
    }
    p->ax[i] += ax;
    p->ay[i] += ay;
    SPH_IF3(p->az[i] += az;)
    if (lg) {
      lg->wf[0][i] += ax;
      lg->wf[1][i] += ay;
      SPH_IF3(lg->wf[2][i] += az;)
      lg->wpow[i] += pw;
      lg->phi[i] = phi;
    }
  }
}
