/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * surface_tension.h - the surface tension between two phases (surface_tension.c;
 * internal to src/solver/).
 */
#ifndef SPH_SURFACE_TENSION_H
#define SPH_SURFACE_TENSION_H

#include "core/particles.h"
#include "neighbours/grid.h"
#include "solver/force_pass.h"

/* The capillary stress Pi at every particle of p (w->sxx, ...: 0 at
 * wall particles and away from the interface) from the colour gradient over
 * the rows of l, with fp->sigma > 0 (Hu & Adams 2006). */
void sph_surface_stress(const sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                        sph_force_work *w);

/* The capillary time-step bound 0.25 (rho_min h^3 / (2 pi sigma))^1/2
 * (Brackbill, Kothe & Zemach 1992; Morris 2000), rho_min the lighter phase's
 * reference density; INFINITY without surface tension. */
double sph_surface_dt(const sph_force_params *fp, double h);

#endif
