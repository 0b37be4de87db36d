/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * analytic.c - the film-flow profile of paper A eq. (26) and the error of an
 * SPH state against it (see analytic.h for the norms).
 *
 * The maximum is order-free; the mean square is a Neumaier-compensated sum,
 * so the L2 norm is the same to the last bit or two whatever the storage
 * order the grid left the particles in. Wall particles are skipped: their
 * velocity is prescribed (zero), not computed.
 */
#include "config.h"

#include "analysis/analytic.h"

#include <math.h>

double sph_film_profile(double y, double g, double nu, double L) {
  return g / nu * (L - 0.5 * y) * y;
}

static int positive(double v) { return isfinite(v) && v > 0.0; }

long sph_film_error(const sph_particles *p, double g, double nu, double L, double y0,
                    double *max_rel, double *l2_rel) {
  if (!positive(g) || !positive(nu) || !positive(L) || !isfinite(y0)) return -1;
  const double vmax = sph_film_profile(L, g, nu, L); /* g L^2 / (2 nu) */
  long n = 0;
  double emax = 0.0, sum = 0.0, carry = 0.0;
  for (size_t i = 0; i < p->n; i++) {
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    const double e = p->vx[i] - sph_film_profile(p->pos[SPH_UP][i] - y0, g, nu, L);
    const double ae = fabs(e);
    if (!(ae <= emax) && !isnan(emax)) emax = ae; /* a NaN, once seen, stays */
    const double e2 = e * e, t = sum + e2;
    carry += fabs(sum) >= e2 ? (sum - t) + e2 : (e2 - t) + sum;
    sum = t;
    n++;
  }
  if (n == 0) return -1;
  *max_rel = emax / vmax;
  *l2_rel = sqrt((sum + carry) / (double)n) / vmax;
  return n;
}
