/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * air.c - physics.air: a second phase, the air over the liquid
 * (doc/case-files.md, physics.air; doc/method.md, Two phases).
 *
 * `air: true` or a mapping of the air's material keys fills the tank's
 * free volume with air particles on the case's lattice (solver/setup.c);
 * `air: false` (the default) leaves one phase. The air has by default the
 * liquid's sound speed (the same-sound-speed approach of Rezavand et al.
 * 2020), so the time step is the one-phase step; `sound_speed` gives it its
 * own (a stiffer cushion; the step then follows the faster phase). The
 * two-phase pair terms are those
 * of the Riemann-solver pressure with Adami walls (the default scheme), and
 * the reader refuses what they do not cover, naming the key.
 *
 * The material's keys are one table (KEYS): each row a field of
 * sph_material (physics/models.h) with its default, its range, and its
 * line of `sph new`'s template; the reader, the defaults, the listing
 * (sph_case_describe) and the template all walk it, so a new key is a
 * field and a row.
 */
#include "config.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "case/case_read.h"

/* A key of the air's material: a number (double) or an integer (int) at
 * `at` in sph_material; an integer takes one of `choices` (0-terminated)
 * when given. `listed` (or NULL: always) says whether the listing shows
 * it. `example` and `help` are its template line. */
typedef struct air_key {
  const char *name;
  int integer;
  size_t at;
  double dflt;
  range r;              /* a number's range */
  const int *choices;   /* an integer's values */
  const char *expected; /* an integer's message: "expected <this>, got N" */
  int (*listed)(const sph_case *c);
  const char *example, *help;
} air_key;

static int with_viscosity(const sph_case *c) { return c->viscosity != SPH_VISCOSITY_NONE; }
/* (the air's band where it is not the liquid's, which it takes by default) */
static int own_band(const sph_case *c) { return c->air_material.density_limit != c->density_limit; }

/* (the surface tension where there is one) */
static int with_surface_tension(const sph_case *c) { return c->air_material.sigma > 0.0; }

static const int LAWS[] = {1, 7, 0};

static const air_key KEYS[] = {
    {.name = "rho0",
     .at = offsetof(sph_material, rho0),
     .dflt = 1.2,
     .r = {1e-6, 1e6, '[', ']', NULL},
     .example = "1.2",
     .help = "its reference density (kg/m^3)"},
    {.name = "exponent",
     .integer = 1,
     .at = offsetof(sph_material, exponent),
     .dflt = 1,
     .choices = LAWS,
     .expected = "1 (the linear law) or 7 (Tait's)",
     .example = "1",
     .help = "its law: 1 linear (default), 7 Tait's"},
    {.name = "sound_speed",
     .at = offsetof(sph_material, c0),
     .r = {0.0, 1e6, '(', ']', NULL},
     .example = "50",
     .help = "its c0 (m/s), default physics.sound_speed"},
    {.name = "mu",
     .at = offsetof(sph_material, mu),
     .dflt = 1.8e-5,
     .r = {0.0, 1e6, '(', ']', NULL},
     .listed = with_viscosity,
     .example = "1.8e-5",
     .help = "its viscosity (Pa s) with physics.viscosity (morris)"},
    {.name = "density_limit",
     .at = offsetof(sph_material, density_limit),
     .dflt = 0.3, /* (numerics.density_limit's, which the case's replaces: sph_case_check_air) */
     .r = {0.0, 1.0, '(', ')', NULL},
     .listed = own_band,
     .example = "0.3",
     .help = "its blow-up band, default numerics.density_limit"},
    {.name = "surface_tension",
     .at = offsetof(sph_material, sigma),
     .dflt = 0.0,
     .r = {0.0, 1e6, '[', ']', NULL},
     .listed = with_surface_tension,
     .example = "0.072",
     .help = "the interface's surface tension (N/m), default 0"},
};
#define N_KEYS (sizeof KEYS / sizeof KEYS[0])

static double *number_at(sph_material *m, const air_key *k) {
  return (double *)(void *)((char *)m + k->at);
}
static int *integer_at(sph_material *m, const air_key *k) {
  return (int *)(void *)((char *)m + k->at);
}
static double number_of(const sph_material *m, const air_key *k) {
  return *(const double *)(const void *)((const char *)m + k->at);
}
static int integer_of(const sph_material *m, const air_key *k) {
  return *(const int *)(const void *)((const char *)m + k->at);
}

void sph_case_air_defaults(sph_case *c) {
  for (size_t k = 0; k < N_KEYS; k++) {
    if (KEYS[k].integer)
      *integer_at(&c->air_material, &KEYS[k]) = (int)KEYS[k].dflt;
    else
      *number_at(&c->air_material, &KEYS[k]) = KEYS[k].dflt;
  }
}

/* Key k of the mapping m into c's material: 0 absent or read, -1 an error. */
static int read_key(const ctx *x, const node *m, const air_key *k, sph_case *c) {
  if (!k->integer)
    return sph_yaml_get_number(&x->t, m, "physics.air", k->name, 0, &k->r,
                               number_at(&c->air_material, k)) < 0
               ? -1
               : 0;
  int lo = k->choices[0], hi = k->choices[0];
  for (const int *v = k->choices; *v; v++)
    lo = *v < lo ? *v : lo, hi = *v > hi ? *v : hi;
  int *out = integer_at(&c->air_material, k);
  const int got = sph_yaml_get_int(&x->t, m, "physics.air", k->name, lo, hi, out);
  if (got <= 0) return got;
  for (const int *v = k->choices; *v; v++)
    if (*v == *out) return 0;
  char path[64];
  snprintf(path, sizeof path, "physics.air.%s", k->name);
  return sph_yaml_fail_at(&x->t, sph_yaml_find(m, k->name)->val, path, "expected %s, got %d",
                          k->expected, *out);
}

int sph_case_read_air(ctx *x, const node *physics, sph_case *c) {
  const entry *e = sph_yaml_find(physics, "air");
  if (!e) return 0;
  x->air_node = e->val;
  if (e->val->kind == SPH_YAML_SCALAR) /* true or false */
    return sph_yaml_get_bool(&x->t, physics, "physics", "air", &c->air) < 0 ? -1 : 0;
  const char *names[N_KEYS + 1];
  char expected[160] = "true, false or a mapping {";
  for (size_t k = 0; k < N_KEYS; k++) {
    names[k] = KEYS[k].name;
    snprintf(expected + strlen(expected), sizeof expected - strlen(expected), "%s%s", k ? ", " : "",
             KEYS[k].name);
  }
  names[N_KEYS] = NULL;
  if (e->val->kind != SPH_YAML_MAP) {
    char b[96];
    return sph_yaml_fail_at(&x->t, e->val, "physics.air", "expected %s}, got %s", expected,
                            sph_yaml_got(e->val, b, sizeof b));
  }
  const node *m;
  if (sph_yaml_get_section(&x->t, physics, "physics", "air", 0, names, &m) < 0) return -1;
  c->air = 1;
  x->air_map = m;
  for (size_t k = 0; k < N_KEYS; k++)
    if (read_key(x, m, &KEYS[k], c)) return -1;
  return 0;
}

/* What the two-phase terms do not cover, or NULL. */
static const char *air_clash(const sph_case *c) {
  if (!c->tank.present) return "a case without geometry.tank (the air fills the tank)";
  if (!c->riemann) return "physics.riemann: off (the two-phase terms are the Riemann pressure's)";
  for (int b = 0; b <= SPH_BOUNDARY_MDBC; b++)
    if (sph_case_has_boundary(c, (sph_boundary_kind)b))
      return "walls other than boundary: adami (the two-phase terms take Adami walls)";
  if (c->n_vessels) return "geometry.vessels"; /* (obstacles: the air around them, setup.c) */
  if (c->diffusion != SPH_DIFFUSION_NONE) return "numerics.density_diffusion";
  if (c->viscosity == SPH_VISCOSITY_STRESS_TENSOR)
    return "physics.viscosity.model: stress_tensor (two phases take morris)";
  if (c->alpha > 0.0 || c->beta > 0.0) return "physics.artificial_viscosity";
  if (c->xsph != 0.0) return "physics.xsph";
  if (c->sps) return "physics.turbulence";
  if (c->shifting) return "numerics.shifting";
  if (c->density_filter != SPH_FILTER_NONE) return "numerics.density_filter";
  if (c->variable_h) return "numerics.smoothing_length: variable";
  if (sph_case_needs_free_surface(c)) return "free-surface flags (free_surface, the stop rule)";
  if (c->periodic) return "a periodic axis";
  return NULL;
}

int sph_case_check_air(const ctx *x, sph_case *c) {
  if (!c->air) return 0;
  const char *why = air_clash(c);
  if (why)
    return sph_yaml_fail_at(&x->t, x->air_node, "physics.air", "cannot be combined with %s", why);
  if (!(x->air_map && sph_yaml_find(x->air_map, "sound_speed")))
    c->air_material.c0 = c->sound_speed; /* the same-sound-speed default */
  if (!(x->air_map && sph_yaml_find(x->air_map, "density_limit")))
    c->air_material.density_limit = c->density_limit; /* the liquid's band */
  const entry *mu = x->air_map ? sph_yaml_find(x->air_map, "mu") : NULL;
  if (mu && c->viscosity == SPH_VISCOSITY_NONE)
    return sph_yaml_fail_at(&x->t, mu->val, "physics.air.mu",
                            "the air's viscosity needs physics.viscosity (model: morris)");
  return 0;
}

/* One key's value as the listing and the template write it. */
static int key_value(char *buf, size_t n, const sph_material *m, const air_key *k) {
  return k->integer ? snprintf(buf, n, "%d", integer_of(m, k))
                    : snprintf(buf, n, "%.17g", number_of(m, k));
}

int sph_case_air_listing(const sph_case *c, char *buf, size_t n) {
  char out[512] = "{";
  size_t len = 1;
  for (size_t k = 0; k < N_KEYS; k++) {
    if (KEYS[k].listed && !KEYS[k].listed(c)) continue;
    char v[40];
    key_value(v, sizeof v, &c->air_material, &KEYS[k]);
    const int w =
        snprintf(out + len, sizeof out - len, "%s%s: %s", len > 1 ? ", " : "", KEYS[k].name, v);
    if (w < 0 || (size_t)w >= sizeof out - len) return -1;
    len += (size_t)w;
  }
  return snprintf(buf, n, "%s}", out);
}

int sph_case_air_template(char *buf, size_t n) {
  char out[2048];
  int w = snprintf(out, sizeof out, "  # %-24s # %s\n",
                   "air:", "a second phase: the tank's free volume filled with air");
  size_t len = (size_t)w;
  for (size_t k = 0; k < N_KEYS; k++) {
    char kv[64];
    snprintf(kv, sizeof kv, "%s: %s", KEYS[k].name, KEYS[k].example);
    w = snprintf(out + len, sizeof out - len, "  #   %-22s # %s\n", kv, KEYS[k].help);
    if (w < 0 || (size_t)w >= sizeof out - len) return -1;
    len += (size_t)w;
  }
  return snprintf(buf, n, "%s", out);
}
