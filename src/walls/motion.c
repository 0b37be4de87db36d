/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * motion.c - the prescribed motion of wall particles (see motion.h). Each
 * particle keeps its rest position (xr, yr, zr); its position at time t is a
 * function of t alone, never an integral of its velocity, so a wall ends a
 * motion exactly where the case says, on every run and after a restart.
 */
#include "config.h"

#include "walls/motion.h"

void sph_motion_point(const sph_motion *m, double t, const double r[SPH_DIM], double x[SPH_DIM],
                      double v[SPH_DIM]) {
  for (int a = 0; a < SPH_DIM; a++) {
    x[a] = r[a];
    v[a] = 0.0;
  }
  if (m->kind == SPH_MOTION_PISTON || m->kind == SPH_MOTION_FLAP) {
    sph_paddle_point(&m->paddle, t, r[0], r[SPH_UP], &x[0], &x[SPH_UP], &v[0], &v[SPH_UP]);
    return;
  }
  if (m->kind != SPH_MOTION_TRANSLATE || t <= m->start) return;
  const double te = t < m->stop ? t : m->stop;
  for (int a = 0; a < SPH_DIM; a++)
    x[a] = r[a] + m->v[a] * (te - m->start);
  if (t < m->stop)
    for (int a = 0; a < SPH_DIM; a++)
      v[a] = m->v[a];
}

void sph_motion_accel(const sph_motion *m, double t, const double r[SPH_DIM], double a[SPH_DIM]) {
  for (int d = 0; d < SPH_DIM; d++)
    a[d] = 0.0;
  if (m->kind != SPH_MOTION_PISTON && m->kind != SPH_MOTION_FLAP) return;
  const double e = 1e-6;
  double x[SPH_DIM], v0[SPH_DIM], v1[SPH_DIM];
  sph_motion_point(m, t - e, r, x, v0);
  sph_motion_point(m, t + e, r, x, v1);
  for (int d = 0; d < SPH_DIM; d++)
    a[d] = (v1[d] - v0[d]) / (2.0 * e);
}
