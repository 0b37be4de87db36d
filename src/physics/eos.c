/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * eos.c - inverse of the equation of state (see eos.h); used only when
 * particles are created, so pow() is fine here.
 */
#include "config.h"

#include "physics/eos.h"

double sph_eos_density(const sph_eos *e, double p) {
  if (e->linear) return e->rho0 * (1.0 + p / e->B);
  return e->rho0 * pow(1.0 + p / e->B, 1.0 / 7.0);
}
