/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_wave_face.c - the front face of a breaking wave (wave_face.h).
 *
 * Synthetic waves on a square lattice (dx = 1 mm): still water 10 mm deep
 * with a hump whose front face is a straight line at a known angle theta
 * from the horizontal (60, 75, 90, 105 and 120 degrees; above 90 the face
 * overhangs). The measured angle must be within 3 degrees (the lattice makes the
 * leading edge a staircase) of theta, the
 * crest the top of the hump, and the result independent of the particles'
 * order. Still water has no face (status 1, NaN); bad arguments are an
 * error.
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "analysis/wave_face.h"
#include "core/particles.h"
#include "physics/kernel.h" /* SPH_PI */
#include "testutil.h"

static const double DX = 0.001, LEVEL = 0.010, TOP = 0.022;
static const double X_FOOT = 0.100; /* the face meets the still level here */

/* Still water over [0, 0.2] plus, from LEVEL to TOP, a hump from x = 0.05
 * to the face x_f(y) = X_FOOT + (y - LEVEL) tan(theta - 90 deg). */
static void build(sph_particles *p, double theta_deg, int reversed) {
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(p, 4096, &err) == 0);
  const double t = tan((theta_deg - 90.0) * SPH_PI / 180.0);
  const long nx = 200, ny = (long)(TOP / DX + 0.5);
  for (long k = 0; k < nx * ny; k++) {
    const long m = reversed ? nx * ny - 1 - k : k;
    const long i = m % nx, j = m / nx;
    const double x = (i + 0.5) * DX, y = (j + 0.5) * DX;
    const int in = y < LEVEL || (x >= 0.05 && x <= X_FOOT + (y - LEVEL) * t);
    if (in)
      CU_ASSERT_FATAL(
          sph_particles_add(p, x, y, 0, 0, 1000, 1e-3, 1.3 * DX, SPH_KIND_FLUID, &err) >= 0);
  }
  /* a wall particle above everything: not fluid, so never the crest */
  CU_ASSERT_FATAL(
      sph_particles_add(p, 0.0, 0.05, 0, 0, 1000, 1e-3, 1.3 * DX, SPH_KIND_WALL, &err) >= 0);
}

static void test_known_angles(void) {
  const double thetas[] = {60.0, 75.0, 90.0, 105.0, 120.0};
  for (size_t k = 0; k < sizeof thetas / sizeof thetas[0]; k++) {
    sph_particles p, q;
    build(&p, thetas[k], 0);
    build(&q, thetas[k], 1);
    sph_wave_face f, g;
    sph_error err;
    CU_ASSERT_EQUAL(sph_wave_face_measure(&p, LEVEL, DX, 0.0, 0.2, &f, &err), 0);
    CU_ASSERT_EQUAL(sph_wave_face_measure(&q, LEVEL, DX, 0.0, 0.2, &g, &err), 0);
    printf("\n  theta %5.1f: measured %7.3f deg over %d bands, crest (%.4f, %.4f), toe %.4f",
           thetas[k], f.angle, f.bands, f.crest_x, f.crest_y, f.toe_x);
    CU_ASSERT(fabs(f.angle - thetas[k]) < 3.0);
    CU_ASSERT(f.bands >= 8);
    CU_ASSERT_DOUBLE_EQUAL(f.crest_y, TOP - 0.5 * DX, 1e-12);
    CU_ASSERT(f.crest_x >= 0.05 && f.crest_x <= 0.2);
    CU_ASSERT(f.toe_x > f.crest_x);
    /* the same set in the reverse order gives the same bits */
    CU_ASSERT(f.angle == g.angle && f.crest_x == g.crest_x && f.toe_x == g.toe_x);
    /* the verdict "vertical or beyond" is the one the angle says */
    if (thetas[k] == 90.0) {
      CU_ASSERT(fabs(f.angle - 90.0) < 1e-9);
    } else {
      CU_ASSERT((f.angle >= 90.0) == (thetas[k] > 90.0));
    }
    sph_particles_free(&p);
    sph_particles_free(&q);
  }
}

static void test_no_face(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 16, &err) == 0);
  sph_wave_face f;
  /* empty */
  CU_ASSERT_EQUAL(sph_wave_face_measure(&p, LEVEL, DX, 0.0, 0.2, &f, &err), 1);
  CU_ASSERT(isnan(f.angle));
  /* still water: the crest is less than 4 dx above the level */
  for (int i = 0; i < 50; i++)
    for (int j = 0; j < 10; j++)
      sph_particles_add(&p, (i + 0.5) * DX, (j + 0.5) * DX, 0, 0, 1000, 1e-3, 1.3 * DX,
                        SPH_KIND_FLUID, &err);
  CU_ASSERT_EQUAL(sph_wave_face_measure(&p, LEVEL, DX, 0.0, 0.2, &f, &err), 1);
  CU_ASSERT(isnan(f.angle));
  CU_ASSERT_DOUBLE_EQUAL(f.crest_y, 0.0095, 1e-12);
  /* bad arguments */
  CU_ASSERT_EQUAL(sph_wave_face_measure(&p, LEVEL, 0.0, 0.0, 0.2, &f, &err), -1);
  CU_ASSERT_EQUAL(sph_wave_face_measure(&p, LEVEL, DX, 0.2, 0.0, &f, &err), -1);
  CU_ASSERT_EQUAL(sph_wave_face_measure(&p, NAN, DX, 0.0, 0.2, &f, &err), -1);
  CU_ASSERT(strstr(err.msg, "wave face") != NULL);
  sph_particles_free(&p);
}

int main(void) {
  CU_TestInfo tests[] = {
      {"a straight face at 60..120 degrees is measured within 3 degrees", test_known_angles},
      {"no face in still water; bad arguments are errors", test_no_face},
      CU_TEST_INFO_NULL};
  return sph_test_main("wave_face", tests);
}
