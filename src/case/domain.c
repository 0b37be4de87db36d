/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * domain.c - the domain a case's fluid may occupy (see domain.h).
 */
#include "config.h"

#include "case/domain.h"

#include <string.h>

void sph_case_domain_around(const sph_case *c, const double bb[2 * SPH_DIM],
                            double domain[2 * SPH_DIM]) {
  enum { UP = 2 * SPH_UP }; /* the vertical axis's lower bound */
  if (c->domain_set) {
    memcpy(domain, c->domain, 2 * SPH_DIM * sizeof *domain);
    return;
  }
  /* the box, widened by half its size sideways and below, and by twice
   * its height above (splashes rise, nothing should fall far) */
  const double hgt = bb[UP + 1] - bb[UP];
  double big = 0.0; /* the largest extent */
  for (int k = 0; k < 2 * SPH_DIM; k += 2)
    if (bb[k + 1] - bb[k] > big) big = bb[k + 1] - bb[k];
  const double m = 0.5 * big + 4.0 * c->h;
  for (int k = 0; k < 2 * SPH_DIM; k += 2) {
    domain[k] = bb[k] - m;
    domain[k + 1] = bb[k + 1] + m;
  }
  domain[UP + 1] = bb[UP + 1] + 2.0 * hgt + m;
  if (c->periodic) { /* an axis wraps: only a runaway beyond a period is an error */
    const double L = c->periodic_range[1] - c->periodic_range[0];
    const int a = 2 * c->periodic_axis;
    domain[a] = c->periodic_range[0] - L;
    domain[a + 1] = c->periodic_range[1] + L;
    if (c->tank.present) return; /* the tank's box above */
    domain[UP] = bb[UP] - hgt - 4.0 * c->h;
    domain[UP + 1] = bb[UP + 1] + 2.0 * hgt + 4.0 * c->h;
  }
}
