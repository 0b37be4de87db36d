/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_probes.c - pressure, level and velocity probes (output.probes,
 * src/analysis/probes.h, probes.csv):
 *   - on a lattice of fluid particles holding the hydrostatic field
 *     p = rho g (H - y) and a uniform velocity: a pressure probe reads the
 *     field exactly (1e-9 of rho g H) in the fluid, on the lattice's side
 *     face and on its floor, a sensor of some diameter reads the mean of
 *     its face, velocity probes read the velocity, and a point away from
 *     the fluid reads 0 (dry); a level gauge reads the top of the fluid
 *     above the bed, 0 and finite where dry;
 *   - the hydrostatic tank (tests/data/still_tank.yaml with its walls as
 *     3 unstaggered layers and the fourtakas density diffusion) run by
 *     `sph run` for 0.3 s: probes.csv has a time column, units in its
 *     header and a row every probe_interval; wall sensors at two depths and
 *     a floor sensor read rho0 g (H - y) within 1 % of rho0 g H, the level
 *     gauge H within dx/2, the velocity probe stays below 1 mm/s;
 *   - the sensor's low-pass response (sph_probe_low_pass): a step input
 *     gives 1 - exp(-2 pi fc t) whatever the steps (1e-12), a sine at the
 *     cut-off comes out at 1/sqrt(2) of its amplitude (1 %); in probes.csv
 *     the filtered column follows the raw one, which it leaves unchanged;
 *   - a sensor's own interpolation (points, smoothing, clip_negative,
 *     hydrostatic, wet_sum) against a brute-force Shepard sum written
 *     here (1e-12): carried along g it still reads the hydrostatic field
 *     exactly with any points and smoothing; not carried, on the lattice's
 *     side face it still reads the field (which varies along the face),
 *     in its floor the mean pressure of the fluid above, 0.5-2.5 dx of
 *     rho g below the field at the floor; a field below 0
 *     reads 0 clipped and below 0 unclipped; a point that sees the fluid
 *     only faintly is dry by default and wet with a small wet_sum;
 *   - case errors name the probe's key.
 * Restart safety of probes.csv is in tests/test_restart.c.
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/probes.h"
#include "case/case.h"
#include "core/particles.h"
#include "physics/kernel.h"
#include "testutil.h"

#define DXL 0.01
#define NX 30
#define NY 20 /* H = 0.2 m */

static void lattice(sph_particles *p) {
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(p, NX * NY, &err) == 0);
  for (int j = 0; j < NY; j++)
    for (int i = 0; i < NX; i++) {
      const double y = (j + 0.5) * DXL;
      const long k = sph_particles_add(p, (i + 0.5) * DXL, y, 0.3, -0.2, 1000.0, 0.1, 1.3 * DXL,
                                       SPH_KIND_FLUID, &err);
      CU_ASSERT_FATAL(k >= 0);
      p->p[k] = 1000.0 * 9.81 * (NY * DXL - y);
    }
}

static sph_probe probe(sph_probe_kind kind, double x, double y, double diameter, int along_x) {
  sph_probe q;
  memset(&q, 0, sizeof q);
  snprintf(q.name, sizeof q.name, "q");
  q.kind = kind;
  q.x = x;
  q.y = y;
  q.diameter = diameter;
  q.along_x = along_x;
  return q;
}

static void test_lattice(void) {
  sph_particles p;
  lattice(&p);
  const double g[2] = {0.0, -9.81}, H = NY * DXL, rgh = 1000.0 * 9.81 * H;
  const double pts[4][3] = {/* x, y, diameter */
                            {0.15, 0.1, 0.0},
                            {0.30, 0.05, 0.0},
                            {0.30, 0.05, 0.004},
                            {0.0, 0.013, 0.004}};
  for (int k = 0; k < 4; k++) {
    const sph_probe q = probe(SPH_PROBE_PRESSURE, pts[k][0], pts[k][1], pts[k][2], 0);
    double v;
    sph_probe_read(&q, &p, SPH_KERNEL_CUBIC_SPLINE, 1.3 * DXL, DXL, 0.0, g, &v);
    CU_ASSERT(fabs(v - 1000.0 * 9.81 * (H - pts[k][1])) < 1e-9 * rgh);
  }
  /* a floor sensor, its face along x */
  sph_probe q = probe(SPH_PROBE_PRESSURE, 0.15, 0.0, 0.01, 1);
  double v[2];
  sph_probe_read(&q, &p, SPH_KERNEL_CUBIC_SPLINE, 1.3 * DXL, DXL, 0.0, g, v);
  CU_ASSERT(fabs(v[0] - rgh) < 1e-9 * rgh);
  /* dry: away from the fluid */
  q = probe(SPH_PROBE_PRESSURE, 0.15, H + 0.05, 0.0, 0);
  sph_probe_read(&q, &p, SPH_KERNEL_CUBIC_SPLINE, 1.3 * DXL, DXL, 0.0, g, v);
  CU_ASSERT(v[0] == 0.0);
  q = probe(SPH_PROBE_VELOCITY, 0.1, 0.1, 0.0, 0);
  sph_probe_read(&q, &p, SPH_KERNEL_CUBIC_SPLINE, 1.3 * DXL, DXL, 0.0, g, v);
  CU_ASSERT(fabs(v[0] - 0.3) < 1e-12 && fabs(v[1] + 0.2) < 1e-12);
  q = probe(SPH_PROBE_VELOCITY, 1.0, 0.1, 0.0, 0);
  sph_probe_read(&q, &p, SPH_KERNEL_CUBIC_SPLINE, 1.3 * DXL, DXL, 0.0, g, v);
  CU_ASSERT(v[0] == 0.0 && v[1] == 0.0);
  q = probe(SPH_PROBE_LEVEL, 0.1, 0.0, 0.0, 0);
  sph_probe_read(&q, &p, SPH_KERNEL_CUBIC_SPLINE, 1.3 * DXL, DXL, 0.0, g, v);
  CU_ASSERT(fabs(v[0] - H) < 1e-12);
  sph_probe_read(&q, &p, SPH_KERNEL_CUBIC_SPLINE, 1.3 * DXL, DXL, -0.1, g,
                 v); /* a bed 0.1 m lower */
  CU_ASSERT(fabs(v[0] - H - 0.1) < 1e-12);
  q = probe(SPH_PROBE_LEVEL, 2.0, 0.0, 0.0, 0);
  sph_probe_read(&q, &p, SPH_KERNEL_CUBIC_SPLINE, 1.3 * DXL, DXL, 0.0, g, v);
  CU_ASSERT(v[0] == 0.0);
  sph_particles_free(&p);
}

/* The oracle: the Shepard sum of the fluid's pressure at (x, y) with h, carried along g or not,
 * clipped or not, in the plainest form; 0 below the kernel sum wet. */
static double shepard_oracle(const sph_particles *p, double x, double y, double h, int carry,
                             int clip, double wet) {
  double sw = 0.0, sp = 0.0;
  for (size_t j = 0; j < p->n; j++) {
    const double r = hypot(x - p->x[j], y - p->y[j]);
    if (r >= 2.0 * h) continue;
    const double w = sph_kernel_w(SPH_KERNEL_CUBIC_SPLINE, r, h) * p->mass[j] / p->rho[j];
    const double pj = clip && p->p[j] < 0.0 ? 0.0 : p->p[j];
    sw += w;
    sp += w * (carry ? pj + p->rho[j] * (-9.81) * (y - p->y[j]) : pj);
  }
  return sw >= wet ? sp / sw : 0.0;
}

static void test_own_interpolation(void) {
  sph_particles p;
  lattice(&p);
  const double g[2] = {0.0, -9.81}, H = NY * DXL, rgh = 1000.0 * 9.81 * H, h = 1.3 * DXL;
  /* TrixiParticles' sensor (10 points, 2h, clipped, not carried) on the side face, and in the
   * floor (its face along x), where the kernel sees the fluid above only */
  sph_probe q = probe(SPH_PROBE_PRESSURE, 0.0, 0.05, 0.0084, 0);
  q.points = 10, q.smoothing = 2.0, q.clip_negative = 1, q.no_carry = 1, q.wet_sum = 1e-12;
  double v, want = 0.0;
  sph_probe_read(&q, &p, SPH_KERNEL_CUBIC_SPLINE, h, DXL, 0.0, g, &v);
  for (int k = 0; k < 10; k++)
    want += shepard_oracle(&p, 0.0, 0.05 + (k / 9.0 - 0.5) * 0.0084, 2 * h, 0, 1, 1e-12) / 10;
  const double exact = 1000.0 * 9.81 * (H - 0.05);
  CU_ASSERT(fabs(v - want) < 1e-12 * rgh);
  CU_ASSERT(fabs(v - exact) < 1e-3 * 1000.0 * 9.81 * DXL); /* the field varies along the face */
  sph_probe fl = q;
  fl.x = 0.15, fl.y = 0.0, fl.along_x = 1;
  sph_probe_read(&fl, &p, SPH_KERNEL_CUBIC_SPLINE, h, DXL, 0.0, g, &v);
  want = 0.0;
  for (int k = 0; k < 10; k++)
    want += shepard_oracle(&p, 0.15 + (k / 9.0 - 0.5) * 0.0084, 0.0, 2 * h, 0, 1, 1e-12) / 10;
  const double below = (rgh - v) / (1000.0 * 9.81 * DXL);
  printf("\n  10 points, 2h, clipped, not carried: in the floor %.6f Pa (oracle %.6f, the field "
         "%.6f: %.2f dx of rho g below it)",
         v, want, rgh, below);
  CU_ASSERT(fabs(v - want) < 1e-12 * rgh);
  CU_ASSERT(below > 0.5 && below < 2.5);
  /* carried, any points and smoothing: the field exactly */
  q.no_carry = 0;
  sph_probe_read(&q, &p, SPH_KERNEL_CUBIC_SPLINE, h, DXL, 0.0, g, &v);
  CU_ASSERT(fabs(v - exact) < 1e-9 * rgh);
  /* a field below 0: clipped reads 0, unclipped below 0 */
  for (size_t j = 0; j < p.n; j++)
    p.p[j] -= 2.0 * rgh;
  q.no_carry = 1;
  sph_probe_read(&q, &p, SPH_KERNEL_CUBIC_SPLINE, h, DXL, 0.0, g, &v);
  CU_ASSERT(v == 0.0);
  q.clip_negative = 0;
  sph_probe_read(&q, &p, SPH_KERNEL_CUBIC_SPLINE, h, DXL, 0.0, g, &v);
  CU_ASSERT(v < -rgh);
  /* a point 1.95 dx beyond the fluid's side face sees its first column faintly (kernel sum
   * below 0.1): dry by default, wet with a small wet_sum */
  for (size_t j = 0; j < p.n; j++)
    p.p[j] += 2.0 * rgh;
  sph_probe f = probe(SPH_PROBE_PRESSURE, -1.95 * DXL, 0.1, 0.0, 0);
  sph_probe_read(&f, &p, SPH_KERNEL_CUBIC_SPLINE, h, DXL, 0.0, g, &v);
  CU_ASSERT(v == 0.0);
  f.wet_sum = 1e-12;
  sph_probe_read(&f, &p, SPH_KERNEL_CUBIC_SPLINE, h, DXL, 0.0, g, &v);
  CU_ASSERT(fabs(v - shepard_oracle(&p, -1.95 * DXL, 0.1, h, 1, 0, 1e-12)) < 1e-9 * rgh);
  CU_ASSERT(v > 0.0);
  sph_particles_free(&p);
}

/* A wire gauge's reading (wetted): still water reads its depth, a jet above it adds its
 * thickness, not its height, where the highest particle reads the jet's top; dry reads 0. Both
 * kernels, within 1 % (the lattice's kernel sum; measured in the log). */
static void test_wetted(void) {
  const sph_kernel_kind kernels[2] = {SPH_KERNEL_CUBIC_SPLINE, SPH_KERNEL_WENDLAND_C2};
  for (int k = 0; k < 2; k++) {
    sph_particles p;
    sph_error err;
    lattice(&p);
    const double g[2] = {0.0, -9.81}, H = NY * DXL;
    sph_probe q = probe(SPH_PROBE_LEVEL, 0.15, 0.0, 0.0, 0);
    q.wetted = 1;
    double still, jet, top, dry;
    sph_probe_read(&q, &p, kernels[k], 1.3 * DXL, DXL, 0.0, g, &still);
    for (int j = 0; j < 3; j++) /* a jet 3 dx thick, its top at 0.48 m */
      for (int i = 10; i < 20; i++)
        CU_ASSERT_FATAL(sph_particles_add(&p, (i + 0.5) * DXL, 0.45 + (j + 0.5) * DXL, 1.0, 0.0,
                                          1000.0, 0.1, 1.3 * DXL, SPH_KIND_FLUID, &err) >= 0);
    sph_probe_read(&q, &p, kernels[k], 1.3 * DXL, DXL, 0.0, g, &jet);
    q.wetted = 0;
    sph_probe_read(&q, &p, kernels[k], 1.3 * DXL, DXL, 0.0, g, &top);
    q.wetted = 1, q.x = 2.0;
    sph_probe_read(&q, &p, kernels[k], 1.3 * DXL, DXL, 0.0, g, &dry);
    printf("\n    kernel %d: still water %.5f m (depth %.2f), with a jet %.5f (top reading %.4f)",
           k, still, H, jet, top);
    CU_ASSERT(fabs(still - H) < 0.01 * H);
    CU_ASSERT(fabs(jet - (H + 3 * DXL)) < 0.01 * (H + 3 * DXL));
    CU_ASSERT(fabs(top - 0.48) < 1e-12);
    CU_ASSERT(dry == 0.0);
    sph_particles_free(&p);
  }
}

/* The first line of the file at path into buf; 0 if it cannot be read. */
static int first_line(const char *path, char *buf, size_t size) {
  FILE *f = fopen(path, "r");
  buf[0] = '\0';
  if (!f) return 0;
  const int ok = fgets(buf, (int)size, f) != NULL;
  fclose(f);
  return ok;
}

static void test_tank(void) {
  char *dir = sph_test_tmpdir();
  char args[8192], out[16384], path[4200];
  snprintf(args, sizeof args,
           "run -q '%s' -o '%s/run' --set time.end=0.3 --set output.snapshots=false "
           "--set 'geometry.tank={x: [0.0, 0.2], y: [0.0, 0.15], layers: 3, stagger: false}' "
           "--set 'numerics.density_diffusion={model: fourtakas}' --set output.probe_interval=0.01 "
           "--set 'output.probes=[{name: P1, kind: pressure, at: [0.2, 0.02], diameter: 0.005}, "
           "{name: P2, kind: pressure, at: [0.0, 0.05]}, "
           "{name: Pf, kind: pressure, at: [0.1, 0.0], along: x, diameter: 0.01}, "
           "{name: H1, kind: level, x: 0.1}, {name: V1, kind: velocity, at: [0.1, 0.05]}]'",
           sph_test_src("tests/data/still_tank.yaml"), dir);
  CU_ASSERT_EQUAL_FATAL(sph_test_sph_ok(args, dir, out, sizeof out), 0);
  snprintf(path, sizeof path, "%s/run/probes.csv", dir);
  char header[512];
  CU_ASSERT_FATAL(first_line(path, header, sizeof header));
  CU_ASSERT_STRING_EQUAL(header,
                         "time (s),P1 (Pa),P2 (Pa),Pf (Pa),H1 (m),V1_vx (m/s),V1_vy (m/s)\n");
  double *col[7];
  const long n = sph_test_csv(path, "#0,#1,#2,#3,#4,#5,#6", col);
  CU_ASSERT_FATAL(n > 0);
  CU_ASSERT(n == 31); /* t = 0, then every 0.01 s to 0.3 s */
  /* on the interval itself, not at the first step past it (issue 39, D11) */
  double off = 0.0;
  for (long r = 0; r < n; r++)
    off = fmax(off, fabs(col[0][r] - (double)r * 0.01));
  CU_ASSERT(off < 1e-12);
  if (!(off < 1e-12)) printf("\n  probe rows off the interval by up to %g s", off);
  const double rgh = 1000.0 * 9.81 * 0.1, want[3] = {0.08, 0.05, 0.1};
  double worst = 0.0, vmax = 0.0;
  for (long r = n / 2; r < n; r++) { /* settled: the second half */
    for (int k = 0; k < 3; k++)
      worst = fmax(worst, fabs(col[k + 1][r] - 1000.0 * 9.81 * want[k]) / rgh);
    vmax = fmax(vmax, hypot(col[5][r], col[6][r]));
    CU_ASSERT(fabs(col[4][r] - 0.1) < 0.0025);
  }
  printf("\n  tank: wall and floor sensors within %.2f %% of rho0 g H, |v| <= %.2e m/s, "
         "level %.5f m\n",
         100 * worst, vmax, col[4][n - 1]);
  CU_ASSERT(worst < 0.01);
  CU_ASSERT(vmax < 1e-3);
  for (int k = 0; k < 7; k++)
    free(col[k]);
  sph_test_rmtree(dir);
  free(dir);
}

/* The first-order low-pass: exact for a step on any partition of time; the
 * amplitude of a sine at the cut-off 1/sqrt(2); and in a run, its column
 * beside an unchanged raw column. */
static void test_low_pass(void) {
  const double fc = 100.0, pi = 3.14159265358979323846;
  double y = 0.0, t = 0.0, worst = 0.0;
  for (int k = 0; k < 2000; k++) { /* steps of 1 to 10 us */
    const double dt = 1e-6 * (1 + (k * 7919) % 10);
    y = sph_probe_low_pass(y, 1.0, dt, fc);
    t += dt;
    worst = fmax(worst, fabs(y - (1.0 - exp(-2.0 * pi * fc * t))));
  }
  CU_ASSERT(worst < 1e-12);
  double amp = 0.0;
  y = 0.0;
  for (int k = 1; k <= 100000; k++) { /* 0.1 s at 1 us: 10 periods, the last 5 settled */
    const double tk = 1e-6 * k;
    y = sph_probe_low_pass(y, sin(2.0 * pi * fc * tk), 1e-6, fc);
    if (tk > 0.05) amp = fmax(amp, fabs(y));
  }
  printf("\n  low-pass: step within %.1e, amplitude at the cut-off %.4f (1/sqrt 2 = 0.7071)", worst,
         amp);
  CU_ASSERT(fabs(amp - sqrt(0.5)) < 0.01 * sqrt(0.5));

  char *dir = sph_test_tmpdir();
  char args[8192], out[16384], path[4200];
  for (int lp = 0; lp < 2; lp++) {
    snprintf(args, sizeof args,
             "run -q '%s' -o '%s/run%d' --set time.end=0.05 --set output.snapshots=false "
             "--set 'output.probes=[{name: P1, kind: pressure, at: [0.2, 0.02]%s}, "
             "{name: H1, kind: level, x: 0.1}]'",
             sph_test_src("tests/data/still_tank.yaml"), dir, lp, lp ? ", low_pass: 50" : "");
    CU_ASSERT_EQUAL_FATAL(sph_test_sph_ok(args, dir, out, sizeof out), 0);
  }
  snprintf(path, sizeof path, "%s/run1/probes.csv", dir);
  char header[512];
  CU_ASSERT_FATAL(first_line(path, header, sizeof header));
  CU_ASSERT_STRING_EQUAL(header, "time (s),P1 (Pa),P1_low_pass (Pa),H1 (m)\n");
  double *a[4], *b[3];
  const long n = sph_test_csv(path, "#0,#1,#2,#3", a);
  snprintf(path, sizeof path, "%s/run0/probes.csv", dir);
  const long m = sph_test_csv(path, "#0,#1,#2", b);
  CU_ASSERT_FATAL(n > 2 && n == m);
  int same = 1;
  double yy = a[1][0]; /* the filter starts at the first reading */
  double off = 0.0;
  for (long r = 0; r < n; r++) {
    same &= a[0][r] == b[0][r] && a[1][r] == b[1][r] && a[3][r] == b[2][r];
    if (r > 0) yy = sph_probe_low_pass(yy, a[1][r], a[0][r] - a[0][r - 1], 50.0);
    off = fmax(off, fabs(yy - a[2][r]));
  }
  CU_ASSERT(same);       /* the raw columns as without the filter */
  CU_ASSERT(off == 0.0); /* the filtered one: the filter of the raw series, bit for bit */
  for (int k = 0; k < 4; k++)
    free(a[k]);
  for (int k = 0; k < 3; k++)
    free(b[k]);
  sph_test_rmtree(dir);
  free(dir);
}

static void expect_err(const char *probes, const char *want) {
  char text[2048];
  snprintf(text, sizeof text,
           "name: t\nphysics: {sound_speed: 20}\nnumerics: {dx: 0.01, scheme: paper_b}\n"
           "time: {end: 1, output_interval: 0.1}\n"
           "geometry:\n  fluid:\n    - {x: [0, 0.5], y: [0, 0.5]}\noutput:\n%s",
           probes);
  sph_case c;
  sph_error err;
  const int rc = sph_case_parse(text, strlen(text), "t.yaml", NULL, 0, &c, &err);
  CU_ASSERT(rc != 0);
  if (rc) {
    if (strcmp(err.msg, want)) printf("\n  want: %s\n  got:  %s\n", want, err.msg);
    CU_ASSERT_STRING_EQUAL(err.msg, want);
  }
  sph_case_free(&c);
}

static void test_case_errors(void) {
  expect_err("  probes:\n    - {name: a, kind: level, at: [0, 0]}\n",
             "t.yaml:10: output.probes[0].at: not a key of a level probe");
  expect_err("  probes:\n    - {name: a, kind: gauge, x: 0}\n",
             "t.yaml:10: output.probes[0].kind: unknown choice 'gauge' (valid: pressure, level, "
             "velocity)");
  expect_err(
      "  probes:\n    - {name: a, kind: level, x: 0}\n    - {name: a, kind: level, x: 0.5}\n",
      "t.yaml:11: output.probes[1].name: expected a name of its own, got 'a' (the name of "
      "output.probes[0])");
  expect_err("  probes:\n    - {name: a b, kind: level, x: 0}\n",
             "t.yaml:10: output.probes[0].name: expected a name of 1 to 64 characters from "
             "[A-Za-z0-9_.-], got 'a b'");
  /* out of the water's reach (issue 39, D6): the domain's default for this
   * block is x [-0.302, 0.802] y [-0.302, 1.802] */
  expect_err("  probes:\n    - {name: a, kind: pressure, at: [5, -3]}\n",
             "t.yaml:10: output.probes[0].at: (5, -3) is outside the domain, x [-0.302, 0.802] "
             "y [-0.302, 1.802] (geometry.domain, or its default from the geometry): the water "
             "cannot reach it");
  expect_err("  probes:\n    - {name: a, kind: level, x: -100}\n",
             "t.yaml:10: output.probes[0].x: x = -100 is outside the domain, x [-0.302, 0.802] "
             "y [-0.302, 1.802] (geometry.domain, or its default from the geometry): the water "
             "cannot reach it");
  expect_err("  probes:\n    - {name: a, kind: pressure, at: [0.5, 0], diameter: 1e300}\n",
             "t.yaml:10: output.probes[0].diameter: expected a number in [0, 2.104], got "
             "'1e300'");
  expect_err("  gauges: [0.2, -100]\n",
             "t.yaml:9: output.gauges[1]: x = -100 is outside the domain, x [-0.302, 0.802] "
             "y [-0.302, 1.802] (geometry.domain, or its default from the geometry): the water "
             "cannot reach it");
  expect_err("  probes:\n    - {name: a, kind: level, x: 0, points: 10}\n",
             "t.yaml:10: output.probes[0].points: not a key of a level probe");
  expect_err("  probes:\n    - {name: a, kind: pressure, at: [0.5, 0], points: 65}\n",
             "t.yaml:10: output.probes[0].points: expected an integer in 1..64, got '65'");
  expect_err("  probes:\n    - {name: a, kind: pressure, at: [0.5, 0], smoothing: 0}\n",
             "t.yaml:10: output.probes[0].smoothing: expected a positive number, got '0'");
  expect_err("  probes:\n    - {name: a, kind: level, x: 0, low_pass: 100}\n",
             "t.yaml:10: output.probes[0].low_pass: not a key of a level probe");
  expect_err("  probes:\n    - {name: a, kind: pressure, at: [0, 0], low_pass: 0}\n",
             "t.yaml:10: output.probes[0].low_pass: expected a positive number, got '0'");
  expect_err("  probe_interval: 0.1\n",
             "t.yaml:9: output.probe_interval: expected output.probes alongside it");
  expect_err("  probe_interval: 2\n  probes:\n    - {name: a, kind: velocity, at: [0, 0]}\n",
             "t.yaml:9: output.probe_interval: expected 0 (a row every step) or a number from "
             "time.end/1000000 (1e-06, at most 1000000 rows) to time.end (1), got '2'");
  /* every column of probes.csv and gauges.csv has a name of its own (issue 61, E10) */
  expect_err("  probes:\n    - {name: V, kind: velocity, at: [0.2, 0.2]}\n"
             "    - {name: V_vx, kind: level, x: 0.1}\n",
             "t.yaml:11: output.probes[1].name: expected a name whose columns are its own, got "
             "'V_vx' (its column 'V_vx' is one of output.probes[0]'s, 'V')");
  expect_err("  probes:\n    - {name: a_low_pass, kind: level, x: 0.1}\n"
             "    - {name: a, kind: pressure, at: [0.2, 0], low_pass: 100}\n",
             "t.yaml:11: output.probes[1].name: expected a name whose columns are its own, got "
             "'a' (its column 'a_low_pass' is one of output.probes[0]'s, 'a_low_pass')");
  expect_err("  probes:\n    - {name: time, kind: level, x: 0.1}\n",
             "t.yaml:10: output.probes[0].name: expected a name whose columns are its own, got "
             "'time' (its column 'time' is probes.csv's first)");
  expect_err("  gauges: [0.1, 0.2, 0.1]\n",
             "t.yaml:9: output.gauges[2]: expected a place of its own, got the column eta_0.1 of "
             "output.gauges[0] (two gauges there read the same)");
  /* a tiny interval would land every step on it for ever (issue 61, E5) */
  expect_err("  probe_interval: 1e-300\n  probes:\n    - {name: a, kind: velocity, at: [0, 0]}\n",
             "t.yaml:9: output.probe_interval: expected 0 (a row every step) or a number from "
             "time.end/1000000 (1e-06, at most 1000000 rows) to time.end (1), got 1e-300");
}

int main(void) {
  CU_TestInfo tests[] = {{"readings on a hydrostatic lattice", test_lattice},
                         {"a wire gauge: still water, a jet above it, dry", test_wetted},
                         {"a sensor's own interpolation", test_own_interpolation},
                         {"hydrostatic tank: probes.csv against rho0 g (H - y)", test_tank},
                         {"a sensor's low-pass response", test_low_pass},
                         {"case errors", test_case_errors},
                         CU_TEST_INFO_NULL};
  return sph_test_main("probes", tests);
}
