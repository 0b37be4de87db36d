/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * domain.h - the domain a case's fluid may occupy: geometry.domain, or its
 * default around a box (doc/case-files.md, geometry.domain). The run
 * widens its initial particles' box (solver/setup.c); the case reader
 * widens the geometry's box to refuse probes and gauges out of the water's
 * reach (case.c). Internal to the library.
 */
#ifndef SPH_CASE_DOMAIN_H
#define SPH_CASE_DOMAIN_H

#include "case/case.h"

/* The domain x0, x1, y0, y1 (, z0, z1) of c around the box bb (the same
 * layout; the last axis is up): geometry.domain if given; else, periodic in
 * x, x from x0 - L to x1 + L, the other horizontal axis as below, and the
 * vertical from the box's bottom - its height - 4h to its top + twice its
 * height + 4h; else the box widened by half its largest side plus 4h on
 * every side and by a further twice its height above. */
void sph_case_domain_around(const sph_case *c, const double bb[2 * SPH_DIM],
                            double domain[2 * SPH_DIM]);

#endif
