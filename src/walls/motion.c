/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * motion.c - the prescribed motion of wall particles (see motion.h). Each
 * particle keeps its rest position (xr, yr); its position at time t is a
 * function of t alone, never an integral of its velocity, so a wall ends a
 * motion exactly where the case says, on every run and after a restart.
 */
#include "config.h"

#include "walls/motion.h"

void sph_motion_point(const sph_motion *m, double t, double xr, double yr, double *x, double *y,
                      double *vx, double *vy) {
  *x = xr;
  *y = yr;
  *vx = *vy = 0.0;
  if (m->kind == SPH_MOTION_PISTON || m->kind == SPH_MOTION_FLAP) {
    sph_paddle_point(&m->paddle, t, xr, yr, x, y, vx, vy);
    return;
  }
  if (m->kind != SPH_MOTION_TRANSLATE || t <= m->start) return;
  const double te = t < m->stop ? t : m->stop;
  *x = xr + m->vx * (te - m->start);
  *y = yr + m->vy * (te - m->start);
  if (t < m->stop) {
    *vx = m->vx;
    *vy = m->vy;
  }
}
