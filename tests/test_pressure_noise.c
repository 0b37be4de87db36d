/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_pressure_noise.c - pressure noise as a number (issue 19, point 5).
 *
 * Two metrics, in units of rho0 g H (H the water depth or column height):
 *   spike   the largest |p_i - <p>_i| over fluid particles, <p>_i the
 *           Shepard-normalised kernel average of its fluid neighbours'
 *           pressures (itself left out): an isolated particle pressure
 *           that its neighbourhood does not share;
 *   rms     the RMS of the same difference over the fluid: the
 *           particle-scale noise.
 * Measured on the coarse Martin & Moyce dam break (a/20) at every output
 * time before the front reaches the far wall (the impact is not noise),
 * with the case's numerics, without and with the recommended density
 * diffusion (fourtakas), and bounded: with the recommended settings no
 * spike above 3 rho0 g H (the pressure issue's bound) and an RMS below
 * 0.25 rho0 g H.
 * The hydrostatic tank's RMS against rho0 g (H - y) is bounded in
 * tests/test_density_diffusion.c. bench/pressure_noise runs this program
 * with SPH_NOISE_RES="20 50" SPH_NOISE_MODELS=... to tabulate more.
 * The models "riemann", "riemann_sps" and "delta_sph" are bench/validation's
 * schemes of those names; "riemann" is its Riemann-solver scheme; run
 * after fourtakas (the default list) its spike and RMS must be no larger
 * than fourtakas' (issue 36's noise target; a/20: 0.227 and 0.038 against
 * 0.809 and 0.076; a/50: 0.151 and 0.015 against 0.523 and 0.036).
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "case/case.h"
#include "physics/kernel.h"
#include "solver/sim.h"
#include "testsim.h"
#include "testutil.h"

/* spike and rms of the state p (see above), h the smoothing length */
static void noise(const sph_particles *p, double h, double unit, double *spike, double *rms) {
  double s2 = 0.0, mx = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < p->n; i++) {
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    double num = 0.0, den = 0.0;
    for (size_t j = 0; j < p->n; j++) {
      if (j == i || p->kind[j] != SPH_KIND_FLUID) continue;
      const double dx = p->x[i] - p->x[j], dy = p->y[i] - p->y[j];
      if (fabs(dx) >= 2 * h || fabs(dy) >= 2 * h) continue;
      const double w = sph_cubic_w(sqrt(dx * dx + dy * dy), h) * p->mass[j] / p->rho[j];
      num += w * p->p[j];
      den += w;
    }
    if (!(den > 0.0)) continue; /* alone */
    const double e = fabs(p->p[i] - num / den) / unit;
    mx = fmax(mx, e);
    s2 += e * e;
    n++;
  }
  *spike = mx;
  *rms = n ? sqrt(s2 / (double)n) : 0.0;
}

/* The dam break at dx = a/res with the diffusion model named (or "none")
 * until the front reaches the far wall; the worst spike and RMS over the
 * output times. */
/* bench/validation's schemes of these names, as its SCHEME sets them (the
 * case gives its own numerics, so each key is set): riemann, Zhang et al.'s
 * pressure and its continuity term, no artificial viscosity, no XSPH, no
 * density diffusion, mdbc walls; riemann_sps, the same with the SPS
 * closure; delta_sph, alpha 0.02, antuono 0.1, Morris viscosity, no XSPH,
 * mdbc walls. Any other name is a density-diffusion model on the case as
 * shipped. */
static const struct {
  const char *name, *sets[8];
} schemes[] = {
    {"riemann",
     {"numerics.density_diffusion={model: none}", "physics.artificial_viscosity.alpha=0",
      "physics.riemann.limiter=3", "physics.xsph=0", "geometry.tank.boundary=mdbc",
      "geometry.tank.layers=3", NULL}},
    {"riemann_sps",
     {"numerics.density_diffusion={model: none}", "physics.artificial_viscosity.alpha=0",
      "physics.riemann.limiter=3", "physics.xsph=0", "geometry.tank.boundary=mdbc",
      "geometry.tank.layers=3", "physics.turbulence.model=sps", NULL}},
    {"delta_sph",
     {"numerics.density_diffusion={model: antuono, delta: 0.1}",
      "physics.artificial_viscosity.alpha=0.02", "physics.viscosity={model: morris, mu: 0.001}",
      "physics.xsph=0", "geometry.tank.boundary=mdbc", "geometry.tank.layers=3", NULL}},
};

static void dam_break(int res, const char *model, double *spike, double *rms) {
  char dx[64], dd[96];
  snprintf(dx, sizeof dx, "numerics.dx=%.17g", 0.05715 / res);
  /* the whole mapping: a delta without a model is refused */
  snprintf(dd, sizeof dd, "numerics.density_diffusion={model: %s}", model);
  const char *sets[10] = {dx, "time.output_interval=0.005", dd};
  size_t n = 3;
  for (size_t k = 0; k < sizeof schemes / sizeof schemes[0]; k++)
    if (strcmp(model, schemes[k].name) == 0)
      for (n = 2; schemes[k].sets[n - 2]; n++)
        sets[n] = schemes[k].sets[n - 2];
  sph_case c;
  sph_sim *s;
  CU_ASSERT_FATAL(sph_test_open_sim("cases/martin_moyce_coarse.yaml", sets, n, &c, &s) == 0);
  const double unit = c.rho0 * 9.81 * 0.1143; /* rho0 g 2a */
  *spike = *rms = 0.0;
  sph_error err;
  for (int k = 1;; k++) {
    int rc = 0;
    const double target = k * c.output_interval;
    while (rc == 0 && sph_sim_time(s) < target)
      rc = sph_sim_step(s, target, &err);
    if (rc) printf("\n%s\n", err.msg);
    CU_ASSERT_FATAL(rc == 0);
    const sph_particles *p = sph_sim_particles(s);
    if (sph_diag_front(p, sph_sim_floor(s), 2 * c.dx) >= c.tank.x1 - 2 * c.h) break; /* impact */
    double sp, r;
    noise(p, c.h, unit, &sp, &r);
    *spike = fmax(*spike, sp);
    *rms = fmax(*rms, r);
  }
  sph_sim_free(s);
  sph_case_free(&c);
}

static void test_dam_break_noise(void) {
  const char *res_env = getenv("SPH_NOISE_RES"), *models_env = getenv("SPH_NOISE_MODELS");
  char res[128], models[256];
  snprintf(res, sizeof res, "%s", res_env ? res_env : "20");
  for (char *sr = NULL, *r = strtok_r(res, " ", &sr); r; r = strtok_r(NULL, " ", &sr)) {
    snprintf(models, sizeof models, "%s", models_env ? models_env : "none fourtakas riemann");
    double f_spike = NAN, f_rms = NAN; /* fourtakas' at this resolution */
    for (char *sm = NULL, *m = strtok_r(models, " ", &sm); m; m = strtok_r(NULL, " ", &sm)) {
      double spike, rms;
      dam_break(atoi(r), m, &spike, &rms);
      printf("\n  noise: dam break a/%s, %-18s: largest spike %.3f, largest RMS %.3f rho0 g 2a", r,
             m, spike, rms);
      if (strcmp(m, "fourtakas") == 0) {
        CU_ASSERT(spike < 3.0);
        CU_ASSERT(rms < 0.25);
        f_spike = spike;
        f_rms = rms;
      }
      /* issue 36: the particle pressure noise no worse than fourtakas' */
      if (strcmp(m, "riemann") == 0 && !isnan(f_spike)) {
        CU_ASSERT(spike <= f_spike);
        CU_ASSERT(rms <= f_rms);
      }
    }
  }
  printf("\n");
}

int main(void) {
  CU_TestInfo tests[] = {{"dam break before impact: spikes and RMS", test_dam_break_noise},
                         CU_TEST_INFO_NULL};
  return sph_test_main("pressure_noise", tests);
}
