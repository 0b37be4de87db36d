/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_turbulence.c - the SPS (Smagorinsky) stress of paper B eq. (4)
 * (src/physics/turbulence.h) and its use in a run.
 *
 * 1. Hand computation: for simple shear v = (gamma y, 0), S_xy = gamma/2,
 *    |S| = (2 S:S)^(1/2) = gamma, nu_t = (C_s Delta)^2 gamma; the stress is
 *    2 nu_t S - (2/3) C_I Delta^2 gamma^2 delta.
 * 2. On a square lattice (through the strain-rate pass of forces.c) the
 *    stress of interior particles is zero (< 1e-12 of the shear case's) for
 *    rigid translation and rigid rotation, and within 3 % of the hand value
 *    for shear: the SPH gradient of a linear field on this lattice
 *    (h = 1.3 dx) is about 1 % off, and the stress goes as its square
 *    (measured: 2.1 %).
 * 3. The coarse SPS dam break (cases/sps_dam_break_coarse.yaml) runs to
 *    t = 0.89 s and its front at every output time matches
 *    golden/sps_dam_break_coarse_front.csv within 0.05 dx (`make golden`).
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/particles.h"
#include "neighbours/grid.h"
#include "physics/turbulence.h"
#include "solver/forces.h"
#include "testutil.h"

static const double CS = 0.12, CI = 0.00066;

static void test_hand_shear(void) {
  const double gamma = 3.7, delta = 0.01;
  const double nut = sph_sps_eddy_viscosity(0.0, 0.5 * gamma, 0.0, CS, delta);
  CU_ASSERT_DOUBLE_EQUAL(nut, CS * CS * delta * delta * gamma, 1e-15 * nut);
  double txx, txy, tyy;
  sph_sps_stress(0.0, 0.5 * gamma, 0.0, CS, CI, delta, &txx, &txy, &tyy);
  const double iso = (2.0 / 3.0) * CI * delta * delta * gamma * gamma;
  CU_ASSERT_DOUBLE_EQUAL(txy, nut * gamma, 1e-15 * nut * gamma);
  CU_ASSERT_DOUBLE_EQUAL(txx, -iso, 1e-15 * iso);
  CU_ASSERT_DOUBLE_EQUAL(tyy, -iso, 1e-15 * iso);
}

/* Strain rate on a 30 x 30 lattice with velocity field f, SPS stress at
 * the particle nearest the centre. */
typedef void (*field_fn)(double x, double y, double *vx, double *vy);
static void translate(double x, double y, double *vx, double *vy) {
  (void)x;
  (void)y;
  *vx = 1.3;
  *vy = -0.4;
}
static void rotate(double x, double y, double *vx, double *vy) {
  *vx = -2.0 * y;
  *vy = 2.0 * x;
}
static void shear(double x, double y, double *vx, double *vy) {
  (void)x;
  *vx = 3.7 * y;
  *vy = 0.0;
}

static void lattice_stress(field_fn f, double *txx, double *txy, double *tyy) {
  const double dx = 0.01, h = 1.3 * dx;
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 1024, &err) == 0);
  for (int j = 0; j < 30; j++)
    for (int i = 0; i < 30; i++) {
      const double x = (i - 14.5) * dx, y = (j - 14.5) * dx;
      double vx, vy;
      f(x, y, &vx, &vy);
      sph_particles_add(&p, x, y, vx, vy, 1000.0, 1000.0 * dx * dx, h, SPH_KIND_FLUID, &err);
    }
  sph_grid g;
  sph_grid_init(&g);
  CU_ASSERT_FATAL(sph_grid_build(&g, &p, 2.0 * h * (1 + 1e-9), 1u << 20, &err) == 0);
  sph_force_params fp = {0};
  fp.h = h;
  double *e = malloc(3 * p.n * sizeof *e);
  double *const eps[SPH_SYM] = {e, e + p.n, e + 2 * p.n};
  CU_ASSERT_FATAL(sph_forces_strain_rate(&p, &g, &fp, eps, &err) == 0);
  size_t c = 0;
  for (size_t i = 0; i < p.n; i++)
    if (hypot(p.x[i], p.y[i]) < hypot(p.x[c], p.y[c])) c = i;
  const double exx = e[c], exy = e[p.n + c], eyy = e[2 * p.n + c];
  /* S from eps as forces.c converts it */
  sph_sps_stress(0.5 * (2.0 * exx + eyy), 0.5 * exy, 0.5 * (2.0 * eyy + exx), CS, CI, dx, txx, txy,
                 tyy);
  free(e);
  sph_grid_free(&g);
  sph_particles_free(&p);
}

static void test_lattice(void) {
  double sxx, sxy, syy, a, b, c;
  lattice_stress(shear, &sxx, &sxy, &syy);
  double hxx, hxy, hyy;
  sph_sps_stress(0.0, 0.5 * 3.7, 0.0, CS, CI, 0.01, &hxx, &hxy, &hyy);
  printf("\n  shear: txy %.12g (hand %.12g), txx %.6g (hand %.6g)", sxy, hxy, sxx, hxx);
  CU_ASSERT_DOUBLE_EQUAL(sxy, hxy, 0.03 * fabs(hxy));
  CU_ASSERT_DOUBLE_EQUAL(sxx, hxx, 0.03 * fabs(hxx));
  CU_ASSERT_DOUBLE_EQUAL(syy, hyy, 0.03 * fabs(hyy));
  const double scale = fabs(hxy);
  lattice_stress(translate, &a, &b, &c);
  CU_ASSERT(fabs(a) < 1e-12 * scale && fabs(b) < 1e-12 * scale && fabs(c) < 1e-12 * scale);
  lattice_stress(rotate, &a, &b, &c);
  printf("\n  rotation: %.3g %.3g %.3g", a, b, c);
  CU_ASSERT(fabs(a) < 1e-12 * scale && fabs(b) < 1e-12 * scale && fabs(c) < 1e-12 * scale);
}

typedef struct series {
  size_t n;
  double t[1024], x[1024];
} series;

static int read_front(const char *path, series *s) {
  s->n = sph_test_csv2(path, "time,front_x", s->t, s->x, 1024);
  return s->n ? 0 : -1;
}

static void test_sps_dam_break_golden(void) {
  char *dir = sph_test_tmpdir(), cmd[8192], path[4096];
  snprintf(cmd, sizeof cmd, "'%s' run --quiet '%s' -o '%s' --set output.snapshots=false",
           sph_test_build("src/sph"), sph_test_src("cases/sps_dam_break_coarse.yaml"), dir);
  CU_ASSERT_FATAL(sph_test_system(cmd) == 0);
  static series sim, gold;
  snprintf(path, sizeof path, "%s/diagnostics.csv", dir);
  CU_ASSERT_FATAL(read_front(path, &sim) == 0);
  CU_ASSERT_FATAL(read_front(sph_test_src("golden/sps_dam_break_coarse_front.csv"), &gold) == 0);
  CU_ASSERT_EQUAL(sim.n, gold.n);
  double worst = 0.0;
  for (size_t i = 0; i < sim.n && i < gold.n; i++) {
    CU_ASSERT_DOUBLE_EQUAL(sim.t[i], gold.t[i], 1e-12);
    if (fabs(sim.x[i] - gold.x[i]) > worst) worst = fabs(sim.x[i] - gold.x[i]);
  }
  printf("\n  SPS dam break: front at t = %.3f s: %.4f m; largest difference from golden %.2e m",
         sim.t[sim.n - 1], sim.x[sim.n - 1], worst);
  CU_ASSERT(worst <= 0.05 * 0.015);
  CU_ASSERT(sim.x[sim.n - 1] > 0.8); /* the surge has crossed the tank */
  sph_test_rmtree(dir);
  free(dir);
}

int main(void) {
  CU_TestInfo tests[] = {
      {"Smagorinsky stress for simple shear by hand", test_hand_shear},
      {"lattice: zero for translation and rotation, hand value for shear", test_lattice},
      {"coarse SPS dam break against its golden front", test_sps_dam_break_golden},
      CU_TEST_INFO_NULL};
  return sph_test_main("turbulence", tests);
}
