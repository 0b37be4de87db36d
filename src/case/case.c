/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * case.c - the case-file schema (see case.h), on the strict YAML tree of
 * src/case/yaml_tree.h (parsing, overrides, typed readers; the describer is
 * src/case/describe.c): the top level, physics, numerics and time here,
 * the geometry section in geometry.c and the output section in output.c
 * (their shared context: case_read.h).
 *
 * Algorithm. The text and its `--set` overrides are read into a tree whose
 * every node remembers its file line or override. Only then is the tree validated, in
 * schema order: every mapping is first checked for unknown keys, then each
 * key is read by a typed reader (number with a range, integer, boolean,
 * choice, string, pair of numbers) which reports the first violation as
 * "origin:line: dotted.key: expected ..., got ...". Defaults are stored in
 * the case before the readers run, so an absent optional key keeps its
 * default; derived values (c0, h) and the cross-checks between sections
 * follow the section they depend on.
 *
 * Invariants. The library never prints or exits: every function that can
 * fail returns non-zero with the error set. Every allocation is released on
 * every path; on failure the case is left zeroed, so sph_case_free is always
 * safe. The result depends only on the text and the overrides: the same
 * input gives the same case, the same first error and the same
 * sph_case_describe text.
 */
#include "config.h"

#include "case/case_read.h"
#include "case/mesh.h"

#include "case/choices.h"
#include "case/presets.h"

#include "physics/density_diffusion.h"
#include "physics/shifting.h"

#include "physics/filter.h"
#include "walls/wavemaker.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <yaml.h>

#define MAX_CASE_BYTES (1u << 20) /* the largest case file read: 1 MiB (issue 21, D8) */
#define MAX_DESCRIPTION 10000     /* the longest description, in bytes (stored in snapshots: D12) */
#define SPH_MAX_GRAVITY 1e6       /* m/s^2: physics.gravity's and body_force's magnitude, at most */
#define SPH_MAX_OUTPUTS 100000    /* output times from time.output_interval, at most */
#define KEYLEN SPH_YAML_KEYLEN

/* ---- choices -------------------------------------------------------------- */

static const char *const kernel_names[] = {"cubic_spline", "wendland_c2", NULL};
static const char *const integrator_names[] = {"predictor_corrector", "leapfrog", NULL};
static const char *const dt_rule_names[] = {"paper_b", "cfl", "fixed", NULL};
static const char *const viscosity_names[] = {"none", "stress_tensor", "morris", NULL};
static const char *const stop_names[] = {"none", "front_at_wall", NULL};

const char *sph_case_choice_name(const char *const *names, int k) {
  for (int i = 0; names[i]; i++)
    if (i == k) return names[i];
  return "unknown";
}

const char *sph_kernel_name(sph_kernel_kind k) {
  return sph_case_choice_name(kernel_names, (int)k);
}
const char *sph_integrator_name(sph_integrator_kind k) {
  return sph_case_choice_name(integrator_names, (int)k);
}
const char *sph_dt_rule_name(sph_dt_rule r) { return sph_case_choice_name(dt_rule_names, (int)r); }
const char *sph_scheme_name(sph_scheme_kind s) {
  size_t n;
  const sph_preset *all = sph_presets(&n);
  return (size_t)s < n ? all[s].name : "unknown";
}
const char *sph_stop_name(sph_stop_kind s) { return sph_case_choice_name(stop_names, (int)s); }
const char *sph_viscosity_name(sph_viscosity_kind v) {
  return sph_case_choice_name(viscosity_names, (int)v);
}

int sph_case_needs_free_surface(const sph_case *c) {
  return c->output_free_surface || c->fs_h_factor > 0.0;
}

/* Why the corrected gradient (numerics.gradient_correction, solver/forces.h)
 * cannot run with c's walls, or NULL: its moment sums every neighbour's
 * volume m/rho, so wall particles must tile the wall as the water's lattice
 * does. Staggered layers dx/2 apart count the wall twice (the 2-D still
 * tank's floor read +12 % and rising), and repulsive wall particles carry
 * no pressure. */
static const char *corrected_gradient_clash(const sph_case *c) {
  if (!c->corrected_gradient) return NULL;
  int repulsive = sph_case_has_boundary(c, SPH_BOUNDARY_REPULSIVE);
  for (size_t k = 0; k < c->n_obstacles; k++)
    repulsive |= c->obstacles[k].boundary == SPH_BOUNDARY_REPULSIVE;
  if (repulsive)
    return "repulsive walls (their particles carry no pressure; use dynamic or mdbc walls)";
  int staggered = c->tank.present && c->tank.boundary != SPH_BOUNDARY_MIRROR && c->tank.stagger;
  for (size_t k = 0; k < c->n_walls; k++)
    staggered |= c->walls[k].boundary != SPH_BOUNDARY_MIRROR && c->walls[k].stagger;
  if (staggered)
    return "staggered walls (layers dx/2 apart count the wall's volume twice; give the tank and "
           "the walls stagger: false)";
  return NULL;
}

/* |g|, its components' squares added in axis order. */
static double gravity_norm(const sph_case *c) {
  double g2 = 0.0;
  for (int a = 0; a < SPH_DIM; a++)
    g2 += c->gravity[a] * c->gravity[a];
  return sqrt(g2);
}

/* ---- the schema ----------------------------------------------------------- */

static const char *const top_keys[] = {"name", "description", "dimension",    "physics", "numerics",
                                       "time", "geometry",    "free_surface", "output",  NULL};
static const char *const fs_keys[] = {"radius_factor", "h_factor", NULL};
static const char *const laminar_keys[] = {"model", "mu", "gradient_correction", NULL};
static const char *const physics_keys[] = {
    "rho0",       "gravity",   "body_force", "sound_speed", "artificial_viscosity", "viscosity",
    "turbulence", "repulsion", "xsph",       "riemann",     "negative_pressure",    "air",
    NULL};
static const char *const c0_keys[] = {"factor", "height", "speed", NULL};
static const char *const visc_keys[] = {"alpha", "beta", "eta", NULL};
static const char *const riemann_keys[] = {"limiter", NULL};
static const char *const numerics_keys[] = {"dx",
                                            "h_factor",
                                            "kernel",
                                            "integrator",
                                            "smoothing_length",
                                            "time_step",
                                            "density_filter",
                                            "density_limit",
                                            "density_diffusion",
                                            "shifting",
                                            "gradient_correction",
                                            "scheme",
                                            NULL};
static const char *const dt_keys[] = {"rule", "factor", "dt", NULL};
static const char *const filter_keys[] = {"kind", "every", NULL};
static const char *const diffusion_keys[] = {"model", "delta", NULL};
static const char *const shifting_keys[] = {"coefficient", NULL};
static const char *const time_keys[] = {"end", "output_interval", "output_times", "stop", NULL};
static const char *const turbulence_keys[] = {"model", "cs", "ci", NULL};
static const char *const turbulence_names[] = {"none", "sps", NULL};
const char *const sph_case_h_names[] = {"constant", "variable", NULL};

/* Whether the dotted key (mappings down from root) is in the tree. */
static int has_key(const node *root, const char *dotted) {
  char part[64];
  const node *m = root;
  for (const char *p = dotted; m && m->kind == SPH_YAML_MAP;) {
    const size_t len = strcspn(p, ".");
    if (len >= sizeof part) return 0;
    memcpy(part, p, len);
    part[len] = '\0';
    const sph_yaml_entry *e = sph_yaml_find(m, part);
    if (!e) return 0;
    if (!p[len]) return 1;
    m = e->val;
    p += len + 1;
  }
  return 0;
}

/* Whether every part of the dotted key's path that the tree holds is a
 * mapping (a scheme's value is put in only there: a case whose numerics is
 * not a mapping is left to the readers to refuse). */
static int path_open(const node *root, const char *dotted) {
  char part[64];
  const node *m = root;
  for (const char *p = dotted;;) {
    if (m->kind != SPH_YAML_MAP) return 0;
    const size_t len = strcspn(p, ".");
    if (!p[len] || len >= sizeof part) return 1;
    memcpy(part, p, len);
    part[len] = '\0';
    const sph_yaml_entry *e = sph_yaml_find(m, part);
    if (!e) return 1;
    m = e->val;
    p += len + 1;
  }
}

/* numerics.scheme (default the presets' first), read before every other
 * key: its values (src/case/presets.c) go into the tree for every key the
 * case leaves out, so the readers read them as the case's own, and every
 * key the case gives keeps its value; those are joined by ", " into
 * c->scheme_kept (the start-up listing says a scheme on a case with its
 * own numerics is a mixture). A numerics that is not a mapping is left to
 * read_numerics to refuse. */
static int read_scheme(ctx *x, node *root, sph_case *c) {
  size_t n;
  const sph_preset *all = sph_presets(&n);
  const char *names[8];
  for (size_t k = 0; k < n && k < 7; k++)
    names[k] = all[k].name;
  names[n < 7 ? n : 7] = NULL;
  const sph_yaml_entry *num = sph_yaml_find(root, "numerics");
  int s = 0;
  if (num && num->val->kind == SPH_YAML_MAP &&
      sph_yaml_get_choice(&x->t, num->val, "numerics", "scheme", names, &s) < 0)
    return -1;
  const sph_preset *ps = &all[s];
  c->scheme = (sph_scheme_kind)s;
  x->t.scheme = ps->name;
  char buf[512] = "";
  for (size_t k = 0; k < SPH_PRESET_KEYS; k++) {
    const sph_preset_key *e = &ps->keys[k];
    if (has_key(root, e->key)) {
      sph_yaml_bprintf(buf + strlen(buf), sizeof buf - strlen(buf), "%s%s", buf[0] ? ", " : "",
                       e->key);
      continue;
    }
    if ((e->needs && !has_key(root, e->needs)) || !path_open(root, e->key)) continue;
    if (sph_yaml_put_default(&x->t, root, e->key, e->value)) return -1;
  }
  c->scheme_kept = sph_yaml_dup(buf, strlen(buf));
  return c->scheme_kept ? 0 : sph_yaml_oom(&x->t);
}

static void set_defaults(sph_case *c) {
  c->rho0 = 1000.0;
  for (int d = 0; d < SPH_DIM; d++)
    c->gravity[d] = 0.0;
  c->gravity[SPH_UP] = -9.81; /* the last axis is up */
  c->alpha = 0.0;
  c->beta = 0.0;
  c->eta = 0.1;
  c->xsph = 0.0;
  c->negative_pressure = 1;
  c->riemann = 0;
  c->riemann_limiter = 3.0;
  sph_case_air_defaults(c);
  c->h_factor = 1.3;
  c->kernel = SPH_KERNEL_CUBIC_SPLINE;
  c->integrator = SPH_INTEGRATOR_PREDICTOR_CORRECTOR;
  c->dt_rule = SPH_DT_PAPER_B;
  c->dt_factor = 0.3;
  c->dt_fixed = 0.0;
  c->density_limit = 0.3;
  c->stop = SPH_STOP_NONE;
  c->snapshots = 1;
  c->viscosity = SPH_VISCOSITY_NONE;
  c->fs_radius_factor = 1.0;
  c->density_filter = SPH_FILTER_NONE;
  c->filter_every = 30;
  c->diffusion = SPH_DIFFUSION_NONE;
  c->diffusion_delta = SPH_DIFFUSION_DELTA_DEFAULT;
  c->shifting_coefficient = SPH_SHIFTING_COEFFICIENT_DEFAULT;
  c->sps_cs = 0.12;
  c->sps_ci = 0.00066;
}

/* The required key `key` of m (under path) as a name: 1 to 64 characters
 * from [A-Za-z0-9_.-] (a case's name, a probe's); *out points into the
 * tree. */
int sph_case_read_plain_name(const ctx *x, const node *m, const char *path, const char *key,
                             const char **out) {
  const node *t;
  char kp[SPH_YAML_KEYLEN], b[96];
  if (sph_yaml_lookup(&x->t, m, path, key, 1, &t, kp) < 0) return -1;
  const char *s = t->kind == SPH_YAML_SCALAR ? t->text : "";
  const size_t n = strlen(s);
  if (n < 1 || n > 64 ||
      strspn(s, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_.-") != n)
    return sph_yaml_fail_at(&x->t, t, kp,
                            "expected a name of 1 to 64 characters from [A-Za-z0-9_.-], got %s",
                            sph_yaml_got(t, b, sizeof b));
  /* a name is a directory's (out/NAME): '.' and '..' would be this one or
   * its parent (issue 61, E7) */
  if (strspn(s, ".") == n)
    return sph_yaml_fail_at(&x->t, t, kp,
                            "expected a name with a character other than '.', got %s (out/%s "
                            "would be a directory that is already there)",
                            sph_yaml_got(t, b, sizeof b), s);
  *out = s;
  return 0;
}

static int read_name(const ctx *x, const node *root, sph_case *c) {
  const char *s;
  if (sph_case_read_plain_name(x, root, "", "name", &s)) return -1;
  c->name = sph_yaml_dup(s, strlen(s));
  return c->name ? 0 : sph_yaml_oom(&x->t);
}

/* c0 = value, or factor*sqrt(2 |g| height), or factor*speed. */
static int read_sound_speed(const ctx *x, const node *m, sph_case *c) {
  static const range what = {0, 0, '(', 0,
                             "a positive number or a mapping {factor, height} or {factor, speed}"};
  const char *kp = "physics.sound_speed";
  const node *t;
  char k[SPH_YAML_KEYLEN];
  double factor = 0, height = 0, speed = 0;
  if (sph_yaml_lookup(&x->t, m, "physics", "sound_speed", 1, &t, k) < 0) return -1;
  if (t->kind != SPH_YAML_MAP) return sph_yaml_read_number(&x->t, t, kp, &what, &c->sound_speed);
  if (sph_yaml_check_keys(&x->t, t, kp, c0_keys)) return -1;
  if (sph_yaml_get_number(&x->t, t, kp, "factor", 1, &SPH_YAML_POS, &factor) < 0) return -1;
  int has_h = sph_yaml_get_number(&x->t, t, kp, "height", 0, &SPH_YAML_POS, &height);
  if (has_h < 0) return -1;
  int has_s = sph_yaml_get_number(&x->t, t, kp, "speed", 0, &SPH_YAML_POS, &speed);
  if (has_s < 0) return -1;
  if (has_h && has_s)
    return sph_yaml_fail_at(&x->t, t, kp, "give either 'height' or 'speed', not both");
  if (!has_h && !has_s)
    return sph_yaml_fail_at(&x->t, t, kp,
                            "expected 'height' (c0 = factor*sqrt(2|g|*height)) or 'speed' "
                            "(c0 = factor*speed) next to 'factor'");
  if (has_s) {
    c->sound_speed = factor * speed;
  } else {
    double g = gravity_norm(c);
    if (g == 0)
      return sph_yaml_fail_at(&x->t, sph_yaml_find(t, "height")->val, "physics.sound_speed.height",
                              "c0 = factor*sqrt(2|g|*height) needs a non-zero physics.gravity");
    c->sound_speed = factor * sqrt(2.0 * g * height);
  }
  if (!isfinite(c->sound_speed)) {
    /* blame where the numbers came from: a --set that gave one of them,
     * else the mapping's line in the file (issue 39, D8) */
    const node *f = sph_yaml_find(t, "factor")->val,
               *o = sph_yaml_find(t, has_s ? "speed" : "height")->val, *at = t;
    const char *ak = kp;
    if (f->src != SPH_YAML_FROM_FILE)
      at = f, ak = "physics.sound_speed.factor";
    else if (o->src != SPH_YAML_FROM_FILE)
      at = o, ak = has_s ? "physics.sound_speed.speed" : "physics.sound_speed.height";
    return sph_yaml_fail_at(&x->t, at, ak, "the resulting c0 = %g*%g is not finite", factor,
                            has_s ? speed : height);
  }
  return 0;
}

/* Where a mapping's `model` came from when the mapping does not give it:
 * the scheme's default (issue 61, E12: "model is 'none'" with no word of
 * the scheme that chose it). */
static const char *whose_default(const ctx *x, const node *mapping) {
  static char buf[96];
  if (sph_yaml_find(mapping, "model")) return "";
  sph_yaml_bprintf(buf, sizeof buf, ", numerics.scheme %s's: give the model", x->t.scheme);
  return buf;
}

static int read_physics(ctx *x, const node *m, sph_case *c) {
  const char *p = "physics";
  const node *v;
  if (sph_yaml_get_number(&x->t, m, p, "rho0", 0, &SPH_YAML_POS, &c->rho0) < 0) return -1;
  int has_g = sph_yaml_get_vector(&x->t, m, p, "gravity", 0, SPH_DIM, c->gravity);
  if (has_g < 0) return -1;
  const node *bf;
  char kp[SPH_YAML_KEYLEN];
  if (sph_yaml_lookup(&x->t, m, p, "body_force", 0, &bf, kp) > 0) {
    if (has_g)
      return sph_yaml_fail_at(&x->t, bf, kp,
                              "give either physics.gravity or physics.body_force, not both");
    if (sph_yaml_read_vector(&x->t, bf, kp, SPH_DIM, c->gravity)) return -1;
  }
  /* an acceleration the run can hold: 1e308 made c0 infinite and the
   * message blamed the sound speed (issue 61, E12) */
  if (!(gravity_norm(c) <= SPH_MAX_GRAVITY)) {
    const char *key = has_g ? "gravity" : "body_force";
    const node *g;
    sph_yaml_lookup(&x->t, m, p, key, 0, &g, kp);
    char got[96];
    sph_yaml_bprintf(got, sizeof got, "[%g, %g" SPH_IF3(", %g") "]",
                     SPH_XYZ(c->gravity[0], c->gravity[1], c->gravity[2]));
    return sph_yaml_fail_at(&x->t, g, kp, "expected an acceleration of at most %g m/s^2, got %s",
                            SPH_MAX_GRAVITY, got);
  }
  if (read_sound_speed(x, m, c)) return -1;
  int rc = sph_yaml_get_section(&x->t, m, p, "viscosity", 0, laminar_keys, &v);
  if (rc < 0) return -1;
  if (rc > 0) {
    const char *vp = "physics.viscosity";
    int model = (int)c->viscosity; /* none, or the scheme's */
    if (sph_yaml_get_choice(&x->t, v, vp, "model", viscosity_names, &model) < 0) return -1;
    c->viscosity = (sph_viscosity_kind)model;
    int has_mu = sph_yaml_get_number(&x->t, v, vp, "mu",
                                     c->viscosity != SPH_VISCOSITY_NONE && !(c->mu > 0.0),
                                     &SPH_YAML_POS, &c->mu);
    if (has_mu < 0) return -1;
    if (has_mu && c->viscosity == SPH_VISCOSITY_NONE)
      return sph_yaml_fail_at(&x->t, sph_yaml_find(v, "mu")->val, "physics.viscosity.mu",
                              "only used with a viscosity model (model is 'none'%s; --set "
                              "'physics.viscosity={model: none}' replaces the whole mapping)",
                              whose_default(x, v));
    int has_gc = sph_yaml_get_bool(&x->t, v, vp, "gradient_correction", &c->gradient_correction);
    if (has_gc < 0) return -1;
    if (has_gc && c->gradient_correction && c->viscosity != SPH_VISCOSITY_STRESS_TENSOR)
      return sph_yaml_fail_at(
          &x->t, sph_yaml_find(v, "gradient_correction")->val,
          "physics.viscosity.gradient_correction",
          "corrects the stress-tensor viscosity: needs model 'stress_tensor', got '%s'",
          sph_viscosity_name(c->viscosity));
  }
  rc = sph_yaml_get_section(&x->t, m, p, "turbulence", 0, turbulence_keys, &v);
  if (rc < 0) return -1;
  if (rc > 0) {
    const char *tp = "physics.turbulence";
    if (sph_yaml_get_choice(&x->t, v, tp, "model", turbulence_names, &c->sps) < 0 ||
        sph_yaml_get_number(&x->t, v, tp, "cs", 0, &SPH_YAML_POS, &c->sps_cs) < 0 ||
        sph_yaml_get_number(&x->t, v, tp, "ci", 0, &SPH_YAML_NONNEG, &c->sps_ci) < 0)
      return -1;
  }
  if (sph_yaml_get_number(&x->t, m, p, "repulsion", 0, &SPH_YAML_POS, &c->repulsion) < 0) return -1;
  rc = sph_yaml_get_section(&x->t, m, p, "artificial_viscosity", 0, visc_keys, &v);
  if (rc < 0) return -1;
  if (rc > 0) {
    const char *vp = "physics.artificial_viscosity";
    if (sph_yaml_get_number(&x->t, v, vp, "alpha", 0, &SPH_YAML_NONNEG, &c->alpha) < 0) return -1;
    if (sph_yaml_get_number(&x->t, v, vp, "beta", 0, &SPH_YAML_NONNEG, &c->beta) < 0) return -1;
    if (sph_yaml_get_number(&x->t, v, vp, "eta", 0, &SPH_YAML_POS, &c->eta) < 0) return -1;
  }
  /* physics.riemann: a mapping {limiter} turns the Riemann pressure on, `off` leaves the plain
   * one (the papers' schemes say so) */
  const sph_yaml_entry *re = sph_yaml_find(m, "riemann");
  if (re && re->val->kind == SPH_YAML_SCALAR && strcmp(re->val->text, "off") == 0) {
    c->riemann = 0;
  } else {
    if (re && re->val->kind != SPH_YAML_MAP) {
      char b[96];
      return sph_yaml_fail_at(&x->t, re->val, "physics.riemann",
                              "expected a mapping {limiter: ...} (the Riemann-solver pressure) or "
                              "off, got %s",
                              sph_yaml_got(re->val, b, sizeof b));
    }
    rc = sph_yaml_get_section(&x->t, m, p, "riemann", 0, riemann_keys, &v);
    if (rc < 0) return -1;
    if (rc > 0) {
      c->riemann = 1;
      if (sph_yaml_get_number(&x->t, v, "physics.riemann", "limiter", 0, &SPH_YAML_NONNEG,
                              &c->riemann_limiter) < 0)
        return -1;
    }
  }
  if (sph_yaml_get_bool(&x->t, m, p, "negative_pressure", &c->negative_pressure) < 0) return -1;
  if (sph_case_read_air(x, m, c)) return -1;
  return sph_yaml_get_number(&x->t, m, p, "xsph", 0, &SPH_YAML_UNIT, &c->xsph) < 0 ? -1 : 0;
}

static int read_time_step(const ctx *x, const node *m, sph_case *c) {
  static const range factor = {0, 1, '(', ']', NULL};
  const char *p = "numerics.time_step";
  const node *t, *dt;
  char kp[SPH_YAML_KEYLEN];
  int rule = (int)c->dt_rule;
  int rc = sph_yaml_get_section(&x->t, m, "numerics", "time_step", 0, dt_keys, &t);
  if (rc <= 0) return rc;
  if (sph_yaml_get_choice(&x->t, t, p, "rule", dt_rule_names, &rule) < 0) return -1;
  c->dt_rule = (sph_dt_rule)rule;
  if (sph_yaml_get_number(&x->t, t, p, "factor", 0, &factor, &c->dt_factor) < 0) return -1;
  if (c->dt_rule == SPH_DT_FIXED) {
    if (sph_yaml_lookup(&x->t, t, p, "dt", 0, &dt, kp) == 0)
      return sph_yaml_fail_at(&x->t, t, kp, "required key is missing (rule 'fixed' needs it)");
    return sph_yaml_read_number(&x->t, dt, kp, &SPH_YAML_POS, &c->dt_fixed);
  }
  if (sph_yaml_lookup(&x->t, t, p, "dt", 0, &dt, kp) > 0)
    return sph_yaml_fail_at(&x->t, dt, kp, "only allowed with rule: fixed (the rule is '%s')",
                            sph_dt_rule_name(c->dt_rule));
  return 0;
}

static int read_numerics(ctx *x, const node *m, sph_case *c) {
  static const range h_factor = {0.5, 4, '[', ']', NULL};
  static const range limit = {0, 1, '(', ')', NULL};
  const char *p = "numerics";
  const node *t;
  char kp[SPH_YAML_KEYLEN];
  int k = (int)c->kernel, in = (int)c->integrator;
  if (sph_yaml_lookup(&x->t, m, p, "dx", 1, &t, kp) < 0) return -1;
  if (sph_yaml_read_number(&x->t, t, kp, &SPH_YAML_POS, &c->dx)) return -1;
  x->dx_node = t;
  c->dx_line = t->src == SPH_YAML_FROM_FILE ? t->line : 0;
  if (sph_yaml_get_number(&x->t, m, p, "h_factor", 0, &h_factor, &c->h_factor) < 0) return -1;
  c->h = c->h_factor * c->dx;
  if (!isfinite(c->h)) return sph_yaml_fail_at(&x->t, t, kp, "h = h_factor*dx overflows");
  if (sph_yaml_get_choice(&x->t, m, p, "smoothing_length", sph_case_h_names, &c->variable_h) < 0)
    return -1;
  if (sph_yaml_get_choice(&x->t, m, p, "kernel", kernel_names, &k) < 0) return -1;
  c->kernel = (sph_kernel_kind)k;
  if (sph_yaml_get_choice(&x->t, m, p, "integrator", integrator_names, &in) < 0) return -1;
  c->integrator = (sph_integrator_kind)in;
  if (read_time_step(x, m, c)) return -1;
  const node *f;
  int rc = sph_yaml_get_section(&x->t, m, p, "density_filter", 0, filter_keys, &f);
  if (rc < 0) return -1;
  if (rc > 0) {
    int kind = (int)c->density_filter;
    if (sph_yaml_get_choice(&x->t, f, "numerics.density_filter", "kind", sph_filter_kind_names,
                            &kind) < 0 ||
        sph_yaml_get_int(&x->t, f, "numerics.density_filter", "every", 1, 1000000,
                         &c->filter_every) < 0)
      return -1;
    c->density_filter = (sph_filter_kind)kind;
  }
  static const range delta = {0, 1, '(', ']', NULL};
  rc = sph_yaml_get_section(&x->t, m, p, "density_diffusion", 0, diffusion_keys, &f);
  if (rc < 0) return -1;
  if (rc > 0) {
    int model = (int)c->diffusion;
    if (sph_yaml_get_choice(&x->t, f, "numerics.density_diffusion", "model",
                            sph_diffusion_kind_names, &model) < 0)
      return -1;
    const int has_delta = sph_yaml_get_number(&x->t, f, "numerics.density_diffusion", "delta", 0,
                                              &delta, &c->diffusion_delta);
    if (has_delta < 0) return -1;
    if (has_delta && model == SPH_DIFFUSION_NONE) /* as physics.viscosity.mu */
      return sph_yaml_fail_at(&x->t, sph_yaml_find(f, "delta")->val,
                              "numerics.density_diffusion.delta",
                              "only used with a density-diffusion model (model is 'none'%s; "
                              "--set 'numerics.density_diffusion={model: none}' replaces the "
                              "whole mapping)",
                              whose_default(x, f));
    c->diffusion = (sph_diffusion_kind)model;
  }
  static const range shift = {0, 10, '(', ']', NULL};
  rc = sph_yaml_get_section(&x->t, m, p, "shifting", 0, shifting_keys, &f);
  if (rc < 0) return -1;
  if (rc > 0) {
    c->shifting = 1;
    x->shifting_node = sph_yaml_find(m, "shifting")->val;
    if (sph_yaml_get_number(&x->t, f, "numerics.shifting", "coefficient", 0, &shift,
                            &c->shifting_coefficient) < 0)
      return -1;
  }
  rc = sph_yaml_get_bool(&x->t, m, p, "gradient_correction", &c->corrected_gradient);
  if (rc < 0) return -1;
  if (rc > 0) x->cgrad_node = sph_yaml_find(m, "gradient_correction")->val;
  return sph_yaml_get_number(&x->t, m, p, "density_limit", 0, &limit, &c->density_limit) < 0 ? -1
                                                                                             : 0;
}

static int read_time(ctx *x, const node *m, sph_case *c) {
  const char *p = "time";
  const node *t;
  char kp[SPH_YAML_KEYLEN], what[96];
  int stop = (int)c->stop;
  if (sph_yaml_get_number(&x->t, m, p, "end", 1, &SPH_YAML_POS, &c->t_end) < 0) return -1;
  /* at most SPH_MAX_OUTPUTS output times from the interval: a tiny one
   * would fill the disk with snapshots (issue 21, D7) */
  const double least = c->t_end / SPH_MAX_OUTPUTS;
  sph_yaml_bprintf(what, sizeof what,
                   "a number from time.end/%d (%g, at most %d outputs) to time.end (%g)",
                   SPH_MAX_OUTPUTS, least, SPH_MAX_OUTPUTS, c->t_end);
  range interval = {least, c->t_end, '[', ']', what};
  const node *ot;
  int has_times = sph_yaml_lookup(&x->t, m, p, "output_times", 0, &ot, kp);
  if (sph_yaml_get_number(&x->t, m, p, "output_interval", !has_times, &interval,
                          &c->output_interval) < 0)
    return -1;
  if (has_times) {
    char b[96];
    if (ot->kind != SPH_YAML_LIST || ot->n == 0)
      return sph_yaml_fail_at(&x->t, ot, kp,
                              "expected a non-empty list of increasing times, got %s",
                              sph_yaml_got(ot, b, sizeof b));
    if (!(c->output_times = calloc(ot->n, sizeof *c->output_times))) return sph_yaml_oom(&x->t);
    c->n_output_times = ot->n;
    for (size_t i = 0; i < ot->n; i++) {
      char ik[SPH_YAML_KEYLEN];
      sph_yaml_bprintf(ik, sizeof ik, "time.output_times[%zu]", i);
      const double lo = i ? c->output_times[i - 1] : 0.0;
      char w2[96];
      sph_yaml_bprintf(w2, sizeof w2,
                       "a time > %g (increasing; times after time.end are not reached)", lo);
      range r = {lo, 0, '(', 0, w2};
      if (sph_yaml_read_number(&x->t, ot->items[i], ik, &r, &c->output_times[i])) return -1;
    }
  }
  int rc = sph_yaml_lookup(&x->t, m, p, "stop", 0, &t, kp);
  if (rc > 0) {
    if (sph_yaml_read_choice(&x->t, t, kp, stop_names, &stop)) return -1;
    x->stop_node = t;
  }
  c->stop = (sph_stop_kind)stop;
  return 0;
}

/* Reads every section of the (overridden) tree into c, in schema order. */
/* The case's dimension: 2 when absent; a case of the other dimension than
 * this build's is refused (sph runs it with the build of its dimension), and
 * in 3-D a tank's `stagger` (a wall segment's, its mirror boundary and a
 * mirror obstacle are refused where they are read). */
static int read_dimension(const ctx *x, const node *root, sph_case *c) {
  int dim = 2;
  if (sph_yaml_get_int(&x->t, root, "", "dimension", 2, 3, &dim) < 0) return -1;
  if (dim != SPH_DIM) {
    const sph_yaml_entry *e = sph_yaml_find(root, "dimension");
    return sph_yaml_fail_at(&x->t, e ? e->val : root, "dimension",
                            "this is the %d-D library, the case is %d-D (sph runs it with the "
                            "%d-D build)",
                            SPH_DIM, dim, dim);
  }
  c->dimension = dim;
  const sph_yaml_entry *g = sph_yaml_find(root, "geometry");
  const sph_yaml_entry *t =
      g && g->val->kind == SPH_YAML_MAP ? sph_yaml_find(g->val, "tank") : NULL;
  const sph_yaml_entry *st =
      SPH_DIM == 3 && t && t->val->kind == SPH_YAML_MAP ? sph_yaml_find(t->val, "stagger") : NULL;
  if (st)
    return sph_yaml_fail_at(&x->t, st->val, "geometry.tank.stagger",
                            "is 2-D only so far (a 3-D tank's layers are dx apart, "
                            "doc/dimensions.md)");
  return 0;
}

static int read_case(ctx *x, const node *root, sph_case *c) {
  const node *s;
  if (sph_yaml_check_keys(&x->t, root, "", top_keys) || read_dimension(x, root, c) ||
      read_name(x, root, c))
    return -1;
  if (sph_yaml_get_string(&x->t, root, "description", 0, &c->description) < 0) return -1;
  if (c->description && strlen(c->description) > MAX_DESCRIPTION)
    return sph_yaml_fail_at(
        &x->t, sph_yaml_find(root, "description")->val, "description",
        "expected at most %d characters (it is stored in every snapshot), got %zu", MAX_DESCRIPTION,
        strlen(c->description));
  if (sph_yaml_get_section(&x->t, root, "", "physics", 1, physics_keys, &s) < 0 ||
      read_physics(x, s, c))
    return -1;
  if (sph_yaml_get_section(&x->t, root, "", "numerics", 1, numerics_keys, &s) < 0 ||
      read_numerics(x, s, c))
    return -1;
  if (sph_yaml_get_section(&x->t, root, "", "time", 1, time_keys, &s) < 0 || read_time(x, s, c))
    return -1;
  if (sph_case_read_geometry(x, root, c)) return -1;
  if (c->repulsion == 0.0) { /* D = 5 |g| H, paper A eq. (22), H the deepest block */
    double H = 0.0;
    for (size_t i = 0; i < c->n_fluid; i++)
      if (c->fluid[i].surface - sph_case_block_bottom(&c->fluid[i]) > H)
        H = c->fluid[i].surface - sph_case_block_bottom(&c->fluid[i]);
    c->repulsion = 5.0 * gravity_norm(c) * H;
  }
  if (c->shifting && c->variable_h)
    return sph_yaml_fail_at(&x->t, x->shifting_node, "numerics.shifting",
                            "cannot be combined with numerics.smoothing_length: variable");
  if (c->shifting && sph_case_has_boundary(c, SPH_BOUNDARY_MIRROR))
    return sph_yaml_fail_at(
        &x->t, x->shifting_node, "numerics.shifting",
        "needs wall particles to count the wall as full, and mirror walls have none "
        "(use boundary: mdbc)");
  if (sph_case_check_air(x, c)) return -1;
  const char *cg_clash = corrected_gradient_clash(c);
  if (cg_clash)
    return sph_yaml_fail_at(&x->t, x->cgrad_node, "numerics.gradient_correction",
                            "cannot be combined with %s", cg_clash);
  if (c->stop == SPH_STOP_FRONT_AT_WALL && !c->tank.present)
    return sph_yaml_fail_at(&x->t, x->stop_node, "time.stop",
                            "'front_at_wall' needs a geometry.tank");
  int rc = sph_yaml_get_section(&x->t, root, "", "free_surface", 0, fs_keys, &s);
  if (rc < 0) return -1;
  if (rc > 0) {
    static const range rf = {0.5, 1.0, '[', ']', NULL};
    static const range hf = {1.0, 4.0, '[', ']', NULL};
    if (sph_yaml_get_number(&x->t, s, "free_surface", "radius_factor", 0, &rf,
                            &c->fs_radius_factor) < 0 ||
        sph_yaml_get_number(&x->t, s, "free_surface", "h_factor", 0, &hf, &c->fs_h_factor) < 0)
      return -1;
  }
  if (c->variable_h && c->fs_h_factor > 0.0)
    return sph_yaml_fail(&x->t, SPH_YAML_FROM_FILE, 0, "free_surface.h_factor",
                         "cannot be combined with numerics.smoothing_length: variable");
  if (c->periodic && c->fs_h_factor > 1.0 &&
      !(c->periodic_range[1] - c->periodic_range[0] >= 4.0 * c->fs_h_factor * c->h))
    return sph_yaml_fail(
        &x->t, SPH_YAML_FROM_FILE, 0, "geometry.periodic_x",
        "expected a period of at least 4 k h = %g m with free_surface.h_factor k = %g, "
        "got %g",
        4.0 * c->fs_h_factor * c->h, c->fs_h_factor, c->periodic_range[1] - c->periodic_range[0]);
  rc = sph_case_read_output(x, root, c);
  if (rc >= 0) sph_case_estimate_particles(c);
  return rc < 0 ? -1 : 0;
}

/* "a\nb\nc" from the overrides. */
static char *join_overrides(const char *const *set, size_t n) {
  size_t len = 0;
  for (size_t i = 0; i < n; i++)
    len += strlen(set[i]) + 1;
  char *s = malloc(len + 1), *p = s;
  if (!s) return NULL;
  for (size_t i = 0; i < n; i++) {
    size_t k = strlen(set[i]);
    if (i) *p++ = '\n';
    memcpy(p, set[i], k);
    p += k;
  }
  *p = '\0';
  return s;
}

static int parse_into(ctx *x, const char *text, size_t len, size_t n_set, sph_case *c) {
  node *root = NULL;
  int rc = sph_yaml_parse(&x->t, text, len, SPH_YAML_FROM_FILE, NULL, &root);
  if (rc) return rc;
  if (root->kind != SPH_YAML_MAP) {
    char b[96];
    rc = sph_yaml_fail_at(&x->t, root, NULL,
                          "expected a mapping of case keys at the top level, got %s",
                          sph_yaml_got(root, b, sizeof b));
  }
  for (size_t i = 0; rc == 0 && i < n_set; i++)
    rc = sph_yaml_apply_set(&x->t, root, (int)i);
  set_defaults(c);
  if (rc == 0) rc = read_scheme(x, root, c);
  if (rc == 0) rc = read_case(x, root, c);
  sph_yaml_free(root);
  if (rc) return rc;
  if (!c->description) c->description = sph_yaml_dup("", 0);
  c->path = sph_yaml_dup(x->t.origin, strlen(x->t.origin));
  c->text = sph_yaml_dup(text, len);
  c->overrides = join_overrides(x->t.set, n_set);
  if (!c->description || !c->path || !c->text || !c->overrides) return sph_yaml_oom(&x->t);
  return 0;
}

/* ---- public --------------------------------------------------------------- */

int sph_case_parse(const char *text, size_t len, const char *origin, const char *const *set,
                   size_t n_set, sph_case *c, sph_error *err) {
  ctx x = {{origin ? origin : "<text>", text ? text : "", text ? len : 0, set, err, NULL},
           NULL,
           NULL,
           NULL,
           NULL,
           NULL,
           NULL};
  memset(c, 0, sizeof *c);
  for (size_t i = 0; i < n_set; i++)
    if (!set || !set[i]) return sph_error_set(err, "%s: an empty --set override", x.t.origin);
  if (n_set > (size_t)0x7fffffff) return sph_error_set(err, "%s: too many overrides", x.t.origin);
  if (parse_into(&x, x.t.text, x.t.len, n_set, c)) {
    sph_case_free(c);
    return -1;
  }
  return 0;
}

/* The whole case file (at most MAX_CASE_BYTES) into *buf (malloc'ed) and *len. */
int sph_case_read_text(const char *path, char **buf_out, size_t *len_out, sph_error *err) {
  if (!path) return sph_error_set(err, "no case file given");
  FILE *f = fopen(path, "rb");
  if (!f) return sph_error_set(err, "%s: cannot open the case file: %s", path, strerror(errno));
  size_t len = 0, cap = 4096;
  char *buf = malloc(cap);
  int bad = buf == NULL, saved = ENOMEM;
  while (!bad) {
    if (len == cap) {
      char *nb = cap > ((size_t)-1) / 2 ? NULL : realloc(buf, cap * 2);
      if (!nb) {
        bad = 1;
        break;
      }
      buf = nb;
      cap *= 2;
    }
    size_t got_n = fread(buf + len, 1, cap - len, f);
    len += got_n;
    if (len > MAX_CASE_BYTES) { /* /dev/zero would never end (issue 21, D8) */
      fclose(f);
      free(buf);
      return sph_error_set(err,
                           "%s: the case file is larger than %u bytes (1 MiB): not a case file",
                           path, MAX_CASE_BYTES);
    }
    if (got_n == 0) {
      if (ferror(f)) {
        saved = errno;
        bad = 1;
      }
      break;
    }
  }
  fclose(f);
  if (bad) {
    free(buf);
    return sph_error_set(err, "%s: cannot read the case file: %s", path, strerror(saved));
  }
  *buf_out = buf;
  *len_out = len;
  return 0;
}

int sph_case_load(const char *path, const char *const *set, size_t n_set, sph_case *c,
                  sph_error *err) {
  memset(c, 0, sizeof *c);
  char *buf;
  size_t len;
  if (sph_case_read_text(path, &buf, &len, err)) return -1;
  int rc = sph_case_parse(buf, len, path, set, n_set, c, err);
  free(buf);
  return rc;
}

int sph_case_text_dimension(const char *text, size_t len, const char *origin,
                            const char *const *set, size_t n_set, int *dim, sph_error *err) {
  *dim = 2;
  ctx x = {{origin, text, len, set, err, NULL}, NULL, NULL, NULL, NULL, NULL, NULL};
  node *root = NULL;
  int rc = sph_yaml_parse(&x.t, text, len, SPH_YAML_FROM_FILE, NULL, &root);
  if (rc == 0 && root->kind == SPH_YAML_MAP) { /* (not a mapping: 2, the full reader says why) */
    for (size_t i = 0; rc == 0 && i < n_set; i++)
      rc = sph_yaml_apply_set(&x.t, root, (int)i);
    if (rc == 0 && sph_yaml_get_int(&x.t, root, "", "dimension", 2, 3, dim) < 0) rc = -1;
  }
  if (root) sph_yaml_free(root);
  return rc ? -1 : 0;
}

int sph_case_file_dimension(const char *path, const char *const *set, size_t n_set, int *dim,
                            sph_error *err) {
  *dim = 2;
  char *buf;
  size_t len;
  if (sph_case_read_text(path, &buf, &len, err)) return -1;
  const int rc = sph_case_text_dimension(buf, len, path, set, n_set, dim, err);
  free(buf);
  return rc;
}

void sph_case_free(sph_case *c) {
  if (!c) return;
  free(c->name);
  free(c->description);
  free(c->path);
  free(c->text);
  free(c->overrides);
  free(c->scheme_kept);
  for (size_t i = 0; c->fluid && i < c->n_fluid; i++) {
    free(c->fluid[i].shape.vertex);
    free(c->fluid[i].shape.file);
    sph_mesh_free(c->fluid[i].shape.mesh);
  }
  free(c->fluid);
  free(c->walls);
  for (size_t i = 0; c->obstacle_shape && i < c->n_obstacles; i++) {
    free(c->obstacle_shape[i].vertex);
    free(c->obstacle_shape[i].file);
    sph_mesh_free(c->obstacle_shape[i].mesh);
  }
  free(c->obstacle_shape);
  free(c->obstacles);
  free(c->output_times);
  free(c->gauges);
  free(c->probes);
  memset(c, 0, sizeof *c);
}
