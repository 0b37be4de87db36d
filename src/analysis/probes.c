/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * probes.c - the readings of pressure, level and velocity probes (see
 * probes.h).
 */
#include "config.h"

#include "analysis/probes.h"

#include <math.h>
#include <stdio.h>

#include "core/kernel_shape.h"
#include "physics/kernel.h"

int sph_probe_columns(const sph_probe *q) {
  return q->kind == SPH_PROBE_VELOCITY || sph_probe_filtered(q) ? 2 : 1;
}

double sph_probe_low_pass(double y, double x, double dt, double cutoff) {
  const double a = -expm1(-2.0 * SPH_PI * cutoff * dt);
  return y + a * (x - y);
}

void sph_probe_header(const sph_probe *q, char *buf, size_t len) {
  switch (q->kind) {
  case SPH_PROBE_PRESSURE:
    if (sph_probe_filtered(q))
      snprintf(buf, len, ",%s (Pa),%s_low_pass (Pa)", q->name, q->name);
    else
      snprintf(buf, len, ",%s (Pa)", q->name);
    break;
  case SPH_PROBE_LEVEL: snprintf(buf, len, ",%s (m)", q->name); break;
  case SPH_PROBE_VELOCITY: snprintf(buf, len, ",%s_vx (m/s),%s_vy (m/s)", q->name, q->name); break;
  }
}

/* Shepard-normalised averages of p (each particle's carried to the point
 * along the hydrostatic gradient: p_j + rho_j g . (x - x_j)), vx and vy
 * over the fluid at (x, y); returns 0 where the point is dry (out
 * untouched). */
static int shepard_at(const sph_particles *p, sph_kernel_kind kernel, double x, double y, double h,
                      const double g[2], double out[3]) {
  const double reach = 2.0 * h;
  double den = 0.0, sp = 0.0, svx = 0.0, svy = 0.0;
  for (size_t j = 0; j < p->n; j++) {
    if (p->kind[j] != SPH_KIND_FLUID) continue;
    const double dx = x - p->x[j], dy = y - p->y[j];
    if (fabs(dx) >= reach || fabs(dy) >= reach) continue;
    const double w = sph_kernel_w(kernel, sqrt(dx * dx + dy * dy), h) * (p->mass[j] / p->rho[j]);
    den += w;
    sp += w * (p->p[j] + p->rho[j] * (g[0] * dx + g[1] * dy));
    svx += w * p->vx[j];
    svy += w * p->vy[j];
  }
  if (!(den >= SPH_PROBE_WET_SUM)) return 0;
  out[0] = sp / den;
  out[1] = svx / den;
  out[2] = svy / den;
  return 1;
}

void sph_probe_read(const sph_probe *q, const sph_particles *p, sph_kernel_kind kernel, double h,
                    double dx, double floor_y, const double g[2], double *out) {
  double v[3];
  switch (q->kind) {
  case SPH_PROBE_PRESSURE: {
    const int n = q->diameter > 0.0 ? SPH_PROBE_FACE_POINTS : 1;
    double sum = 0.0;
    for (int k = 0; k < n; k++) {
      const double s = n > 1 ? ((double)k / (n - 1) - 0.5) * q->diameter : 0.0;
      const double x = q->x + (q->along_x ? s : 0.0), y = q->y + (q->along_x ? 0.0 : s);
      if (shepard_at(p, kernel, x, y, h, g, v)) sum += v[0];
    }
    out[0] = sum / n;
    break;
  }
  case SPH_PROBE_LEVEL: {
    double top = -INFINITY;
    for (size_t j = 0; j < p->n; j++)
      if (p->kind[j] == SPH_KIND_FLUID && fabs(p->x[j] - q->x) < dx && p->y[j] > top) top = p->y[j];
    const double depth = top + 0.5 * dx - floor_y;
    out[0] = isfinite(depth) && depth > 0.0 ? depth : 0.0;
    break;
  }
  case SPH_PROBE_VELOCITY:
    out[0] = out[1] = 0.0;
    if (shepard_at(p, kernel, q->x, q->y, h, g, v)) {
      out[0] = v[1];
      out[1] = v[2];
    }
    break;
  }
}
