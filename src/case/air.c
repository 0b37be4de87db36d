/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * air.c - physics.air: a second phase, the air over the liquid
 * (doc/case-files.md, physics.air; doc/method.md, Two phases).
 *
 * `air: true` or a mapping {rho0, exponent, mu} fills the tank's free volume
 * with air particles on the case's lattice (solver/setup.c); `mu` is the
 * air's dynamic viscosity where physics.viscosity (Morris') is on; `air: false`
 * (the default) leaves one phase. The air has the liquid's sound speed
 * (the same-sound-speed approach of Rezavand et al. 2020), so the time
 * step is the one-phase step. The two-phase pair terms are those of the
 * Riemann-solver pressure with Adami walls (the default scheme), and the
 * reader refuses what they do not cover, naming the key.
 */
#include "config.h"

#include <string.h>

#include "case/case_read.h"

static const char *const air_keys[] = {"rho0", "exponent", "mu", NULL};

int sph_case_read_air(ctx *x, const node *physics, sph_case *c) {
  static const range rho = {1e-6, 1e6, '[', ']', NULL};
  static const range mu = {0.0, 1e6, '(', ']', NULL};
  const entry *e = sph_yaml_find(physics, "air");
  if (!e) return 0;
  x->air_node = e->val;
  if (e->val->kind == SPH_YAML_SCALAR) /* true or false */
    return sph_yaml_get_bool(&x->t, physics, "physics", "air", &c->air) < 0 ? -1 : 0;
  if (e->val->kind != SPH_YAML_MAP) {
    char b[96];
    return sph_yaml_fail_at(&x->t, e->val, "physics.air",
                            "expected true, false or a mapping {rho0, exponent, mu}, got %s",
                            sph_yaml_got(e->val, b, sizeof b));
  }
  const node *m;
  if (sph_yaml_get_section(&x->t, physics, "physics", "air", 0, air_keys, &m) < 0) return -1;
  c->air = 1;
  if (sph_yaml_get_number(&x->t, m, "physics.air", "rho0", 0, &rho, &c->air_rho0) < 0) return -1;
  const int got = sph_yaml_get_int(&x->t, m, "physics.air", "exponent", 1, 7, &c->air_exponent);
  if (got < 0) return -1;
  if (got && c->air_exponent != 1 && c->air_exponent != 7)
    return sph_yaml_fail_at(&x->t, sph_yaml_find(m, "exponent")->val, "physics.air.exponent",
                            "expected 1 (the linear law) or 7 (Tait's), got %d", c->air_exponent);
  const int got_mu = sph_yaml_get_number(&x->t, m, "physics.air", "mu", 0, &mu, &c->air_mu);
  if (got_mu < 0) return -1;
  if (got_mu) x->air_mu_node = sph_yaml_find(m, "mu")->val;
  return 0;
}

/* What the two-phase terms do not cover, or NULL. */
static const char *air_clash(const sph_case *c) {
  if (!c->tank.present) return "a case without geometry.tank (the air fills the tank)";
  if (!c->riemann) return "physics.riemann: off (the two-phase terms are the Riemann pressure's)";
  for (int b = 0; b <= SPH_BOUNDARY_MDBC; b++)
    if (sph_case_has_boundary(c, (sph_boundary_kind)b))
      return "walls other than boundary: adami (the two-phase terms take Adami walls)";
  if (c->n_obstacles) return "geometry.obstacles or geometry.vessels";
  if (c->diffusion != SPH_DIFFUSION_NONE) return "numerics.density_diffusion";
  if (c->viscosity == SPH_VISCOSITY_STRESS_TENSOR)
    return "physics.viscosity.model: stress_tensor (two phases take morris)";
  if (c->alpha > 0.0 || c->beta > 0.0) return "physics.artificial_viscosity";
  if (c->xsph != 0.0) return "physics.xsph";
  if (c->sps) return "physics.turbulence";
  if (c->shifting) return "numerics.shifting";
  if (c->density_filter != SPH_FILTER_NONE) return "numerics.density_filter";
  if (c->variable_h) return "numerics.smoothing_length: variable";
  if (c->corrected_gradient) return "numerics.gradient_correction";
  if (sph_case_needs_free_surface(c)) return "free-surface flags (free_surface, the stop rule)";
  if (c->periodic) return "a periodic axis";
  return NULL;
}

int sph_case_check_air(const ctx *x, const sph_case *c) {
  if (!c->air) return 0;
  const char *why = air_clash(c);
  if (why)
    return sph_yaml_fail_at(&x->t, x->air_node, "physics.air", "cannot be combined with %s", why);
  if (x->air_mu_node && c->viscosity == SPH_VISCOSITY_NONE)
    return sph_yaml_fail_at(&x->t, x->air_mu_node, "physics.air.mu",
                            "the air's viscosity needs physics.viscosity (model: morris)");
  return 0;
}
