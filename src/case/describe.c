/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * describe.c - sph_case_describe (see case.h): the case as it runs, every
 * key with its value, defaults filled in, as YAML that sph_case_parse reads
 * back to the same case.
 */
#include "config.h"

#include "case/case.h"
#include "case/case_read.h"
#include "case/choices.h"
#include "case/yaml_tree.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct sbuf {
  char *s;
  size_t len, cap;
  int failed;
} sbuf;

static void sb_add(sbuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void sb_add(sbuf *b, const char *fmt, ...) {
  va_list ap;
  if (b->failed) return;
  va_start(ap, fmt);
  int n = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  if (n < 0) {
    b->failed = 1;
    return;
  }
  if (b->len + (size_t)n + 1 > b->cap) {
    size_t cap = b->cap ? b->cap : 1024;
    while (b->len + (size_t)n + 1 > cap)
      cap *= 2;
    char *s = realloc(b->s, cap);
    if (!s) {
      b->failed = 1;
      return;
    }
    b->s = s;
    b->cap = cap;
  }
  va_start(ap, fmt);
  vsnprintf(b->s + b->len, b->cap - b->len, fmt, ap);
  va_end(ap);
  b->len += (size_t)n;
}

/* A double-quoted, escaped string, so any description stays on one line. */
static void sb_quoted(sbuf *b, const char *s) {
  sb_add(b, "\"");
  for (; s && *s; s++) {
    unsigned char ch = (unsigned char)*s;
    if (ch == '"' || ch == '\\')
      sb_add(b, "\\%c", ch);
    else if (ch == '\n')
      sb_add(b, "\\n");
    else if (ch == '\t')
      sb_add(b, "\\t");
    else if (ch < 0x20 || ch == 0x7f)
      sb_add(b, "\\x%02x", ch);
    else
      sb_add(b, "%c", ch);
  }
  sb_add(b, "\"\n");
}

static void sb_pair(sbuf *b, const char *key, double v0, double v1) {
  sb_add(b, "%s: [%.17g, %.17g]\n", key, v0, v1);
}

/* prefix.KEY: [v0, v1(, v2)] for a vector of SPH_DIM components. */
static void sb_vector(sbuf *b, const char *prefix, const char *key, const double v[SPH_DIM]) {
  sb_add(b, "%s%s%s: [", prefix, *prefix ? "." : "", key);
  for (int a = 0; a < SPH_DIM; a++)
    sb_add(b, a ? ", %.17g" : "%.17g", v[a]);
  sb_add(b, "]\n");
}

/* prefix.x: [lo, hi], prefix.y: ... (, prefix.z): a box's ranges, axis by axis. */
static void sb_box(sbuf *b, const char *prefix, const double lo[SPH_DIM],
                   const double hi[SPH_DIM]) {
  for (int a = 0; a < SPH_DIM; a++)
    sb_add(b, "%s.%c: [%.17g, %.17g]\n", prefix, "xyz"[a], lo[a], hi[a]);
}

/* A block's extent: its box, or its shape (a 3-D polygon with its y range). */
static void describe_shape(sbuf *b, const char *k, const sph_shape *s, const double *lo,
                           const double *hi) {
  switch (s->kind) {
  case SPH_SHAPE_POLYGON:
    sb_add(b, "%s.polygon: [", k);
    for (size_t v = 0; v < s->n; v++)
      sb_add(b, "%s[%.17g, %.17g]", v ? ", " : "", s->vertex[2 * v], s->vertex[2 * v + 1]);
    sb_add(b, "]\n");
    if (SPH_DIM == 3) sb_add(b, "%s.y: [%.17g, %.17g]\n", k, lo[1], hi[1]);
    break;
  case SPH_SHAPE_BALL:
    sb_vector(b, k, SPH_DIM == 2 ? "circle.centre" : "sphere.centre", s->centre);
    sb_add(b, "%s.%s.radius: %.17g\n", k, SPH_DIM == 2 ? "circle" : "sphere", s->radius);
    break;
  case SPH_SHAPE_CYLINDER:
    sb_vector(b, k, "cylinder.from", s->centre);
    sb_vector(b, k, "cylinder.to", s->end);
    sb_add(b, "%s.cylinder.radius: %.17g\n", k, s->radius);
    break;
  case SPH_SHAPE_MESH:
    sb_add(b, "%s.mesh.file: %s\n", k, s->file);
    sb_add(b, "%s.mesh.scale: %.17g\n", k, s->scale);
    sb_vector(b, k, "mesh.offset", s->offset);
    break;
  default: sb_box(b, k, lo, hi); break;
  }
}

static void describe_geometry(sbuf *b, const sph_case *c) {
  char k[SPH_YAML_KEYLEN];
  if (c->tank.present) {
    sb_box(b, "geometry.tank", c->tank.lo, c->tank.hi);
    sb_add(b, "geometry.tank.layers: %d\n", c->tank.layers);
    sb_add(b, "geometry.tank.boundary: %s\n", sph_boundary_name(c->tank.boundary));
    /* written only when not the default, so that older records still match */
    if (!c->tank.stagger) sb_add(b, "geometry.tank.stagger: false\n");
    if (c->tank.extrapolated) sb_add(b, "geometry.tank.extrapolated_velocity: true\n");
    if (c->tank.free_slip) sb_add(b, "geometry.tank.free_slip: true\n");
    if (c->tank.lid) sb_add(b, "geometry.tank.lid: true\n");
  } else {
    sb_add(b, "geometry.tank: none\n");
  }
  for (size_t i = 0; i < c->n_fluid; i++) {
    const sph_fluid_block *f = &c->fluid[i];
    sph_yaml_bprintf(k, sizeof k, "geometry.fluid[%zu]", i);
    describe_shape(b, k, &f->shape, f->lo, f->hi);
    sb_vector(b, k, "velocity", f->v);
    sb_add(b, "%s.hydrostatic: %s\n", k, f->hydrostatic ? "true" : "false");
    sb_add(b, "%s.surface: %.17g\n", k, f->surface);
    sb_add(b, "%s.jitter: %.17g\n", k, f->jitter);
    sb_add(b, "%s.seed: %d\n", k, f->seed);
  }
  const size_t n_boxes = c->n_obstacles - c->n_vessels; /* then the vessels */
  for (size_t i = 0; i < c->n_obstacles; i++) {         /* listed only when there are some */
    const sph_obstacle *o = &c->obstacles[i];
    if (i < n_boxes)
      sph_yaml_bprintf(k, sizeof k, "geometry.obstacles[%zu]", i);
    else
      sph_yaml_bprintf(k, sizeof k, "geometry.vessels[%zu]", i - n_boxes);
    if (o->inside)
      describe_shape(b, k, o->shape, o->lo, o->hi);
    else
      sb_box(b, k, o->lo, o->hi);
    sb_add(b, "%s.layers: %d\n", k, o->layers);
    sb_add(b, "%s.boundary: %s\n", k, sph_boundary_name(o->boundary));
  }
  if (c->n_walls == 0) sb_add(b, "geometry.walls: []\n");
  for (size_t i = 0; i < c->n_walls; i++) {
    const sph_wall_segment *w = &c->walls[i];
    sph_yaml_bprintf(k, sizeof k, "geometry.walls[%zu]", i);
#if SPH_DIM == 2
    sb_add(b, "%s.from: [%.17g, %.17g]\n", k, w->x0, w->y0);
    sb_add(b, "%s.to: [%.17g, %.17g]\n", k, w->x1, w->y1);
#else /* from and to in the x-z plane, across y */
    sb_add(b, "%s.from: [%.17g, %.17g]\n", k, w->x0, w->z0);
    sb_add(b, "%s.to: [%.17g, %.17g]\n", k, w->x1, w->z1);
    sb_add(b, "%s.y: [%.17g, %.17g]\n", k, w->y0, w->y1);
#endif
    sb_add(b, "%s.layers: %d\n", k, w->layers);
    sb_add(b, "%s.boundary: %s\n", k, sph_boundary_name(w->boundary));
    if (!w->stagger) sb_add(b, "%s.stagger: false\n", k);
    if (w->extrapolated) sb_add(b, "%s.extrapolated_velocity: true\n", k);
    if (w->free_slip) sb_add(b, "%s.free_slip: true\n", k);
    if (w->motion.kind == SPH_MOTION_PISTON || w->motion.kind == SPH_MOTION_FLAP) {
      const sph_paddle *pd = &w->motion.paddle;
      sb_add(b, "%s.motion.type: %s\n", k, sph_case_motion_names[w->motion.kind]);
      sb_add(b, "%s.motion.period: %.17g\n", k, pd->period);
      sb_add(b, "%s.motion.stroke: %.17g\n", k, pd->stroke);
      sb_add(b, "%s.motion.depth: %.17g\n", k, pd->depth);
      sb_add(b, "%s.motion.ramp: %.17g\n", k, pd->ramp);
      sb_add(b, "%s.motion.hinge: [%.17g, %.17g]\n", k, pd->hinge_x, pd->hinge_y);
    }
    if (w->motion.kind == SPH_MOTION_TRANSLATE) {
      sb_add(b, "%s.motion.type: translate\n", k);
      sb_vector(b, k, "motion.velocity", w->motion.v);
      sb_add(b, "%s.motion.start: %.17g\n", k, w->motion.start);
      sb_add(b, "%s.motion.stop: %.17g\n", k, w->motion.stop);
    }
  }
  static const char *const periodic_keys[3] = {"geometry.periodic_x", "geometry.periodic_y",
                                               "geometry.periodic_z"};
  if (c->periodic)
    sb_pair(b, periodic_keys[c->periodic_axis], c->periodic_range[0], c->periodic_range[1]);
  if (c->domain_set) {
    for (int a = 0; a < SPH_DIM; a++)
      sb_add(b, "geometry.domain.%c: [%.17g, %.17g]\n", "xyz"[a], c -> domain[2 * a],
             c -> domain[2 * a + 1]);
  } else {
    sb_add(b, "geometry.domain: none\n");
  }
  /* listed only when not the default: the parameters of every case that
   * stops are those it had before the key existed */
  if (c->leaving == SPH_LEAVING_REMOVE) sb_add(b, "geometry.leaving: remove\n");
}

char *sph_case_describe(const sph_case *c) {
  sbuf b = {NULL, 0, 0, 0};
  if (!c) return NULL;
  sb_add(&b, "name: %s\n", c->name ? c->name : "");
  sb_add(&b, "description: ");
  sb_quoted(&b, c->description);
  sb_add(&b, "physics.rho0: %.17g\n", c->rho0);
  /* (a 2-D case's listing has no dimension line: the records of older runs match) */
  if (SPH_DIM == 3) sb_add(&b, "dimension: 3\n");
  sb_vector(&b, "", "physics.gravity", c->gravity);
  sb_add(&b, "physics.sound_speed: %.17g\n", c->sound_speed);
  sb_add(&b, "physics.artificial_viscosity.alpha: %.17g\n", c->alpha);
  sb_add(&b, "physics.artificial_viscosity.beta: %.17g\n", c->beta);
  sb_add(&b, "physics.artificial_viscosity.eta: %.17g\n", c->eta);
  sb_add(&b, "physics.xsph: %.17g\n", c->xsph);
  if (!c->negative_pressure) sb_add(&b, "physics.negative_pressure: false\n");
  if (c->riemann) sb_add(&b, "physics.riemann.limiter: %.17g\n", c->riemann_limiter);
  if (c->air) {
    char air[512];
    if (sph_case_air_listing(c, air, sizeof air) >= (int)sizeof air) b.failed = 1;
    sb_add(&b, "physics.air: %s\n", air);
  }
  sb_add(&b, "physics.viscosity.model: %s\n", sph_viscosity_name(c->viscosity));
  if (c->viscosity != SPH_VISCOSITY_NONE) sb_add(&b, "physics.viscosity.mu: %.17g\n", c->mu);
  if (c->gradient_correction) sb_add(&b, "physics.viscosity.gradient_correction: true\n");
  sb_add(&b, "physics.turbulence.model: %s\n", c->sps ? "sps" : "none");
  if (c->sps) {
    sb_add(&b, "physics.turbulence.cs: %.17g\n", c->sps_cs);
    sb_add(&b, "physics.turbulence.ci: %.17g\n", c->sps_ci);
  }
  sb_add(&b, "physics.repulsion: %.17g\n", c->repulsion);
  sb_add(&b, "numerics.scheme: %s\n", sph_scheme_name(c->scheme));
  sb_add(&b, "numerics.dx: %.17g\n", c->dx);
  sb_add(&b, "numerics.h_factor: %.17g\n", c->h_factor);
  sb_add(&b, "numerics.h: %.17g\n", c->h);
  sb_add(&b, "numerics.smoothing_length: %s\n", sph_case_h_names[c->variable_h]);
  sb_add(&b, "numerics.kernel: %s\n", sph_kernel_name(c->kernel));
  sb_add(&b, "numerics.integrator: %s\n", sph_integrator_name(c->integrator));
  sb_add(&b, "numerics.time_step.rule: %s\n", sph_dt_rule_name(c->dt_rule));
  sb_add(&b, "numerics.time_step.factor: %.17g\n", c->dt_factor);
  if (c->dt_rule == SPH_DT_FIXED) sb_add(&b, "numerics.time_step.dt: %.17g\n", c->dt_fixed);
  sb_add(&b, "numerics.density_filter.kind: %s\n", sph_filter_name(c->density_filter));
  sb_add(&b, "numerics.density_filter.every: %d\n", c->filter_every);
  sb_add(&b, "numerics.density_diffusion.model: %s\n", sph_diffusion_name(c->diffusion));
  sb_add(&b, "numerics.density_diffusion.delta: %.17g\n", c->diffusion_delta);
  if (c->shifting) sb_add(&b, "numerics.shifting.coefficient: %.17g\n", c->shifting_coefficient);
  if (c->corrected_gradient) sb_add(&b, "numerics.gradient_correction: true\n");
  sb_add(&b, "numerics.density_limit: %.17g\n", c->density_limit);
  sb_add(&b, "time.end: %.17g\n", c->t_end);
  sb_add(&b, "time.output_interval: %.17g\n", c->output_interval);
  for (size_t i = 0; i < c->n_output_times; i++)
    sb_add(&b, "time.output_times[%zu]: %.17g\n", i, c->output_times[i]);
  sb_add(&b, "time.stop: %s\n", sph_stop_name(c->stop));
  describe_geometry(&b, c);
  sb_add(&b, "free_surface.radius_factor: %.17g\n", c->fs_radius_factor);
  sb_add(&b, "free_surface.h_factor: %.17g\n", c->fs_h_factor);
  sb_add(&b, "output.snapshots: %s\n", c->snapshots ? "true" : "false");
  sb_add(&b, "output.free_surface: %s\n", c->output_free_surface ? "true" : "false");
  sb_add(&b, "output.energy: %s\n", c->energy ? "true" : "false");
  for (size_t i = 0; i < c->n_gauges; i++)
#if SPH_DIM == 2
    sb_add(&b, "output.gauges[%zu]: %.17g\n", i, c->gauges[i]);
#else
    sb_add(&b, "output.gauges[%zu]: [%.17g, %.17g]\n", i, c->gauges[2 * i], c->gauges[2 * i + 1]);
#endif
  for (size_t i = 0; i < c->n_probes; i++) {
    const sph_probe *q = &c->probes[i];
    sb_add(&b, "output.probes[%zu]: %s %s", i, q->name, sph_probe_kind_name(q->kind));
#if SPH_DIM == 3
    if (q->kind == SPH_PROBE_LEVEL)
      sb_add(&b, " at [%.17g, %.17g]%s\n", q->x, q->y, q->wetted ? " wetted" : "");
    else if (q->kind == SPH_PROBE_VELOCITY)
      sb_add(&b, " at [%.17g, %.17g, %.17g]\n", q->x, q->y, q->z);
    else {
      sb_add(&b, " at [%.17g, %.17g, %.17g] diameter %.17g normal [%.17g, %.17g, %.17g]", q->x,
             q->y, q->z, q->diameter, q->normal[0], q->normal[1], q->normal[2]);
#else
    if (q->kind == SPH_PROBE_LEVEL)
      sb_add(&b, " x %.17g%s\n", q->x, q->wetted ? " wetted" : "");
    else if (q->kind == SPH_PROBE_VELOCITY)
      sb_add(&b, " at [%.17g, %.17g]\n", q->x, q->y);
    else {
      sb_add(&b, " at [%.17g, %.17g] diameter %.17g along %s", q->x, q->y, q->diameter,
             q->along_x ? "x" : "y");
#endif
      if (sph_probe_filtered(q)) sb_add(&b, " low_pass %.17g", q->low_pass);
      /* a sensor's own interpolation, where it states one */
      if (q->points) sb_add(&b, " points %d", q->points);
      if (q->smoothing > 0.0) sb_add(&b, " smoothing %.17g", q->smoothing);
      if (q->clip_negative) sb_add(&b, " clip_negative");
      if (q->no_carry) sb_add(&b, " hydrostatic false");
      if (q->wet_sum > 0.0) sb_add(&b, " wet_sum %.17g", q->wet_sum);
      sb_add(&b, "\n");
    }
  }
  if (c->n_probes) sb_add(&b, "output.probe_interval: %.17g\n", c->probe_interval);
  if (b.failed) {
    free(b.s);
    return NULL;
  }
  return b.s;
}
