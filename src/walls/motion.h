/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * motion.h - the prescribed motion of a wall: where each of its particles
 * is at time t, and how fast it moves (a gate translated at a constant
 * velocity, paper A §6; a piston or flap paddle, paper B §4.2).
 */
#ifndef SPH_MOTION_H
#define SPH_MOTION_H

#include "walls/wall_types.h"

/* Where a wall point at rest position r is at time t (x), and its
 * velocity (v), under the motion m. A paddle moves in the vertical plane
 * of x and the up axis (core/dim.h): a 3-D point keeps its y. */
void sph_motion_point(const sph_motion *m, double t, const double r[SPH_DIM], double x[SPH_DIM],
                      double v[SPH_DIM]);

/* The acceleration a of that point at time t: 0 for a translation (its
 * start and stop are jumps of the velocity, not accelerations), and for
 * a paddle the central difference of its velocity over t +- 1e-6 s
 * (exact to about 1e-10 of the velocity's scale for the paddles' periods
 * of 0.5 s and more; a function of t alone). */
void sph_motion_accel(const sph_motion *m, double t, const double r[SPH_DIM], double a[SPH_DIM]);

#endif
