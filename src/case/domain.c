/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * domain.c - the domain a case's fluid may occupy (see domain.h).
 */
#include "config.h"

#include "case/domain.h"

#include <string.h>

void sph_case_domain_around(const sph_case *c, const double bb[4], double domain[4]) {
  if (c->domain_set) {
    memcpy(domain, c->domain, 4 * sizeof *domain);
  } else if (c->periodic) { /* x wraps: only a runaway beyond a period is an error */
    const double L = c->periodic_x[1] - c->periodic_x[0], hgt = bb[3] - bb[2];
    domain[0] = c->periodic_x[0] - L;
    domain[1] = c->periodic_x[1] + L;
    domain[2] = bb[2] - hgt - 4.0 * c->h;
    domain[3] = bb[3] + 2.0 * hgt + 4.0 * c->h;
  } else {
    /* the box, widened by half its size sideways and below, and by twice
     * its height above (splashes rise, nothing should fall far) */
    const double w = bb[1] - bb[0], hgt = bb[3] - bb[2];
    const double m = 0.5 * (w > hgt ? w : hgt) + 4.0 * c->h;
    domain[0] = bb[0] - m;
    domain[1] = bb[1] + m;
    domain[2] = bb[2] - m;
    domain[3] = bb[3] + 2.0 * hgt + m;
  }
}
