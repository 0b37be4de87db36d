/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_case.c - the strict YAML case reader (case.h).
 *
 * Most tests parse inline text with sph_case_parse under the origin
 * "t.yaml" and compare the whole error message, so the file, the 1-based
 * line, the dotted key and the expectation are all checked at once. The
 * texts below are built from numbered lines (see MINIMAL) so that the
 * expected line numbers can be read off. A few fixture files under
 * tests/data/cases_bad/ go through sph_case_load, and a valid file is
 * written to a temporary directory to check path and text.
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "case/case.h"
#include "case/presets.h"
#include "physics/shifting.h"
#include "testutil.h"

/* The smallest valid case: every optional key left to its default. */
static const char MINIMAL[] = "name: mini\n"             /* 1 */
                              "physics:\n"               /* 2 */
                              "  sound_speed: 20\n"      /* 3 */
                              "numerics:\n"              /* 4 */
                              "  dx: 0.01\n"             /* 5 */
                              "time:\n"                  /* 6 */
                              "  end: 1\n"               /* 7 */
                              "  output_interval: 0.1\n" /* 8 */
                              "geometry:\n"              /* 9 */
                              "  fluid:\n"               /* 10 */
                              "    - x: [0, 1]\n"        /* 11 */
                              "      y: [0, 0.5]\n";     /* 12 */

/* Every key of the schema given. */
static const char FULL[] = "# a complete case\n"                           /* 1 */
                           "name: martin_moyce\n"                          /* 2 */
                           "description: \"Dam break\"\n"                  /* 3 */
                           "physics:\n"                                    /* 4 */
                           "  rho0: 998.0\n"                               /* 5 */
                           "  gravity: [0.0, -9.81]\n"                     /* 6 */
                           "  sound_speed: {factor: 10, height: 0.1143}\n" /* 7 */
                           "  artificial_viscosity:\n"                     /* 8 */
                           "    alpha: 0.3\n"                              /* 9 */
                           "    beta: 0.1\n"                               /* 10 */
                           "    eta: 0.2\n"                                /* 11 */
                           "  xsph: 0.5\n"                                 /* 12 */
                           "numerics:\n"                                   /* 13 */
                           "  dx: 0.001143\n"                              /* 14 */
                           "  h_factor: 1.5\n"                             /* 15 */
                           "  kernel: cubic_spline\n"                      /* 16 */
                           "  integrator: predictor_corrector\n"           /* 17 */
                           "  time_step:\n"                                /* 18 */
                           "    rule: cfl\n"                               /* 19 */
                           "    factor: 0.25\n"                            /* 20 */
                           "  density_limit: 0.2\n"                        /* 21 */
                           "time:\n"                                       /* 22 */
                           "  end: 0.5\n"                                  /* 23 */
                           "  output_interval: 0.01\n"                     /* 24 */
                           "  stop: front_at_wall\n"                       /* 25 */
                           "geometry:\n"                                   /* 26 */
                           "  tank:\n"                                     /* 27 */
                           "    x: [0.0, 0.2286]\n"                        /* 28 */
                           "    y: [0.0, 0.2]\n"                           /* 29 */
                           "    layers: 3\n"                               /* 30 */
                           "    boundary: dynamic\n"                       /* 31 */
                           "  fluid:\n"                                    /* 32 */
                           "    - x: [0.0, 0.05715]\n"                     /* 33 */
                           "      y: [0.0, 0.1143]\n"                      /* 34 */
                           "      velocity: [0.5, -0.25]\n"                /* 35 */
                           "      hydrostatic: false\n"                    /* 36 */
                           "      surface: 0.12\n"                         /* 37 */
                           "    - x: [0.1, 0.2]\n"                         /* 38 */
                           "      y: [0.0, 0.01]\n"                        /* 39 */
                           "  walls:\n"                                    /* 40 */
                           "    - from: [0.1, 0.0]\n"                      /* 41 */
                           "      to: [0.1, 0.05]\n"                       /* 42 */
                           "      layers: 1\n"                             /* 43 */
                           "      boundary: dynamic\n"                     /* 44 */
                           "  domain:\n"                                   /* 45 */
                           "    x: [-0.01, 0.24]\n"                        /* 46 */
                           "    y: [-0.01, 0.5]\n"                         /* 47 */
                           "output:\n"                                     /* 48 */
                           "  snapshots: false\n";                         /* 49 */

static const char *const TOP_KEYS =
    "name, description, dimension, physics, numerics, time, geometry, free_surface, output";
static const char *const PHYSICS_KEYS =
    "rho0, gravity, body_force, sound_speed, artificial_viscosity, viscosity, turbulence, "
    "repulsion, xsph, riemann, negative_pressure, air";

/* MINIMAL with line `line` (1-based) replaced by `repl` (which may hold
 * several lines, or be "" to delete it). Returns one of two static buffers. */
static const char *edit(const char *base, int line, const char *repl) {
  static char bufs[2][8192];
  static int which;
  char *buf = bufs[which ^= 1]; /* two buffers, so that edits can nest */
  const char *p = base;
  size_t n = 0;
  for (int l = 1; *p; l++) {
    const char *eol = strchr(p, '\n');
    size_t len = eol ? (size_t)(eol - p) + 1 : strlen(p);
    if (l == line) {
      size_t k = strlen(repl);
      memcpy(buf + n, repl, k);
      n += k;
    } else {
      memcpy(buf + n, p, len);
      n += len;
    }
    p += len;
  }
  buf[n] = '\0';
  return buf;
}

static int parse(const char *text, const char *const *set, size_t n, sph_case *c, sph_error *e) {
  return sph_case_parse(text, strlen(text), "t.yaml", set, n, c, e);
}

static int is_empty(const sph_case *c) {
  static const sph_case zero;
  return memcmp(c, &zero, sizeof zero) == 0;
}

/* The parse must fail with exactly `want`, leaving the case empty. */
static void expect_err_set(const char *text, const char *const *set, size_t n, const char *want) {
  sph_case c;
  sph_error e = {{0}};
  int rc = parse(text, set, n, &c, &e);
  CU_ASSERT(rc != 0);
  CU_ASSERT_STRING_EQUAL(e.msg, want);
  if (rc == 0 || strcmp(e.msg, want) != 0)
    fprintf(stderr, "\n  want: %s\n  got:  %s\n", want, rc ? e.msg : "(success)");
  CU_ASSERT(is_empty(&c));
  sph_case_free(&c);
}

static void expect_err(const char *text, const char *want) { expect_err_set(text, NULL, 0, want); }

static void expect_ok(const char *text, const char *const *set, size_t n, sph_case *c) {
  sph_error e = {{0}};
  int rc = parse(text, set, n, c, &e);
  CU_ASSERT_EQUAL(rc, 0);
  if (rc) fprintf(stderr, "\n  unexpected error: %s\n", e.msg);
}

/* ---- valid cases ---------------------------------------------------------- */

static void test_minimal_defaults(void) {
  sph_case c;
  expect_ok(MINIMAL, NULL, 0, &c);
  CU_ASSERT_STRING_EQUAL(c.name, "mini");
  CU_ASSERT_STRING_EQUAL(c.description, "");
  CU_ASSERT_STRING_EQUAL(c.path, "t.yaml");
  CU_ASSERT_STRING_EQUAL(c.text, MINIMAL);
  CU_ASSERT_STRING_EQUAL(c.overrides, "");
  CU_ASSERT_EQUAL(c.rho0, 1000.0);
  CU_ASSERT_EQUAL(c.gravity[0], 0.0);
  CU_ASSERT_EQUAL(c.gravity[1], -9.81);
  CU_ASSERT_EQUAL(c.sound_speed, 20.0);
  CU_ASSERT_EQUAL(c.alpha, 0.0);
  CU_ASSERT_EQUAL(c.beta, 0.0);
  CU_ASSERT_EQUAL(c.eta, 0.1);
  CU_ASSERT_EQUAL(c.xsph, 0.0);
  CU_ASSERT_EQUAL(c.dx, 0.01);
  /* the default scheme's (test_schemes) */
  CU_ASSERT_EQUAL(c.scheme, SPH_SCHEME_RIEMANN);
  CU_ASSERT_EQUAL(c.riemann, 1);
  CU_ASSERT_EQUAL(c.h_factor, 2.0);
  CU_ASSERT_EQUAL(c.h, 2.0 * 0.01);
  CU_ASSERT_EQUAL(c.kernel, SPH_KERNEL_WENDLAND_C2);
  CU_ASSERT_EQUAL(c.integrator, SPH_INTEGRATOR_LEAPFROG);
  CU_ASSERT_EQUAL(c.dt_rule, SPH_DT_CFL);
  CU_ASSERT_EQUAL(c.dt_factor, 0.3);
  CU_ASSERT_EQUAL(c.dt_fixed, 0.0);
  CU_ASSERT_EQUAL(c.density_limit, 0.3);
  CU_ASSERT_EQUAL(c.t_end, 1.0);
  CU_ASSERT_EQUAL(c.output_interval, 0.1);
  CU_ASSERT_EQUAL(c.stop, SPH_STOP_NONE);
  CU_ASSERT_EQUAL(c.tank.present, 0);
  CU_ASSERT_EQUAL_FATAL(c.n_fluid, 1);
  CU_ASSERT_EQUAL(c.fluid[0].x0, 0.0);
  CU_ASSERT_EQUAL(c.fluid[0].x1, 1.0);
  CU_ASSERT_EQUAL(c.fluid[0].y0, 0.0);
  CU_ASSERT_EQUAL(c.fluid[0].y1, 0.5);
  CU_ASSERT_EQUAL(c.fluid[0].vx, 0.0);
  CU_ASSERT_EQUAL(c.fluid[0].vy, 0.0);
  CU_ASSERT_EQUAL(c.fluid[0].hydrostatic, 1);
  CU_ASSERT_EQUAL(c.fluid[0].surface, 0.5);
  CU_ASSERT_EQUAL(c.n_walls, 0);
  CU_ASSERT_PTR_NULL(c.walls);
  CU_ASSERT_EQUAL(c.domain_set, 0);
  CU_ASSERT_EQUAL(c.snapshots, 1);
  sph_case_free(&c);
  CU_ASSERT(is_empty(&c));
}

static void test_full_case(void) {
  sph_case c;
  expect_ok(FULL, NULL, 0, &c);
  CU_ASSERT_STRING_EQUAL(c.name, "martin_moyce");
  CU_ASSERT_STRING_EQUAL(c.description, "Dam break");
  CU_ASSERT_EQUAL(c.rho0, 998.0);
  CU_ASSERT_EQUAL(c.sound_speed, 10.0 * sqrt(2.0 * 9.81 * 0.1143));
  CU_ASSERT_EQUAL(c.alpha, 0.3);
  CU_ASSERT_EQUAL(c.beta, 0.1);
  CU_ASSERT_EQUAL(c.eta, 0.2);
  CU_ASSERT_EQUAL(c.xsph, 0.5);
  CU_ASSERT_EQUAL(c.dx, 0.001143);
  CU_ASSERT_EQUAL(c.h_factor, 1.5);
  CU_ASSERT_EQUAL(c.h, 1.5 * 0.001143);
  CU_ASSERT_EQUAL(c.dt_rule, SPH_DT_CFL);
  CU_ASSERT_EQUAL(c.dt_factor, 0.25);
  CU_ASSERT_EQUAL(c.density_limit, 0.2);
  CU_ASSERT_EQUAL(c.t_end, 0.5);
  CU_ASSERT_EQUAL(c.output_interval, 0.01);
  CU_ASSERT_EQUAL(c.stop, SPH_STOP_FRONT_AT_WALL);
  CU_ASSERT_EQUAL(c.tank.present, 1);
  CU_ASSERT_EQUAL(c.tank.x0, 0.0);
  CU_ASSERT_EQUAL(c.tank.x1, 0.2286);
  CU_ASSERT_EQUAL(c.tank.y0, 0.0);
  CU_ASSERT_EQUAL(c.tank.y1, 0.2);
  CU_ASSERT_EQUAL(c.tank.layers, 3);
  CU_ASSERT_EQUAL(c.tank.boundary, SPH_BOUNDARY_DYNAMIC);
  CU_ASSERT_EQUAL_FATAL(c.n_fluid, 2);
  CU_ASSERT_EQUAL(c.fluid[0].x1, 0.05715);
  CU_ASSERT_EQUAL(c.fluid[0].y1, 0.1143);
  CU_ASSERT_EQUAL(c.fluid[0].vx, 0.5);
  CU_ASSERT_EQUAL(c.fluid[0].vy, -0.25);
  CU_ASSERT_EQUAL(c.fluid[0].hydrostatic, 0);
  CU_ASSERT_EQUAL(c.fluid[0].surface, 0.12);
  CU_ASSERT_EQUAL(c.fluid[1].x0, 0.1);
  CU_ASSERT_EQUAL(c.fluid[1].hydrostatic, 1);
  CU_ASSERT_EQUAL(c.fluid[1].surface, 0.01);
  CU_ASSERT_EQUAL_FATAL(c.n_walls, 1);
  CU_ASSERT_EQUAL(c.walls[0].x0, 0.1);
  CU_ASSERT_EQUAL(c.walls[0].y0, 0.0);
  CU_ASSERT_EQUAL(c.walls[0].x1, 0.1);
  CU_ASSERT_EQUAL(c.walls[0].y1, 0.05);
  CU_ASSERT_EQUAL(c.walls[0].layers, 1);
  CU_ASSERT_EQUAL(c.domain_set, 1);
  CU_ASSERT_EQUAL(c.domain[0], -0.01);
  CU_ASSERT_EQUAL(c.domain[1], 0.24);
  CU_ASSERT_EQUAL(c.domain[2], -0.01);
  CU_ASSERT_EQUAL(c.domain[3], 0.5);
  CU_ASSERT_EQUAL(c.snapshots, 0);
  sph_case_free(&c);
}

static void test_sound_speed(void) {
  sph_case c;
  /* factor and height: c0 = factor sqrt(2 |g| height), with |g| the length of g */
  expect_ok(edit(MINIMAL, 3, "  sound_speed: {factor: 10, height: 0.1143}\n"), NULL, 0, &c);
  CU_ASSERT_DOUBLE_EQUAL(c.sound_speed, 14.97519949783642, 1e-12);
  sph_case_free(&c);
  expect_ok(
      edit(MINIMAL, 3, "  gravity: [3, -4]\n  sound_speed:\n    factor: 2\n    height: 0.4\n"),
      NULL, 0, &c);
  CU_ASSERT_DOUBLE_EQUAL(c.sound_speed, 4.0, 1e-15); /* 2 sqrt(2 * 5 * 0.4) */
  sph_case_free(&c);
  expect_ok(edit(MINIMAL, 3, "  sound_speed: {factor: 10, speed: 1.5}\n"), NULL, 0, &c);
  CU_ASSERT_EQUAL(c.sound_speed, 15.0);
  sph_case_free(&c);

  /* a gravity beyond what a run holds is the gravity's fault, not the sound
   * speed's (issue 61, E12) */
  expect_err(edit(MINIMAL, 3, "  gravity: [0, -1e308]\n  sound_speed: {factor: 10, height: 0.1}\n"),
             "t.yaml:3: physics.gravity: expected an acceleration of at most 1e+06 m/s^2, got "
             "[0, -1e+308]");
  expect_err(edit(MINIMAL, 3, "  sound_speed: {factor: 10, height: 1, speed: 1}\n"),
             "t.yaml:3: physics.sound_speed: give either 'height' or 'speed', not both");
  expect_err(edit(MINIMAL, 3, "  sound_speed: {factor: 10}\n"),
             "t.yaml:3: physics.sound_speed: expected 'height' (c0 = factor*sqrt(2|g|*height)) "
             "or 'speed' (c0 = factor*speed) next to 'factor'");
  expect_err(edit(MINIMAL, 3, "  sound_speed: {height: 0.1}\n"),
             "t.yaml:3: physics.sound_speed.factor: required key is missing");
  expect_err(edit(MINIMAL, 3, "  sound_speed: {factor: 0, speed: 1}\n"),
             "t.yaml:3: physics.sound_speed.factor: expected a positive number, got '0'");
  expect_err(edit(MINIMAL, 3, "  gravity: [0, 0]\n  sound_speed: {factor: 10, height: 0.1}\n"),
             "t.yaml:4: physics.sound_speed.height: c0 = factor*sqrt(2|g|*height) needs a "
             "non-zero physics.gravity");
  expect_err(edit(MINIMAL, 3, "  sound_speed: {factor: 1, velocity: 1}\n"),
             "t.yaml:3: physics.sound_speed.velocity: unknown key (valid keys in "
             "'physics.sound_speed': factor, height, speed)");
  expect_err(edit(MINIMAL, 3, "  sound_speed: fast\n"),
             "t.yaml:3: physics.sound_speed: expected a positive number or a mapping "
             "{factor, height} or {factor, speed}, got 'fast'");
  expect_err(edit(MINIMAL, 3, "  rho0: 1000\n"),
             "t.yaml:3: physics.sound_speed: required key is missing");
}

/* numerics.scheme (src/case/presets.c): the default riemann, read before
 * the other keys; each of its keys the case leaves out takes its value, each
 * it gives keeps its own (the table's keys are the unit: a mapping the case
 * gives is its own whole), and the start-up listing names those. */
static void test_schemes(void) {
  const char *tank = "geometry:\n  tank: {x: [0, 2], y: [0, 1]}\n";
  char text[8192];
  sph_case c, d;
  snprintf(text, sizeof text, "%s", edit(MINIMAL, 9, tank));
  expect_ok(text, NULL, 0, &c); /* no scheme: the default */
  CU_ASSERT_EQUAL(c.scheme, SPH_SCHEME_RIEMANN);
  CU_ASSERT_EQUAL(c.riemann, 1);
  CU_ASSERT_EQUAL(c.riemann_limiter, 3.0);
  CU_ASSERT_EQUAL(c.alpha, 0.0);
  CU_ASSERT_EQUAL(c.xsph, 0.0);
  CU_ASSERT_EQUAL(c.diffusion, SPH_DIFFUSION_NONE);
  CU_ASSERT_EQUAL(c.viscosity, SPH_VISCOSITY_NONE);
  CU_ASSERT_EQUAL(c.kernel, SPH_KERNEL_WENDLAND_C2);
  CU_ASSERT_EQUAL(c.h_factor, 2.0);
  CU_ASSERT_EQUAL(c.h, 2.0 * c.dx);
  CU_ASSERT_EQUAL(c.dt_rule, SPH_DT_CFL);
  CU_ASSERT_EQUAL(c.tank.boundary, SPH_BOUNDARY_ADAMI);
  CU_ASSERT_EQUAL(c.tank.layers, 4); /* as many as fill the support 2h = 4 dx */
  CU_ASSERT_EQUAL(c.tank.stagger, 0);
  CU_ASSERT_STRING_EQUAL(c.scheme_kept, ""); /* the case gives none of the scheme's keys */
  char *s = sph_case_describe(&c);
  CU_ASSERT_PTR_NOT_NULL(s && strstr(s, "numerics.scheme: riemann\n"));
  free(s);
  /* the same case written out key by key under another scheme is the same case */
  const char *keys[] = {"numerics.scheme=paper_b",
                        "physics.riemann={limiter: 3}",
                        "physics.artificial_viscosity.alpha=0",
                        "physics.xsph=0",
                        "physics.viscosity={model: none}",
                        "numerics.density_diffusion={model: none}",
                        "numerics.kernel=wendland_c2",
                        "numerics.h_factor=2",
                        "numerics.time_step.rule=cfl",
                        "geometry.tank.boundary=adami"};
  expect_ok(text, keys, 10, &d);
  CU_ASSERT_EQUAL(d.scheme, SPH_SCHEME_PAPER_B);
  CU_ASSERT_EQUAL(d.riemann, c.riemann);
  CU_ASSERT_EQUAL(d.alpha, c.alpha);
  CU_ASSERT_EQUAL(d.kernel, c.kernel);
  CU_ASSERT_EQUAL(d.h, c.h);
  CU_ASSERT_EQUAL(d.dt_rule, c.dt_rule);
  CU_ASSERT_EQUAL(d.tank.boundary, c.tank.boundary);
  CU_ASSERT_EQUAL(d.tank.layers, c.tank.layers);
  CU_ASSERT_EQUAL(d.tank.stagger, c.tank.stagger);
  CU_ASSERT_STRING_EQUAL(d.scheme_kept,
                         "physics.riemann, physics.artificial_viscosity.alpha, physics.xsph, "
                         "physics.viscosity, numerics.density_diffusion, numerics.kernel, "
                         "numerics.h_factor, numerics.time_step.rule, geometry.tank.boundary");
  sph_case_free(&c);
  sph_case_free(&d);
  /* the papers' base: the plain pressure, the cubic spline at 1.3 dx, paper B's rule, dynamic
   * walls (the built-in defaults of every key) */
  const char *paper[] = {"numerics.scheme=paper_a"};
  expect_ok(text, paper, 1, &c);
  CU_ASSERT_EQUAL(c.scheme, SPH_SCHEME_PAPER_A);
  CU_ASSERT_EQUAL(c.riemann, 0);
  CU_ASSERT_EQUAL(c.kernel, SPH_KERNEL_CUBIC_SPLINE);
  CU_ASSERT_EQUAL(c.h_factor, 1.3);
  CU_ASSERT_EQUAL(c.dt_rule, SPH_DT_PAPER_B);
  CU_ASSERT_EQUAL(c.tank.boundary, SPH_BOUNDARY_DYNAMIC);
  CU_ASSERT_EQUAL(c.tank.layers, 2);
  s = sph_case_describe(&c);
  CU_ASSERT_PTR_NOT_NULL(s && strstr(s, "numerics.scheme: paper_a\n"));
  free(s);
  sph_case_free(&c);
  /* delta-SPH, and the case's own keys over the scheme's */
  const char *set[] = {"numerics.scheme=delta_sph"};
  expect_ok(text, set, 1, &c);
  CU_ASSERT_EQUAL(c.scheme, SPH_SCHEME_DELTA_SPH);
  CU_ASSERT_EQUAL(c.riemann, 0);
  CU_ASSERT_EQUAL(c.alpha, 0.02);
  CU_ASSERT_EQUAL(c.diffusion, SPH_DIFFUSION_ANTUONO);
  CU_ASSERT_EQUAL(c.diffusion_delta, 0.1);
  CU_ASSERT_EQUAL(c.viscosity, SPH_VISCOSITY_MORRIS);
  CU_ASSERT_EQUAL(c.mu, 1.0e-3);
  CU_ASSERT_EQUAL(c.tank.boundary, SPH_BOUNDARY_MDBC);
  sph_case_free(&c);
  const char *own[] = {"numerics.scheme=delta_sph", "physics.artificial_viscosity.alpha=0.1",
                       "physics.viscosity={model: morris, mu: 0.002}",
                       "numerics.density_diffusion={model: antuono, delta: 0.2}",
                       "geometry.tank.boundary=dynamic"};
  expect_ok(text, own, 5, &c);
  CU_ASSERT_EQUAL(c.alpha, 0.1);
  CU_ASSERT_EQUAL(c.viscosity, SPH_VISCOSITY_MORRIS);
  CU_ASSERT_EQUAL(c.mu, 0.002);
  CU_ASSERT_EQUAL(c.diffusion, SPH_DIFFUSION_ANTUONO);
  CU_ASSERT_EQUAL(c.diffusion_delta, 0.2);
  CU_ASSERT_EQUAL(c.tank.boundary, SPH_BOUNDARY_DYNAMIC);
  /* the start-up listing names them, in the table's order: a mixture is never silent */
  CU_ASSERT_STRING_EQUAL(c.scheme_kept, "physics.artificial_viscosity.alpha, physics.viscosity, "
                                        "numerics.density_diffusion, geometry.tank.boundary");
  sph_case_free(&c);
  /* no tank: none is made for the scheme's wall model; physics.riemann: off */
  const char *off[] = {"physics.riemann=off"};
  expect_ok(MINIMAL, off, 1, &c);
  CU_ASSERT_EQUAL(c.tank.present, 0);
  CU_ASSERT_EQUAL(c.riemann, 0);
  CU_ASSERT_STRING_EQUAL(c.scheme_kept, "physics.riemann");
  sph_case_free(&c);
  expect_err(edit(MINIMAL, 3, "  sound_speed: 20\n  riemann: 3\n"),
             "t.yaml:4: physics.riemann: expected a mapping {limiter: ...} (the Riemann-solver "
             "pressure) or off, got '3'");
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n  scheme: sphysics\n"),
             "t.yaml:6: numerics.scheme: unknown choice 'sphysics' (valid: riemann, paper_a, "
             "paper_b, delta_sph)");
}

/* doc/method.md's table of the schemes is the presets' table: a row per key in the table's
 * order, a column per scheme, each cell the value as a case writes it. */
static void test_schemes_doc(void) {
  char *doc = sph_test_read_file(sph_test_src("doc/method.md"), NULL);
  CU_ASSERT_FATAL(doc != NULL);
  const char *t = strstr(doc, "| key | `riemann` (default) |");
  CU_ASSERT_FATAL(t != NULL);
  size_t n;
  const sph_preset *all = sph_presets(&n);
  char head[512] = "| key |";
  for (size_t k = 0; k < n; k++)
    snprintf(head + strlen(head), sizeof head - strlen(head), " `%s`%s |", all[k].name,
             k == 0 ? " (default)" : "");
  CU_ASSERT(strncmp(t, head, strlen(head)) == 0);
  const char *line = strchr(t, '\n') + 1;
  line = strchr(line, '\n') + 1; /* the |---| row */
  int rows = 0;
  for (size_t r = 0; r < SPH_PRESET_KEYS; r++) {
    char want[1024];
    snprintf(want, sizeof want, "| `%s` |", all[0].keys[r].key);
    for (size_t k = 0; k < n; k++) {
      CU_ASSERT_STRING_EQUAL(all[k].keys[r].key, all[0].keys[r].key); /* the same keys */
      snprintf(want + strlen(want), sizeof want - strlen(want), " `%s` |", all[k].keys[r].value);
    }
    const size_t len = strcspn(line, "\n");
    if (len != strlen(want) || strncmp(line, want, len) != 0)
      printf("\n  doc/method.md: %.*s\n  want:          %s", (int)len, line, want);
    else
      rows++;
    line += len + 1;
  }
  CU_ASSERT_EQUAL(rows, SPH_PRESET_KEYS);
  free(doc);
}

static void test_time_step_rules(void) {
  sph_case c;
  expect_ok(edit(MINIMAL, 5, "  dx: 0.01\n  time_step: {rule: fixed, dt: 1.0e-4}\n"), NULL, 0, &c);
  CU_ASSERT_EQUAL(c.dt_rule, SPH_DT_FIXED);
  CU_ASSERT_EQUAL(c.dt_fixed, 1.0e-4);
  CU_ASSERT_EQUAL(c.dt_factor, 0.3);
  sph_case_free(&c);
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n  time_step:\n    rule: fixed\n"),
             "t.yaml:7: numerics.time_step.dt: required key is missing (rule 'fixed' needs it)");
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n  time_step:\n    dt: 0.001\n"),
             "t.yaml:7: numerics.time_step.dt: only allowed with rule: fixed (the rule is "
             "'cfl')");
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n  time_step: {rule: cfl, factor: 0}\n"),
             "t.yaml:6: numerics.time_step.factor: expected a number in (0, 1], got '0'");
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n  time_step: {rule: adaptive}\n"),
             "t.yaml:6: numerics.time_step.rule: unknown choice 'adaptive' (valid: paper_b, cfl, "
             "fixed)");
}

static void test_load_file(void) {
  char *dir = sph_test_tmpdir();
  char path[4200];
  snprintf(path, sizeof path, "%s/ok.yaml", dir);
  FILE *f = fopen(path, "wb");
  CU_ASSERT_PTR_NOT_NULL_FATAL(f);
  fputs(FULL, f);
  fclose(f);
  sph_case c;
  sph_error e = {{0}};
  const char *set[] = {"numerics.dx=0.002", "time.end=2"};
  CU_ASSERT_EQUAL(sph_case_load(path, set, 2, &c, &e), 0);
  CU_ASSERT_STRING_EQUAL(c.path, path);
  CU_ASSERT_STRING_EQUAL(c.text, FULL);
  CU_ASSERT_STRING_EQUAL(c.overrides, "numerics.dx=0.002\ntime.end=2");
  CU_ASSERT_EQUAL(c.dx, 0.002);
  CU_ASSERT_EQUAL(c.t_end, 2.0);
  sph_case_free(&c);
  sph_test_rmtree(dir);
  free(dir);
}

/* ---- errors --------------------------------------------------------------- */

static void test_unknown_key(void) {
  char want[512];
  snprintf(want, sizeof want,
           "t.yaml:4: physics.viscosty: unknown key (valid keys in 'physics': %s)", PHYSICS_KEYS);
  expect_err(edit(MINIMAL, 3, "  sound_speed: 20\n  viscosty: 0.1\n"), want);
  snprintf(want, sizeof want, "t.yaml:13: foo: unknown key (valid top-level keys: %s)", TOP_KEYS);
  expect_err(edit(MINIMAL, 12, "      y: [0, 0.5]\nfoo: 1\n"), want);
  expect_err(
      edit(MINIMAL, 12, "      y: [0, 0.5]\n      colour: blue\n"),
      "t.yaml:13: geometry.fluid[0].colour: unknown key (valid keys in "
      "'geometry.fluid[0]': x, y, polygon, circle, velocity, hydrostatic, surface, jitter, seed)");
}

static void test_wrong_type(void) {
  expect_err(edit(MINIMAL, 5, "  dx: {a: 1}\n"),
             "t.yaml:5: numerics.dx: expected a positive number, got a mapping");
  expect_err(edit(MINIMAL, 5, "  dx: abc\n"),
             "t.yaml:5: numerics.dx: expected a positive number, got 'abc'");
  expect_err(edit(MINIMAL, 5, "  dx: \"0.01\"\n"),
             "t.yaml:5: numerics.dx: expected a positive number, got the string '0.01'");
  expect_err(edit(MINIMAL, 5, "  dx: [0.01]\n"),
             "t.yaml:5: numerics.dx: expected a positive number, got a list of 1 item");
  expect_err(edit(MINIMAL, 5, "  dx:\n"),
             "t.yaml:5: numerics.dx: expected a positive number, got nothing");
  expect_err(edit(edit(MINIMAL, 5, ""), 4, "numerics: 3\n"),
             "t.yaml:4: numerics: expected a mapping, got '3'");
  expect_err(edit(edit(edit(MINIMAL, 12, ""), 11, ""), 10, "  fluid: {x: 1}\n"),
             "t.yaml:10: geometry.fluid: expected a non-empty list of mappings, got a mapping");
  expect_err(edit(edit(edit(MINIMAL, 12, ""), 11, ""), 10, "  fluid: []\n"),
             "t.yaml:10: geometry.fluid: expected a non-empty list of mappings, got an empty "
             "list");
  expect_err(edit(MINIMAL, 12, "      y: [0, 0.5]\n    - 7\n"),
             "t.yaml:13: geometry.fluid[1]: expected a mapping, got '7'");
  expect_err(edit(MINIMAL, 12, "      y: [0, 0.5]\n      hydrostatic: yes\n"),
             "t.yaml:13: geometry.fluid[0].hydrostatic: expected true or false, got 'yes'");
  expect_err(edit(MINIMAL, 1, "name: two words\n"),
             "t.yaml:1: name: expected a name of 1 to 64 characters from [A-Za-z0-9_.-], got "
             "'two words'");
  expect_err(edit(MINIMAL, 1, "name: ..\n"),
             "t.yaml:1: name: expected a name with a character other than '.', got '..' "
             "(out/.. would be a directory that is already there)");
  expect_err(edit(MINIMAL, 1, "name: .\n"),
             "t.yaml:1: name: expected a name with a character other than '.', got '.' "
             "(out/. would be a directory that is already there)");
  expect_err(edit(MINIMAL, 1, "name: [a]\n"),
             "t.yaml:1: name: expected a name of 1 to 64 characters from [A-Za-z0-9_.-], got a "
             "list of 1 item");
  expect_err(edit(MINIMAL, 1, "name: mini\ndescription: {a: b}\n"),
             "t.yaml:2: description: expected a string, got a mapping");
  expect_err("- 1\n- 2\n", "t.yaml:1: expected a mapping of case keys at the top level, got a "
                           "list of 2 items");
  expect_err("", "t.yaml:1: expected a mapping of case keys at the top level, got nothing");
}

static void test_bad_lists(void) {
  expect_err(edit(MINIMAL, 3, "  gravity: [0, -9.81, 1]\n  sound_speed: 20\n"),
             "t.yaml:3: physics.gravity: expected a list of 2 numbers, got a list of 3 items");
  expect_err(edit(MINIMAL, 3, "  gravity: -9.81\n  sound_speed: 20\n"),
             "t.yaml:3: physics.gravity: expected a list of 2 numbers, got '-9.81'");
  expect_err(edit(MINIMAL, 3, "  gravity:\n    - 0\n    - down\n  sound_speed: 20\n"),
             "t.yaml:5: physics.gravity[1]: expected a number, got 'down'");
  expect_err(edit(MINIMAL, 11, "    - x: [1, 0]\n"),
             "t.yaml:11: geometry.fluid[0].x: expected [x0, x1] with x0 < x1, got [1, 0]");
  expect_err(edit(MINIMAL, 12, "      y: [0.5, 0.5]\n"),
             "t.yaml:12: geometry.fluid[0].y: expected [y0, y1] with y0 < y1, got [0.5, 0.5]");
  expect_err(edit(MINIMAL, 12, "      y: [0, 0.5]\n  walls:\n    - {from: [1, 2], to: [1, 2]}\n"),
             "t.yaml:14: geometry.walls[0].to: expected a point different from 'from', got "
             "[1, 2]");
  /* a wall shorter than dx (issue 39, D7): its particles would sit on one another */
  expect_err(
      edit(MINIMAL, 12, "      y: [0, 0.5]\n  walls:\n    - {from: [0, 0], to: [0, 1e-12]}\n"),
      "t.yaml:14: geometry.walls[0].to: the wall from [0, 0] is 1e-12 m long, shorter than "
      "numerics.dx = 0.01 m: expected a wall at least dx long");
  expect_err(edit(MINIMAL, 12, "      y: [0, 0.5]\n  walls: {from: [1, 2]}\n"),
             "t.yaml:13: geometry.walls: expected a list of mappings, got a mapping");
}

static void test_missing_key(void) {
  expect_err(edit(MINIMAL, 5, "  h_factor: 1.3\n"),
             "t.yaml:5: numerics.dx: required key is missing");
  expect_err(edit(edit(edit(MINIMAL, 8, ""), 7, ""), 6, ""),
             "t.yaml:1: time: required key is missing");
  expect_err(edit(MINIMAL, 1, "description: no name\n"), "t.yaml:1: name: required key is missing");
  expect_err(edit(MINIMAL, 11, "    - velocity: [0, 0]\n"),
             "t.yaml:11: geometry.fluid[0].x: required key is missing");
  expect_err(edit(MINIMAL, 5, ""), "t.yaml:4: numerics: expected a mapping, got nothing");
  expect_err(edit(MINIMAL, 10, "  tank: {x: [0, 1]}\n  fluid:\n"),
             "t.yaml:10: geometry.tank.y: required key is missing");
}

static void test_out_of_range(void) {
  expect_err(edit(MINIMAL, 5, "  dx: -1\n"),
             "t.yaml:5: numerics.dx: expected a positive number, got '-1'");
  expect_err(edit(MINIMAL, 5, "  dx: 0\n"),
             "t.yaml:5: numerics.dx: expected a positive number, got '0'");
  expect_err(edit(MINIMAL, 5, "  dx: nan\n"),
             "t.yaml:5: numerics.dx: expected a positive number, got 'nan'");
  expect_err(edit(MINIMAL, 5, "  dx: .inf\n"),
             "t.yaml:5: numerics.dx: expected a positive number, got '.inf'");
  expect_err(edit(MINIMAL, 5, "  dx: 1e999\n"),
             "t.yaml:5: numerics.dx: expected a positive number, got '1e999'");
  expect_err(edit(MINIMAL, 5, "  dx: 0x10\n"),
             "t.yaml:5: numerics.dx: expected a positive number, got '0x10'");
  expect_err(edit(MINIMAL, 5, "  dx: 0.01m\n"),
             "t.yaml:5: numerics.dx: expected a positive number, got '0.01m'");
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n  h_factor: 5\n"),
             "t.yaml:6: numerics.h_factor: expected a number in [0.5, 4], got '5'");
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n  density_limit: 1\n"),
             "t.yaml:6: numerics.density_limit: expected a number in (0, 1), got '1'");
  expect_err(edit(MINIMAL, 3, "  sound_speed: 20\n  xsph: 1.5\n"),
             "t.yaml:4: physics.xsph: expected a number in [0, 1], got '1.5'");
  expect_err(edit(MINIMAL, 3, "  sound_speed: 20\n  artificial_viscosity: {alpha: -0.1}\n"),
             "t.yaml:4: physics.artificial_viscosity.alpha: expected a number >= 0, got '-0.1'");
  expect_err(edit(MINIMAL, 8, "  output_interval: 2\n"),
             "t.yaml:8: time.output_interval: expected a number from time.end/100000 (1e-05, at "
             "most 100000 outputs) to time.end (1), got '2'");
  /* a huge end time: the output schedule (k * interval, k an integer) has
   * at most 100000 times, so it neither merges times nor hangs before the
   * first step (issue 21, D2: time.end=1e308 used to hang) */
  expect_err(edit(MINIMAL, 7, "  end: 1e308\n"),
             "t.yaml:8: time.output_interval: expected a number from time.end/100000 (1e+303, at "
             "most 100000 outputs) to time.end (1e+308), got '0.1'");
  /* a tiny interval would fill the disk with snapshots (issue 21, D7) */
  expect_err(edit(MINIMAL, 8, "  output_interval: 1e-12\n"),
             "t.yaml:8: time.output_interval: expected a number from time.end/100000 (1e-05, at "
             "most 100000 outputs) to time.end (1), got '1e-12'");
  expect_err(edit(MINIMAL, 10, "  tank: {x: [0, 1], y: [0, 1], layers: 9}\n  fluid:\n"),
             "t.yaml:10: geometry.tank.layers: expected an integer in 1..8, got '9'");
  expect_err(edit(MINIMAL, 10, "  tank: {x: [0, 1], y: [0, 1], layers: 2.0}\n  fluid:\n"),
             "t.yaml:10: geometry.tank.layers: expected an integer in 1..8, got '2.0'");
  expect_err(edit(MINIMAL, 12, "      y: [0, 0.5]\n      surface: 0.4\n"),
             "t.yaml:13: geometry.fluid[0].surface: expected a number >= the block's y1 (0.5), "
             "got '0.4'");
}

static void test_unknown_choice(void) {
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n  kernel: wendland\n"),
             "t.yaml:6: numerics.kernel: unknown choice 'wendland' (valid: cubic_spline, "
             "wendland_c2)");
  expect_err(
      edit(MINIMAL, 5, "  dx: 0.01\n  kernel: [cubic_spline]\n"),
      "t.yaml:6: numerics.kernel: expected one of: cubic_spline, wendland_c2, got a list of 1 "
      "item");
  expect_err(edit(MINIMAL, 8, "  output_interval: 0.1\n  stop: never\n"),
             "t.yaml:9: time.stop: unknown choice 'never' (valid: none, front_at_wall)");
  /* overlapping fluid blocks (issue 21, D5) */
  expect_err(edit(MINIMAL, 12, "      y: [0, 0.5]\n    - {x: [0.5, 1.5], y: [0.25, 1]}\n"),
             "t.yaml:13: geometry.fluid[1]: expected a block apart from geometry.fluid[0], got one "
             "that overlaps it in [0.5, 1] x [0.25, 0.5] (their particles would coincide)");
  sph_case c0;
  expect_ok(edit(MINIMAL, 12, "      y: [0, 0.5]\n    - {x: [1, 1.5], y: [0, 1]}\n"), NULL, 0,
            &c0); /* touching is not overlapping */
  sph_case_free(&c0);
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n  density_diffusion: {model: delta_sph}\n"),
             "t.yaml:6: numerics.density_diffusion.model: unknown choice 'delta_sph' (valid: none, "
             "molteni_colagrossi, antuono, fourtakas)");
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n  density_diffusion: {model: antuono, delta: 0}\n"),
             "t.yaml:6: numerics.density_diffusion.delta: expected a number in (0, 1], got '0'");
  /* a delta without a model, as a viscosity without one (issue 39, D8) */
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n  density_diffusion: {model: none, delta: 0.1}\n"),
             "t.yaml:6: numerics.density_diffusion.delta: only used with a density-diffusion "
             "model (model is 'none'; --set 'numerics.density_diffusion={model: none}' replaces "
             "the whole mapping)");
  /* without a model of its own, the message names the scheme whose default
   * it is (issue 61, E12) */
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n  density_diffusion: {delta: 0.1}\n"),
             "t.yaml:6: numerics.density_diffusion.delta: only used with a density-diffusion "
             "model (model is 'none', numerics.scheme riemann's: give the model; --set "
             "'numerics.density_diffusion={model: none}' replaces the whole mapping)");
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n  density_diffusion: {model: antuono, d: 0.1}\n"),
             "t.yaml:6: numerics.density_diffusion.d: unknown key (valid keys in "
             "'numerics.density_diffusion': model, delta)");
  sph_case c;
  expect_ok(edit(MINIMAL, 5, "  dx: 0.01\n  density_diffusion: {model: fourtakas, delta: 0.05}\n"),
            NULL, 0, &c);
  CU_ASSERT_EQUAL(c.diffusion, SPH_DIFFUSION_FOURTAKAS);
  CU_ASSERT_EQUAL(c.diffusion_delta, 0.05);
  sph_case_free(&c);
  /* particle shifting (src/physics/shifting.h) */
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n  shifting: {coefficient: 0}\n"),
             "t.yaml:6: numerics.shifting.coefficient: expected a number in (0, 10], got '0'");
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n  shifting: {A: 2}\n"),
             "t.yaml:6: numerics.shifting.A: unknown key (valid keys in 'numerics.shifting': "
             "coefficient)");
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n  shifting: true\n"),
             "t.yaml:6: numerics.shifting: expected a mapping, got 'true'");
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n  shifting: {}\n  smoothing_length: variable\n"),
             "t.yaml:6: numerics.shifting: cannot be combined with numerics.smoothing_length: "
             "variable");
  /* a c0 that overflows is blamed on the --set that gave it (issue 39, D8) */
  const char *huge[] = {"physics.sound_speed.factor=1e308"};
  expect_err_set(edit(MINIMAL, 3, "  sound_speed: {factor: 10, speed: 2}\n"), huge, 1,
                 "--set physics.sound_speed.factor=1e308: physics.sound_speed.factor: the "
                 "resulting c0 = 1e+308*2 is not finite");
  expect_err(edit(MINIMAL, 3, "  sound_speed: {factor: 1e308, speed: 2}\n"),
             "t.yaml:3: physics.sound_speed: the resulting c0 = 1e+308*2 is not finite");
  const char *mirror[] = {"geometry.tank={x: [0, 1], y: [0, 1], boundary: mirror}"};
  expect_err_set(edit(MINIMAL, 5, "  dx: 0.01\n  shifting: {}\n"), mirror, 1,
                 "t.yaml:6: numerics.shifting: needs wall particles to count the wall as full, and "
                 "mirror walls have none (use boundary: mdbc)");
  expect_ok(edit(MINIMAL, 5, "  dx: 0.01\n  shifting: {}\n"), NULL, 0, &c);
  CU_ASSERT_EQUAL(c.shifting, 1);
  CU_ASSERT_EQUAL(c.shifting_coefficient, SPH_SHIFTING_COEFFICIENT_DEFAULT);
  sph_case_free(&c);
  expect_ok(edit(MINIMAL, 5, "  dx: 0.01\n  shifting: {coefficient: 4}\n"), NULL, 0, &c);
  CU_ASSERT_EQUAL(c.shifting_coefficient, 4.0);
  sph_case_free(&c);
  expect_ok(MINIMAL, NULL, 0, &c);
  CU_ASSERT_EQUAL(c.shifting, 0);
  sph_case_free(&c);
  expect_ok(edit(MINIMAL, 5, "  dx: 0.01\n  kernel: \"cubic_spline\"\n"), NULL, 0, &c);
  CU_ASSERT_EQUAL(c.kernel, SPH_KERNEL_CUBIC_SPLINE);
  sph_case_free(&c);
}

static void test_cross_checks(void) {
  expect_err(edit(MINIMAL, 5, "  dx: 0.5\n"),
             "t.yaml:5: numerics.dx: expected a positive number smaller than the width (1) and "
             "height (0.5) of geometry.fluid[0], got '0.5'");
  expect_err(edit(MINIMAL, 8, "  output_interval: 0.1\n  stop: front_at_wall\n"),
             "t.yaml:9: time.stop: 'front_at_wall' needs a geometry.tank");
  expect_err(edit(MINIMAL, 10, "  tank: {x: [0, 0.8], y: [0, 1]}\n  fluid:\n"),
             "t.yaml:12: geometry.fluid[0].x: expected a range inside the tank's inner box [0, "
             "0.8], got [0, 1]");
  /* a box obstacle in 2-D: x and y; a z is refused */
  sph_case c;
  expect_ok(edit(MINIMAL, 10, "  obstacles: [{x: [0.2, 0.4], y: [0, 0.1], layers: 3}]\n  fluid:\n"),
            NULL, 0, &c);
  CU_ASSERT(c.n_obstacles == 1 && c.obstacles[0].hi[1] == 0.1 && c.obstacles[0].layers == 3);
  sph_case_free(&c);
  expect_err(
      edit(MINIMAL, 10, "  obstacles: [{x: [0.2, 0.4], y: [0, 0.1], z: [0, 1]}]\n  fluid:\n"),
      "t.yaml:10: geometry.obstacles[0].z: unknown key (valid keys in "
      "'geometry.obstacles[0]': x, y, polygon, circle, layers, boundary)");
  /* an obstacle inside the tank; its top may stand above the walls (issue 61, E11) */
  expect_err(edit(MINIMAL, 10,
                  "  tank: {x: [0, 1], y: [0, 1]}\n  obstacles: [{x: [1.2, 1.4], y: [0, 0.1]}]\n"
                  "  fluid:\n"),
             "t.yaml:11: geometry.obstacles[0].x: expected a range inside the tank's inner box [0, "
             "1], got [1.2, 1.4]");
  expect_err(edit(MINIMAL, 10,
                  "  tank: {x: [0, 1], y: [0, 1]}\n  obstacles: [{x: [0.2, 0.4], y: [-0.1, 0.1]}]\n"
                  "  fluid:\n"),
             "t.yaml:11: geometry.obstacles[0].y: expected a range inside the tank's inner box [0, "
             "1] (its top may stand above it), got [-0.1, 0.1]");
  expect_ok(edit(MINIMAL, 10,
                 "  tank: {x: [0, 1], y: [0, 1]}\n  obstacles: [{x: [0.6, 0.8], y: [0, 1.2]}]\n"
                 "  fluid:\n"),
            NULL, 0, &c);
  sph_case_free(&c);
  /* only x wraps in 2-D; a 2-D tank is never periodic */
  expect_err(edit(MINIMAL, 10, "  periodic_y: [0, 1]\n  fluid:\n"),
             "t.yaml:10: geometry.periodic_y: is 3-D only: a 2-D case is periodic in x only (y is "
             "up)");
  expect_err(edit(MINIMAL, 10, "  periodic_x: [0, 1]\n  tank: {x: [0, 1], y: [0, 1]}\n  fluid:\n"),
             "t.yaml:10: geometry.periodic_x: a periodic domain cannot have a tank (use "
             "geometry.walls for the bed)");
  expect_err(edit(MINIMAL, 10, "  periodic_x: [0, 0.05]\n  fluid:\n"),
             "t.yaml:10: geometry.periodic_x: expected a period of at least 4 h = 0.08 m, got "
             "0.05");
}

static void test_duplicate_key(void) {
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n  dx: 0.02\n"),
             "t.yaml:6: numerics.dx: duplicate key (first given at line 5)");
  expect_err(edit(MINIMAL, 12, "      y: [0, 0.5]\nphysics: {}\n"),
             "t.yaml:13: physics: duplicate key (first given at line 2)");
}

static void test_yaml_syntax(void) {
  expect_err(edit(MINIMAL, 5, "  dx: [0.01\n"),
             "t.yaml:6:5: YAML syntax error: did not find expected ',' or ']' (while parsing a "
             "flow sequence at line 5, column 7)");
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n   bad: 1\n"),
             "t.yaml:6:7: YAML syntax error: mapping values are not allowed in this context");
  expect_err(edit(MINIMAL, 5, "  dx: *a\n"),
             "t.yaml:5:7: YAML syntax error: found undefined alias");
  expect_err(edit(MINIMAL, 5, "  dx: &a 0.01\n  h_factor: *a\n"),
             "t.yaml:6: numerics.h_factor: aliases (*name) are not supported");
  expect_err(edit(MINIMAL, 5, "  dx: !!float 0.01\n"),
             "t.yaml:5: numerics.dx: tags such as 'tag:yaml.org,2002:float' are not supported");
  expect_err(edit(MINIMAL, 12, "      y: [0, 0.5]\n---\nname: again\n"),
             "t.yaml:14: only one YAML document is allowed");
  expect_err("name: \xff\n", "t.yaml:1:7: YAML syntax error: invalid leading UTF-8 octet");
}

/* Hostile inputs are refused before they cost time or memory (issue 21):
 * D6, nesting 100000 levels deep fails at once; D8, an endless file
 * (/dev/zero) and one over 1 MiB are refused; D12, a description over
 * 10000 characters (stored in every snapshot) is refused. */
static void test_bounded_input(void) {
  sph_case c;
  sph_error e = {{0}};
  const size_t deep = 100000;
  char *text = malloc(2 * deep + 64);
  CU_ASSERT_FATAL(text != NULL);
  if (!text) return; /* (CU_ASSERT_FATAL does; this says so to the compiler) */
  size_t n = (size_t)sprintf(text, "name: x\nphysics: ");
  memset(text + n, '[', deep);
  memset(text + n + deep, ']', deep);
  n += 2 * deep;
  text[n++] = '\n';
  const clock_t t0 = clock();
  CU_ASSERT(sph_case_parse(text, n, "d.yaml", NULL, 0, &c, &e) != 0);
  const double cpu = (double)(clock() - t0) / CLOCKS_PER_SEC;
  CU_ASSERT_STRING_EQUAL(e.msg, "d.yaml:2: nested deeper than 64 levels");
  printf("\n  100000 levels of nesting refused in %.3f s CPU", cpu);
  CU_ASSERT(cpu < 1.0); /* was 20 s, quadratic */
  sph_case_free(&c);
  free(text);
  FILE *z = fopen("/dev/zero", "rb");
  if (z) {
    fclose(z);
    CU_ASSERT(sph_case_load("/dev/zero", NULL, 0, &c, &e) != 0);
    CU_ASSERT_STRING_EQUAL(e.msg, "/dev/zero: the case file is larger than 1048576 bytes (1 MiB): "
                                  "not a case file");
    sph_case_free(&c);
  }
  char *dir = sph_test_tmpdir(), path[4200];
  snprintf(path, sizeof path, "%s/big.yaml", dir);
  FILE *f = fopen(path, "w");
  CU_ASSERT_FATAL(f != NULL);
  for (int k = 0; k < 40000; k++)
    fputs("# a comment line of some thirty bytes\n", f);
  fclose(f);
  CU_ASSERT(sph_case_load(path, NULL, 0, &c, &e) != 0);
  CU_ASSERT(strstr(e.msg, "larger than 1048576 bytes") != NULL);
  sph_case_free(&c);
  sph_test_rmtree(dir);
  free(dir);
  static char big[12000];
  char aaa[10002];
  memset(aaa, 'a', 10001);
  aaa[10001] = 0;
  const size_t first = (size_t)(strchr(MINIMAL, '\n') - MINIMAL) + 1;
  snprintf(big, sizeof big, "%.*sdescription: %s\n%s", (int)first, MINIMAL, aaa, MINIMAL + first);
  CU_ASSERT(sph_case_parse(big, strlen(big), "t.yaml", NULL, 0, &c, &e) != 0);
  CU_ASSERT_STRING_EQUAL(e.msg, "t.yaml:2: description: expected at most 10000 characters (it is "
                                "stored in every snapshot), got 10001");
  sph_case_free(&c);
}

static void test_missing_file(void) {
  sph_case c;
  sph_error e = {{0}};
  CU_ASSERT(sph_case_load("/nonexistent/dir/x.yaml", NULL, 0, &c, &e) != 0);
  CU_ASSERT_STRING_EQUAL(e.msg,
                         "/nonexistent/dir/x.yaml: cannot open the case file: No such file or "
                         "directory");
  CU_ASSERT(is_empty(&c));
  sph_case_free(&c);
  const char *dir = sph_test_src("tests/data");
  char want[4200];
  snprintf(want, sizeof want, "%s: cannot read the case file: Is a directory", dir);
  CU_ASSERT(sph_case_load(dir, NULL, 0, &c, &e) != 0);
  CU_ASSERT_STRING_EQUAL(e.msg, want);
  sph_case_free(&c);
}

/* The fixture's path followed by `tail`. */
static void expect_fixture(const char *rel, const char *tail) {
  sph_case c;
  sph_error e = {{0}};
  char want[4200];
  const char *path = sph_test_src(rel);
  snprintf(want, sizeof want, "%s%s", path, tail);
  CU_ASSERT(sph_case_load(path, NULL, 0, &c, &e) != 0);
  CU_ASSERT_STRING_EQUAL(e.msg, want);
  if (strcmp(e.msg, want) != 0) fprintf(stderr, "\n  want: %s\n  got:  %s\n", want, e.msg);
  CU_ASSERT(is_empty(&c));
  sph_case_free(&c);
}

static void test_fixture_files(void) {
  char tail[512];
  snprintf(tail, sizeof tail, ":5: physics.viscosty: unknown key (valid keys in 'physics': %s)",
           PHYSICS_KEYS);
  expect_fixture("tests/data/cases_bad/unknown_key.yaml", tail);
  expect_fixture("tests/data/cases_bad/syntax_error.yaml",
                 ":6:9: YAML syntax error: did not find expected ',' or ']' (while parsing a flow "
                 "sequence at line 5, column 12)");
  expect_fixture("tests/data/cases_bad/dx_too_large.yaml",
                 ":6: numerics.dx: expected a positive number smaller than the width (1) and "
                 "height (0.5) of geometry.fluid[0], got '0.6'");
  expect_fixture("tests/data/cases_bad/fluid_outside_tank.yaml",
                 ":18: geometry.fluid[1].x: expected a range inside the tank's inner box [0, 2], "
                 "got [1.5, 2.5]");
}

/* ---- overrides ------------------------------------------------------------ */

static void test_set_overrides(void) {
  sph_case c;
  const char *s1[] = {"numerics.dx=0.005", "numerics.dx=0.002"}; /* the last one wins */
  expect_ok(MINIMAL, s1, 2, &c);
  CU_ASSERT_EQUAL(c.dx, 0.002);
  CU_ASSERT_EQUAL(c.h, 2.0 * 0.002); /* the default scheme's h_factor */
  CU_ASSERT_STRING_EQUAL(c.overrides, "numerics.dx=0.005\nnumerics.dx=0.002");
  CU_ASSERT_STRING_EQUAL(c.text, MINIMAL); /* the file text is kept as written */
  sph_case_free(&c);

  const char *s2[] = {"physics.gravity=[0,-1]",      "time.stop=none",
                      "physics.xsph=0.25",           "output.snapshots=false",
                      "numerics.time_step.rule=cfl", "description=from the command line"};
  expect_ok(MINIMAL, s2, 6, &c);
  CU_ASSERT_EQUAL(c.gravity[0], 0.0);
  CU_ASSERT_EQUAL(c.gravity[1], -1.0);
  CU_ASSERT_EQUAL(c.stop, SPH_STOP_NONE);
  CU_ASSERT_EQUAL(c.xsph, 0.25);   /* added to an existing mapping */
  CU_ASSERT_EQUAL(c.snapshots, 0); /* added with a new intermediate mapping */
  CU_ASSERT_EQUAL(c.dt_rule, SPH_DT_CFL);
  CU_ASSERT_STRING_EQUAL(c.description, "from the command line");
  sph_case_free(&c);

  const char *s3[] = {"physics.sound_speed={factor: 10, speed: 2}"};
  expect_ok(MINIMAL, s3, 1, &c);
  CU_ASSERT_EQUAL(c.sound_speed, 20.0);
  sph_case_free(&c);
}

static void test_set_errors(void) {
  char want[512];
  const char *s1[] = {"numerics.dx=abc"};
  expect_err_set(MINIMAL, s1, 1,
                 "--set numerics.dx=abc: numerics.dx: expected a positive number, got 'abc'");
  const char *s2[] = {"physics.viscosty=1"};
  snprintf(want, sizeof want,
           "--set physics.viscosty=1: physics.viscosty: unknown key (valid keys in 'physics': %s)",
           PHYSICS_KEYS);
  expect_err_set(MINIMAL, s2, 1, want);
  const char *s3[] = {"nosuch.key=1"};
  snprintf(want, sizeof want, "--set nosuch.key=1: nosuch: unknown key (valid top-level keys: %s)",
           TOP_KEYS);
  expect_err_set(MINIMAL, s3, 1, want);
  const char *s4[] = {"numerics.dx"};
  expect_err_set(MINIMAL, s4, 1,
                 "--set numerics.dx: expected dotted.key=value (a key such as numerics.dx, then "
                 "'=', then a YAML value)");
  const char *s5[] = {"physics.gravity=[0,"};
  expect_err_set(MINIMAL, s5, 1,
                 "--set physics.gravity=[0,: physics.gravity: YAML syntax error in the value at "
                 "its end: did not find expected node content (while parsing a flow node)");
  const char *s6[] = {"physics.sound_speed.factor=10"};
  expect_err_set(MINIMAL, s6, 1,
                 "--set physics.sound_speed.factor=10: physics.sound_speed: is '20' (line 3), not "
                 "a mapping, so 'factor' cannot be set in it");
  const char *s7[] = {"numerics.time_step.rule=fixed"};
  expect_err_set(MINIMAL, s7, 1,
                 "--set numerics.time_step.rule=fixed: numerics.time_step.dt: required key is "
                 "missing (rule 'fixed' needs it)");
  const char *s8[] = {"physics.gravity=[0, -1, 2]"};
  expect_err_set(MINIMAL, s8, 1,
                 "--set physics.gravity=[0, -1, 2]: physics.gravity: expected a list of 2 "
                 "numbers, got a list of 3 items");
  const char *s9[] = {"numerics..dx=1"};
  expect_err_set(MINIMAL, s9, 1,
                 "--set numerics..dx=1: expected dotted.key=value (a key such as numerics.dx, "
                 "then '=', then a YAML value)");
  /* an override is validated even when the file itself is fine */
  const char *s10[] = {"numerics.dx=1"};
  expect_err_set(MINIMAL, s10, 1,
                 "--set numerics.dx=1: numerics.dx: expected a positive number smaller than the "
                 "width (1) and height (0.5) of geometry.fluid[0], got '1'");
}

/* ---- lifecycle and description -------------------------------------------- */

static void test_free_after_failure(void) {
  sph_case c;
  sph_error e;
  memset(&c, 0x5a, sizeof c); /* garbage in: the parser must not free it */
  CU_ASSERT(parse(edit(FULL, 47, "    y: [0.5, -0.01]\n"), NULL, 0, &c, &e) != 0);
  CU_ASSERT(is_empty(&c));
  sph_case_free(&c);
  sph_case_free(&c);
  sph_case_free(NULL);
  CU_ASSERT(is_empty(&c));
  /* and a NULL error is allowed */
  CU_ASSERT(parse("name: [", NULL, 0, &c, NULL) != 0);
  sph_case_free(&c);
}

static const char MINIMAL_DESCRIPTION[] = "name: mini\n"
                                          "description: \"\"\n"
                                          "physics.rho0: 1000\n"
                                          "physics.gravity: [0, -9.8100000000000005]\n"
                                          "physics.sound_speed: 20\n"
                                          "physics.artificial_viscosity.alpha: 0\n"
                                          "physics.artificial_viscosity.beta: 0\n"
                                          "physics.artificial_viscosity.eta: 0.10000000000000001\n"
                                          "physics.xsph: 0\n"
                                          "physics.negative_pressure: false\n"
                                          "physics.riemann.limiter: 3\n"
                                          "physics.viscosity.model: none\n"
                                          "physics.turbulence.model: none\n"
                                          "physics.repulsion: 24.525000000000002\n"
                                          "numerics.scheme: riemann\n"
                                          "numerics.dx: 0.01\n"
                                          "numerics.h_factor: 2\n"
                                          "numerics.h: 0.02\n"
                                          "numerics.smoothing_length: constant\n"
                                          "numerics.kernel: wendland_c2\n"
                                          "numerics.integrator: leapfrog\n"
                                          "numerics.time_step.rule: cfl\n"
                                          "numerics.time_step.factor: 0.29999999999999999\n"
                                          "numerics.density_filter.kind: none\n"
                                          "numerics.density_filter.every: 30\n"
                                          "numerics.density_diffusion.model: none\n"
                                          "numerics.density_diffusion.delta: 0.10000000000000001\n"
                                          "numerics.density_limit: 0.29999999999999999\n"
                                          "time.end: 1\n"
                                          "time.output_interval: 0.10000000000000001\n"
                                          "time.stop: none\n"
                                          "geometry.tank: none\n"
                                          "geometry.fluid[0].x: [0, 1]\n"
                                          "geometry.fluid[0].y: [0, 0.5]\n"
                                          "geometry.fluid[0].velocity: [0, 0]\n"
                                          "geometry.fluid[0].hydrostatic: true\n"
                                          "geometry.fluid[0].surface: 0.5\n"
                                          "geometry.fluid[0].jitter: 0\n"
                                          "geometry.fluid[0].seed: 1\n"
                                          "geometry.walls: []\n"
                                          "geometry.domain: none\n"
                                          "free_surface.radius_factor: 1\n"
                                          "free_surface.h_factor: 0\n"
                                          "output.snapshots: true\n"
                                          "output.free_surface: false\n"
                                          "output.energy: false\n";

static void test_describe(void) {
  sph_case a, b;
  expect_ok(MINIMAL, NULL, 0, &a);
  char *d = sph_case_describe(&a);
  CU_ASSERT_PTR_NOT_NULL_FATAL(d);
  CU_ASSERT_STRING_EQUAL(d, MINIMAL_DESCRIPTION);
  if (strcmp(d, MINIMAL_DESCRIPTION) != 0) fprintf(stderr, "\n%s", d);
  free(d);
  sph_case_free(&a);

  /* the same input twice gives the same bytes */
  expect_ok(FULL, NULL, 0, &a);
  expect_ok(FULL, NULL, 0, &b);
  char *d1 = sph_case_describe(&a), *d2 = sph_case_describe(&b);
  CU_ASSERT_PTR_NOT_NULL_FATAL(d1);
  CU_ASSERT_PTR_NOT_NULL_FATAL(d2);
  CU_ASSERT_STRING_EQUAL(d1, d2);
  char c0[128];
  snprintf(c0, sizeof c0, "\nphysics.sound_speed: %.17g\n", 10.0 * sqrt(2.0 * 9.81 * 0.1143));
  CU_ASSERT_PTR_NOT_NULL(strstr(d1, c0));
  CU_ASSERT_PTR_NOT_NULL(strstr(d1, "\nnumerics.h: 0.0017144999999999999\n"));
  CU_ASSERT_PTR_NOT_NULL(strstr(d1, "\ngeometry.fluid[0].x: [0, 0.057149999999999999]\n"));
  CU_ASSERT_PTR_NOT_NULL(strstr(d1, "\ngeometry.fluid[1].hydrostatic: true\n"));
  CU_ASSERT_PTR_NOT_NULL(strstr(d1, "\ngeometry.tank.layers: 3\n"));
  CU_ASSERT_PTR_NOT_NULL(strstr(d1, "\ngeometry.walls[0].to: [0.10000000000000001, "
                                    "0.050000000000000003]\n"));
  CU_ASSERT_PTR_NOT_NULL(strstr(d1, "\ngeometry.domain.y: [-0.01, 0.5]\n"));
  CU_ASSERT_PTR_NOT_NULL(strstr(d1, "\ntime.stop: front_at_wall\n"));
  CU_ASSERT_PTR_NOT_NULL(strstr(d1, "\noutput.snapshots: false\n"));
  free(d1);
  free(d2);
  sph_case_free(&a);
  sph_case_free(&b);

  /* a multi-line description stays on one line */
  expect_ok(edit(MINIMAL, 1, "name: mini\ndescription: |\n  two \"lines\"\n  here\n"), NULL, 0, &a);
  d = sph_case_describe(&a);
  CU_ASSERT_PTR_NOT_NULL(strstr(d, "\ndescription: \"two \\\"lines\\\"\\nhere\\n\"\n"));
  free(d);
  sph_case_free(&a);
}

/* physics.riemann: on by default (the default scheme's limiter 3), off with
 * `off`, on with its mapping (the default limiter 3), the limiter checked, and
 * in the description only when on. */
static void test_riemann(void) {
  sph_case c;
  expect_ok(MINIMAL, NULL, 0, &c);
  CU_ASSERT_EQUAL(c.riemann, 1);
  CU_ASSERT_EQUAL(c.riemann_limiter, 3.0);
  sph_case_free(&c);
  expect_ok(edit(MINIMAL, 3, "  sound_speed: 20\n  riemann: off\n"), NULL, 0, &c);
  CU_ASSERT_EQUAL(c.riemann, 0);
  char *d = sph_case_describe(&c);
  CU_ASSERT_PTR_NULL(strstr(d, "riemann.limiter"));
  free(d);
  sph_case_free(&c);
  expect_ok(edit(MINIMAL, 3, "  sound_speed: 20\n  riemann: {}\n"), NULL, 0, &c);
  CU_ASSERT_EQUAL(c.riemann, 1);
  CU_ASSERT_EQUAL(c.riemann_limiter, 3.0);
  sph_case_free(&c);
  const char *set[] = {"physics.riemann.limiter=1.5"};
  expect_ok(MINIMAL, set, 1, &c);
  CU_ASSERT_EQUAL(c.riemann, 1);
  CU_ASSERT_EQUAL(c.riemann_limiter, 1.5);
  d = sph_case_describe(&c);
  CU_ASSERT_PTR_NOT_NULL(strstr(d, "\nphysics.riemann.limiter: 1.5\n"));
  free(d);
  sph_case_free(&c);
  expect_err(edit(MINIMAL, 3, "  sound_speed: 20\n  riemann: {limiter: -1}\n"),
             "t.yaml:4: physics.riemann.limiter: expected a number >= 0, got '-1'");
  expect_err(
      edit(MINIMAL, 3, "  sound_speed: 20\n  riemann: {eta: 1}\n"),
      "t.yaml:4: physics.riemann.eta: unknown key (valid keys in 'physics.riemann': limiter)");
}

/* numerics.gradient_correction: off by default, a boolean, in the description only when on. */
static void test_corrected_gradient(void) {
  sph_case c;
  expect_ok(MINIMAL, NULL, 0, &c);
  CU_ASSERT_EQUAL(c.corrected_gradient, 0);
  char *d = sph_case_describe(&c);
  CU_ASSERT_PTR_NULL(strstr(d, "gradient_correction"));
  free(d);
  sph_case_free(&c);
  expect_ok(edit(MINIMAL, 5, "  dx: 0.01\n  gradient_correction: true\n"), NULL, 0, &c);
  CU_ASSERT_EQUAL(c.corrected_gradient, 1);
  d = sph_case_describe(&c);
  CU_ASSERT_PTR_NOT_NULL(strstr(d, "\nnumerics.gradient_correction: true\n"));
  free(d);
  sph_case_free(&c);
  const char *set[] = {"numerics.gradient_correction=false"};
  expect_ok(edit(MINIMAL, 5, "  dx: 0.01\n  gradient_correction: true\n"), set, 1, &c);
  CU_ASSERT_EQUAL(c.corrected_gradient, 0);
  sph_case_free(&c);
  /* not with walls whose particles do not tile the wall as the water's lattice does */
  const char *tank[] = {"geometry.tank={x: [0, 1], y: [0, 1], boundary: dynamic}"};
  expect_err_set(edit(MINIMAL, 5, "  dx: 0.01\n  gradient_correction: true\n"), tank, 1,
                 "t.yaml:6: numerics.gradient_correction: cannot be combined with staggered walls "
                 "(layers dx/2 apart count the wall's volume twice; give the tank and the walls "
                 "stagger: false)");
  const char *rep[] = {"geometry.tank={x: [0, 1], y: [0, 1], boundary: repulsive}"};
  expect_err_set(edit(MINIMAL, 5, "  dx: 0.01\n  gradient_correction: true\n"), rep, 1,
                 "t.yaml:6: numerics.gradient_correction: cannot be combined with repulsive walls "
                 "(their particles carry no pressure; use dynamic or mdbc walls)");
  const char *lattice[] = {
      "geometry.tank={x: [0, 1], y: [0, 1], boundary: dynamic, stagger: false}"};
  expect_ok(edit(MINIMAL, 5, "  dx: 0.01\n  gradient_correction: true\n"), lattice, 1, &c);
  CU_ASSERT_EQUAL(c.corrected_gradient, 1);
  sph_case_free(&c);
  expect_err(edit(MINIMAL, 5, "  dx: 0.01\n  gradient_correction: 1\n"),
             "t.yaml:6: numerics.gradient_correction: expected true or false, got '1'");
}

static void test_names(void) {
  CU_ASSERT_STRING_EQUAL(sph_kernel_name(SPH_KERNEL_CUBIC_SPLINE), "cubic_spline");
  CU_ASSERT_STRING_EQUAL(sph_integrator_name(SPH_INTEGRATOR_PREDICTOR_CORRECTOR),
                         "predictor_corrector");
  CU_ASSERT_STRING_EQUAL(sph_dt_rule_name(SPH_DT_PAPER_B), "paper_b");
  CU_ASSERT_STRING_EQUAL(sph_dt_rule_name(SPH_DT_CFL), "cfl");
  CU_ASSERT_STRING_EQUAL(sph_dt_rule_name(SPH_DT_FIXED), "fixed");
  CU_ASSERT_STRING_EQUAL(sph_boundary_name(SPH_BOUNDARY_DYNAMIC), "dynamic");
  CU_ASSERT_STRING_EQUAL(sph_stop_name(SPH_STOP_NONE), "none");
  CU_ASSERT_STRING_EQUAL(sph_stop_name(SPH_STOP_FRONT_AT_WALL), "front_at_wall");
  CU_ASSERT_STRING_EQUAL(sph_stop_name((sph_stop_kind)7), "unknown");
}

int main(void) {
  CU_TestInfo tests[] = {{"minimal case: every default", test_minimal_defaults},
                         {"complete case: every value", test_full_case},
                         {"sound speed: value, factor*height, factor*speed", test_sound_speed},
                         {"time step rules", test_time_step_rules},
                         {"numerics.scheme: defaults a case's keys override", test_schemes},
                         {"doc/method.md's table of the schemes is the presets'", test_schemes_doc},
                         {"load from a file with overrides", test_load_file},
                         {"unknown key", test_unknown_key},
                         {"wrong type", test_wrong_type},
                         {"bad lists", test_bad_lists},
                         {"missing required key", test_missing_key},
                         {"out of range", test_out_of_range},
                         {"unknown choice", test_unknown_choice},
                         {"cross-checks", test_cross_checks},
                         {"duplicate key", test_duplicate_key},
                         {"YAML syntax errors", test_yaml_syntax},
                         {"missing file", test_missing_file},
                         {"bounded input: nesting, size, description", test_bounded_input},
                         {"fixture files", test_fixture_files},
                         {"--set overrides", test_set_overrides},
                         {"--set errors", test_set_errors},
                         {"free after failure", test_free_after_failure},
                         {"describe", test_describe},
                         {"physics.riemann", test_riemann},
                         {"numerics.gradient_correction", test_corrected_gradient},
                         {"choice names", test_names},
                         CU_TEST_INFO_NULL};
  return sph_test_main("case", tests);
}
