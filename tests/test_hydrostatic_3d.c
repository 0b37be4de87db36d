/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_hydrostatic_3d.c - the 3-D build end to end at the library level
 * (built with -DSPH_DIM=3, linked with src/libsph3.la; doc/dimensions.md):
 * a case file with `dimension: 3` is read, its tank (a box of dynamic wall
 * particles, z up) and fluid block are made, and the run is stepped.
 *
 * - The case reader: a 3-D case reads (gravity (0, 0, -9.81) by default,
 *   the block's surface its z1), the listing says "dimension: 3"; a 2-D
 *   case, a gravity of two components and the keys that are 2-D only so far
 *   (a tank's or a wall's stagger, mirror obstacles and wall segments) are
 *   refused with the file, line and key; wave gauges are [x, y] pairs inside
 *   the domain; a wall segment is a plate across the flume (from and to in
 *   the x-z plane, y the tank's range unless given, a velocity of three
 *   components, a flap's hinge at its lower end); mdbc and repulsive
 * tanks and obstacles, free-slip, no-slip and mirror tanks read; sph_case_file_dimension reads the
 * dimension a --set gives.
 * - Still water 0.1 m deep in a 0.2 x 0.1 m tank at dx = 0.01 m (2000
 *   fluid particles) for 1 s, with the corrected gradient of
 *   tests/data/still_tank_3d.yaml (numerics.gradient_correction). The pressure
 *   as SPH reads a field (the particles' own pressure, layer by layer away
 *   from the side walls, less rho0 g (H - z)): inside the water (layers 2-8)
 *   and in the lowest layer within 1 % of rho0 g H on average, every layer
 *   within 3 % (plain WCSPH's odd-even pattern, test_hydrostatic). The
 *   floor sensor (a disc 20 mm across) within 1 % of rho0 g H on average
 *   over 0.05-1 s, at every step from 0.3 s on and at 1 s (the issue's
 *   target; +0.52 %, without the correction +1.85 %). The water stays at
 *   rest (|v| < 2 % of sqrt(g H)); no particle is lost, and its first
 *   0.3 s are the same bits on one and two threads.
 * - A wave gauge within dx of a periodic seam reads the particles across it
 *   (sph_diag_gauge_level): at y = 0.98 and 0.02 of a period [0, 1] each
 *   line alone reads 0.35 m, across the seam 0.65 m; away from the seam,
 *   or without a period, it is sph_diag_surface_at_xy's reading bit for bit.
 * - 3-D snapshots: a snapshot written at t = 0.2 s (leap-frog, so the
 *   restart record carries v_z's half step; the corrected gradient) holds z and v_z with its
 *   "dimension" 3, reads back bit for bit, its /vectors/position is n x 3
 *   and its XDMF index an XYZ geometry; a run restored from it ends at
 *   t = 0.3 s with the bits of the run that never stopped; the 2-D library
 *   refuses it (tests/test_snapshot: "a 3-D snapshot").
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "case/case.h"
#include "io/snapshot.h"
#include "solver/diag.h"
#include "solver/sim.h"
#include "testutil.h"
#include "walls/boundary.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#if SPH_DIM != 3
#error "test_hydrostatic_3d is built with -DSPH_DIM=3"
#endif

static const char *const CASE3 = "name: hydrostatic_3d\n"
                                 "dimension: 3\n"
                                 "physics:\n"
                                 "  rho0: 1000.0\n"
                                 "  sound_speed: {factor: 10, height: 0.1}\n"
                                 "  artificial_viscosity: {alpha: 0.1}\n"
                                 "numerics:\n"
                                 "  scheme: paper_b\n"
                                 "  dx: 0.01\n"
                                 "time:\n"
                                 "  end: 1.0\n"
                                 "  output_interval: 0.5\n"
                                 "geometry:\n"
                                 "  tank: {x: [0.0, 0.2], y: [0.0, 0.1], z: [0.0, 0.15]}\n"
                                 "  fluid:\n"
                                 "    - {x: [0.0, 0.2], y: [0.0, 0.1], z: [0.0, 0.1]}\n"
                                 "output: {snapshots: false}\n";

static int parse(const char *text, const char *const *set, size_t n_set, sph_case *c,
                 sph_error *err) {
  return sph_case_parse(text, strlen(text), "hydrostatic_3d.yaml", set, n_set, c, err);
}

/* The override `set` on CASE3 is refused, naming `key`. */
static void refused(const char *set, const char *key) {
  sph_case c;
  sph_error err;
  const char *const sets[1] = {set};
  const int rc = parse(CASE3, sets, 1, &c, &err);
  CU_ASSERT(rc != 0);
  if (rc == 0) {
    printf("\n    accepted: %s", set);
    sph_case_free(&c);
    return;
  }
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, key));
  printf("\n    %s -> %s", set, err.msg);
}

static void test_reader(void) {
  sph_case c;
  sph_error err;
  CU_ASSERT_FATAL(parse(CASE3, NULL, 0, &c, &err) == 0);
  CU_ASSERT_EQUAL(c.dimension, 3);
  CU_ASSERT_EQUAL(c.gravity[0], 0.0);
  CU_ASSERT_EQUAL(c.gravity[1], 0.0);
  CU_ASSERT_EQUAL(c.gravity[2], -9.81);
  CU_ASSERT_EQUAL(c.fluid[0].z1, 0.1);
  CU_ASSERT_EQUAL(c.fluid[0].surface, 0.1); /* the block's top along z */
  CU_ASSERT_EQUAL(c.tank.z1, 0.15);
  CU_ASSERT(c.est_fluid == 2000.0);
  char *d = sph_case_describe(&c);
  CU_ASSERT_PTR_NOT_NULL(d && strstr(d, "dimension: 3\n"));
  CU_ASSERT_PTR_NOT_NULL(d && strstr(d, "geometry.fluid[0].z: [0, 0.10000000000000001]\n"));
  free(d);
  sph_case_free(&c);
  /* wave gauges: vertical lines at (x, y) */
  const char *const gauges[1] = {"output.gauges=[[0.1, 0.05], [0.15, 0.02]]"};
  CU_ASSERT_FATAL(parse(CASE3, gauges, 1, &c, &err) == 0);
  CU_ASSERT(c.n_gauges == 2 && c.gauges[0] == 0.1 && c.gauges[1] == 0.05 && c.gauges[2] == 0.15 &&
            c.gauges[3] == 0.02);
  d = sph_case_describe(&c);
  CU_ASSERT_PTR_NOT_NULL(d && strstr(d, "output.gauges[1]: [0.14999999999999999, 0.02]\n"));
  free(d);
  sph_case_free(&c);
  refused("dimension=2", "dimension");
  refused("physics.gravity=[0, -9.81]", "physics.gravity");
  /* wall segments: plates across the flume, from and to in the x-z plane */
  const char *const plate[1] = {
      "geometry.walls=[{from: [0.05, 0.0], to: [0.05, 0.1], motion: {type: translate, "
      "velocity: [0.0, 0.0, 0.5], stop: 0.2}}, {from: [0.1, 0.0], to: [0.15, 0.05], y: [0.02, "
      "0.08], boundary: mdbc, motion: {type: flap, period: 1.0, stroke: 0.02, depth: 0.1}}]"};
  CU_ASSERT_FATAL(parse(CASE3, plate, 1, &c, &err) == 0);
  CU_ASSERT(c.n_walls == 2 && c.walls[0].x0 == 0.05 && c.walls[0].z0 == 0.0 &&
            c.walls[0].z1 == 0.1 && c.walls[0].y0 == c.tank.y0 && c.walls[0].y1 == c.tank.y1);
  CU_ASSERT(c.walls[0].motion.vx == 0.0 && c.walls[0].motion.vz == 0.5 && !c.walls[0].stagger);
  CU_ASSERT(c.walls[1].y0 == 0.02 && c.walls[1].y1 == 0.08 && c.walls[1].layers == 3);
  /* the flap's hinge: the lower end, (x, z) */
  CU_ASSERT(c.walls[1].motion.paddle.hinge_x == 0.1 && c.walls[1].motion.paddle.hinge_y == 0.0);
  d = sph_case_describe(&c);
  CU_ASSERT_PTR_NOT_NULL(d && strstr(d, "geometry.walls[1].y: [0.02, 0.080000000000000002]\n"));
  CU_ASSERT_PTR_NOT_NULL(d && strstr(d, "geometry.walls[0].motion.velocity: [0, 0, 0.5]\n"));
  free(d);
  sph_case_free(&c);
  refused("geometry.walls=[{from: [0.05, 0], to: [0.05, 0.1], motion: {type: translate, "
          "velocity: [0.1, 0]}}]",
          "geometry.walls[0].motion.velocity: expected a list of 3 numbers");
  refused("geometry.walls=[{from: [0.05, 0], to: [0.05, 0.1], stagger: true}]",
          "geometry.walls[0].stagger: is 2-D only so far");
  refused("geometry.walls=[{from: [0.05, 0], to: [0.05, 0.1], boundary: mirror}]",
          "geometry.walls[0].boundary: 'mirror' is 2-D only so far");
  refused("geometry.walls=[{from: [0.05, 0], to: [0.05, 0.1], y: [0.1, 0.0]}]",
          "geometry.walls[0].y");
  refused("output.gauges=[0.1]", "output.gauges[0]: expected a list of 2 numbers");
  refused("output.gauges=[[0.1, 0.05], [0.1, 9.0]]",
          "output.gauges[1]: y = 9 is outside the domain");
  refused("output.probes=[{name: P1, kind: pressure, at: [0.1, 0.05, 0.0]}]",
          "output.probes[0].normal"); /* a 3-D sensor needs its face's normal */
  refused("output.probes=[{name: P1, kind: pressure, at: [0.1, 0.0, 0.0], normal: [0, 0, 0]}]",
          "output.probes[0].normal");
  refused("output.probes=[{name: H1, kind: level, x: 0.1}]", "output.probes[0].x");
  refused("output.probes=[{name: P1, kind: pressure, at: [0.1, 0.05, 0.0], normal: [0, 0, 1], "
          "wetted: true}]",
          "output.probes[0].wetted"); /* a wire gauge is a level probe */
  refused("geometry.tank.stagger=false", "geometry.tank.stagger");
  refused("geometry.obstacles=[{x: [0.05, 0.1], y: [0.0, 0.05], z: [0.0, 0.05], "
          "boundary: mirror}]",
          "geometry.obstacles[0].boundary");
  refused("geometry.obstacles=[{x: [0.05, 0.1], y: [0.0, 0.05], z: [0.0, 0.05], "
          "boundary: repulsive, layers: 2}]",
          "geometry.obstacles[0].layers: repulsive walls have exactly 1 layer");
  /* walls with a normal: mdbc, free-slip; adami (the default scheme's tank); no-slip;
   * repulsive walls; a mirror tank; particle shifting */
  static const char *const normal[][2] = {
      {"geometry.tank.boundary=mdbc", "geometry.tank.free_slip=true"},
      {"numerics.scheme=riemann", "geometry.obstacles=[{x: [0.05, 0.1], y: [0.0, 0.05], "
                                  "z: [0.0, 0.05], boundary: mdbc}]"},
      {"physics.viscosity={model: stress_tensor, mu: 0.001}",
       "geometry.tank.extrapolated_velocity=true"},
      {"geometry.tank.boundary=repulsive", "geometry.obstacles=[{x: [0.05, 0.1], y: [0.0, 0.05], "
                                           "z: [0.0, 0.05], boundary: repulsive}]"},
      {"geometry.tank.boundary=mirror", "geometry.tank.boundary=mirror"},
      {"geometry.tank.boundary=mdbc", "numerics.shifting={coefficient: 2}"}};
  for (size_t k = 0; k < 6; k++) {
    const int rc = parse(CASE3, normal[k], 2, &c, &err);
    CU_ASSERT(rc == 0);
    if (rc) {
      printf("\n    %s", err.msg);
      continue;
    }
    static const sph_boundary_kind want[6] = {SPH_BOUNDARY_MDBC,    SPH_BOUNDARY_ADAMI,
                                              SPH_BOUNDARY_DYNAMIC, SPH_BOUNDARY_REPULSIVE,
                                              SPH_BOUNDARY_MIRROR,  SPH_BOUNDARY_MDBC};
    CU_ASSERT(c.tank.boundary == want[k]);
    CU_ASSERT(c.tank.free_slip == (k == 0) && c.tank.extrapolated == (k == 2));
    if (k == 3) CU_ASSERT(c.tank.layers == 1 && c.obstacles[0].layers == 1);
    if (k == 5) CU_ASSERT(c.shifting == 1 && c.shifting_coefficient == 2.0);
    sph_case_free(&c);
  }
  refused("geometry.tank={x: [0.0, 0.2], y: [0.0, 0.1], z: [0.0, 0.05]}",
          "geometry.fluid[0].z"); /* the block reaches above the tank */
  /* periodic along y (or x): the tank open along it, its range the period, whole dx */
  const char *const py[1] = {"geometry.periodic_y=[0.0, 0.1]"};
  CU_ASSERT_FATAL(parse(CASE3, py, 1, &c, &err) == 0);
  CU_ASSERT(c.periodic && c.periodic_axis == 1 && c.tank.open_along == 2);
  d = sph_case_describe(&c);
  CU_ASSERT_PTR_NOT_NULL(d && strstr(d, "geometry.periodic_y: [0, 0.10000000000000001]\n"));
  free(d);
  sph_case_free(&c);
  refused("geometry.periodic_y=[0.0, 0.09]", "geometry.periodic_y: expected the tank's y range");
  refused("geometry.periodic_z=[0.0, 0.15]", "geometry.periodic_z: a tank cannot be periodic");
  const char *const two_axes[2] = {"geometry.periodic_x=[0.0, 0.2]",
                                   "geometry.periodic_y=[0.0, 0.1]"};
  CU_ASSERT(parse(CASE3, two_axes, 2, &c, &err) != 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "expected one periodic axis"));
  const char *const half_dx[2] = {"geometry.tank.y=[0.0, 0.105]", "geometry.periodic_y=[0, 0.105]"};
  CU_ASSERT(parse(CASE3, half_dx, 2, &c, &err) != 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "whole number of numerics.dx"));
  printf("\n    %s", err.msg);
  /* the dimension a file says, with --set */
  char *dir = sph_test_tmpdir(), path[4200];
  snprintf(path, sizeof path, "%s/c.yaml", dir);
  FILE *f = fopen(path, "w");
  CU_ASSERT_FATAL(f != NULL);
  fputs(CASE3, f);
  fclose(f);
  int dim = 0;
  CU_ASSERT(sph_case_file_dimension(path, NULL, 0, &dim, &err) == 0 && dim == 3);
  const char *const two[1] = {"dimension=2"};
  CU_ASSERT(sph_case_file_dimension(path, two, 1, &dim, &err) == 0 && dim == 2);
  const char *const bad[1] = {"dimension=4"};
  CU_ASSERT(sph_case_file_dimension(path, bad, 1, &dim, &err) != 0);
  sph_test_rmtree(dir);
  free(dir);
}

/* The probes' readings at the end of the last run (run()). */
static double probe_read[4][3];
/* The floor sensor through the last run, in parts of rho0 g H: its mean over
 * 0.05-1 s, its largest |error| over 0.05-0.3 s (the start's acoustic
 * transient) and over 0.3-1 s. */
static double floor_mean, floor_start, floor_worst;

/* The floor sensor of tests/data/still_tank_3d.yaml: a disc 20 mm across at the centre, normal up.
 */
static sph_probe floor_sensor(void) {
  sph_probe q;
  memset(&q, 0, sizeof q);
  q.kind = SPH_PROBE_PRESSURE, q.x = 0.1, q.y = 0.05, q.z = 0.0, q.diameter = 0.02;
  q.normal[2] = 1.0;
  return q;
}

/* The still-water run's scheme: the corrected gradient of tests/data/still_tank_3d.yaml. */
static const char *const CORRECTED[1] = {"numerics.gradient_correction=true"};

/* The particles' state by id (x, y, z, vx, vy, vz, p: 7 per particle; p NaN for walls). */
static double *state_by_id(const sph_particles *p) {
  double *out = calloc(7 * p->n, sizeof *out);
  CU_ASSERT_FATAL(out != NULL);
  for (size_t i = 0; i < p->n; i++) {
    double *o = out + 7 * (size_t)p->id[i];
    for (int d = 0; d < 3; d++)
      o[d] = p->pos[d][i], o[3 + d] = p->vel[d][i];
    o[6] = p->kind[i] == SPH_KIND_FLUID ? p->p[i] : NAN;
  }
  return out;
}

/* Runs CASE3 with the corrected gradient to t = t_end (1 s: the floor sensor's statistics above
 * are this run's), stepping to t_mid exactly on the way (where 0 < t_mid < t_end); the particles'
 * state by id at t_end into out, at t_mid into mid (NULL: not wanted), their count into *n. */
static void run(double t_end, double t_mid, double **out, double **mid, size_t *n) {
  sph_case c;
  sph_error err;
  CU_ASSERT_FATAL(parse(CASE3, CORRECTED, 1, &c, &err) == 0);
  sph_sim *s = NULL;
  if (sph_sim_create(&c, &s, &err)) printf("\n    %s", err.msg);
  CU_ASSERT_FATAL(s != NULL);
  const sph_probe fs = floor_sensor();
  const double ref = c.rho0 * 9.81 * 0.1;
  double sum = 0.0;
  size_t count = 0;
  floor_start = floor_worst = 0.0;
  while (sph_sim_time(s) < t_end) {
    const double to = t_mid > 0.0 && sph_sim_time(s) < t_mid ? t_mid : t_end;
    const int rc = sph_sim_step(s, to, &err);
    if (rc) printf("\n    step: %s", err.msg);
    CU_ASSERT_FATAL(rc == 0);
    const double t = sph_sim_time(s);
    if (mid && t == t_mid) *mid = state_by_id(sph_sim_particles(s));
    if (t < 0.05) continue;
    double v;
    sph_probe_read(&fs, sph_sim_particles(s), c.kernel, c.h, c.dx, sph_sim_floor(s), c.gravity, &v);
    const double e = v / ref - 1.0;
    sum += e;
    count++;
    if (t < 0.3)
      floor_start = fmax(floor_start, fabs(e));
    else
      floor_worst = fmax(floor_worst, fabs(e));
  }
  floor_mean = sum / (double)count;
  sph_particles *p = sph_sim_particles(s);
  *n = p->n;
  *out = state_by_id(p);
  printf("\n    %zu particles, %ld steps", p->n, sph_sim_steps(s));
  /* the 3-D probes on the final state: a floor sensor (normal up, 20 mm), a
   * level gauge at the centre, a velocity probe mid-depth */
  sph_probe q[4];
  memset(q, 0, sizeof q);
  q[0] = floor_sensor();
  q[1].kind = SPH_PROBE_LEVEL, q[1].x = 0.1, q[1].y = 0.05;
  q[2].kind = SPH_PROBE_VELOCITY, q[2].x = 0.1, q[2].y = 0.05, q[2].z = 0.05;
  q[3] = q[1], q[3].wetted = 1; /* the same gauge as a wire: its wetted length */
  for (int k = 0; k < 4; k++)
    sph_probe_read(&q[k], p, c.kernel, c.h, c.dx, sph_sim_floor(s), c.gravity, probe_read[k]);
  sph_sim_free(s);
  sph_case_free(&c);
}

static void test_still_water(void) {
  double *a, *b, *mid = NULL;
  size_t n, m;
#ifdef _OPENMP
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1); /* (the state at 0.3 s is compared with two threads' below) */
#endif
  run(1.0, 0.3, &a, &mid, &n);
  CU_ASSERT_FATAL(mid != NULL);
  const double rho0 = 1000.0, g = 9.81, H = 0.1, dx = 0.01;
  double sum = 0.0, want = 0.0, vmax = 0.0, top = -INFINITY, bottom = INFINITY;
  size_t fluid = 0, floor_n = 0;
  double lp[10] = {0.0}, lw[10] = {0.0}; /* per layer: own pressure, rho0 g (H - z) */
  size_t ln[10] = {0};
  for (size_t k = 0; k < n; k++) {
    const double *o = a + 7 * k;
    if (isnan(o[6])) continue;
    fluid++;
    top = fmax(top, o[2]), bottom = fmin(bottom, o[2]);
    vmax = fmax(vmax, sqrt(o[3] * o[3] + o[4] * o[4] + o[5] * o[5]));
    /* away from the side walls, by layer */
    const long layer = (long)floor(o[2] / dx);
    if (layer < 0 || layer > 9 ||
        !(o[0] > 2.5 * dx && o[0] < 0.2 - 2.5 * dx && o[1] > 2.5 * dx && o[1] < 0.1 - 2.5 * dx))
      continue;
    lp[layer] += o[6];
    lw[layer] += rho0 * g * (H - o[2]);
    ln[layer]++;
  }
  double worst = 0.0, mean_inside = 0.0;
  printf("\n    layer: own pressure - rho0 g (H - z), %% of rho0 g H:");
  for (int l = 0; l < 10; l++) {
    const double e = (lp[l] - lw[l]) / (double)ln[l] / (rho0 * g * H);
    printf(" %+.2f", 100.0 * e);
    worst = fmax(worst, fabs(e));
    if (l >= 1 && l <= 7) mean_inside += e / 7.0;
  }
  printf("\n    inside (layers 2-8): mean %+.2f %%", 100.0 * mean_inside);
  sum = lp[0], want = lw[0], floor_n = ln[0];
  printf("\n    lowest layer: %zu particles, mean p %.2f Pa, rho0 g (H - z) %.2f Pa (%+.2f %%); "
         "max |v| %.3g m/s; fluid z from %.5f to %.5f",
         floor_n, sum / (double)floor_n, want / (double)floor_n, 100.0 * (sum / want - 1.0), vmax,
         bottom, top);
  CU_ASSERT_EQUAL(fluid, 2000);
  CU_ASSERT(floor_n >= 50);
  /* inside the water (above the lowest layer, below the two nearest the surface) on
   * average within the 1 %, and so the lowest layer; every layer, with plain
   * WCSPH's odd-even pattern (test_hydrostatic) and the free surface's uncorrected
   * gradient in the top two, within 3 %. */
  CU_ASSERT(fabs(mean_inside) < 0.01);
  CU_ASSERT(fabs(sum / want - 1.0) < 0.01);
  CU_ASSERT(worst < 0.03);
  CU_ASSERT(vmax < 0.02 * sqrt(g * H));
  /* the floor target, rho0 g H within 1 % at the floor's sensor over 1 s: on
   * average over 0.05-1 s and at every step after the start's acoustic transient (0.3 s;
   * during it 2.7 %), and at 1 s; without the corrected gradient the lattice's SPH gradient
   * leaves it at +1.85 % (doc/dimensions.md) */
  CU_ASSERT(fabs(floor_mean) < 0.01);
  CU_ASSERT(floor_worst < 0.01);
  CU_ASSERT(fabs(probe_read[0][0] / (rho0 * g * H) - 1.0) < 0.01);
  /* the level H within dx/2; the velocity at rest */
  printf("\n    floor sensor through the run: mean over 0.05-1 s %+.2f %%, largest |error| "
         "%.2f %% over 0.05-0.3 s, %.2f %% over 0.3-1 s",
         100.0 * floor_mean, 100.0 * floor_start, 100.0 * floor_worst);
  printf("\n    probes: floor %.2f Pa (%+.2f %% of rho0 g H), level %.5f m, |v| %.2g m/s",
         probe_read[0][0], 100.0 * (probe_read[0][0] / (rho0 * g * H) - 1.0), probe_read[1][0],
         fabs(probe_read[2][0]) + fabs(probe_read[2][1]) + fabs(probe_read[2][2]));
  CU_ASSERT(fabs(probe_read[1][0] - H) < 0.5 * dx);
  printf("\n    wetted level %.5f m (%+.2f %% of H)", probe_read[3][0],
         100.0 * (probe_read[3][0] / H - 1.0));
  CU_ASSERT(fabs(probe_read[3][0] - H) < 0.01 * H);
  CU_ASSERT(fabs(probe_read[2][0]) + fabs(probe_read[2][1]) + fabs(probe_read[2][2]) <
            0.02 * sqrt(g * H));
  free(a);
#ifdef _OPENMP
  /* the same bits on two threads as the run above on one (make check's), through the start's
   * acoustic transient (0.3 s, where the run above stopped on its way): the whole second on two
   * threads would add as much again to the test's time */
  omp_set_num_threads(2);
  run(0.3, 0.0, &b, NULL, &m);
  omp_set_num_threads(saved);
  CU_ASSERT_EQUAL(m, n);
  CU_ASSERT(m == n && memcmp(mid, b, 7 * n * sizeof *b) == 0);
  free(b);
#endif
  free(mid);
}

/* Steps s to t (the step reaching t exactly). */
static void step_to(sph_sim *s, double t) {
  sph_error err;
  while (sph_sim_time(s) < t) {
    const int rc = sph_sim_step(s, t, &err);
    if (rc) printf("\n    step: %s", err.msg);
    CU_ASSERT_FATAL(rc == 0);
  }
}

/* The state by id: x, y, z, vx, vy, vz, rho (7 per particle). */
static double *state(sph_sim *s) {
  sph_particles *p = sph_sim_particles(s);
  double *o = calloc(7 * p->n, sizeof *o);
  for (size_t i = 0; i < p->n; i++) {
    double *r = o + 7 * (size_t)p->id[i];
    for (int d = 0; d < 3; d++)
      r[d] = p->pos[d][i], r[3 + d] = p->vel[d][i];
    r[6] = p->rho[i];
  }
  return o;
}

/* A box obstacle: the reader (its keys, errors and listing), its particles (a shell two
 * points deep on the lattice inside the box, every one inside it, none twice), and still water
 * around a submerged box: the fluid the box displaces is removed at set-up (fluid-in-wall
 * removal), the box's particles start hydrostatic like the tank's, and after 0.3 s the water
 * is still at rest (|v| < 2 % of sqrt(g H)) with no particle lost. */
static void test_obstacle(void) {
  const char *const box[1] = {
      "geometry.obstacles=[{x: [0.06, 0.14], y: [0.02, 0.08], z: [0.0, 0.04]}]"};
  sph_case c;
  sph_error err;
  CU_ASSERT_FATAL(parse(CASE3, box, 1, &c, &err) == 0);
  CU_ASSERT_FATAL(c.n_obstacles == 1);
  const sph_obstacle *o = &c.obstacles[0];
  CU_ASSERT(o->lo[0] == 0.06 && o->hi[1] == 0.08 && o->hi[2] == 0.04 && o->layers == 2);
  CU_ASSERT_EQUAL(o->boundary, SPH_BOUNDARY_DYNAMIC);
  char *d = sph_case_describe(&c);
  CU_ASSERT_PTR_NOT_NULL(d && strstr(d, "geometry.obstacles[0].z: [0, 0.040000000000000001]\n"));
  free(d);
  /* the particles: 8 x 6 x 4 points, the 4 x 2 x 0 inside the shell left out */
  sph_particles q;
  CU_ASSERT_FATAL(sph_particles_init(&q, 16, &err) == 0);
  CU_ASSERT_FATAL(sph_boundary_add_box(&q, o, -INFINITY, c.dx, 1000.0, 1.0, c.h, 0, &err) == 0);
  CU_ASSERT_EQUAL(q.n, 8 * 6 * 4);
  sph_obstacle big = *o;
  big.hi[2] = 0.1; /* 8 x 6 x 10: the inside 4 x 2 x 6 left out */
  const size_t before = q.n;
  CU_ASSERT_FATAL(sph_boundary_add_box(&q, &big, -INFINITY, c.dx, 1000.0, 1.0, c.h, 0, &err) == 0);
  CU_ASSERT_EQUAL(q.n - before, 8 * 6 * 10 - 4 * 2 * 6);
  size_t outside = 0, off = 0, twice = 0;
  for (size_t i = before; i < q.n; i++) {
    for (int a = 0; a < 3; a++) {
      const double u = (q.pos[a][i] - big.lo[a]) / c.dx - 0.5;
      outside += q.pos[a][i] <= big.lo[a] || q.pos[a][i] >= big.hi[a];
      off += fabs(u - nearbyint(u)) > 1e-9;
    }
    for (size_t j = before; j < i; j++)
      twice += fabs(q.x[i] - q.x[j]) + fabs(q.y[i] - q.y[j]) + fabs(q.z[i] - q.z[j]) < 1e-9;
    CU_ASSERT_EQUAL(q.kind[i], SPH_KIND_WALL);
  }
  CU_ASSERT_EQUAL(outside, 0);
  CU_ASSERT_EQUAL(off, 0);
  CU_ASSERT_EQUAL(twice, 0);
  sph_particles_free(&q);
  /* still water around it */
  sph_sim *s = NULL;
  if (sph_sim_create(&c, &s, &err)) printf("\n    %s", err.msg);
  CU_ASSERT_FATAL(s != NULL);
  size_t fluid0 = 0;
  const sph_particles *p = sph_sim_particles(s);
  for (size_t i = 0; i < p->n; i++)
    fluid0 += p->kind[i] == SPH_KIND_FLUID;
  step_to(s, 0.3);
  size_t fluid = 0;
  double vmax = 0.0;
  for (size_t i = 0; i < p->n; i++) {
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    fluid++;
    vmax = fmax(vmax, sqrt(p->vx[i] * p->vx[i] + p->vy[i] * p->vy[i] + p->vz[i] * p->vz[i]));
  }
  printf("\n    box of %d x %d x %d points in still water: %zu fluid particles (the block's 2000 "
         "less %zu inside the box), max |v| %.3g m/s at 0.3 s",
         8, 6, 4, fluid0, 2000 - fluid0, vmax);
  CU_ASSERT_EQUAL(fluid0, 2000 - 8 * 6 * 4);
  CU_ASSERT_EQUAL(fluid, fluid0);
  CU_ASSERT(vmax < 0.02 * sqrt(9.81 * 0.1));
  sph_sim_free(s);
  sph_case_free(&c);
  refused("geometry.obstacles=[{x: [0.06, 0.065], y: [0.02, 0.08], z: [0.0, 0.04]}]",
          "geometry.obstacles[0].x: expected a range at least numerics.dx");
  refused("geometry.obstacles=[{x: [0.06, 0.14], y: [0.02, 0.08], z: [0.0, 0.04], boundary: "
          "mirror}]",
          "geometry.obstacles[0].boundary");
  refused("geometry.obstacles=[{x: [0.06, 0.14], y: [0.02, 0.08]}]", "geometry.obstacles[0]");
}

static void test_snapshots(void) {
  /* the leap-frog and the corrected gradient (its moments from the restored state) */
  const char *const lf[2] = {"numerics.integrator=leapfrog", "numerics.gradient_correction=true"};
  sph_case c;
  sph_error err;
  CU_ASSERT_FATAL(parse(CASE3, lf, 2, &c, &err) == 0);
  sph_sim *s = NULL, *r = NULL;
  CU_ASSERT_FATAL(sph_sim_create(&c, &s, &err) == 0);
  step_to(s, 0.2);
  char *dir = sph_test_tmpdir(), path[4200], xmf[4200];
  snprintf(path, sizeof path, "%s/snap_0001.h5", dir);
  snprintf(xmf, sizeof xmf, "%s/snapshots.xmf", dir);
  int rc = sph_sim_write_run_snapshot(s, path, 1, NULL, 0, NULL, 0, &err);
  if (rc) printf("\n    %s", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  /* read back: z and v_z bit for bit */
  sph_snapshot *snap = NULL;
  rc = sph_snapshot_open(path, &snap, &err);
  if (rc) printf("\n    %s", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  sph_particles q;
  CU_ASSERT_FATAL(sph_snapshot_read_particles(snap, &q, &err) == 0);
  double *a = state(s);
  size_t bad = 0;
  for (size_t i = 0; i < q.n; i++) /* the snapshot's rows are in id order */
    bad += q.z[i] != a[7 * i + 2] || q.vz[i] != a[7 * i + 5] || q.x[i] != a[7 * i];
  CU_ASSERT_EQUAL(bad, 0);
  CU_ASSERT(sph_snapshot_has_field(snap, "z") && sph_snapshot_has_field(snap, "vz"));
  double dim = 0.0;
  CU_ASSERT(sph_snapshot_number(snap, "dimension", &dim, 1, &err) == 0 && dim == 3.0);
  sph_particles_free(&q);
  sph_snapshot_close(snap);
  const char *names[1] = {"snap_0001.h5"};
  const double times[1] = {0.2};
  const size_t np = sph_sim_particles(s)->n;
  CU_ASSERT_FATAL(sph_xdmf_write(xmf, 1, names, times, &np, 0, &err) == 0);
  char *text = sph_test_read_file(xmf, NULL), dims[64];
  snprintf(dims, sizeof dims, "Dimensions=\"%zu 3\"", np);
  CU_ASSERT_PTR_NOT_NULL(text && strstr(text, "GeometryType=\"XYZ\""));
  CU_ASSERT_PTR_NOT_NULL(text && strstr(text, dims));
  free(text);
  free(a);
  /* continued, and restored from the snapshot: the same bits at 0.3 s */
  step_to(s, 0.3);
  a = state(s);
  CU_ASSERT_FATAL(sph_sim_create(&c, &r, &err) == 0);
  sph_snapshot_restart_data rd;
  rc = sph_sim_restore(r, path, &rd, &err);
  if (rc) printf("\n    restore: %s", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  /* its per-particle arrays, in the store by then, released before the pass */
  CU_ASSERT(rd.order == NULL && rd.vxh == NULL && rd.vzh == NULL && rd.rhoh == NULL);
  sph_snapshot_restart_free(&rd);
  step_to(r, 0.3);
  double *b = state(r);
  const size_t n = sph_sim_particles(s)->n;
  CU_ASSERT(memcmp(a, b, 7 * n * sizeof *a) == 0);
  printf("\n    restart at 0.2 s: %s at 0.3 s",
         memcmp(a, b, 7 * n * sizeof *a) ? "differs" : "identical");
  free(a);
  free(b);
  sph_sim_free(s);
  sph_sim_free(r);
  sph_case_free(&c);
  sph_test_rmtree(dir);
  free(dir);
}

/* A wave gauge at a periodic seam (y periodic over [0, 1], dx = 0.1):
 * it reads the particles across the seam too, and away from the seam
 * exactly what sph_diag_surface_at_xy reads. */
static void test_gauge_seam(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 8, &err) == 0);
  const double at[3][3] = {{0.5, 0.95, 0.3}, {0.5, 0.5, 0.1}, {0.5, 0.03, 0.6}};
  const double v[3] = {0.0, 0.0, 0.0};
  for (int k = 0; k < 3; k++)
    CU_ASSERT_FATAL(sph_particles_add_at(&p, at[k], v, 1000.0, 1.0, 0.13, SPH_KIND_FLUID, &err) >=
                    0);
  const double range[2] = {0.0, 1.0}, dx = 0.1;
  const double g0[2] = {0.5, 0.02}, g1[2] = {0.5, 0.5}, g2[2] = {0.5, 0.98}, g3[2] = {0.5, 0.25};
  /* y = 0.98 reads the particle at 0.95 (0.3 + dx/2) alone, and across the
   * seam the one at 0.03 (0.6 + dx/2) */
  const double l2 = sph_diag_gauge_level(&p, g2, dx, dx, 1, range);
  const double plain2 = sph_diag_surface_at_xy(&p, 0.5, 0.98, dx, dx);
  /* swap the two heights: y = 0.02 then reads 0.3 + dx/2 alone, 0.6 + dx/2 across */
  p.z[0] = 0.6;
  p.z[2] = 0.3;
  const double l0 = sph_diag_gauge_level(&p, g0, dx, dx, 1, range);
  const double plain0 = sph_diag_surface_at_xy(&p, 0.5, 0.02, dx, dx);
  printf("\n    at y = 0.98: %.3f m (the line alone %.3f); at y = 0.02: %.3f m (alone %.3f)", l2,
         plain2, l0, plain0);
  CU_ASSERT_DOUBLE_EQUAL(plain2, 0.35, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(l2, 0.65, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(plain0, 0.35, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(l0, 0.65, 1e-12);
  /* away from the seam, and without a period: the plain reading, bit for bit */
  CU_ASSERT(sph_diag_gauge_level(&p, g1, dx, dx, 1, range) ==
            sph_diag_surface_at_xy(&p, 0.5, 0.5, dx, dx));
  CU_ASSERT(sph_diag_gauge_level(&p, g0, dx, dx, -1, range) ==
            sph_diag_surface_at_xy(&p, 0.5, 0.02, dx, dx));
  CU_ASSERT(isinf(sph_diag_gauge_level(&p, g3, dx, dx, 1, range))); /* dry */
  /* periodic along x: the seam is not near this gauge */
  CU_ASSERT(sph_diag_gauge_level(&p, g0, dx, dx, 0, range) ==
            sph_diag_surface_at_xy(&p, 0.5, 0.02, dx, dx));
  sph_particles_free(&p);
}

int main(void) {
  CU_TestInfo tests[] = {
      {"a wave gauge at a periodic seam reads across it", test_gauge_seam},
      {"a 3-D case reads; what is 2-D only is refused by key", test_reader},
      {"a box obstacle: its keys, its particles, still water around it", test_obstacle},
      {"3-D still water over 1 s: rho0 g (H - z) within 1 % inside, the floor sensor within 1 %",
       test_still_water},
      {"3-D snapshots: z and v_z, read back, restart bitwise", test_snapshots},
      CU_TEST_INFO_NULL};
  return sph_test_main("hydrostatic_3d", tests);
}
