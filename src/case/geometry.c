/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * geometry.c - the case file's geometry section (see case.h): the tank,
 * the fluid blocks, the wall segments and their motions (gates, piston
 * and flap paddles), the periodic axis, the box obstacles and the domain;
 * the wall models' names and default layers; and the particle count the
 * geometry makes, bounded before any particle is (issue 21, D3).
 *
 * Each reader checks its keys first and reports the first violation as
 * case.c does ("origin:line: dotted.key: expected ..., got ..."); the
 * defaults are in the case before they run.
 */
#include "config.h"

#include "case/case_read.h"
#include "case/choices.h"
#include "case/mesh.h"
#include "case/presets.h"
#include "case/shape.h"

#include "walls/wavemaker.h"

#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *const geometry_keys[] = {"tank",    "fluid",      "walls",      "obstacles",
                                            "vessels", "periodic_x", "periodic_y", "periodic_z",
                                            "domain",  "leaving",    NULL};
static const char *const axis_key[3] = {"x", "y", "z"};
static const char *const tank_keys[] = {"x",         "y",       SPH_IF3("z", ) "layers",
                                        "boundary",  "stagger", "extrapolated_velocity",
                                        "free_slip", "lid",     NULL};
#if SPH_DIM == 2
#define BALL_KEY "circle"
#else
#define BALL_KEY "sphere"
#endif
static const char *const fluid_keys[] = {"x",
                                         "y",
                                         SPH_IF3("z", ) "polygon",
                                         BALL_KEY,
                                         SPH_IF3("cylinder", "mesh", ) "velocity",
                                         "hydrostatic",
                                         "surface",
                                         "jitter",
                                         "seed",
                                         NULL};
/* a block's shapes (shape.h), each instead of the box's ranges */
static const char *const obstacle_keys[] = {
    "x",        "y", SPH_IF3("z", ) "polygon", BALL_KEY, SPH_IF3("cylinder", "mesh", ) "layers",
    "boundary", NULL};
static const char *const vessel_keys[] = {
    "polygon", BALL_KEY, SPH_IF3("y", "cylinder", "mesh", ) "layers", "boundary", NULL};
static const char *const shape_keys[] = {"polygon", BALL_KEY, SPH_IF3("cylinder", "mesh", ) NULL};
static const char *const mesh_keys[] = {"file", "scale", "offset", NULL};
static const char *const ball_keys[] = {"centre", "radius", NULL};
static const char *const cylinder_keys[] = {"from", "to", "radius", NULL};
#define SPH_POLYGON_MAX_VERTICES 10000 /* the simple-polygon check takes n^2 / 2 edge pairs */
static const char *const wall_keys[] = {"from",      "to",
                                        "points",    "layers",
                                        "boundary",  "motion",
                                        "stagger",   "extrapolated_velocity",
                                        "free_slip", SPH_IF3("y", ) NULL};
static const char *const motion_keys[] = {"type",   "velocity", "start",       "stop",
                                          "period", "stroke",   "wave_height", "depth",
                                          "ramp",   "hinge",    NULL};
const char *const sph_case_motion_names[] = {"none", "translate", "piston", "flap", NULL};
static const char *const domain_keys[] = {"x", "y", SPH_IF3("z", ) NULL};
const char *const sph_case_leaving_names[] = {"stop", "remove", NULL};
static const char *const boundary_names[] = {"dynamic", "fixed_layers", "repulsive", "mirror",
                                             "mdbc",    "adami",        NULL};

const char *sph_boundary_name(sph_boundary_kind b) {
  return sph_case_choice_name(boundary_names, (int)b);
}

int sph_case_has_boundary(const sph_case *c, sph_boundary_kind b) {
  int has = c->tank.present && c->tank.boundary == b;
  for (size_t k = 0; k < c->n_walls; k++)
    has |= c->walls[k].boundary == b;
  return has;
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
 * layers). For adami, whose wall particles complete the fluid's kernel
 * sums, as many layers on the lattice as fill the support 2h (3 at the
 * default h = 1.3 dx, 4 at h = 2 dx as TrixiParticles' dam break runs). */
static int default_layers(sph_boundary_kind b, const sph_case *c) {
  if (b == SPH_BOUNDARY_ADAMI) {
    const int k = (int)ceil(2.0 * c->h_factor - 1e-9);
    return k < 1 ? 1 : k > 8 ? 8 : k;
  }
  return b == SPH_BOUNDARY_MDBC ? 3 : 2;
}
static int default_stagger(sph_boundary_kind b) {
  return SPH_DIM == 2 && b != SPH_BOUNDARY_MDBC && b != SPH_BOUNDARY_ADAMI;
}

/* A wall segment's heights at its ends (from, to): y in 2-D, z in 3-D. */
static double *wall_up(sph_wall_segment *w, int end) {
#if SPH_DIM == 2
  return end ? &w->y1 : &w->y0;
#else
  return end ? &w->z1 : &w->z0;
#endif
}

/* `stagger`, `extrapolated_velocity` and `free_slip` of a wall of
 * particles with a density (dynamic, fixed_layers, mdbc, adami); an error
 * on the others, and the extrapolated velocity only where a strain-rate
 * pass uses it, never on adami walls (their no-slip velocity is AHA12's,
 * in every viscous term: walls/adami.h). */
static int read_layout(const ctx *x, const node *m, const char *p, const sph_case *c,
                       sph_boundary_kind b, int *stagger, int *extrapolated, int *free_slip) {
  const node *t;
  char kp[SPH_YAML_KEYLEN];
  const int evolving = b == SPH_BOUNDARY_DYNAMIC || b == SPH_BOUNDARY_FIXED_LAYERS ||
                       b == SPH_BOUNDARY_MDBC || b == SPH_BOUNDARY_ADAMI;
  static const char *const keys[] = {"stagger", "extrapolated_velocity", "free_slip"};
  for (int k = 0; k < 3; k++)
    if (!evolving && sph_yaml_lookup(&x->t, m, p, keys[k], 0, &t, kp) > 0)
      return sph_yaml_fail_at(&x->t, t, kp,
                              "only for 'dynamic', 'fixed_layers', 'mdbc' and 'adami' walls "
                              "(this one is '%s')",
                              sph_boundary_name(b));
  if (b == SPH_BOUNDARY_ADAMI &&
      sph_yaml_lookup(&x->t, m, p, "extrapolated_velocity", 0, &t, kp) > 0)
    return sph_yaml_fail_at(&x->t, t, kp,
                            "not on an 'adami' wall: its no-slip velocity is Adami et al.'s, in "
                            "every viscous term (free_slip: true turns it off)");
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
  /* (every scheme gives the tank's wall model: src/case/presets.c) */
  int b = (int)SPH_BOUNDARY_DYNAMIC;
  int rc = sph_yaml_get_section(&x->t, m, "geometry", "tank", 0, tank_keys, &t);
  if (rc <= 0) return rc;
  c->tank.present = 1;
  for (int a = 0; a < SPH_DIM; a++) {
    if (sph_yaml_get_pair(&x->t, t, p, axis_key[a], 1, "xyz"[a], v) < 0) return -1;
    c->tank.lo[a] = v[0];
    c->tank.hi[a] = v[1];
  }
  if (sph_yaml_get_choice(&x->t, t, p, "boundary", boundary_names, &b) < 0) return -1;
  c->tank.boundary = (sph_boundary_kind)b;
  c->tank.layers = default_layers(c->tank.boundary, c);
  if (sph_yaml_get_int(&x->t, t, p, "layers", 1, 8, &c->tank.layers) < 0) return -1;
  c->tank.stagger = default_stagger(c->tank.boundary);
  if (read_layout(x, t, p, c, c->tank.boundary, &c->tank.stagger, &c->tank.extrapolated,
                  &c->tank.free_slip))
    return -1;
  if ((rc = sph_yaml_get_bool(&x->t, t, p, "lid", &c->tank.lid)) < 0) return -1;
  if (rc > 0 && c->tank.lid && c->tank.boundary == SPH_BOUNDARY_MIRROR)
    return sph_yaml_fail_at(&x->t, sph_yaml_find(t, "lid")->val, "geometry.tank.lid",
                            "expected false with boundary: mirror (a lid is a wall of particles: "
                            "give the tank a particle wall model), got true");
  return check_layers(x, t, p, c->tank.boundary, &c->tank.layers);
}

/* The block (its shape's bounding box) must be wider and taller than dx, and inside the tank if
 * any; `at` is the node that gave its extent along each axis (its range, or its shape). */
static int check_block(const ctx *x, const node *const at[SPH_DIM], const char *const key[SPH_DIM],
                       const sph_case *c, const sph_fluid_block *f, const char *p) {
  double w = f->x1 - f->x0, h = f->y1 - f->y0;
  const sph_tank *k = &c->tank;
  char kp[SPH_YAML_KEYLEN], b[96];
  if (!(c->dx < w && c->dx < h))
    return sph_yaml_fail_at(
        &x->t, x->dx_node, "numerics.dx",
        "expected a positive number smaller than the width (%g) and height (%g) of "
        "%s, got %s",
        w, h, p, sph_yaml_got(x->dx_node, b, sizeof b));
  for (int a = 2; a < SPH_DIM; a++) /* (3-D: the z extent) */
    if (!(c->dx < f->hi[a] - f->lo[a]))
      return sph_yaml_fail_at(&x->t, x->dx_node, "numerics.dx",
                              "expected a positive number smaller than the %s extent (%g) of %s, "
                              "got %s",
                              axis_key[a], f->hi[a] - f->lo[a], p,
                              sph_yaml_got(x->dx_node, b, sizeof b));
  for (int a = 0; a < SPH_DIM; a++)
    if (k->present && (f->lo[a] < k->lo[a] || f->hi[a] > k->hi[a])) {
      sph_yaml_join(kp, sizeof kp, p, key[a]);
      if (f->shape.kind != SPH_SHAPE_BOX && strcmp(key[a], axis_key[a]))
        return sph_yaml_fail_at(&x->t, at[a], kp,
                                "expected a shape inside the tank's inner box, [%g, %g] along %s, "
                                "got one reaching [%g, %g]",
                                k->lo[a], k->hi[a], axis_key[a], f->lo[a], f->hi[a]);
      return sph_yaml_fail_at(&x->t, at[a], kp,
                              "expected a range inside the tank's inner box [%g, %g], got [%g, %g]",
                              k->lo[a], k->hi[a], f->lo[a], f->hi[a]);
    }
  return 0;
}

/* A polygon: a list of 3..SPH_POLYGON_MAX_VERTICES points [x, y] ([x, z] in 3-D), simple. */
static int read_polygon(const ctx *x, const node *t, const char *kp, sph_shape *s) {
  char b[96], why[256];
  if (t->kind != SPH_YAML_LIST || t->n < 3 || t->n > SPH_POLYGON_MAX_VERTICES)
    return sph_yaml_fail_at(&x->t, t, kp,
                            "expected a list of 3 to %d vertices [x, %c] in order around the "
                            "polygon, got %s",
                            SPH_POLYGON_MAX_VERTICES, SPH_DIM == 2 ? 'y' : 'z',
                            t->kind == SPH_YAML_LIST
                                ? (sph_yaml_bprintf(b, sizeof b, "%zu", t->n), b)
                                : sph_yaml_got(t, b, sizeof b));
  if (!(s->vertex = malloc(2 * t->n * sizeof *s->vertex))) return sph_yaml_oom(&x->t);
  s->kind = SPH_SHAPE_POLYGON;
  s->n = t->n;
  for (size_t i = 0; i < t->n; i++) {
    char ik[SPH_YAML_KEYLEN];
    sph_yaml_bprintf(ik, sizeof ik, "%s[%zu]", kp, i);
    if (sph_yaml_read_vector(&x->t, t->items[i], ik, 2, s->vertex + 2 * i)) return -1;
  }
  if (sph_polygon_defect(s->vertex, s->n, why, sizeof why))
    return sph_yaml_fail_at(&x->t, t, kp, "expected a simple polygon, got one where %s", why);
  return 0;
}

/* A circle (2-D) or a sphere (3-D): {centre, radius}; a cylinder (3-D): {from, to, radius}. */
static int read_round(const ctx *x, const node *m, const char *p, const char *key, sph_shape *s) {
  const node *t;
  char kp[SPH_YAML_KEYLEN];
  const int cyl = !strcmp(key, "cylinder");
  if (sph_yaml_get_section(&x->t, m, p, key, 1, cyl ? cylinder_keys : ball_keys, &t) < 0) return -1;
  sph_yaml_join(kp, sizeof kp, p, key);
  s->kind = cyl ? SPH_SHAPE_CYLINDER : SPH_SHAPE_BALL;
  if (sph_yaml_get_vector(&x->t, t, kp, cyl ? "from" : "centre", 1, SPH_DIM, s->centre) < 0)
    return -1;
  if (cyl) {
    if (sph_yaml_get_vector(&x->t, t, kp, "to", 1, SPH_DIM, s->end) < 0) return -1;
    int same = 1;
    for (int a = 0; a < SPH_DIM; a++)
      same &= s->centre[a] == s->end[a];
    if (same) {
      char tk[SPH_YAML_KEYLEN];
      sph_yaml_join(tk, sizeof tk, kp, "to");
      return sph_yaml_fail_at(&x->t, sph_yaml_find(t, "to")->val, tk,
                              "expected an end of the axis other than 'from', got the same point");
    }
  }
  return sph_yaml_get_number(&x->t, t, kp, "radius", 1, &SPH_YAML_POS, &s->radius) < 0 ? -1 : 0;
}

/* A closed surface from a mesh file: {file, scale (default 1), offset (default 0)}; the file
 * relative to the case file's folder (mesh.h). */
static int read_mesh(const ctx *x, const node *m, const char *p, sph_shape *s) {
  const node *t;
  char kp[SPH_YAML_KEYLEN], path[4096], why[600];
  if (sph_yaml_get_section(&x->t, m, p, "mesh", 1, mesh_keys, &t) < 0) return -1;
  sph_yaml_join(kp, sizeof kp, p, "mesh");
  s->kind = SPH_SHAPE_MESH;
  const node *fn;
  char fk[SPH_YAML_KEYLEN], b[96];
  if (sph_yaml_lookup(&x->t, t, kp, "file", 1, &fn, fk) < 0) return -1;
  if (fn->kind != SPH_YAML_SCALAR || !*fn->text)
    return sph_yaml_fail_at(&x->t, fn, fk, "expected a file name, got %s",
                            sph_yaml_got(fn, b, sizeof b));
  if (!(s->file = sph_yaml_dup(fn->text, strlen(fn->text)))) return sph_yaml_oom(&x->t);
  s->scale = 1.0;
  if (sph_yaml_get_number(&x->t, t, kp, "scale", 0, &SPH_YAML_POS, &s->scale) < 0) return -1;
  if (sph_yaml_get_vector(&x->t, t, kp, "offset", 0, 3, s->offset) < 0) return -1;
  const char *slash = strrchr(x->t.origin, '/');
  if (s->file[0] == '/' || !slash)
    snprintf(path, sizeof path, "%s", s->file);
  else
    snprintf(path, sizeof path, "%.*s/%s", (int)(slash - x->t.origin), x->t.origin, s->file);
  if (sph_mesh_read(path, s->scale, s->offset, &s->mesh, why, sizeof why))
    return sph_yaml_fail_at(&x->t, fn, fk, "expected a closed triangle surface, got %s%s%s", path,
                            strstr(why, path) == why ? "" : ": ",
                            strstr(why, path) == why ? why + strlen(path) : why);
  return 0;
}

/* The block's extent: its box's ranges, or its shape (one of shape_keys, instead of the ranges;
 * a 3-D polygon's y range is the box's, the tank's by default). at/key get the node and key that
 * gave each axis. */
static int read_extent(const ctx *x, const node *m, const char *p, const sph_case *c,
                       sph_fluid_block *f, const node *at[SPH_DIM], const char *key[SPH_DIM]) {
  char kp[SPH_YAML_KEYLEN], b[96];
  const char *shape = NULL;
  for (int k = 0; shape_keys[k]; k++) {
    if (!sph_yaml_find(m, shape_keys[k])) continue;
    if (shape) {
      sph_yaml_join(kp, sizeof kp, p, shape_keys[k]);
      return sph_yaml_fail_at(&x->t, sph_yaml_find(m, shape_keys[k])->val, kp,
                              "expected one shape per block, got %s and %s", shape, shape_keys[k]);
    }
    shape = shape_keys[k];
  }
  const int prism = shape && !strcmp(shape, "polygon") && SPH_DIM == 3; /* its y is a range */
  for (int a = 0; a < SPH_DIM; a++) {
    double v[2] = {0, 0};
    key[a] = shape && !(prism && a == 1) ? shape : axis_key[a];
    if (shape && !(prism && a == 1)) {
      const sph_yaml_entry *e = sph_yaml_find(m, axis_key[a]);
      if (e) {
        sph_yaml_join(kp, sizeof kp, p, axis_key[a]);
        return sph_yaml_fail_at(&x->t, e->val, kp,
                                "expected no %s range in a block with a %s (its shape gives its "
                                "extent), got %s",
                                axis_key[a], shape, sph_yaml_got(e->val, b, sizeof b));
      }
      continue;
    }
    const int required = !(prism && c->tank.present);
    if (prism && !required) v[0] = c->tank.lo[1], v[1] = c->tank.hi[1];
    if (sph_yaml_get_pair(&x->t, m, p, axis_key[a], required, "xyz"[a], v) < 0) return -1;
    f->lo[a] = v[0];
    f->hi[a] = v[1];
    const sph_yaml_entry *e = sph_yaml_find(m, axis_key[a]);
    at[a] = e ? e->val : m;
  }
  if (!shape) return 0;
  const node *t = sph_yaml_find(m, shape)->val;
  sph_yaml_join(kp, sizeof kp, p, shape);
  if (!strcmp(shape, "polygon") ? read_polygon(x, t, kp, &f->shape)
      : !strcmp(shape, "mesh")  ? read_mesh(x, m, p, &f->shape)
                                : read_round(x, m, p, shape, &f->shape))
    return -1;
  sph_shape_bounds(&f->shape, f->lo, f->hi);
  for (int a = 0; a < SPH_DIM; a++)
    if (!(prism && a == 1)) at[a] = t;
  return 0;
}

static int read_block(const ctx *x, const node *m, const char *p, const sph_case *c,
                      sph_fluid_block *f) {
  char what[96], b[96];
  if (m->kind != SPH_YAML_MAP)
    return sph_yaml_fail_at(&x->t, m, p, "expected a mapping, got %s",
                            sph_yaml_got(m, b, sizeof b));
  if (sph_yaml_check_keys(&x->t, m, p, fluid_keys)) return -1;
  const node *at[SPH_DIM];
  const char *key[SPH_DIM];
  f->line = m->line;
  if (read_extent(x, m, p, c, f, at, key)) return -1;
  for (int a = 0; a < SPH_DIM; a++)
    f->v[a] = 0.0;
  if (sph_yaml_get_vector(&x->t, m, p, "velocity", 0, SPH_DIM, f->v) < 0) return -1;
  f->hydrostatic = 1;
  if (sph_yaml_get_bool(&x->t, m, p, "hydrostatic", &f->hydrostatic) < 0) return -1;
  f->surface = sph_case_block_top(f);
  sph_yaml_bprintf(what, sizeof what, "a number >= the block's %s (%g)", SPH_DIM == 2 ? "y1" : "z1",
                   sph_case_block_top(f));
  range surface = {sph_case_block_top(f), 0, '[', 0, what};
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
  return check_block(x, at, key, c, f, p);
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
      if (a->shape.kind != SPH_SHAPE_BOX || o->shape.kind != SPH_SHAPE_BOX)
        continue; /* shapes: their lattice points, when they are made (solver/setup.c) */
      int overlap = 1;
      for (int d = 0; d < SPH_DIM; d++)
        overlap &= fmin(a->hi[d], o->hi[d]) - fmax(a->lo[d], o->lo[d]) > 1e-9 * c->dx;
      if (overlap)
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

/* A segment's wall model when it names none: the scheme's (its tank's default, presets.c), so
 * that a wall drawn in a case of the default scheme holds the fluid as the tank does. */
static int scheme_wall_model(const sph_case *c) {
  size_t n;
  const sph_preset *all = sph_presets(&n);
  const sph_preset *ps = (size_t)c->scheme < n ? &all[c->scheme] : sph_preset_default();
  for (size_t k = 0; k < SPH_PRESET_KEYS; k++)
    if (!strcmp(ps->keys[k].key, "geometry.tank.boundary"))
      for (int b = 0; boundary_names[b]; b++)
        if (!strcmp(boundary_names[b], ps->keys[k].value)) return b;
  return (int)SPH_BOUNDARY_DYNAMIC;
}

/* A segment's end `to` (at the node t, key kp) after `from`: another point, at least dx away. */
static int check_end(const ctx *x, const node *t, const char *kp, const sph_case *c,
                     const double from[2], const double to[2], const char *what) {
  if (from[0] == to[0] && from[1] == to[1])
    return sph_yaml_fail_at(&x->t, t, kp, "expected a point different from %s, got [%g, %g]", what,
                            to[0], to[1]);
  const double len = hypot(to[0] - from[0], to[1] - from[1]);
  if (c->dx > 0.0 && !(len >= c->dx)) /* issue 39, D7: particles on top of one another */
    return sph_yaml_fail_at(&x->t, t, kp,
                            "the wall from [%g, %g] is %g m long, shorter than numerics.dx = %g m: "
                            "expected a wall at least dx long",
                            from[0], from[1], len, c->dx);
  return 0;
}

/* The points of a wall written as `points` (a polyline): at least two, each a pair; *n their
 * count (0: the wall is from/to). */
static int polyline_points(const ctx *x, const node *m, const char *p, size_t *n) {
  char kp[SPH_YAML_KEYLEN], b[96];
  *n = 0;
  const sph_yaml_entry *e = m->kind == SPH_YAML_MAP ? sph_yaml_find(m, "points") : NULL;
  if (!e) return 0;
  sph_yaml_join(kp, sizeof kp, p, "points");
  for (int k = 0; k < 2; k++)
    if (sph_yaml_find(m, k ? "to" : "from")) {
      char fk[SPH_YAML_KEYLEN];
      sph_yaml_join(fk, sizeof fk, p, k ? "to" : "from");
      return sph_yaml_fail_at(&x->t, sph_yaml_find(m, k ? "to" : "from")->val, fk,
                              "expected either from and to or points, got both");
    }
  if (e->val->kind != SPH_YAML_LIST || e->val->n < 2)
    return sph_yaml_fail_at(&x->t, e->val, kp,
                            "expected a list of at least 2 points [x, %c] along the wall, got %s",
                            SPH_DIM == 2 ? 'y' : 'z', sph_yaml_got(e->val, b, sizeof b));
  *n = e->val->n;
  return 0;
}

/* The wall's ends: from/to, or segment k of its `points`. */
static int read_ends(const ctx *x, const node *m, const char *p, const sph_case *c, size_t k,
                     double from[2], double to[2]) {
  const sph_yaml_entry *e = sph_yaml_find(m, "points");
  if (!e) {
    if (sph_yaml_get_pair(&x->t, m, p, "from", 1, 0, from) < 0) return -1;
    if (sph_yaml_get_pair(&x->t, m, p, "to", 1, 0, to) < 0) return -1;
    char kp[SPH_YAML_KEYLEN];
    sph_yaml_join(kp, sizeof kp, p, "to");
    return check_end(x, sph_yaml_find(m, "to")->val, kp, c, from, to, "'from'");
  }
  char k0[SPH_YAML_KEYLEN], k1[SPH_YAML_KEYLEN];
  sph_yaml_bprintf(k0, sizeof k0, "%s.points[%zu]", p, k);
  sph_yaml_bprintf(k1, sizeof k1, "%s.points[%zu]", p, k + 1);
  if (sph_yaml_read_vector(&x->t, e->val->items[k], k0, 2, from) ||
      sph_yaml_read_vector(&x->t, e->val->items[k + 1], k1, 2, to))
    return -1;
  return check_end(x, e->val->items[k + 1], k1, c, from, to, "the point before it");
}

/* Segment k of the wall at m (k = 0 for a from/to wall). */
static int read_wall(const ctx *x, const node *m, const char *p, const sph_case *c, size_t k,
                     sph_wall_segment *w) {
  char b[96];
  double from[2], to[2];
  int bnd = scheme_wall_model(c);
  if (m->kind != SPH_YAML_MAP)
    return sph_yaml_fail_at(&x->t, m, p, "expected a mapping, got %s",
                            sph_yaml_got(m, b, sizeof b));
  if (sph_yaml_check_keys(&x->t, m, p, wall_keys)) return -1;
  if (read_ends(x, m, p, c, k, from, to)) return -1;
  w->x0 = from[0];
  *wall_up(w, 0) = from[1];
  w->x1 = to[0];
  *wall_up(w, 1) = to[1];
#if SPH_DIM == 3 /* a plate across the flume: its extent along y, the tank's by default */
  double across[2] = {c->tank.y0, c->tank.y1};
  if (sph_yaml_get_pair(&x->t, m, p, "y", !c->tank.present, 'y', across) < 0) return -1;
  if (c->dx > 0.0 && !(across[1] - across[0] >= c->dx)) { /* one row would be a line (E11) */
    char kp[SPH_YAML_KEYLEN];
    sph_yaml_join(kp, sizeof kp, p, "y");
    const sph_yaml_entry *e = sph_yaml_find(m, "y");
    return sph_yaml_fail_at(&x->t, e ? e->val : m, kp,
                            "expected a range at least numerics.dx = %g m wide across the flume, "
                            "got [%g, %g]",
                            c->dx, across[0], across[1]);
  }
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
  w->layers = default_layers(w->boundary, c);
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
  size_t segments = 0; /* a polyline of n points is n - 1 segments, in order */
  for (size_t i = 0; i < t->n; i++) {
    size_t n;
    sph_yaml_bprintf(kp, sizeof kp, "geometry.walls[%zu]", i);
    if (polyline_points(x, t->items[i], kp, &n)) return -1;
    segments += n ? n - 1 : 1;
  }
  if (!(c->walls = calloc(segments, sizeof *c->walls))) return sph_yaml_oom(&x->t);
  c->n_walls = segments;
  size_t w = 0;
  for (size_t i = 0; i < t->n; i++) {
    size_t n;
    sph_yaml_bprintf(kp, sizeof kp, "geometry.walls[%zu]", i);
    if (polyline_points(x, t->items[i], kp, &n)) return -1;
    for (size_t k = 0; k < (n ? n - 1 : 1); k++)
      if (read_wall(x, t->items[i], kp, c, k, &c->walls[w++])) return -1;
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
    if (!(L >= 4.0 * c->h))
      return sph_yaml_fail_at(&x->t, v, kp, "expected a period of at least 4 h = %g m, got %g",
                              4.0 * c->h, L);
    if (!c->tank.present) continue;
    if (SPH_DIM == 2)
      return sph_yaml_fail_at(
          &x->t, v, kp, "a periodic domain cannot have a tank (use geometry.walls for the bed)");
    if (a == SPH_UP)
      return sph_yaml_fail_at(&x->t, v, kp,
                              "a tank cannot be periodic along z: its floor is normal to z");
    const double t0 = c->tank.lo[a], t1 = c->tank.hi[a];
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
/* An obstacle's (or a vessel's) wall model and layers: any model but mirror walls for a box;
 * dynamic, fixed_layers, adami or mdbc for a shape (repulsive walls' normals come from a box's
 * faces so far); layers 1..8, by default 2 (adami, and mdbc on a shape: ceil(2 h_factor), the
 * layers that fill the kernel's support). mdbc on a shape takes no fewer: with 2 layers round a
 * circle 16 dx across still water ran into it within 0.3 s; with 4 (the default scheme's
 * h = 2 dx) a circle 16 and 8 dx across holds it, and a 3-D cylinder 10 dx across (test_shapes,
 * test_shapes_3d). A vessel's model is by default the scheme's where a shape takes it, as a wall
 * segment's. */
static int read_obstacle_model(const ctx *x, const node *m, const char *p, const sph_case *c,
                               int shaped, sph_obstacle *o) {
  char kp[SPH_YAML_KEYLEN];
  int bnd = SPH_BOUNDARY_DYNAMIC;
  if (o->vessel) {
    const int b = scheme_wall_model(c);
    if (b == SPH_BOUNDARY_FIXED_LAYERS || b == SPH_BOUNDARY_ADAMI || b == SPH_BOUNDARY_MDBC)
      bnd = b;
  }
  if (sph_yaml_get_choice(&x->t, m, p, "boundary", boundary_names, &bnd) < 0) return -1;
  o->boundary = (sph_boundary_kind)bnd;
  const int refused = bnd == SPH_BOUNDARY_MIRROR || (shaped && bnd == SPH_BOUNDARY_REPULSIVE);
  if (refused) {
    sph_yaml_join(kp, sizeof kp, p, "boundary");
    const char *what = o->vessel ? "a vessel" : "an obstacle of a shape";
    if (!shaped)
      return sph_yaml_fail_at(&x->t, sph_yaml_find(m, "boundary")->val, kp,
                              "expected 'dynamic', 'fixed_layers', 'mdbc', 'adami' or "
                              "'repulsive' (an obstacle is a box of wall particles), got '%s'",
                              sph_boundary_name(o->boundary));
    return sph_yaml_fail_at(&x->t, sph_yaml_find(m, "boundary")->val, kp,
                            "expected 'dynamic', 'fixed_layers', 'adami' or 'mdbc' for %s "
                            "(repulsive and mirror walls need a box's faces so far), got '%s'",
                            what, sph_boundary_name(o->boundary));
  }
  const int fill = default_layers(SPH_BOUNDARY_ADAMI, c); /* ceil(2 h_factor) */
  const int mdbc = shaped && o->boundary == SPH_BOUNDARY_MDBC;
  o->layers = o->boundary == SPH_BOUNDARY_ADAMI || mdbc ? fill : 2;
  if (sph_yaml_get_int(&x->t, m, p, "layers", 1, 8, &o->layers) < 0) return -1;
  if (mdbc && o->layers < fill) {
    const node *t;
    sph_yaml_lookup(&x->t, m, p, "layers", 0, &t, kp);
    return sph_yaml_fail_at(&x->t, t, kp,
                            "expected at least %d for mdbc walls on a shape (the layers that fill "
                            "the kernel's support, ceil(2 h_factor)), got %d",
                            fill, o->layers);
  }
  return check_layers(x, m, p, o->boundary, &o->layers); /* (repulsive: exactly 1) */
}

/* A shape's wall particles are the points o->lo + (i + 1/2) dx inside (or, for a vessel,
 * outside) its surface: its box's corners put on the lattice of the fluid around it (that of the
 * first fluid block whose box meets the shape's grown by its layers, else the tank's inner box),
 * so that its wall particles and the fluid's points are one lattice, as a tank's are, and no
 * fluid particle starts less than dx from a wall particle (on its own box's lattice a shape
 * off the fluid's had them as close as the offset: a 3-D cylinder of adami walls 2.5 dx above
 * the floor let 16 particles more than dx into it by 0.5 s at dx = 0.02 m). A corner on the lattice
 * already stays as given (to the bit: an STL box is the box obstacle's particles); the box grows to
 * the lattice around it, and a point between the two boxes is outside the shape. */
static void snap_to_fluid_lattice(const sph_case *c, sph_obstacle *o) {
  const double dx = c->dx, grow = (double)o->layers * dx;
  if (!(dx > 0.0)) return;
  const double *ref = NULL;
  for (size_t b = 0; b < c->n_fluid && !ref; b++) {
    const sph_fluid_block *f = &c->fluid[b];
    int meets = 1;
    for (int a = 0; a < SPH_DIM; a++)
      meets &= f->lo[a] < o->hi[a] + grow && f->hi[a] > o->lo[a] - grow;
    if (meets) ref = f->lo;
  }
  if (!ref && c->tank.present) ref = c->tank.lo;
  if (!ref) return;
  for (int a = 0; a < SPH_DIM; a++) {
    const double s = (o->lo[a] - ref[a]) / dx;
    if (fabs(s - floor(s + 0.5)) <= 1e-6) continue;
    const double e = (o->hi[a] - ref[a]) / dx;
    o->lo[a] = ref[a] + floor(s) * dx;
    o->hi[a] = ref[a] + ceil(e) * dx;
  }
}

/* A shaped obstacle: its shape (as a fluid block's, read_extent) inside the tank (its top may
 * stand above it), its bounding box the obstacle's box; dynamic, fixed_layers, adami or (2-D)
 * mdbc walls (read_obstacle_model). */
static int read_shaped_obstacle(const ctx *x, const node *m, const char *p, const sph_case *c,
                                sph_obstacle *o, sph_shape *shape) {
  sph_fluid_block f;
  const node *at[SPH_DIM];
  const char *key[SPH_DIM];
  char kp[SPH_YAML_KEYLEN];
  memset(&f, 0, sizeof f);
  const int rc = read_extent(x, m, p, c, &f, at, key);
  *shape = f.shape; /* owned by the case from here, read or not */
  if (rc) return -1;
  const sph_tank *k = &c->tank;
  for (int a = 0; a < SPH_DIM; a++) {
    sph_yaml_join(kp, sizeof kp, p, key[a]);
    if (c->dx > 0.0 && !(f.hi[a] - f.lo[a] >= c->dx))
      return sph_yaml_fail_at(&x->t, at[a], kp,
                              "expected a shape at least numerics.dx = %g m across along %s, got "
                              "%g m",
                              c->dx, axis_key[a], f.hi[a] - f.lo[a]);
    const double tol = 1e-9 * c->dx;
    if (k->present && (f.lo[a] < k->lo[a] - tol || (a != SPH_UP && f.hi[a] > k->hi[a] + tol)))
      return sph_yaml_fail_at(&x->t, at[a], kp,
                              "expected a shape inside the tank's inner box, [%g, %g] along %s%s, "
                              "got one reaching [%g, %g]",
                              k->lo[a], k->hi[a], axis_key[a],
                              a == SPH_UP ? " (its top may stand above it)" : "", f.lo[a], f.hi[a]);
    o->lo[a] = f.lo[a];
    o->hi[a] = f.hi[a];
  }
  if (read_obstacle_model(x, m, p, c, 1, o)) return -1;
  snap_to_fluid_lattice(c, o);
  o->inside = sph_shape_winding_of;
  o->offset = sph_shape_offset_of;
  o->shape = shape;
  return 0;
}

/* Whether the mapping m names a shape (one of shape_keys). */
static int has_shape(const node *m) {
  for (int k = 0; shape_keys[k]; k++)
    if (sph_yaml_find(m, shape_keys[k])) return 1;
  return 0;
}

static int read_obstacle(const ctx *x, const node *m, const char *p, const sph_case *c,
                         sph_obstacle *o, sph_shape *shape) {
  char b[96], kp[SPH_YAML_KEYLEN];
  if (m->kind != SPH_YAML_MAP)
    return sph_yaml_fail_at(&x->t, m, p, "expected a mapping, got %s",
                            sph_yaml_got(m, b, sizeof b));
  if (sph_yaml_check_keys(&x->t, m, p, obstacle_keys)) return -1;
  if (has_shape(m)) return read_shaped_obstacle(x, m, p, c, o, shape);
  for (int a = 0; a < SPH_DIM; a++) {
    const char *const key = axis_key[a];
    double v[2];
    if (sph_yaml_get_pair(&x->t, m, p, key, 1, key[0], v) < 0) return -1;
    if (c->dx > 0.0 && !(v[1] - v[0] >= c->dx)) {
      sph_yaml_join(kp, sizeof kp, p, key);
      return sph_yaml_fail_at(&x->t, sph_yaml_find(m, key)->val, kp,
                              "expected a range at least numerics.dx = %g m wide, got [%g, %g]",
                              c->dx, v[0], v[1]);
    }
    /* inside the tank (it may stand above the walls' top): a box outside
     * it is no obstacle to the water (issue 61, E11) */
    const sph_tank *k = &c->tank;
    const double tlo = k->lo[a], thi = k->hi[a], tol = 1e-9 * c->dx;
    if (k->present && (v[0] < tlo - tol || (a != SPH_DIM - 1 && v[1] > thi + tol) || v[1] <= tlo ||
                       v[0] >= thi)) {
      sph_yaml_join(kp, sizeof kp, p, key);
      return sph_yaml_fail_at(&x->t, sph_yaml_find(m, key)->val, kp,
                              "expected a range inside the tank's inner box [%g, %g]%s, got "
                              "[%g, %g]",
                              tlo, thi, a == SPH_DIM - 1 ? " (its top may stand above it)" : "",
                              v[0], v[1]);
    }
    o->lo[a] = v[0];
    o->hi[a] = v[1];
  }
  return read_obstacle_model(x, m, p, c, 0, o);
}

/* geometry.vessels[i]: a shape (as an obstacle's, no box ranges) holding the fluid: the wall
 * particles a shell `layers` deep outside its surface, the fluid's points outside every vessel
 * not made; the wall models of a shaped obstacle (read_obstacle_model). */
static int read_vessel(const ctx *x, const node *m, const char *p, const sph_case *c,
                       sph_obstacle *o, sph_shape *shape) {
  char b[96];
  if (m->kind != SPH_YAML_MAP)
    return sph_yaml_fail_at(&x->t, m, p, "expected a mapping, got %s",
                            sph_yaml_got(m, b, sizeof b));
  if (!has_shape(m))
    return sph_yaml_fail_at(&x->t, m, p,
                            "expected a shape (polygon, " BALL_KEY SPH_IF3(
                                ", cylinder or mesh") "): a vessel is the surface that holds the "
                                                      "water (a box is the tank)");
  if (sph_yaml_check_keys(&x->t, m, p, vessel_keys)) return -1;
  o->vessel = 1; /* (read_obstacle_model's default and messages) */
  return read_shaped_obstacle(x, m, p, c, o, shape);
}

/* geometry.obstacles, then geometry.vessels, into c->obstacles. */
static int read_obstacles(const ctx *x, const node *m, sph_case *c) {
  const node *t[2] = {NULL, NULL};
  static const char *const list[2] = {"obstacles", "vessels"};
  char kp[2][SPH_YAML_KEYLEN], b[96];
  for (int l = 0; l < 2; l++) {
    const int rc = sph_yaml_lookup(&x->t, m, "geometry", list[l], 0, &t[l], kp[l]);
    if (rc < 0) return rc;
    if (rc == 0) t[l] = NULL;
    if (t[l] && t[l]->kind != SPH_YAML_LIST)
      return sph_yaml_fail_at(&x->t, t[l], kp[l], "expected a list of mappings, got %s",
                              sph_yaml_got(t[l], b, sizeof b));
  }
  const size_t n0 = t[0] ? t[0]->n : 0, n1 = t[1] ? t[1]->n : 0;
  if (n0 + n1 == 0) return 0;
  if (!(c->obstacles = calloc(n0 + n1, sizeof *c->obstacles)) ||
      !(c->obstacle_shape = calloc(n0 + n1, sizeof *c->obstacle_shape)))
    return sph_yaml_oom(&x->t);
  for (size_t i = 0; i < n0 + n1; i++) {
    const size_t k = i < n0 ? i : i - n0;
    sph_yaml_bprintf(kp[0], sizeof kp[0], "geometry.%s[%zu]", list[i >= n0], k);
    c->n_obstacles = i + 1; /* (what is read so far, for sph_case_free) */
    c->n_vessels = i >= n0 ? k + 1 : 0;
    if (i < n0 ? read_obstacle(x, t[0]->items[k], kp[0], c, &c->obstacles[i], &c->obstacle_shape[i])
               : read_vessel(x, t[1]->items[k], kp[0], c, &c->obstacles[i], &c->obstacle_shape[i]))
      return -1;
  }
  return 0;
}

int sph_case_read_geometry(const ctx *x, const node *root, sph_case *c) {
  const node *d, *m;
  if (sph_yaml_get_section(&x->t, root, "", "geometry", 1, geometry_keys, &m) < 0) return -1;
  if (read_tank(x, m, c) || read_fluid(x, m, c) || read_walls(x, m, c) || read_obstacles(x, m, c))
    return -1;
  if (read_periodic(x, m, c)) return -1;
  int leaving = SPH_LEAVING_STOP;
  if (sph_yaml_get_choice(&x->t, m, "geometry", "leaving", sph_case_leaving_names, &leaving) < 0)
    return -1;
  c->leaving = (sph_leaving_kind)leaving;
  int rc = sph_yaml_get_section(&x->t, m, "geometry", "domain", 0, domain_keys, &d);
  if (rc <= 0) return rc;
  c->domain_set = 1;
  for (int a = 0; a < SPH_DIM; a++)
    if (sph_yaml_get_pair(&x->t, d, "geometry.domain", axis_key[a], 1, "xyz"[a],
                          &c -> domain[2 * a]) < 0)
      return -1;
  return 0;
}

/* The particles the geometry makes at dx, from above, in floating point (a
 * tiny dx gives a huge or infinite count, never an overflow): the fluid
 * blocks' lattices, and for the tank and each wall segment a row of
 * particles dx apart per layer along its length, plus the corners. */
void sph_case_estimate_particles(sph_case *c) {
  const double dx = c->dx;
  double fluid = 0.0, wall = 0.0;
  for (size_t b = 0; b < c->n_fluid; b++) {
    const sph_fluid_block *f = &c->fluid[b];
    double points = 1.0;
    for (int a = 0; a < SPH_DIM; a++)
      points *= (double)sph_case_lattice_points(f->lo[a], f->hi[a], dx);
    fluid += points;
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
    const sph_obstacle *o = &c->obstacles[i];
    double box = 1.0;
    for (int a = 0; a < SPH_DIM; a++) /* (a vessel's shell stands outside its box) */
      box *= floor((o->hi[a] - o->lo[a]) / dx + 0.5) + 1.0 + (o->vessel ? 2.0 * o->layers : 0.0);
    wall += box;
  }
  int mirror = c->tank.present && c->tank.boundary == SPH_BOUNDARY_MIRROR;
  for (size_t i = 0; i < c->n_walls; i++)
    mirror |= c->walls[i].boundary == SPH_BOUNDARY_MIRROR;
  if (c->air && c->tank.present) { /* the air: at most the tank's whole lattice */
    double points = 1.0;
    for (int a = 0; a < SPH_DIM; a++)
      points *= (double)sph_case_lattice_points(c->tank.lo[a], c->tank.hi[a], dx);
    fluid += points;
  }
  c->est_fluid = fluid;
  c->est_wall = wall + (mirror ? fluid : 0.0); /* mirror images of the fluid, at most */
}

double sph_case_default_max(void) {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  double bytes = pages > 0 && page > 0 ? (double)pages * (double)page : 4e9;
  const double max = 0.5 * bytes / SPH_BYTES_PER_PARTICLE;
  return max < SPH_MAX_PARTICLES_HARD ? max : SPH_MAX_PARTICLES_HARD;
}

long sph_case_lattice_points(double lo, double hi, double dx) {
  /* hi - lo carries up to an ulp of each end: a few DBL_EPSILON of their
   * size, in units of dx; 1e-9 of dx at the origin (a range that is a
   * whole number of dx up to printing) */
  const double tol = 1e-9 + 8.0 * DBL_EPSILON * (fabs(lo) + fabs(hi)) / dx;
  const double n = floor((hi - lo) / dx + tol);
  return n > 0.0 ? (n < (double)LONG_MAX ? (long)n : LONG_MAX) : 0;
}

/* The largest |coordinate| of the geometry (tank, fluid blocks, walls,
 * obstacles). */
static double largest_coordinate(const sph_case *c) {
  double m = 0.0;
#define SEE(v) m = fmax(m, fabs(v))
  for (int a = 0; a < SPH_DIM; a++) {
    if (c->tank.present) SEE(c->tank.lo[a]), SEE(c->tank.hi[a]);
    for (size_t b = 0; b < c->n_fluid; b++)
      SEE(c->fluid[b].lo[a]), SEE(c->fluid[b].hi[a]);
  }
  for (size_t i = 0; i < c->n_walls; i++) {
    const sph_wall_segment *w = &c->walls[i];
    SEE(w->x0), SEE(w->x1), SEE(w->y0), SEE(w->y1);
#if SPH_DIM == 3
    SEE(w->z0), SEE(w->z1);
#endif
  }
  for (size_t i = 0; i < c->n_obstacles; i++)
    for (int a = 0; a < SPH_DIM; a++)
      SEE(c->obstacles[i].lo[a]), SEE(c->obstacles[i].hi[a]);
#undef SEE
  return m;
}

/* The geometry's coordinates against dx: doubles must resolve the lattice,
 * and far from the origin they are too coarse for it (at 1e15 m they are
 * 0.125 m apart; issue 61, E8). */
static int check_coordinates(const sph_case *c, sph_error *err) {
  const double far = largest_coordinate(c), ulp = far * DBL_EPSILON;
  if (ulp <= 1e-4 * c->dx) return 0;
  return sph_error_set(err,
                       "%s: the geometry reaches %g m from the origin, where doubles are %.3g m "
                       "apart: too coarse for dx = %g m (at most dx/10000): expected the "
                       "geometry nearer the origin",
                       c->path ? c->path : "the case", far, ulp, c->dx);
}

int sph_case_check_size(const sph_case *c, double max, sph_error *err) {
  const int given = max > 0.0;
  if (!given) max = sph_case_default_max();
  if (max > SPH_MAX_PARTICLES_HARD) max = SPH_MAX_PARTICLES_HARD;
  const double n = c->est_fluid + c->est_wall;
  if (n <= max) return check_coordinates(c, err);
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
