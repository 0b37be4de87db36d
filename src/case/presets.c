/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * presets.c - the schemes' table (see presets.h). Each value is the YAML a
 * case would write for the key; doc/method.md, Schemes, says why each
 * scheme takes it, with the measurements.
 */
#include "config.h"

#include "case/presets.h"

#include <string.h>

/* The keys every scheme sets, in this order. */
#define TANK "geometry.tank"

/* The Riemann-solver scheme (ZH17) as validated for issue 56: the interface pressure with the
 * limiter 3 and its continuity term, no artificial viscosity, no XSPH, no density diffusion
 * (the pressure jump's term diffuses), the Wendland kernel at h = 2 dx (the kernel width that
 * makes the wall's reading quiet: bench/results/validation.md), the acoustic step rule
 * h / (c + |v|) (paper B's rule adds h |v_ij . r_ij| / r_ij^2, the artificial viscosity's, which
 * for two particles meeting head on without it shrinks the step geometrically: the 3-D
 * collapse), paper A's leap-frog (one pass a step instead of the predictor-corrector's two, at
 * 0.55-0.6 of the CPU time; against the experiments the same verdicts but two, doc/method.md,
 * Schemes), Adami walls (AHA12), a fluid that holds no tension (its density held at rho0 or
 * above: a sheet thrown up a wall neither sticks to it nor pulls the wall's sensors below 0,
 * doc/method.md, Negative pressure). */
static const sph_preset_key riemann[SPH_PRESET_KEYS] = {
    {"physics.riemann", "{limiter: 3}", NULL},
    {"physics.artificial_viscosity.alpha", "0", NULL},
    {"physics.xsph", "0", NULL},
    {"physics.viscosity", "{model: none}", NULL},
    {"numerics.density_diffusion", "{model: none}", NULL},
    {"numerics.kernel", "wendland_c2", NULL},
    {"numerics.h_factor", "2", NULL},
    {"numerics.time_step.rule", "cfl", NULL},
    {"numerics.integrator", "leapfrog", NULL},
    {"geometry.tank.boundary", "adami", TANK},
    {"physics.negative_pressure", "false", NULL}};

/* The papers' common base (paper A, the dam-break paper; paper B, the breaking-wave paper): the
 * plain pressure p_i/rho_i^2 + p_j/rho_j^2, the cubic spline at h = 1.3 dx, paper B's step rule,
 * paper B's predictor-corrector (a case of paper A's that runs its leap-frog says so), dynamic
 * walls; the artificial viscosity, XSPH and viscosity each paper's cases give
 * themselves. */
static const sph_preset_key paper[SPH_PRESET_KEYS] = {
    {"physics.riemann", "off", NULL},
    {"physics.artificial_viscosity.alpha", "0", NULL},
    {"physics.xsph", "0", NULL},
    {"physics.viscosity", "{model: none}", NULL},
    {"numerics.density_diffusion", "{model: none}", NULL},
    {"numerics.kernel", "cubic_spline", NULL},
    {"numerics.h_factor", "1.3", NULL},
    {"numerics.time_step.rule", "paper_b", NULL},
    {"numerics.integrator", "predictor_corrector", NULL},
    {"geometry.tank.boundary", "dynamic", TANK},
    {"physics.negative_pressure", "true", NULL}};

/* delta-SPH (MA11, the diffusion of AC10) with a small artificial viscosity and water's
 * laminar viscosity, mdbc walls. */
static const sph_preset_key delta_sph[SPH_PRESET_KEYS] = {
    {"physics.riemann", "off", NULL},
    {"physics.artificial_viscosity.alpha", "0.02", NULL},
    {"physics.xsph", "0", NULL},
    {"physics.viscosity", "{model: morris, mu: 0.001}", NULL},
    {"numerics.density_diffusion", "{model: antuono, delta: 0.1}", NULL},
    {"numerics.kernel", "cubic_spline", NULL},
    {"numerics.h_factor", "1.3", NULL},
    {"numerics.time_step.rule", "paper_b", NULL},
    {"numerics.integrator", "predictor_corrector", NULL},
    {"geometry.tank.boundary", "mdbc", TANK},
    {"physics.negative_pressure", "true", NULL}};

static const sph_preset presets[] = {
    {"riemann",
     "Riemann-solver pressure (ZH17), Wendland h = 2 dx, leap-frog, Adami walls, no tension: "
     "the default",
     riemann},
    {"paper_a",
     "the dam-break paper's base: plain pressure, cubic spline h = 1.3 dx, dynamic walls", paper},
    {"paper_b",
     "the breaking-wave paper's base: plain pressure, cubic spline h = 1.3 dx, dynamic walls",
     paper},
    {"delta_sph", "delta-SPH (MA11): alpha 0.02, antuono diffusion 0.1, water's viscosity, mdbc",
     delta_sph}};

const sph_preset *sph_presets(size_t *n) {
  *n = sizeof presets / sizeof presets[0];
  return presets;
}

const sph_preset *sph_preset_named(const char *name) {
  for (size_t k = 0; k < sizeof presets / sizeof presets[0]; k++)
    if (strcmp(presets[k].name, name) == 0) return &presets[k];
  return NULL;
}

const sph_preset *sph_preset_default(void) { return &presets[0]; }
