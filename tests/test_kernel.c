/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_kernel.c - properties of the 2-D kernels (kernel.h), each test for
 * the cubic spline and the Wendland C2 kernel:
 * normalisation, positivity, compact support, exact antisymmetry of the
 * gradient, the moment properties of GOST R 57700.6 (A.18-A.20), and the
 * derivative against a finite difference; the branch-free evaluator of
 * the interaction loops (sph_kernel_w_f: W and (1/r) dW/dr) against the
 * reference one (sph_kernel_w_dw) to round-off over the whole support;
 * and the Wendland kernel's closed form at a few radii.
 *
 * Integrals over the plane are lattice (midpoint) sums with spacing h/100:
 * the kernel is C2 with compact support, so such sums converge far below
 * the 1e-6 tolerance used here.
 */
#include "config.h"

#include <math.h>
#include <stdio.h>

#include "physics/kernel.h"
#include "testutil.h"

static const double H = 0.013; /* any smoothing length */

static sph_kernel_kind kind; /* the kernel under test */
static double kw(double r, double h) { return sph_kernel_w(kind, r, h); }
static void kwdw(double r, double h, double *w, double *dw) { sph_kernel_w_dw(kind, r, h, w, dw); }
static void kgrad(double dx, double dy, double h, double *gx, double *gy) {
  const double r = sqrt(dx * dx + dy * dy);
  double w, dw;
  kwdw(r, h, &w, &dw);
  *gx = r > 0.0 ? dw * dx / r : 0.0;
  *gy = r > 0.0 ? dw * dy / r : 0.0;
}

/* sum over a lattice covering the support around (cx, cy) of f(x', y') W(|c - x'|) dA */
typedef double (*weight_fn)(double x, double y);
static double one(double x, double y) {
  (void)x;
  (void)y;
  return 1.0;
}
static double fx(double x, double y) {
  (void)y;
  return x;
}
static double fy(double x, double y) {
  (void)x;
  return y;
}

static double lattice_integral(double cx, double cy, weight_fn f) {
  const int n = 100; /* points per h */
  const double d = H / n;
  double sum = 0.0;
  for (int i = -2 * n; i < 2 * n; i++)
    for (int j = -2 * n; j < 2 * n; j++) {
      const double x = cx + (i + 0.5) * d, y = cy + (j + 0.5) * d;
      const double r = sqrt((x - cx) * (x - cx) + (y - cy) * (y - cy));
      sum += f(x, y) * kw(r, H) * d * d;
    }
  return sum;
}

static double radial(double r) { return kw(r, H) * r; } /* W r, the 2-D radial integrand */

static void body_normalisation(void) {
  const double s = lattice_integral(0.0, 0.0, one);
  printf("\n  %s: integral of W = %.12f\n", kind ? "wendland_c2" : "cubic_spline", s);
  CU_ASSERT_DOUBLE_EQUAL(s, 1.0, 1e-6);
  /* and by radial Simpson quadrature, 2 pi int_0^2h W(r) r dr */
  CU_ASSERT_DOUBLE_EQUAL(2.0 * SPH_PI * sph_test_simpson(radial, 0.0, 2.0 * H, 2000), 1.0, 1e-9);
}

static void body_positive_and_compact(void) {
  for (int k = 0; k <= 4000; k++) {
    const double r = k * (3.0 * H / 4000);
    double w, dw;
    kwdw(r, H, &w, &dw);
    CU_ASSERT(w >= 0.0);
    CU_ASSERT(dw <= 0.0); /* W decreases with r */
    if (r >= 2.0 * H) {
      CU_ASSERT_EQUAL(w, 0.0);
      CU_ASSERT_EQUAL(dw, 0.0);
    } else {
      CU_ASSERT(w > 0.0);
    }
  }
  /* continuity of W and dW/dr at q = 1 */
  double w1, d1, w2, d2;
  kwdw(H * (1 - 1e-12), H, &w1, &d1);
  kwdw(H * (1 + 1e-12), H, &w2, &d2);
  CU_ASSERT_DOUBLE_EQUAL(w1, w2, 1e-8 * w1);
  CU_ASSERT_DOUBLE_EQUAL(d1, d2, 1e-8 * fabs(d1));
}

static void body_gradient_antisymmetric(void) {
  unsigned long long s = 12345;
  for (int k = 0; k < 10000; k++) {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    const double dx = ((double)(s >> 11) / 9007199254740992.0 - 0.5) * 4.4 * H;
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    const double dy = ((double)(s >> 11) / 9007199254740992.0 - 0.5) * 4.4 * H;
    double gx, gy, hx, hy;
    kgrad(dx, dy, H, &gx, &gy);
    kgrad(-dx, -dy, H, &hx, &hy);
    CU_ASSERT(gx == -hx && gy == -hy); /* bitwise */
    /* the gradient points from j to i with a negative radial slope */
    CU_ASSERT(gx * dx + gy * dy <= 0.0);
  }
  double gx, gy;
  kgrad(0.0, 0.0, H, &gx, &gy);
  CU_ASSERT(gx == 0.0 && gy == 0.0);
}

static void body_derivative_matches_difference(void) {
  for (int k = 1; k < 200; k++) {
    const double r = k * (2.0 * H / 200);
    const double e = 1e-6 * H;
    const double fd = (kw(r + e, H) - kw(r - e, H)) / (2 * e);
    double w, dw;
    kwdw(r, H, &w, &dw);
    CU_ASSERT_DOUBLE_EQUAL(dw, fd, 1e-6 * kw(0, H) / H);
  }
}

/* A.18-A.20: int W = 1, int r' W(r - r') dr' = r, int (r - r') W dr' = 0,
 * at a point off the origin. */
static void body_moments(void) {
  const double cx = 0.3 * H + 1.7, cy = -0.7 * H + 0.2;
  const double m0 = lattice_integral(cx, cy, one);
  const double mx = lattice_integral(cx, cy, fx);
  const double my = lattice_integral(cx, cy, fy);
  printf("\n  moments: %.12f %.12g %.12g\n", m0, mx - cx, my - cy);
  CU_ASSERT_DOUBLE_EQUAL(m0, 1.0, 1e-6);
  CU_ASSERT_DOUBLE_EQUAL(mx, cx, 1e-6 * H + 1e-6 * fabs(cx));
  CU_ASSERT_DOUBLE_EQUAL(my, cy, 1e-6 * H + 1e-6 * fabs(cy));
  CU_ASSERT_DOUBLE_EQUAL(cx * m0 - mx, 0.0, 1e-6 * fabs(cx));
}

/* sph_cubic_w_f against sph_cubic_w_dw: relative differences at the
 * round-off level (a few ulps of the larger terms it sums) for 0 < r < 2h. */
static void body_branch_free_form(void) {
  double worst_w = 0.0, worst_f = 0.0;
  const double inv_h = 1.0 / H, wmax = kw(0.0, H);
  for (int k = 1; k < 20000; k++) {
    const double r = 2.0 * H * k / 20000.0;
    double w, dw, w2, f;
    kwdw(r, H, &w, &dw);
    sph_kernel_w_f(kind, r, 1.0 / r, inv_h, &w2, &f);
    const double ew = fabs(w2 - w) / wmax;
    const double ef = fabs(f * r - dw) / (wmax * inv_h);
    if (ew > worst_w) worst_w = ew;
    if (ef > worst_f) worst_f = ef;
  }
  printf("\n  largest difference: W %.2e, dW/dr %.2e (relative to the kernel's scale)", worst_w,
         worst_f);
  CU_ASSERT(worst_w < 1e-14);
  CU_ASSERT(worst_f < 1e-14);
}

/* The Wendland C2 kernel against its closed form: W(0) = 7/(4 pi h^2),
 * W(h) = (3/16) W(0), dW/dr(h) = -(5/8) W(0)/h. */
static void test_wendland_values(void) {
  const double w0 = 7.0 / (4.0 * SPH_PI * H * H);
  double w, dw;
  sph_kernel_w_dw(SPH_KERNEL_WENDLAND_C2, 0.0, H, &w, &dw);
  CU_ASSERT_DOUBLE_EQUAL(w, w0, 1e-15 * w0);
  CU_ASSERT_EQUAL(dw, 0.0);
  sph_kernel_w_dw(SPH_KERNEL_WENDLAND_C2, H, H, &w, &dw);
  CU_ASSERT_DOUBLE_EQUAL(w, 3.0 / 16.0 * w0, 1e-15 * w0);
  CU_ASSERT_DOUBLE_EQUAL(dw, -5.0 / 8.0 * w0 / H, 1e-15 * w0 / H);
  sph_kernel_w_dw(SPH_KERNEL_WENDLAND_C2, 2.0 * H * (1.0 + 1e-12), H, &w, &dw);
  CU_ASSERT(w == 0.0 && dw == 0.0);
}

static void test_normalisation(void) {
  for (int k = 0; k < 2; k++) {
    kind = (sph_kernel_kind)k;
    body_normalisation();
  }
}
static void test_positive_and_compact(void) {
  for (int k = 0; k < 2; k++) {
    kind = (sph_kernel_kind)k;
    body_positive_and_compact();
  }
}
static void test_gradient_antisymmetric(void) {
  for (int k = 0; k < 2; k++) {
    kind = (sph_kernel_kind)k;
    body_gradient_antisymmetric();
  }
}
static void test_derivative_matches_difference(void) {
  for (int k = 0; k < 2; k++) {
    kind = (sph_kernel_kind)k;
    body_derivative_matches_difference();
  }
}
static void test_moments(void) {
  for (int k = 0; k < 2; k++) {
    kind = (sph_kernel_kind)k;
    body_moments();
  }
}
static void test_branch_free_form(void) {
  for (int k = 0; k < 2; k++) {
    kind = (sph_kernel_kind)k;
    body_branch_free_form();
  }
}

int main(void) {
  CU_TestInfo tests[] = {
      {"normalisation (lattice sum and radial quadrature)", test_normalisation},
      {"W >= 0, decreasing, zero beyond 2h, continuous", test_positive_and_compact},
      {"grad W antisymmetric in the pair (bitwise)", test_gradient_antisymmetric},
      {"dW/dr matches a finite difference", test_derivative_matches_difference},
      {"moment properties A.18-A.20", test_moments},
      {"branch-free W and dW/dr / r agree with the reference form", test_branch_free_form},
      {"Wendland C2 closed form", test_wendland_values},
      CU_TEST_INFO_NULL};
  return sph_test_main("kernel", tests);
}
