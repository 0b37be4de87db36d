/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * eos.h - the Tait equation of state (paper A eq. (9)-(10); paper B eq. (5)):
 *   p = B [(rho/rho0)^gamma - 1],  B = rho0 c0^2 / gamma,  gamma = 7,
 * and the local sound speed c = c0 (rho/rho0)^((gamma-1)/2) = c0 (rho/rho0)^3.
 * gamma = 7 is written as multiplications, never pow(). A second phase's
 * law may be the linear one, gamma = 1: p = c0^2 (rho - rho0), c = c0
 * (the air of a two-phase run: doc/method.md, Two phases). A run's phases
 * each have their own law (sph_eos_of).
 */
#ifndef SPH_EOS_H
#define SPH_EOS_H

#include <math.h>
#include <stddef.h>

/* The most phases a run has (physics.air: the liquid, 0, and the air, 1). */
#define SPH_PHASES_MAX 2

typedef struct sph_eos {
  double rho0, c0, B; /* B = rho0 c0^2 / gamma */
  double rho_min;     /* the fluid's density floor: rho0 where the fluid holds no tension
                         (physics.negative_pressure: false), else 0 (no floor) */
  int linear;         /* 1: gamma = 1, else gamma = 7 */
} sph_eos;

static inline sph_eos sph_eos_tait(double rho0, double c0) {
  sph_eos e = {rho0, c0, rho0 * c0 * c0 / 7.0, 0.0, 0};
  return e;
}
/* The linear law, gamma = 1: B = rho0 c0^2. */
static inline sph_eos sph_eos_linear(double rho0, double c0) {
  sph_eos e = {rho0, c0, rho0 * c0 * c0, 0.0, 1};
  return e;
}
/* Particle i's law: table[phase[i]], or table[0] where phase is NULL (one phase). */
static inline const sph_eos *sph_eos_of(const sph_eos *table, const unsigned char *phase,
                                        size_t i) {
  return phase ? table + phase[i] : table;
}

/* A fluid particle's density held at the floor or above (physics.negative_pressure: false):
 * its pressure is then never below 0, the air's. A particle that a stretching jet or sheet
 * would expand below rho0 stays at rho0 instead of pulling on its neighbours (doc/method.md,
 * Negative pressure). With no floor (0) every density passes unchanged. */
static inline double sph_eos_floor(const sph_eos *e, double rho) {
  return rho < e->rho_min ? e->rho_min : rho;
}

static inline double sph_eos_pressure(const sph_eos *e, double rho) {
  if (e->linear) return e->B * (rho / e->rho0 - 1.0);
  const double r = rho / e->rho0;
  const double r2 = r * r;
  const double r3 = r2 * r;
  return e->B * (r3 * r3 * r - 1.0);
}

static inline double sph_eos_sound_speed(const sph_eos *e, double rho) {
  if (e->linear) return e->c0;
  const double r = rho / e->rho0;
  return e->c0 * r * r * r;
}

/* The density whose pressure is p (inverse of the law), for a
 * hydrostatic start: rho = rho0 (1 + p/B)^(1/7), or rho0 (1 + p/B). */
double sph_eos_density(const sph_eos *e, double p);

#endif
