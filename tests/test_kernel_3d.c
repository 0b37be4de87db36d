/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_kernel_3d.c - the kernels as a 3-D build compiles them: this file
 * is built with -DSPH_DIM=3 (Makefile.am) and includes only
 * core/kernel_shape.h, the shapes and normalisation constants every
 * evaluator takes (issue 37, point 2: both kernels with their 3-D
 * normalisation). For the cubic spline and the Wendland C2 kernel: the
 * integral of W over space is 1 (radial Simpson quadrature and a lattice
 * sum over the support's cube), dW/dr matches a finite difference of W,
 * and the constants are the closed forms C_3 = 1/pi and 21/(16 pi). The
 * 2-D build's constants are checked by test_kernel.
 */
#include "config.h"

#include <math.h>
#include <stdio.h>

#include "core/kernel_shape.h"
#include "testutil.h"

#if SPH_DIM != 3
#error "test_kernel_3d is built with -DSPH_DIM=3"
#endif

static const double H = 0.013; /* any smoothing length */

static int kind; /* SPH_SHAPE_* under test */
static void kwdw(double r, double *w, double *dw) {
  if (kind == SPH_SHAPE_WENDLAND_C2)
    sph_shape_wendland_c2(r, H, w, dw);
  else
    sph_shape_cubic(r, H, w, dw);
}
static double kw(double r) {
  double w, dw;
  kwdw(r, &w, &dw);
  return w;
}
static const char *name(void) { return kind == SPH_SHAPE_WENDLAND_C2 ? "wendland_c2" : "cubic"; }

static void body_dimension(void) {
  CU_ASSERT_EQUAL(SPH_SYM, 6); /* xx, xy, xz, yy, yz, zz */
  CU_ASSERT_DOUBLE_EQUAL(sph_pow_dim(1.0, 1.0 / H), 1.0 / (H * H * H), 1e-12 / (H * H * H));
  const double c = sph_kernel_c(kind);
  CU_ASSERT_EQUAL(c, kind == SPH_SHAPE_WENDLAND_C2 ? 21.0 / (16.0 * SPH_PI) : 1.0 / SPH_PI);
}

static double radial3(double r) { return kw(r) * r * r; } /* W r^2, the 3-D radial integrand */

static void body_normalisation(void) {
  /* 4 pi int_0^2h W(r) r^2 dr by Simpson's rule */
  const double radial = 4.0 * SPH_PI * sph_test_simpson(radial3, 0.0, 2.0 * H, 2000);
  /* the midpoint sum over the cube [-2h, 2h]^3 at spacing h/40 */
  const int n = 40;
  const double d = H / n;
  double sum = 0.0;
  for (int i = -2 * n; i < 2 * n; i++)
    for (int j = -2 * n; j < 2 * n; j++)
      for (int k = -2 * n; k < 2 * n; k++) {
        const double x = (i + 0.5) * d, y = (j + 0.5) * d, z = (k + 0.5) * d;
        sum += kw(sqrt(x * x + y * y + z * z));
      }
  sum *= d * d * d;
  printf("\n  %s: integral of W in 3-D = %.12f (radial), %.9f (lattice h/40)", name(), radial, sum);
  CU_ASSERT_DOUBLE_EQUAL(radial, 1.0, 1e-9);
  CU_ASSERT_DOUBLE_EQUAL(sum, 1.0, 1e-5);
}

static void body_derivative(void) {
  double worst = 0.0;
  for (int k = 1; k < 400; k++) {
    const double r = k * (2.0 * H / 400), e = 1e-6 * H;
    double w, dw;
    kwdw(r, &w, &dw);
    const double fd = (kw(r + e) - kw(r - e)) / (2.0 * e);
    const double scale = 1.0 / (H * H * H * H);
    const double err = fabs(fd - dw) / scale;
    if (err > worst) worst = err;
  }
  printf("\n  %s: largest |dW/dr - difference| = %.3g h^-4", name(), worst);
  CU_ASSERT(worst < 1e-6);
  double w, dw;
  kwdw(2.0 * H * (1.0 + 1e-12), &w, &dw); /* just past the support: nothing */
  CU_ASSERT_EQUAL(w, 0.0);
  CU_ASSERT_EQUAL(dw, 0.0);
}

#define BOTH(body)                                                                                 \
  static void test_##body(void) {                                                                  \
    for (kind = SPH_SHAPE_CUBIC_SPLINE; kind <= SPH_SHAPE_WENDLAND_C2; kind++)                     \
      body_##body();                                                                               \
  }
BOTH(dimension)
BOTH(normalisation)
BOTH(derivative)

int main(void) {
  CU_TestInfo tests[] = {{"3-D constants: SPH_SYM 6, h^-3, C_3", test_dimension},
                         {"integral of W over space is 1 in 3-D", test_normalisation},
                         {"dW/dr matches a finite difference", test_derivative},
                         CU_TEST_INFO_NULL};
  return sph_test_main("kernel_3d", tests);
}
