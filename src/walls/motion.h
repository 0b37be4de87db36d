/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * motion.h - the prescribed motion of a wall: where each of its particles
 * is at time t, and how fast it moves (a gate translated at a constant
 * velocity, paper A §6; a piston or flap paddle, paper B §4.2).
 */
#ifndef SPH_MOTION_H
#define SPH_MOTION_H

#include "walls/wall_types.h"

/* Where a wall point at rest position (xr, yr) is at time t, and its
 * velocity, under the motion m. */
void sph_motion_point(const sph_motion *m, double t, double xr, double yr, double *x, double *y,
                      double *vx, double *vy);

#endif
