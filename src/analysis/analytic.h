/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * analytic.h - analytic solutions that validation cases are measured
 * against.
 *
 * Film flow down an inclined plane (paper A §7): with x along the plane, a
 * body force g = g sin(alpha) along x, kinematic viscosity nu, a no-slip bed
 * at y = 0 and a free surface at y = L, the steady velocity profile is
 * paper A eq. (26),
 *   v(y) = (g / nu) (L - y/2) y,    0 <= y <= L,
 * with its maximum v_max = g L^2 / (2 nu) at the surface. The error of an
 * SPH state against it is measured over the fluid particles only, relative
 * to v_max (paper A does not define its norm; these are ours):
 *   max_rel = max_i |vx_i - v(y_i)| / v_max
 *   l2_rel  = sqrt( (1/N) sum_i (vx_i - v(y_i))^2 ) / v_max
 * where y_i is the particle's height above the bed.
 */
#ifndef SPH_ANALYTIC_H
#define SPH_ANALYTIC_H

#include "core/particles.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Paper A eq. (26): the steady film velocity at height y above the bed. */
double sph_film_profile(double y, double g, double nu, double L);

/* The two error norms above over the fluid particles of p, with y measured
 * from the bed at y0 along the vertical axis (y_i = p->y[i] - y0 in 2-D,
 * p->z[i] - y0 in 3-D: SPH_UP). Returns the number of fluid
 * particles used (> 0), or -1 (outputs untouched) if there is none or g,
 * nu or L is not a positive finite number. The sums run in storage order
 * with compensation, so the result does not depend on the order beyond the
 * last bit. */
long sph_film_error(const sph_particles *p, double g, double nu, double L, double y0,
                    double *max_rel, double *l2_rel);

#ifdef __cplusplus
}
#endif

#endif
