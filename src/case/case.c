/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * case.c - the case-file schema (see case.h), on the strict YAML tree of
 * src/case/yaml_tree.h (parsing, overrides, typed readers; the describer is
 * src/case/describe.c).
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

#include "case/case.h"
#include "case/choices.h"
#include "case/domain.h"
#include "case/yaml_tree.h"

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
#define SPH_MAX_OUTPUTS 100000    /* output times from time.output_interval, at most */
#define KEYLEN SPH_YAML_KEYLEN

typedef sph_yaml_node node;
typedef sph_yaml_entry entry;
typedef sph_yaml_range range;

/* The reader's context and what the cross-checks between sections need. */
typedef struct ctx {
  sph_yaml_ctx t;
  const node *dx_node;       /* numerics.dx, for the cross-checks */
  const node *stop_node;     /* time.stop if given */
  const node *shifting_node; /* numerics.shifting if given */
  const node *cgrad_node;    /* numerics.gradient_correction if given */
} ctx;

/* ---- choices -------------------------------------------------------------- */

static const char *const kernel_names[] = {"cubic_spline", "wendland_c2", NULL};
static const char *const integrator_names[] = {"predictor_corrector", "leapfrog", NULL};
static const char *const dt_rule_names[] = {"paper_b", "cfl", "fixed", NULL};
static const char *const scheme_names[] = {"none", "riemann", "delta_sph", NULL};
static const char *const boundary_names[] = {"dynamic", "fixed_layers", "repulsive",
                                             "mirror",  "mdbc",         NULL};
static const char *const viscosity_names[] = {"none", "stress_tensor", "morris", NULL};
static const char *const stop_names[] = {"none", "front_at_wall", NULL};

static const char *choice_name(const char *const *names, int k) {
  for (int i = 0; names[i]; i++)
    if (i == k) return names[i];
  return "unknown";
}

const char *sph_kernel_name(sph_kernel_kind k) { return choice_name(kernel_names, (int)k); }
const char *sph_integrator_name(sph_integrator_kind k) {
  return choice_name(integrator_names, (int)k);
}
const char *sph_dt_rule_name(sph_dt_rule r) { return choice_name(dt_rule_names, (int)r); }
const char *sph_boundary_name(sph_boundary_kind b) { return choice_name(boundary_names, (int)b); }
const char *sph_scheme_name(sph_scheme_kind s) { return choice_name(scheme_names, (int)s); }
const char *sph_stop_name(sph_stop_kind s) { return choice_name(stop_names, (int)s); }
const char *sph_viscosity_name(sph_viscosity_kind v) {
  return choice_name(viscosity_names, (int)v);
}

int sph_case_needs_free_surface(const sph_case *c) {
  return c->output_free_surface || c->fs_h_factor > 0.0;
}

int sph_case_has_boundary(const sph_case *c, sph_boundary_kind b) {
  int has = c->tank.present && c->tank.boundary == b;
  for (size_t k = 0; k < c->n_walls; k++)
    has |= c->walls[k].boundary == b;
  return has;
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
  double g2 = c->gravity[0] * c->gravity[0] + c->gravity[1] * c->gravity[1];
#if SPH_DIM == 3
  g2 += c->gravity[2] * c->gravity[2];
#endif
  return sqrt(g2);
}

/* A block's bottom and top along the vertical (y; z in 3-D). */
static double block_bottom(const sph_fluid_block *f) {
#if SPH_DIM == 2
  return f->y0;
#else
  return f->z0;
#endif
}
static double block_top(const sph_fluid_block *f) {
#if SPH_DIM == 2
  return f->y1;
#else
  return f->z1;
#endif
}

/* ---- the schema ----------------------------------------------------------- */

static const char *const top_keys[] = {"name", "description", "dimension",    "physics", "numerics",
                                       "time", "geometry",    "free_surface", "output",  NULL};
static const char *const fs_keys[] = {"radius_factor", "h_factor", NULL};
static const char *const laminar_keys[] = {"model", "mu", "gradient_correction", NULL};
static const char *const physics_keys[] = {
    "rho0",      "gravity",    "body_force", "sound_speed", "artificial_viscosity",
    "viscosity", "turbulence", "repulsion",  "xsph",        "riemann",
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
static const char *const geometry_keys[] = {"tank",       "fluid",      "walls",
                                            "obstacles",  "periodic_x", "periodic_y",
                                            "periodic_z", "domain",     NULL};
static const char *const obstacle_keys[] = {"x", "y", SPH_IF3("z", ) "layers", "boundary", NULL};
static const char *const tank_keys[] = {
    "x", "y", "layers", "boundary", "stagger", "extrapolated_velocity", "free_slip",
#if SPH_DIM == 3
    "z",
#endif
    NULL};
static const char *const fluid_keys[] = {"x",       "y",      "velocity", "hydrostatic",
                                         "surface", "jitter", "seed",
#if SPH_DIM == 3
                                         "z",
#endif
                                         NULL};
static const char *const wall_keys[] = {"from",
                                        "to",
                                        "layers",
                                        "boundary",
                                        "motion",
                                        "stagger",
                                        "extrapolated_velocity",
                                        "free_slip",
                                        SPH_IF3("y", ) NULL};
static const char *const motion_keys[] = {"type",   "velocity", "start",       "stop",
                                          "period", "stroke",   "wave_height", "depth",
                                          "ramp",   "hinge",    NULL};
const char *const sph_case_motion_names[] = {"none", "translate", "piston", "flap", NULL};
static const char *const turbulence_keys[] = {"model", "cs", "ci", NULL};
static const char *const turbulence_names[] = {"none", "sps", NULL};
const char *const sph_case_h_names[] = {"constant", "variable", NULL};
static const char *const domain_keys[] = {"x", "y",
#if SPH_DIM == 3
                                          "z",
#endif
                                          NULL};
static const char *const output_keys[] = {"snapshots", "free_surface",   "energy", "gauges",
                                          "probes",    "probe_interval", NULL};
static const char *const probe_keys[] = {"name",     "kind",  "at",       "x",
                                         "diameter", "along", "low_pass", "wetted",
#if SPH_DIM == 3
                                         "normal",
#endif
                                         NULL};
static const char *const probe_kind_names[] = {"pressure", "level", "velocity", NULL};
static const char *const along_names[] = {"y", "x", NULL};

const char *sph_probe_kind_name(sph_probe_kind k) { return choice_name(probe_kind_names, (int)k); }

/* The defaults of numerics.scheme s (doc/method.md, Schemes), on top of
 * set_defaults: what a case gets for every key it leaves out. */
static void scheme_defaults(sph_case *c, sph_scheme_kind s) {
  c->scheme = s;
  switch (s) {
  case SPH_SCHEME_NONE: break;
  case SPH_SCHEME_RIEMANN: /* Zhang, Hu & Adams 2017 (ZH17) */
    c->alpha = 0.0;
    c->xsph = 0.0;
    c->riemann = 1;
    c->riemann_limiter = 3.0;
    c->diffusion = SPH_DIFFUSION_NONE;
    break;
  case SPH_SCHEME_DELTA_SPH: /* delta-SPH, MA11 with AC10's diffusion (doc/method.md) */
    c->alpha = 0.02;
    c->xsph = 0.0;
    c->diffusion = SPH_DIFFUSION_ANTUONO;
    c->diffusion_delta = 0.1;
    c->viscosity = SPH_VISCOSITY_MORRIS;
    c->mu = 1.0e-3; /* water at 20 C */
    break;
  }
}

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

/* The keys of scheme s's set that the case gives itself, joined by ", "
 * into c->scheme_kept (the start-up listing says they keep the case's
 * values: a scheme on a case with its own numerics is a mixture). */
static int note_kept_keys(const ctx *x, const node *root, sph_case *c) {
  static const char *const riemann[] = {
      "physics.riemann",        "physics.artificial_viscosity.alpha",
      "physics.xsph",           "numerics.density_diffusion",
      "geometry.tank.boundary", NULL};
  static const char *const delta[] = {"physics.artificial_viscosity.alpha",
                                      "physics.xsph",
                                      "numerics.density_diffusion",
                                      "physics.viscosity",
                                      "geometry.tank.boundary",
                                      NULL};
  const char *const *keys = c->scheme == SPH_SCHEME_RIEMANN     ? riemann
                            : c->scheme == SPH_SCHEME_DELTA_SPH ? delta
                                                                : NULL;
  char buf[512] = "";
  for (size_t k = 0; keys && keys[k]; k++)
    if (has_key(root, keys[k]))
      sph_yaml_bprintf(buf + strlen(buf), sizeof buf - strlen(buf), "%s%s", buf[0] ? ", " : "",
                       keys[k]);
  c->scheme_kept = sph_yaml_dup(buf, strlen(buf));
  return c->scheme_kept ? 0 : sph_yaml_oom(&x->t);
}

/* numerics.scheme, read before every other key so that its defaults are in
 * place when they are read (a key the case gives wins over the scheme). A
 * numerics that is not a mapping is left to read_numerics to refuse. */
static int read_scheme(const ctx *x, const node *root, sph_case *c) {
  const sph_yaml_entry *n = sph_yaml_find(root, "numerics");
  int s = (int)SPH_SCHEME_NONE;
  if (n && n->val->kind == SPH_YAML_MAP &&
      sph_yaml_get_choice(&x->t, n->val, "numerics", "scheme", scheme_names, &s) < 0)
    return -1;
  scheme_defaults(c, (sph_scheme_kind)s);
  return note_kept_keys(x, root, c);
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
  c->riemann = 0;
  c->riemann_limiter = 3.0;
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
static int read_plain_name(const ctx *x, const node *m, const char *path, const char *key,
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
  *out = s;
  return 0;
}

static int read_name(const ctx *x, const node *root, sph_case *c) {
  const char *s;
  if (read_plain_name(x, root, "", "name", &s)) return -1;
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

static int read_physics(const ctx *x, const node *m, sph_case *c) {
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
                              "only used with a viscosity model (model is 'none'; --set "
                              "'physics.viscosity={model: none}' replaces the whole mapping)");
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
  rc = sph_yaml_get_section(&x->t, m, p, "riemann", 0, riemann_keys, &v);
  if (rc < 0) return -1;
  if (rc > 0) {
    c->riemann = 1;
    if (sph_yaml_get_number(&x->t, v, "physics.riemann", "limiter", 0, &SPH_YAML_NONNEG,
                            &c->riemann_limiter) < 0)
      return -1;
  }
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
                              "only used with a density-diffusion model (model is 'none'; --set "
                              "'numerics.density_diffusion={model: none}' replaces the whole "
                              "mapping)");
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

/* Repulsive walls are one layer (paper A §6 a) and mirror walls have no
 * particles: `layers` is fixed for them and an error if given otherwise. */
static int check_layers(const ctx *x, const node *m, const char *p, sph_boundary_kind b,
                        int *layers) {
  const node *t;
  char kp[SPH_YAML_KEYLEN];
  int given = sph_yaml_lookup(&x->t, m, p, "layers", 0, &t, kp);
  if (b == SPH_BOUNDARY_REPULSIVE) {
    if (given && *layers != 1)
      return sph_yaml_fail_at(&x->t, t, kp, "repulsive walls have exactly 1 layer, got %d",
                              *layers);
    *layers = 1;
  } else if (b == SPH_BOUNDARY_MIRROR) {
    if (given)
      return sph_yaml_fail_at(&x->t, t, kp, "mirror walls have no particle layers: remove the key");
    *layers = 0;
  }
  return 0;
}

/* The layers of a wall by default: 2 staggered layers dx/2 apart for the
 * dynamic models; for mdbc, whose wall density continues the fluid's
 * field, 3 layers on the fluid's lattice continued (they fill the support
 * 2h = 2.6 dx; in still water the floor particles then carry their
 * hydrostatic load within 3 %, against 42-53 % under it with 2 staggered
 * layers). */
static int default_layers(sph_boundary_kind b) { return b == SPH_BOUNDARY_MDBC ? 3 : 2; }
static int default_stagger(sph_boundary_kind b) { return SPH_DIM == 2 && b != SPH_BOUNDARY_MDBC; }

/* A wall segment's heights at its ends (from, to): y in 2-D, z in 3-D. */
static double *wall_up(sph_wall_segment *w, int end) {
#if SPH_DIM == 2
  return end ? &w->y1 : &w->y0;
#else
  return end ? &w->z1 : &w->z0;
#endif
}

/* `stagger`, `extrapolated_velocity` and `free_slip` of a wall of
 * particles with a density (dynamic, fixed_layers, mdbc); an error on the
 * others, and the extrapolated velocity only where a strain-rate pass uses
 * it. */
static int read_layout(const ctx *x, const node *m, const char *p, const sph_case *c,
                       sph_boundary_kind b, int *stagger, int *extrapolated, int *free_slip) {
  const node *t;
  char kp[SPH_YAML_KEYLEN];
  const int evolving =
      b == SPH_BOUNDARY_DYNAMIC || b == SPH_BOUNDARY_FIXED_LAYERS || b == SPH_BOUNDARY_MDBC;
  static const char *const keys[] = {"stagger", "extrapolated_velocity", "free_slip"};
  for (int k = 0; k < 3; k++)
    if (!evolving && sph_yaml_lookup(&x->t, m, p, keys[k], 0, &t, kp) > 0)
      return sph_yaml_fail_at(
          &x->t, t, kp, "only for 'dynamic', 'fixed_layers' and 'mdbc' walls (this one is '%s')",
          sph_boundary_name(b));
  if (sph_yaml_get_bool(&x->t, m, p, "stagger", stagger) < 0) return -1;
  if (sph_yaml_get_bool(&x->t, m, p, "free_slip", free_slip) < 0) return -1;
  int rc = sph_yaml_get_bool(&x->t, m, p, "extrapolated_velocity", extrapolated);
  if (rc < 0) return -1;
  if (rc > 0 && *extrapolated && c->viscosity != SPH_VISCOSITY_STRESS_TENSOR && !c->sps) {
    sph_yaml_lookup(&x->t, m, p, "extrapolated_velocity", 0, &t, kp);
    return sph_yaml_fail_at(
        &x->t, t, kp,
        "acts in the strain-rate pass: needs physics.viscosity.model 'stress_tensor' "
        "or physics.turbulence (viscosity model is '%s')",
        sph_viscosity_name(c->viscosity));
  }
  return 0;
}

static int read_tank(const ctx *x, const node *m, sph_case *c) {
  const char *p = "geometry.tank";
  const node *t;
  double v[2];
  /* a scheme's tank carries the fluid's pressure (mdbc); without one, dynamic */
  int b = c->scheme != SPH_SCHEME_NONE ? (int)SPH_BOUNDARY_MDBC : (int)SPH_BOUNDARY_DYNAMIC;
  int rc = sph_yaml_get_section(&x->t, m, "geometry", "tank", 0, tank_keys, &t);
  if (rc <= 0) return rc;
  c->tank.present = 1;
  if (sph_yaml_get_pair(&x->t, t, p, "x", 1, 'x', v) < 0) return -1;
  c->tank.x0 = v[0];
  c->tank.x1 = v[1];
  if (sph_yaml_get_pair(&x->t, t, p, "y", 1, 'y', v) < 0) return -1;
  c->tank.y0 = v[0];
  c->tank.y1 = v[1];
#if SPH_DIM == 3
  if (sph_yaml_get_pair(&x->t, t, p, "z", 1, 'z', v) < 0) return -1;
  c->tank.z0 = v[0];
  c->tank.z1 = v[1];
#endif
  if (sph_yaml_get_choice(&x->t, t, p, "boundary", boundary_names, &b) < 0) return -1;
  c->tank.boundary = (sph_boundary_kind)b;
  c->tank.layers = default_layers(c->tank.boundary);
  if (sph_yaml_get_int(&x->t, t, p, "layers", 1, 8, &c->tank.layers) < 0) return -1;
  c->tank.stagger = default_stagger(c->tank.boundary);
  if (read_layout(x, t, p, c, c->tank.boundary, &c->tank.stagger, &c->tank.extrapolated,
                  &c->tank.free_slip))
    return -1;
  return check_layers(x, t, p, c->tank.boundary, &c->tank.layers);
}

/* The block must be wider and taller than dx, and inside the tank if any. */
static int check_block(const ctx *x, const node *m, const char *p, const sph_case *c,
                       const sph_fluid_block *f) {
  double w = f->x1 - f->x0, h = f->y1 - f->y0;
  const sph_tank *k = &c->tank;
  char kp[SPH_YAML_KEYLEN], b[96];
  if (!(c->dx < w && c->dx < h))
    return sph_yaml_fail_at(
        &x->t, x->dx_node, "numerics.dx",
        "expected a positive number smaller than the width (%g) and height (%g) of "
        "%s, got %s",
        w, h, p, sph_yaml_got(x->dx_node, b, sizeof b));
#if SPH_DIM == 3
  if (!(c->dx < f->z1 - f->z0))
    return sph_yaml_fail_at(&x->t, x->dx_node, "numerics.dx",
                            "expected a positive number smaller than the z extent (%g) of %s, "
                            "got %s",
                            f->z1 - f->z0, p, sph_yaml_got(x->dx_node, b, sizeof b));
  if (k->present && (f->z0 < k->z0 || f->z1 > k->z1)) {
    sph_yaml_join(kp, sizeof kp, p, "z");
    return sph_yaml_fail_at(&x->t, sph_yaml_find(m, "z")->val, kp,
                            "expected a range inside the tank's inner box [%g, %g], got [%g, %g]",
                            k->z0, k->z1, f->z0, f->z1);
  }
#endif
  if (k->present && (f->x0 < k->x0 || f->x1 > k->x1)) {
    sph_yaml_join(kp, sizeof kp, p, "x");
    return sph_yaml_fail_at(&x->t, sph_yaml_find(m, "x")->val, kp,
                            "expected a range inside the tank's inner box [%g, %g], got [%g, %g]",
                            k->x0, k->x1, f->x0, f->x1);
  }
  if (k->present && (f->y0 < k->y0 || f->y1 > k->y1)) {
    sph_yaml_join(kp, sizeof kp, p, "y");
    return sph_yaml_fail_at(&x->t, sph_yaml_find(m, "y")->val, kp,
                            "expected a range inside the tank's inner box [%g, %g], got [%g, %g]",
                            k->y0, k->y1, f->y0, f->y1);
  }
  return 0;
}

static int read_block(const ctx *x, const node *m, const char *p, const sph_case *c,
                      sph_fluid_block *f) {
  char what[96], b[96];
  double v[2] = {0, 0};
  if (m->kind != SPH_YAML_MAP)
    return sph_yaml_fail_at(&x->t, m, p, "expected a mapping, got %s",
                            sph_yaml_got(m, b, sizeof b));
  if (sph_yaml_check_keys(&x->t, m, p, fluid_keys)) return -1;
  if (sph_yaml_get_pair(&x->t, m, p, "x", 1, 'x', v) < 0) return -1;
  f->x0 = v[0];
  f->x1 = v[1];
  if (sph_yaml_get_pair(&x->t, m, p, "y", 1, 'y', v) < 0) return -1;
  f->y0 = v[0];
  f->y1 = v[1];
#if SPH_DIM == 3
  if (sph_yaml_get_pair(&x->t, m, p, "z", 1, 'z', v) < 0) return -1;
  f->z0 = v[0];
  f->z1 = v[1];
#endif
  double vel[SPH_DIM] = {0.0};
  if (sph_yaml_get_vector(&x->t, m, p, "velocity", 0, SPH_DIM, vel) < 0) return -1;
  f->vx = vel[0];
  f->vy = vel[1];
  SPH_IF3(f->vz = vel[2];)
  f->hydrostatic = 1;
  if (sph_yaml_get_bool(&x->t, m, p, "hydrostatic", &f->hydrostatic) < 0) return -1;
  f->surface = block_top(f);
  sph_yaml_bprintf(what, sizeof what, "a number >= the block's %s (%g)", SPH_DIM == 2 ? "y1" : "z1",
                   block_top(f));
  range surface = {block_top(f), 0, '[', 0, what};
  if (sph_yaml_get_number(&x->t, m, p, "surface", 0, &surface, &f->surface) < 0) return -1;
  static const range jitter = {0, 0.5, '[', ')', NULL};
  const int has_jitter = sph_yaml_get_number(&x->t, m, p, "jitter", 0, &jitter, &f->jitter);
  if (has_jitter < 0) return -1;
  f->seed = 1;
  const int has_seed = sph_yaml_get_int(&x->t, m, p, "seed", 0, 2147483647L, &f->seed);
  if (has_seed < 0) return -1;
  if (has_seed && !has_jitter) {
    char kp[SPH_YAML_KEYLEN];
    sph_yaml_join(kp, sizeof kp, p, "seed");
    return sph_yaml_fail_at(&x->t, sph_yaml_find(m, "seed")->val, kp,
                            "expected no seed without %s.jitter, got %s", p,
                            sph_yaml_got(sph_yaml_find(m, "seed")->val, b, sizeof b));
  }
  return check_block(x, m, p, c, f);
}

static int read_fluid(const ctx *x, const node *m, sph_case *c) {
  const node *t;
  char kp[SPH_YAML_KEYLEN], b[96];
  if (sph_yaml_lookup(&x->t, m, "geometry", "fluid", 1, &t, kp) < 0) return -1;
  if (t->kind != SPH_YAML_LIST || t->n == 0)
    return sph_yaml_fail_at(&x->t, t, kp, "expected a non-empty list of mappings, got %s",
                            sph_yaml_got(t, b, sizeof b));
  if (!(c->fluid = calloc(t->n, sizeof *c->fluid))) return sph_yaml_oom(&x->t);
  c->n_fluid = t->n;
  for (size_t i = 0; i < t->n; i++) {
    sph_yaml_bprintf(kp, sizeof kp, "geometry.fluid[%zu]", i);
    if (read_block(x, t->items[i], kp, c, &c->fluid[i])) return -1;
    /* blocks that overlap would put particles on top of one another: twice
     * the mass there (issue 21, D5) */
    const sph_fluid_block *a = &c->fluid[i];
    for (size_t k = 0; k < i; k++) {
      const sph_fluid_block *o = &c->fluid[k];
      const double w = fmin(a->x1, o->x1) - fmax(a->x0, o->x0);
      const double hh = fmin(a->y1, o->y1) - fmax(a->y0, o->y0);
#if SPH_DIM == 3
      if (!(fmin(a->z1, o->z1) - fmax(a->z0, o->z0) > 1e-9 * c->dx)) continue;
#endif
      if (w > 1e-9 * c->dx && hh > 1e-9 * c->dx)
        return sph_yaml_fail_at(
            &x->t, t->items[i], kp,
            "expected a block apart from geometry.fluid[%zu], got one that overlaps "
            "it in [%g, %g] x [%g, %g] (their particles would coincide)",
            k, fmax(a->x0, o->x0), fmin(a->x1, o->x1), fmax(a->y0, o->y0), fmin(a->y1, o->y1));
    }
  }
  return 0;
}

/* A paddle: {type: piston|flap, period, stroke | wave_height, depth, ramp,
 * hinge}. With wave_height the stroke comes from the linear transfer
 * function (needs depth); the flap's hinge defaults to the wall's lower end
 * and its depth is required; the ramp defaults to one period. */
static int read_paddle(const ctx *x, const node *t, const char *kp, sph_wall_segment *w) {
  sph_paddle *pd = &w->motion.paddle;
  pd->kind = w->motion.kind == SPH_MOTION_FLAP ? SPH_PADDLE_FLAP : SPH_PADDLE_PISTON;
  if (sph_yaml_get_number(&x->t, t, kp, "period", 1, &SPH_YAML_POS, &pd->period) < 0) return -1;
  int has_d = sph_yaml_get_number(&x->t, t, kp, "depth", pd->kind == SPH_PADDLE_FLAP, &SPH_YAML_POS,
                                  &pd->depth);
  if (has_d < 0) return -1;
  int has_s = sph_yaml_get_number(&x->t, t, kp, "stroke", 0, &SPH_YAML_POS, &pd->stroke);
  if (has_s < 0) return -1;
  double H = 0.0;
  int has_h = sph_yaml_get_number(&x->t, t, kp, "wave_height", 0, &SPH_YAML_POS, &H);
  if (has_h < 0) return -1;
  if (has_s == has_h)
    return sph_yaml_fail_at(&x->t, t, kp, "expected exactly one of 'stroke' or 'wave_height'");
  if (has_h) {
    if (!has_d)
      return sph_yaml_fail_at(&x->t, t, kp,
                              "'wave_height' needs 'depth' (for the transfer function)");
    sph_error e;
    if (sph_paddle_stroke(pd->kind, H, pd->period, pd->depth, 9.81, &pd->stroke, &e))
      return sph_yaml_fail_at(&x->t, t, kp, "%s", e.msg);
  }
  pd->ramp = pd->period;
  if (sph_yaml_get_number(&x->t, t, kp, "ramp", 0, &SPH_YAML_NONNEG, &pd->ramp) < 0) return -1;
  const double u0 = *wall_up(w, 0), u1 = *wall_up(w, 1); /* the lower end */
  double hinge[2] = {u0 < u1 ? w->x0 : w->x1, u0 < u1 ? u0 : u1};
  if (sph_yaml_get_pair(&x->t, t, kp, "hinge", 0, 0, hinge) < 0) return -1;
  pd->hinge_x = hinge[0];
  pd->hinge_y = hinge[1];
  w->motion.start = 0.0;
  w->motion.stop = INFINITY;
  sph_error e;
  if (sph_paddle_check(pd, &e)) return sph_yaml_fail_at(&x->t, t, kp, "%s", e.msg);
  return 0;
}

/* walls[i].motion: {type: translate, velocity: [vx, vy(, vz)], start: 0, stop: t} */
static int read_motion(const ctx *x, const node *m, const char *p, sph_wall_segment *w) {
  const node *t;
  char kp[SPH_YAML_KEYLEN];
  sph_yaml_join(kp, sizeof kp, p, "motion");
  memset(&w->motion, 0, sizeof w->motion);
  w->motion.stop = INFINITY;
  int rc = sph_yaml_get_section(&x->t, m, p, "motion", 0, motion_keys, &t);
  if (rc <= 0) return rc;
  int kind = 0;
  const node *tt;
  char tk[SPH_YAML_KEYLEN];
  if (sph_yaml_lookup(&x->t, t, kp, "type", 1, &tt, tk) < 0 ||
      sph_yaml_read_choice(&x->t, tt, tk, sph_case_motion_names, &kind))
    return -1;
  w->motion.kind = (sph_motion_kind)kind;
  if (w->motion.kind == SPH_MOTION_NONE) {
    if (t->n > 1) return sph_yaml_fail_at(&x->t, t, kp, "type 'none' takes no other keys");
    return 0;
  }
  if (w->boundary == SPH_BOUNDARY_MIRROR)
    return sph_yaml_fail_at(&x->t, t, kp, "a mirror wall has no particles to move");
  if (w->motion.kind == SPH_MOTION_PISTON || w->motion.kind == SPH_MOTION_FLAP)
    return read_paddle(x, t, kp, w);
  if (sph_yaml_get_vector(&x->t, t, kp, "velocity", 1, SPH_DIM, w->motion.v) < 0) return -1;
  if (sph_yaml_get_number(&x->t, t, kp, "start", 0, &SPH_YAML_NONNEG, &w->motion.start) < 0)
    return -1;
  char what[96];
  sph_yaml_bprintf(what, sizeof what, "a number > start (%g)", w->motion.start);
  range after = {w->motion.start, 0, '(', 0, what};
  return sph_yaml_get_number(&x->t, t, kp, "stop", 0, &after, &w->motion.stop) < 0 ? -1 : 0;
}

static int read_wall(const ctx *x, const node *m, const char *p, const sph_case *c,
                     sph_wall_segment *w) {
  char b[96];
  double from[2], to[2];
  int bnd = (int)SPH_BOUNDARY_DYNAMIC;
  if (m->kind != SPH_YAML_MAP)
    return sph_yaml_fail_at(&x->t, m, p, "expected a mapping, got %s",
                            sph_yaml_got(m, b, sizeof b));
  if (sph_yaml_check_keys(&x->t, m, p, wall_keys)) return -1;
  if (sph_yaml_get_pair(&x->t, m, p, "from", 1, 0, from) < 0) return -1;
  if (sph_yaml_get_pair(&x->t, m, p, "to", 1, 0, to) < 0) return -1;
  if (from[0] == to[0] && from[1] == to[1]) {
    char kp[SPH_YAML_KEYLEN];
    sph_yaml_join(kp, sizeof kp, p, "to");
    return sph_yaml_fail_at(&x->t, sph_yaml_find(m, "to")->val, kp,
                            "expected a point different from 'from', got [%g, %g]", to[0], to[1]);
  }
  const double len = hypot(to[0] - from[0], to[1] - from[1]);
  if (c->dx > 0.0 && !(len >= c->dx)) { /* issue 39, D7: particles on top of one another */
    char kp[SPH_YAML_KEYLEN];
    sph_yaml_join(kp, sizeof kp, p, "to");
    return sph_yaml_fail_at(&x->t, sph_yaml_find(m, "to")->val, kp,
                            "the wall from [%g, %g] is %g m long, shorter than numerics.dx = %g m: "
                            "expected a wall at least dx long",
                            from[0], from[1], len, c->dx);
  }
  w->x0 = from[0];
  *wall_up(w, 0) = from[1];
  w->x1 = to[0];
  *wall_up(w, 1) = to[1];
#if SPH_DIM == 3 /* a plate across the flume: its extent along y, the tank's by default */
  double across[2] = {c->tank.y0, c->tank.y1};
  if (sph_yaml_get_pair(&x->t, m, p, "y", !c->tank.present, 'y', across) < 0) return -1;
  w->y0 = across[0];
  w->y1 = across[1];
#endif
  if (sph_yaml_get_choice(&x->t, m, p, "boundary", boundary_names, &bnd) < 0) return -1;
  w->boundary = (sph_boundary_kind)bnd;
  if (SPH_DIM == 3 && w->boundary == SPH_BOUNDARY_MIRROR) {
    const node *t;
    char kp[SPH_YAML_KEYLEN];
    sph_yaml_lookup(&x->t, m, p, "boundary", 0, &t, kp);
    return sph_yaml_fail_at(&x->t, t, kp, "'mirror' is 2-D only so far for a wall segment");
  }
  if (SPH_DIM == 3 && sph_yaml_find(m, "stagger")) {
    char kp[SPH_YAML_KEYLEN];
    sph_yaml_join(kp, sizeof kp, p, "stagger");
    return sph_yaml_fail_at(&x->t, sph_yaml_find(m, "stagger")->val, kp,
                            "is 2-D only so far (a 3-D wall's layers are dx apart, "
                            "doc/dimensions.md)");
  }
  w->layers = default_layers(w->boundary);
  if (sph_yaml_get_int(&x->t, m, p, "layers", 1, 8, &w->layers) < 0) return -1;
  if (check_layers(x, m, p, w->boundary, &w->layers)) return -1;
  w->stagger = default_stagger(w->boundary);
  if (read_layout(x, m, p, c, w->boundary, &w->stagger, &w->extrapolated, &w->free_slip)) return -1;
  if (read_motion(x, m, p, w)) return -1;
  if ((w->extrapolated || w->free_slip) && w->motion.kind == SPH_MOTION_FLAP) {
    const node *t;
    char kp[SPH_YAML_KEYLEN];
    const char *key = w->extrapolated ? "extrapolated_velocity" : "free_slip";
    sph_yaml_lookup(&x->t, m, p, key, 0, &t, kp);
    return sph_yaml_fail_at(&x->t, t, kp,
                            "not on a turning wall (motion type 'flap'): its mirror points and "
                            "normals would turn with it");
  }
  return 0;
}

static int read_walls(const ctx *x, const node *m, sph_case *c) {
  const node *t;
  char kp[SPH_YAML_KEYLEN], b[96];
  int rc = sph_yaml_lookup(&x->t, m, "geometry", "walls", 0, &t, kp);
  if (rc <= 0) return rc;
  if (t->kind != SPH_YAML_LIST)
    return sph_yaml_fail_at(&x->t, t, kp, "expected a list of mappings, got %s",
                            sph_yaml_got(t, b, sizeof b));
  if (t->n == 0) return 0;
  if (!(c->walls = calloc(t->n, sizeof *c->walls))) return sph_yaml_oom(&x->t);
  c->n_walls = t->n;
  for (size_t i = 0; i < t->n; i++) {
    sph_yaml_bprintf(kp, sizeof kp, "geometry.walls[%zu]", i);
    if (read_wall(x, t->items[i], kp, c, &c->walls[i])) return -1;
  }
  return 0;
}

/* geometry.periodic_x (in 3-D also periodic_y or periodic_z): the one axis
 * that wraps. In 2-D without a tank; in 3-D a tank is open along a
 * periodic x or y (its faces normal to that axis left out), the period
 * then its range along that axis and a whole number of dx. */
static int read_periodic(const ctx *x, const node *m, sph_case *c) {
  static const char *const keys[3] = {"periodic_x", "periodic_y", "periodic_z"};
  char kp[SPH_YAML_KEYLEN];
  for (int a = 0; a < 3; a++) {
    double r[2];
    const int pr = sph_yaml_get_pair(&x->t, m, "geometry", keys[a], 0, "xyz"[a], r);
    if (pr < 0) return -1;
    if (pr == 0) continue;
    const node *v = sph_yaml_find(m, keys[a])->val;
    sph_yaml_join(kp, sizeof kp, "geometry", keys[a]);
    if (SPH_DIM == 2 && a > 0)
      return sph_yaml_fail_at(&x->t, v, kp,
                              "is 3-D only: a 2-D case is periodic in x only (y is up)");
    if (c->periodic)
      return sph_yaml_fail_at(&x->t, v, kp, "expected one periodic axis, got geometry.%s too",
                              keys[c->periodic_axis]);
    c->periodic = 1;
    c->periodic_axis = a;
    c->periodic_range[0] = r[0];
    c->periodic_range[1] = r[1];
    const double L = r[1] - r[0];
    if (!(L >= 6.0 * c->h))
      return sph_yaml_fail_at(&x->t, v, kp, "expected a period of at least 6 h = %g m, got %g",
                              6.0 * c->h, L);
    if (!c->tank.present) continue;
    if (SPH_DIM == 2)
      return sph_yaml_fail_at(
          &x->t, v, kp, "a periodic domain cannot have a tank (use geometry.walls for the bed)");
    if (a == SPH_UP)
      return sph_yaml_fail_at(&x->t, v, kp,
                              "a tank cannot be periodic along z: its floor is normal to z");
    const double t0 = a ? c->tank.y0 : c->tank.x0, t1 = a ? c->tank.y1 : c->tank.x1;
    if (!(fabs(r[0] - t0) <= 1e-9 * L && fabs(r[1] - t1) <= 1e-9 * L))
      return sph_yaml_fail_at(&x->t, v, kp,
                              "expected the tank's %c range [%g, %g] (a tank is open along its "
                              "periodic axis), got [%g, %g]",
                              "xyz"[a], t0, t1, r[0], r[1]);
    const double n = L / c->dx;
    if (!(fabs(n - floor(n + 0.5)) <= 1e-6 * n))
      return sph_yaml_fail_at(&x->t, v, kp,
                              "expected a period of a whole number of numerics.dx = %g m (the "
                              "lattice continues across the seam), got %g m = %.6g dx",
                              c->dx, L, n);
    c->tank.open_along = 1 + a;
  }
  return 0;
}

/* geometry.obstacles[i]: {x, y (, z): ranges at least dx wide, layers (1-8, default 2; 1
 * for repulsive), boundary: dynamic (default), fixed_layers, mdbc or repulsive}. */
static int read_obstacle(const ctx *x, const node *m, const char *p, const sph_case *c,
                         sph_obstacle *o) {
  char b[96], kp[SPH_YAML_KEYLEN];
  if (m->kind != SPH_YAML_MAP)
    return sph_yaml_fail_at(&x->t, m, p, "expected a mapping, got %s",
                            sph_yaml_got(m, b, sizeof b));
  if (sph_yaml_check_keys(&x->t, m, p, obstacle_keys)) return -1;
  for (int a = 0; a < SPH_DIM; a++) {
    const char key[2] = {"xyz"[a], 0};
    double v[2];
    if (sph_yaml_get_pair(&x->t, m, p, key, 1, key[0], v) < 0) return -1;
    if (c->dx > 0.0 && !(v[1] - v[0] >= c->dx)) {
      sph_yaml_join(kp, sizeof kp, p, key);
      return sph_yaml_fail_at(&x->t, sph_yaml_find(m, key)->val, kp,
                              "expected a range at least numerics.dx = %g m wide, got [%g, %g]",
                              c->dx, v[0], v[1]);
    }
    o->lo[a] = v[0];
    o->hi[a] = v[1];
  }
  int bnd = SPH_BOUNDARY_DYNAMIC;
  if (sph_yaml_get_choice(&x->t, m, p, "boundary", boundary_names, &bnd) < 0) return -1;
  o->boundary = (sph_boundary_kind)bnd;
  if (bnd == SPH_BOUNDARY_MIRROR) {
    sph_yaml_join(kp, sizeof kp, p, "boundary");
    return sph_yaml_fail_at(&x->t, sph_yaml_find(m, "boundary")->val, kp,
                            "expected 'dynamic', 'fixed_layers', 'mdbc' or 'repulsive' (an "
                            "obstacle is a box of wall particles), got '%s'",
                            sph_boundary_name(o->boundary));
  }
  o->layers = 2;
  if (sph_yaml_get_int(&x->t, m, p, "layers", 1, 8, &o->layers) < 0) return -1;
  return check_layers(x, m, p, o->boundary, &o->layers); /* (repulsive: exactly 1) */
}

static int read_obstacles(const ctx *x, const node *m, sph_case *c) {
  const node *t;
  char kp[SPH_YAML_KEYLEN], b[96];
  int rc = sph_yaml_lookup(&x->t, m, "geometry", "obstacles", 0, &t, kp);
  if (rc <= 0) return rc;
  if (t->kind != SPH_YAML_LIST)
    return sph_yaml_fail_at(&x->t, t, kp, "expected a list of mappings, got %s",
                            sph_yaml_got(t, b, sizeof b));
  if (t->n == 0) return 0;
  if (!(c->obstacles = calloc(t->n, sizeof *c->obstacles))) return sph_yaml_oom(&x->t);
  c->n_obstacles = t->n;
  for (size_t i = 0; i < t->n; i++) {
    sph_yaml_bprintf(kp, sizeof kp, "geometry.obstacles[%zu]", i);
    if (read_obstacle(x, t->items[i], kp, c, &c->obstacles[i])) return -1;
  }
  return 0;
}

static int read_geometry(const ctx *x, const node *m, sph_case *c) {
  const node *d;
  if (read_tank(x, m, c) || read_fluid(x, m, c) || read_walls(x, m, c) || read_obstacles(x, m, c))
    return -1;
  if (read_periodic(x, m, c)) return -1;
  int rc = sph_yaml_get_section(&x->t, m, "geometry", "domain", 0, domain_keys, &d);
  if (rc <= 0) return rc;
  c->domain_set = 1;
  if (sph_yaml_get_pair(&x->t, d, "geometry.domain", "x", 1, 'x', &c->domain[0]) < 0) return -1;
#if SPH_DIM == 3
  if (sph_yaml_get_pair(&x->t, d, "geometry.domain", "z", 1, 'z', &c->domain[4]) < 0) return -1;
#endif
  return sph_yaml_get_pair(&x->t, d, "geometry.domain", "y", 1, 'y', &c->domain[2]) < 0 ? -1 : 0;
}

/* The particles the geometry makes at dx, from above, in floating point (a
 * tiny dx gives a huge or infinite count, never an overflow): the fluid
 * blocks' lattices, and for the tank and each wall segment a row of
 * particles dx apart per layer along its length, plus the corners. */
static void estimate_particles(sph_case *c) {
  const double dx = c->dx;
  double fluid = 0.0, wall = 0.0;
  for (size_t b = 0; b < c->n_fluid; b++) {
    const sph_fluid_block *f = &c->fluid[b];
    fluid += floor((f->x1 - f->x0) / dx + 1e-9) * floor((f->y1 - f->y0) / dx + 1e-9)
#if SPH_DIM == 3
             * floor((f->z1 - f->z0) / dx + 1e-9)
#endif
        ;
  }
  if (c->tank.present) {
    const sph_tank *k = &c->tank;
#if SPH_DIM == 2
    const double per_layer = (k->x1 - k->x0 + 2.0 * (k->y1 - k->y0)) / dx + 8.0 * k->layers;
    wall += k->layers * per_layer;
#else /* the box grown by the layers sideways and below, less the inside */
    const double L = k->layers, nx = (k->x1 - k->x0) / dx + 1.0, ny = (k->y1 - k->y0) / dx + 1.0;
    const double nz = (k->z1 - k->z0) / dx + 1.0;
    wall += (nx + 2.0 * L) * (ny + 2.0 * L) * (nz + L) - nx * ny * nz;
#endif
  }
  for (size_t i = 0; i < c->n_walls; i++) {
    const sph_wall_segment *w = &c->walls[i];
#if SPH_DIM == 2
    const double len = hypot(w->x1 - w->x0, w->y1 - w->y0);
    wall += w->layers * (len / dx + 2.0);
#else /* across y */
    const double len = hypot(w->x1 - w->x0, w->z1 - w->z0);
    wall += w->layers * (len / dx + 2.0) * ((w->y1 - w->y0) / dx + 1.0);
#endif
  }
  for (size_t i = 0; i < c->n_obstacles; i++) { /* the whole box, from above */
    double box = 1.0;
    for (int a = 0; a < SPH_DIM; a++)
      box *= floor((c->obstacles[i].hi[a] - c->obstacles[i].lo[a]) / dx + 0.5) + 1.0;
    wall += box;
  }
  int mirror = c->tank.present && c->tank.boundary == SPH_BOUNDARY_MIRROR;
  for (size_t i = 0; i < c->n_walls; i++)
    mirror |= c->walls[i].boundary == SPH_BOUNDARY_MIRROR;
  c->est_fluid = fluid;
  c->est_wall = wall + (mirror ? fluid : 0.0); /* mirror images of the fluid, at most */
}

double sph_case_default_max(void) {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  double bytes = pages > 0 && page > 0 ? (double)pages * (double)page : 4e9;
  const double max = 0.5 * bytes / SPH_BYTES_PER_PARTICLE;
  return max < SPH_MAX_PARTICLES_HARD ? max : SPH_MAX_PARTICLES_HARD;
}

int sph_case_check_size(const sph_case *c, double max, sph_error *err) {
  const int given = max > 0.0;
  if (!given) max = sph_case_default_max();
  if (max > SPH_MAX_PARTICLES_HARD) max = SPH_MAX_PARTICLES_HARD;
  const double n = c->est_fluid + c->est_wall;
  if (n <= max) return 0;
  char where[4200];
  if (c->dx_line)
    snprintf(where, sizeof where, "%s:%zu: numerics.dx", c->path ? c->path : "", c->dx_line);
  else
    snprintf(where, sizeof where, "--set numerics.dx");
  return sph_error_set(err,
                       "%s: %g makes about %.3g particles (fluid %.3g, walls %.3g), about %.3g "
                       "GB; the bound is %.0f particles (%s; --max-particles N changes it): "
                       "expected a larger dx",
                       where, c->dx, n, c->est_fluid, c->est_wall, n * SPH_BYTES_PER_PARTICLE / 1e9,
                       max,
                       max >= SPH_MAX_PARTICLES_HARD ? "what 32-bit indices reach"
                       : given                       ? "the bound asked for"
                                                     : "half this machine's memory");
}

/* The domain the water can reach, from the case alone: the domain the run
 * takes (domain.h) around the box of the tank's inner faces, the walls and
 * the fluid blocks instead of the particles'; the probes and gauges must
 * lie in it (issue 39, D6). */
static void reach_box(const sph_case *c, double box[2 * SPH_DIM]) {
  double bb[2 * SPH_DIM];
  for (int k = 0; k < 2 * SPH_DIM; k += 2)
    bb[k] = INFINITY, bb[k + 1] = -INFINITY;
#define GROW(k, a, b)                                                                              \
  do {                                                                                             \
    bb[k] = fmin(bb[k], fmin(a, b));                                                               \
    bb[k + 1] = fmax(bb[k + 1], fmax(a, b));                                                       \
  } while (0)
  if (c->tank.present) {
    GROW(0, c->tank.x0, c->tank.x1);
    GROW(2, c->tank.y0, c->tank.y1);
    SPH_IF3(GROW(4, c->tank.z0, c->tank.z1);)
  }
  for (size_t i = 0; i < c->n_walls; i++) {
    GROW(0, c->walls[i].x0, c->walls[i].x1);
    GROW(2, c->walls[i].y0, c->walls[i].y1);
    SPH_IF3(GROW(4, c->walls[i].z0, c->walls[i].z1);)
  }
  for (size_t i = 0; i < c->n_fluid; i++) {
    GROW(0, c->fluid[i].x0, c->fluid[i].x1);
    GROW(2, c->fluid[i].y0, c->fluid[i].y1);
    SPH_IF3(GROW(4, c->fluid[i].z0, c->fluid[i].z1);)
  }
#undef GROW
  sph_case_domain_around(c, bb, box);
}

/* A probe's or gauge's place outside box (the node t at key k): the error. */
static int outside_reach(const ctx *x, const node *t, const char *k, const char *what,
                         const double box[2 * SPH_DIM]) {
  return sph_yaml_fail_at(&x->t, t, k,
                          "%s is outside the domain, x [%g, %g] y [%g, %g] (geometry.domain, "
                          "or its default from the geometry): the water cannot reach it",
                          what, box[0], box[1], box[2], box[3]);
}

/* One entry of output.probes (p its key, output.probes[i]), inside box. */
static int read_probe(const ctx *x, const node *m, const char *p, const double box[2 * SPH_DIM],
                      sph_probe *pr) {
  const node *t;
  char kp[SPH_YAML_KEYLEN], b[96];
  if (m->kind != SPH_YAML_MAP)
    return sph_yaml_fail_at(&x->t, m, p, "expected a mapping, got %s",
                            sph_yaml_got(m, b, sizeof b));
  if (sph_yaml_check_keys(&x->t, m, p, probe_keys)) return -1;
  const char *s;
  if (read_plain_name(x, m, p, "name", &s)) return -1;
  memcpy(pr->name, s, strlen(s) + 1);
  int kind = -1;
  if (sph_yaml_lookup(&x->t, m, p, "kind", 1, &t, kp) < 0 ||
      sph_yaml_read_choice(&x->t, t, kp, probe_kind_names, &kind))
    return -1;
  pr->kind = (sph_probe_kind)kind;
  const int level = pr->kind == SPH_PROBE_LEVEL, pressure = pr->kind == SPH_PROBE_PRESSURE;
  /* the keys each kind takes (3-D: a level gauge is at (x, y), a pressure
   * sensor has a normal instead of along) */
  static const char *const only[] = {"at",       "x",      "diameter", "along",
                                     "low_pass", "normal", "wetted"};
#if SPH_DIM == 2
  const int allowed[3][7] = {{1, 0, 1, 1, 1, 0, 0}, {0, 1, 0, 0, 0, 0, 1}, {1, 0, 0, 0, 0, 0, 0}};
#else
  const int allowed[3][7] = {{1, 0, 1, 0, 1, 1, 0}, {1, 0, 0, 0, 0, 0, 1}, {1, 0, 0, 0, 0, 0, 0}};
#endif
  for (int k = 0; k < 7; k++)
    if (!allowed[kind][k] && sph_yaml_lookup(&x->t, m, p, only[k], 0, &t, kp) > 0)
      return sph_yaml_fail_at(&x->t, t, kp, "not a key of a %s probe", probe_kind_names[kind]);
  if (level && sph_yaml_get_bool(&x->t, m, p, "wetted", &pr->wetted) < 0) return -1;
#if SPH_DIM == 3
  if (level) { /* the vertical line at (x, y) */
    double at[2];
    if (sph_yaml_get_vector(&x->t, m, p, "at", 1, 2, at) < 0) return -1;
    pr->x = at[0];
    pr->y = at[1];
    if (!(at[0] >= box[0] && at[0] <= box[1] && at[1] >= box[2] && at[1] <= box[3])) {
      sph_yaml_lookup(&x->t, m, p, "at", 1, &t, kp);
      sph_yaml_bprintf(b, sizeof b, "(%g, %g)", at[0], at[1]);
      return outside_reach(x, t, kp, b, box);
    }
    return 0;
  }
  double at[3];
  if (sph_yaml_get_vector(&x->t, m, p, "at", 1, 3, at) < 0) return -1;
  pr->x = at[0];
  pr->y = at[1];
  pr->z = at[2];
  if (!(at[0] >= box[0] && at[0] <= box[1] && at[1] >= box[2] && at[1] <= box[3] &&
        at[2] >= box[4] && at[2] <= box[5])) {
    sph_yaml_lookup(&x->t, m, p, "at", 1, &t, kp);
    sph_yaml_bprintf(b, sizeof b, "(%g, %g, %g)", at[0], at[1], at[2]);
    return outside_reach(x, t, kp, b, box);
  }
  if (pressure) {
    const double side = fmax(fmax(box[1] - box[0], box[3] - box[2]), box[5] - box[4]);
    const range dia = {0, side, '[', ']', NULL};
    if (sph_yaml_get_number(&x->t, m, p, "diameter", 0, &dia, &pr->diameter) < 0 ||
        sph_yaml_get_number(&x->t, m, p, "low_pass", 0, &SPH_YAML_POS, &pr->low_pass) < 0 ||
        sph_yaml_get_vector(&x->t, m, p, "normal", 1, 3, pr->normal) < 0)
      return -1;
    const double *nv = pr->normal;
    const double len = sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
    if (!(len > 0.0) || !isfinite(len)) {
      sph_yaml_lookup(&x->t, m, p, "normal", 1, &t, kp);
      return sph_yaml_fail_at(&x->t, t, kp, "expected a non-zero vector, got [%g, %g, %g]", nv[0],
                              nv[1], nv[2]);
    }
    for (int d = 0; d < 3; d++)
      pr->normal[d] /= len;
  }
  return 0;
#endif
  if (level) {
    if (sph_yaml_get_number(&x->t, m, p, "x", 1, &SPH_YAML_ANY, &pr->x) < 0) return -1;
    if (!(pr->x >= box[0] && pr->x <= box[1])) {
      sph_yaml_lookup(&x->t, m, p, "x", 1, &t, kp);
      sph_yaml_bprintf(b, sizeof b, "x = %g", pr->x);
      return outside_reach(x, t, kp, b, box);
    }
    return 0;
  }
  double v[2] = {0, 0};
  if (sph_yaml_get_pair(&x->t, m, p, "at", 1, 0, v) < 0) return -1;
  pr->x = v[0];
  pr->y = v[1];
  if (!(v[0] >= box[0] && v[0] <= box[1] && v[1] >= box[2] && v[1] <= box[3])) {
    sph_yaml_lookup(&x->t, m, p, "at", 1, &t, kp);
    sph_yaml_bprintf(b, sizeof b, "(%g, %g)", v[0], v[1]);
    return outside_reach(x, t, kp, b, box);
  }
  if (pressure) {
    /* a face no wider than the domain */
    const double side = fmax(box[1] - box[0], box[3] - box[2]);
    const range dia = {0, side, '[', ']', NULL};
    int along = 0;
    if (sph_yaml_get_number(&x->t, m, p, "diameter", 0, &dia, &pr->diameter) < 0 ||
        sph_yaml_get_choice(&x->t, m, p, "along", along_names, &along) < 0 ||
        sph_yaml_get_number(&x->t, m, p, "low_pass", 0, &SPH_YAML_POS, &pr->low_pass) < 0)
      return -1;
    pr->along_x = along;
  }
  return 0;
}

/* output.probes and output.probe_interval. */
static int read_probes(const ctx *x, const node *s, sph_case *c) {
  const node *t;
  char kp[SPH_YAML_KEYLEN], b[96];
  if (sph_yaml_lookup(&x->t, s, "output", "probes", 0, &t, kp) <= 0) {
    if (sph_yaml_lookup(&x->t, s, "output", "probe_interval", 0, &t, kp) > 0)
      return sph_yaml_fail_at(&x->t, t, kp, "expected output.probes alongside it");
    return 0;
  }
  if (t->kind != SPH_YAML_LIST || t->n == 0)
    return sph_yaml_fail_at(&x->t, t, kp, "expected a non-empty list of probes, got %s",
                            sph_yaml_got(t, b, sizeof b));
  if (t->n > 1000)
    return sph_yaml_fail_at(&x->t, t, kp, "expected at most 1000 probes, got %zu", t->n);
  if (!(c->probes = calloc(t->n, sizeof *c->probes))) return sph_yaml_oom(&x->t);
  c->n_probes = t->n;
  double box[2 * SPH_DIM];
  reach_box(c, box);
  for (size_t i = 0; i < t->n; i++) {
    sph_yaml_bprintf(kp, sizeof kp, "output.probes[%zu]", i);
    if (read_probe(x, t->items[i], kp, box, &c->probes[i])) return -1;
    for (size_t k = 0; k < i; k++)
      if (strcmp(c->probes[k].name, c->probes[i].name) == 0) {
        char nk[SPH_YAML_KEYLEN];
        sph_yaml_bprintf(nk, sizeof nk, "%s.name", kp);
        return sph_yaml_fail_at(
            &x->t, sph_yaml_find(t->items[i], "name")->val, nk,
            "expected a name of its own, got '%s' (the name of output.probes[%zu])",
            c->probes[i].name, k);
      }
  }
  char what[128];
  sph_yaml_bprintf(what, sizeof what, "a number from 0 (every step) to time.end (%g)", c->t_end);
  const range iv = {0, c->t_end, '[', ']', what};
  return sph_yaml_get_number(&x->t, s, "output", "probe_interval", 0, &iv, &c->probe_interval) < 0
             ? -1
             : 0;
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
  if (sph_yaml_get_section(&x->t, root, "", "geometry", 1, geometry_keys, &s) < 0 ||
      read_geometry(x, s, c))
    return -1;
  if (c->repulsion == 0.0) { /* D = 5 |g| H, paper A eq. (22), H the deepest block */
    double H = 0.0;
    for (size_t i = 0; i < c->n_fluid; i++)
      if (c->fluid[i].surface - block_bottom(&c->fluid[i]) > H)
        H = c->fluid[i].surface - block_bottom(&c->fluid[i]);
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
      !(c->periodic_range[1] - c->periodic_range[0] >= 6.0 * c->fs_h_factor * c->h))
    return sph_yaml_fail(
        &x->t, SPH_YAML_FROM_FILE, 0, "geometry.periodic_x",
        "expected a period of at least 6 k h = %g m with free_surface.h_factor k = %g, "
        "got %g",
        6.0 * c->fs_h_factor * c->h, c->fs_h_factor, c->periodic_range[1] - c->periodic_range[0]);
  rc = sph_yaml_get_section(&x->t, root, "", "output", 0, output_keys, &s);
  if (rc > 0) rc = sph_yaml_get_bool(&x->t, s, "output", "snapshots", &c->snapshots);
  if (rc >= 0 && s)
    rc = sph_yaml_get_bool(&x->t, s, "output", "free_surface", &c->output_free_surface);
  if (rc >= 0 && s) rc = sph_yaml_get_bool(&x->t, s, "output", "energy", &c->energy);
  const node *gl;
  char gk[SPH_YAML_KEYLEN];
  if (rc >= 0 && s && sph_yaml_lookup(&x->t, s, "output", "gauges", 0, &gl, gk) > 0) {
    char b[96];
    enum { H = SPH_DIM - 1 }; /* a gauge's horizontal coordinates */
    if (gl->kind != SPH_YAML_LIST || gl->n == 0)
      return sph_yaml_fail_at(&x->t, gl, gk, "expected a non-empty list of %s, got %s",
                              H == 1 ? "x positions" : "[x, y] positions",
                              sph_yaml_got(gl, b, sizeof b));
    if (!(c->gauges = calloc(gl->n * H, sizeof *c->gauges))) return sph_yaml_oom(&x->t);
    c->n_gauges = gl->n;
    double box[2 * SPH_DIM];
    reach_box(c, box);
    for (size_t i = 0; i < gl->n; i++) {
      char ik[SPH_YAML_KEYLEN];
      double *at = c->gauges + i * H;
      sph_yaml_bprintf(ik, sizeof ik, "output.gauges[%zu]", i);
      if (H == 1 ? sph_yaml_read_number(&x->t, gl->items[i], ik, &SPH_YAML_ANY, at)
                 : sph_yaml_read_vector(&x->t, gl->items[i], ik, H, at))
        return -1;
      for (int a = 0; a < H; a++)
        if (!(at[a] >= box[2 * a] && at[a] <= box[2 * a + 1])) {
          sph_yaml_bprintf(b, sizeof b, "%c = %g", "xy"[a], at[a]);
          return outside_reach(x, gl->items[i], ik, b, box);
        }
    }
  }
  if (rc >= 0 && s && read_probes(x, s, c)) return -1;
  if (rc >= 0) estimate_particles(c);
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
  ctx x = {{origin ? origin : "<text>", text ? text : "", text ? len : 0, set, err},
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
static int read_case_file(const char *path, char **buf_out, size_t *len_out, sph_error *err) {
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
  if (read_case_file(path, &buf, &len, err)) return -1;
  int rc = sph_case_parse(buf, len, path, set, n_set, c, err);
  free(buf);
  return rc;
}

int sph_case_file_dimension(const char *path, const char *const *set, size_t n_set, int *dim,
                            sph_error *err) {
  *dim = 2;
  char *buf;
  size_t len;
  if (read_case_file(path, &buf, &len, err)) return -1;
  ctx x = {{path, buf, len, set, err}, NULL, NULL, NULL, NULL};
  node *root = NULL;
  int rc = sph_yaml_parse(&x.t, buf, len, SPH_YAML_FROM_FILE, NULL, &root);
  if (rc == 0 && root->kind == SPH_YAML_MAP) { /* (not a mapping: 2, the full reader says why) */
    for (size_t i = 0; rc == 0 && i < n_set; i++)
      rc = sph_yaml_apply_set(&x.t, root, (int)i);
    if (rc == 0 && sph_yaml_get_int(&x.t, root, "", "dimension", 2, 3, dim) < 0) rc = -1;
  }
  if (root) sph_yaml_free(root);
  free(buf);
  return rc ? -1 : 0;
}

void sph_case_free(sph_case *c) {
  if (!c) return;
  free(c->name);
  free(c->description);
  free(c->path);
  free(c->text);
  free(c->overrides);
  free(c->scheme_kept);
  free(c->fluid);
  free(c->walls);
  free(c->obstacles);
  free(c->output_times);
  free(c->gauges);
  free(c->probes);
  memset(c, 0, sizeof *c);
}
