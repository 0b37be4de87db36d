/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_wavemaker.c - linear wavemaker theory and paddle motion
 * (wavemaker.h).
 *
 * The dispersion solver satisfies its equation to 1e-12 over shallow to
 * deep water and has the right limits; the transfer functions match values
 * computed independently with 30-digit arithmetic (mpmath, g = 9.81) and
 * the formula exactly as printed, have the right shallow- and deep-water
 * limits and never overflow; the paper B numbers come out as PAPERS.md
 * says; the velocity of each paddle law is the time derivative of its
 * position (central differences), with and without the ramp; the flap
 * crosses the still-water level at X(t) and moves rigidly.
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "physics/kernel.h" /* SPH_PI */
#include "testutil.h"
#include "walls/wavemaker.h"

static const double G = 9.81;

static double rel(double a, double b) { return fabs(a - b) / fabs(b); }

/* The transfer functions exactly as printed (paper B §4.2; piston as in
 * PAPERS.md), for moderate kd. */
static double flap_printed(double y) {
  return 4.0 * (sinh(y) / y) * (y * sinh(y) - cosh(y) + 1.0) / (sinh(2 * y) + 2 * y);
}
static double piston_printed(double y) { return 2.0 * (cosh(2 * y) - 1.0) / (sinh(2 * y) + 2 * y); }

static void test_dispersion_residual(void) {
  double worst = 0.0, ymin = INFINITY, ymax = 0.0;
  sph_error err;
  for (int i = 0; i < 31; i++)
    for (int j = 0; j < 31; j++) {
      const double T = 0.05 * pow(1000.0, i / 30.0); /* 0.05 .. 50 s */
      const double d = 1e-4 * pow(1e8, j / 30.0);    /* 0.1 mm .. 10 km */
      const double omega = 2.0 * SPH_PI / T;
      double k = -1.0;
      CU_ASSERT_FATAL(sph_wave_number(omega, d, G, &k, &err) == 0);
      const double r = fabs(omega * omega - G * k * tanh(k * d)) / (omega * omega);
      if (r > worst) worst = r;
      if (k * d < ymin) ymin = k * d;
      if (k * d > ymax) ymax = k * d;
      CU_ASSERT(rel(sph_wave_frequency(k, d, G), omega) < 1e-12);
    }
  printf("\n  dispersion: kd from %.2e to %.2e, max relative residual %.2e ", ymin, ymax, worst);
  CU_ASSERT(worst < 1e-12);
  CU_ASSERT(ymin < 1e-3 && ymax > 1e4);
  /* against 30-digit values */
  double k;
  sph_wave_number(2.0 * SPH_PI / 4.7, 4.0, G, &k, &err);
  CU_ASSERT(rel(k, 0.243024862463290481) < 1e-13);
  sph_wave_number(2.0 * SPH_PI / 0.308, 0.013, G, &k, &err);
  CU_ASSERT(rel(k, 62.9346209704272966) < 1e-13);
}

static void test_dispersion_limits(void) {
  sph_error err;
  double k;
  /* shallow: k -> omega / sqrt(g d), relative difference (kd)^2 / 6 + O((kd)^4) */
  const double T = 20.0, d = 1e-3, omega = 2.0 * SPH_PI / T;
  CU_ASSERT(sph_wave_number(omega, d, G, &k, &err) == 0);
  const double ks = omega / sqrt(G * d);
  printf("\n  shallow: kd = %.2e, k / (omega/sqrt(gd)) - 1 = %.2e ", k * d, k / ks - 1.0);
  CU_ASSERT(fabs((k / ks - 1.0) / ((k * d) * (k * d) / 6.0) - 1.0) < 1e-4);
  /* deep: k = omega^2 / g */
  CU_ASSERT(sph_wave_number(2.0 * SPH_PI / 1.0, 100.0, G, &k, &err) == 0);
  CU_ASSERT(rel(k, (2.0 * SPH_PI) * (2.0 * SPH_PI) / G) < 1e-15);
  double L;
  CU_ASSERT(sph_wave_length(1.0, 1e3, G, &L, &err) == 0);
  CU_ASSERT(rel(L, G / (2.0 * SPH_PI)) < 1e-15); /* L0 = g T^2 / (2 pi) */
}

static void test_transfer_table(void) {
  /* {kd, flap, piston}, 30 digits (mpmath) */
  static const double tab[][3] = {
      {0.1, 0.0500415140502541077, 0.0999997782009160839},
      {0.5, 0.254743763760548938, 0.499338301580736964},
      {0.921, 0.483878927348030336, 0.908552282069808807},
      {1.0, 0.528087623589260846, 0.981789307313034423},
      {2.0, 1.04123859086434250, 1.68157893613291135},
  };
  for (size_t i = 0; i < sizeof tab / sizeof tab[0]; i++) {
    CU_ASSERT(rel(sph_paddle_transfer(SPH_PADDLE_FLAP, tab[i][0]), tab[i][1]) < 1e-14);
    CU_ASSERT(rel(sph_paddle_transfer(SPH_PADDLE_PISTON, tab[i][0]), tab[i][2]) < 1e-14);
  }
  /* the table value: kd = 0.921 gives H/S = 0.485 (to the 2-3 digits
   * given: the exact value is 0.48388) */
  const double hs = sph_paddle_transfer(SPH_PADDLE_FLAP, 0.921);
  printf("\n  flap H/S at kd = 0.921: %.6f ", hs);
  CU_ASSERT(fabs(hs - 0.485) < 0.0015);
  /* the printed formulas, where they are well conditioned */
  double worst = 0.0;
  for (int i = 0; i <= 200; i++) {
    const double y = 0.05 * pow(400.0, i / 200.0); /* 0.05 .. 20 */
    const double a = rel(sph_paddle_transfer(SPH_PADDLE_FLAP, y), flap_printed(y));
    const double b = rel(sph_paddle_transfer(SPH_PADDLE_PISTON, y), piston_printed(y));
    if (a > worst) worst = a;
    if (b > worst) worst = b;
  }
  printf("\n  against the printed formulas, kd in [0.05, 20]: max rel diff %.2e ", worst);
  CU_ASSERT(worst < 1e-12);
}

static void test_transfer_limits(void) {
  /* shallow: piston -> kd, flap -> kd / 2 */
  for (double y = 1e-8; y < 2e-3; y *= 10.0) {
    CU_ASSERT(fabs(sph_paddle_transfer(SPH_PADDLE_PISTON, y) / y - 1.0) < y);
    CU_ASSERT(fabs(sph_paddle_transfer(SPH_PADDLE_FLAP, y) / (0.5 * y) - 1.0) < y);
  }
  CU_ASSERT(sph_paddle_transfer(SPH_PADDLE_PISTON, 1e-300) == 1e-300);
  CU_ASSERT(sph_paddle_transfer(SPH_PADDLE_FLAP, 0.0) == 0.0);
  /* deep: piston -> 2, flap -> 2 (1 - 1/kd) */
  const double big[] = {40.0, 400.0, 800.0, 1e5, 1e300, INFINITY};
  for (size_t i = 0; i < sizeof big / sizeof big[0]; i++) {
    CU_ASSERT(sph_paddle_transfer(SPH_PADDLE_PISTON, big[i]) == 2.0);
    CU_ASSERT(rel(sph_paddle_transfer(SPH_PADDLE_FLAP, big[i]), 2.0 * (1.0 - 1.0 / big[i])) <
              1e-15);
  }
  CU_ASSERT(isnan(sph_paddle_transfer(SPH_PADDLE_FLAP, -1.0)));
  CU_ASSERT(isnan(sph_paddle_transfer(SPH_PADDLE_PISTON, NAN)));
  /* both increase with kd; the piston makes the higher wave */
  double pf = 0.0, pp = 0.0;
  for (int i = 1; i <= 400; i++) {
    const double y = 0.025 * i;
    const double f = sph_paddle_transfer(SPH_PADDLE_FLAP, y);
    const double p = sph_paddle_transfer(SPH_PADDLE_PISTON, y);
    CU_ASSERT(f > pf && p > pp && p > f);
    pf = f;
    pp = p;
  }
}

/* Paper B §4.2 and §4.3 (PAPERS.md). */
static void test_paper_cases(void) {
  sph_error err;
  /* linear wave: H = 1.02 m, L = 27.3 m, d = 4 m -> kd = 0.921, S = 2.11 m */
  const double kd = 2.0 * SPH_PI * 4.0 / 27.3;
  const double S1 = 1.02 / sph_paddle_transfer(SPH_PADDLE_FLAP, kd);
  printf("\n  paper B 4.2 from L = 27.3 m: kd = %.4f, H/S = %.4f, S = %.4f m ", kd, 1.02 / S1, S1);
  CU_ASSERT(rel(S1, 2.10890649703778712) < 1e-13);
  CU_ASSERT(fabs(S1 - 2.11) < 0.005);
  /* the same from T = 4.7 s: the dispersion relation gives L = 25.85 m, not
   * 27.3 m (which needs T = 4.907 s) */
  double L, S2, Sp;
  CU_ASSERT(sph_wave_length(4.7, 4.0, G, &L, &err) == 0);
  CU_ASSERT(sph_paddle_stroke(SPH_PADDLE_FLAP, 1.02, 4.7, 4.0, G, &S2, &err) == 0);
  CU_ASSERT(sph_paddle_stroke(SPH_PADDLE_PISTON, 1.02, 4.7, 4.0, G, &Sp, &err) == 0);
  const double T27 = 2.0 * SPH_PI / sph_wave_frequency(2.0 * SPH_PI / 27.3, 4.0, G);
  printf("\n  paper B 4.2 from T = 4.7 s: L = %.4f m, S = %.4f m (flap), %.4f m (piston);"
         " L = 27.3 m needs T = %.4f s ",
         L, S2, Sp, T27);
  CU_ASSERT(rel(L, 25.8540844072226457) < 1e-12);
  CU_ASSERT(rel(S2, 1.99041801162088707) < 1e-12);
  CU_ASSERT(rel(Sp, 1.06682026756890186) < 1e-12);
  CU_ASSERT(rel(T27, 4.90695869928254564) < 1e-12);
  /* plunging breaker: H = 0.013 m, T = 0.308 s, d = 0.013 m: L = 0.1 m and
   * S = 0.0305 m (the paper prints 0.305 m) */
  double S3;
  CU_ASSERT(sph_wave_length(0.308, 0.013, G, &L, &err) == 0);
  CU_ASSERT(sph_paddle_stroke(SPH_PADDLE_FLAP, 0.013, 0.308, 0.013, G, &S3, &err) == 0);
  printf("\n  paper B 4.3: L = %.5f m, d/L = %.4f, S = %.5f m (flap) ", L, 0.013 / L, S3);
  CU_ASSERT(rel(L, 0.0998367068919351687) < 1e-12);
  CU_ASSERT(rel(S3, 0.0304659234726008312) < 1e-12);
  CU_ASSERT(fabs(S3 - 0.0305) < 0.0001);
  CU_ASSERT(fabs(0.013 / L - 0.13) < 0.001);
}

/* Largest |velocity - central difference of position| over three periods,
 * relative to omega S / 2, for the displacement law and for points at
 * several rest positions (on the paddle plane below, at and above the
 * still-water level, and behind or in front of it). */
static double fd_error(const sph_paddle *pd) {
  static const double pts[][2] = {{0.0, 0.0},  {0.0, 1.0},  {0.0, 4.0}, {0.0, 5.5},
                                  {-0.1, 2.0}, {-0.2, 0.3}, {0.15, 3.0}};
  const double T = pd->period, dt = 1e-6 * T;
  const double scale = SPH_PI / T * pd->stroke;
  double worst = 0.0;
  for (int i = 1; i < 300; i++) {
    const double t = 3.0 * T * (i + 0.3183) / 300.0; /* never within dt of 0 or T_ramp */
    double X, U, Xp, Xm, u;
    sph_paddle_displacement(pd, t, &X, &U);
    sph_paddle_displacement(pd, t + dt, &Xp, &u);
    sph_paddle_displacement(pd, t - dt, &Xm, &u);
    const double e = fabs(U - (Xp - Xm) / (2 * dt)) / scale;
    if (e > worst) worst = e;
    for (size_t j = 0; j < sizeof pts / sizeof pts[0]; j++) {
      const double xr = pd->hinge_x + pts[j][0], yr = pd->hinge_y + pts[j][1];
      double x, y, vx, vy, xp, yp, xm, ym, v;
      sph_paddle_point(pd, t, xr, yr, &x, &y, &vx, &vy);
      sph_paddle_point(pd, t + dt, xr, yr, &xp, &yp, &v, &v);
      sph_paddle_point(pd, t - dt, xr, yr, &xm, &ym, &v, &v);
      const double ex = fabs(vx - (xp - xm) / (2 * dt)) / scale;
      const double ey = fabs(vy - (yp - ym) / (2 * dt)) / scale;
      if (ex > worst) worst = ex;
      if (ey > worst) worst = ey;
    }
  }
  return worst;
}

/* Paper B 4.2 dimensions: S = 2.11 m, T = 4.7 s, d = 4 m. */
static sph_paddle paddle(sph_paddle_kind kind, double ramp) {
  sph_paddle pd = {kind, 2.11, 4.7, 4.0, ramp, 1.5, -0.25};
  return pd;
}

static void test_velocity_is_derivative(void) {
  sph_error err;
  for (int kind = 0; kind < 2; kind++)
    for (int r = 0; r < 2; r++) {
      const sph_paddle pd = paddle((sph_paddle_kind)kind, r ? 4.7 : 0.0);
      CU_ASSERT_FATAL(sph_paddle_check(&pd, &err) == 0);
      const double e = fd_error(&pd);
      printf("\n  %s, %s ramp: max |v - FD| / (omega S/2) = %.2e ", sph_paddle_name(pd.kind),
             r ? "with" : "no", e);
      CU_ASSERT(e < 1e-7);
    }
}

static void test_ramp(void) {
  for (int kind = 0; kind < 2; kind++) {
    const sph_paddle a = paddle((sph_paddle_kind)kind, 0.0);
    const sph_paddle b = paddle((sph_paddle_kind)kind, 2.35);
    double X, U, Xa, Ua, th, om;
    /* at rest before the start; the ramped paddle starts with zero velocity */
    sph_paddle_displacement(&b, -1.0, &X, &U);
    CU_ASSERT(X == 0.0 && U == 0.0);
    sph_paddle_displacement(&b, 0.0, &X, &U);
    CU_ASSERT(X == 0.0 && U == 0.0);
    sph_paddle_displacement(&a, 0.0, &X, &U);
    CU_ASSERT(X == 0.0 && rel(U, 2.0 * SPH_PI / 4.7 * 1.055) < 1e-15);
    /* after the ramp, the unramped law exactly; velocity continuous at its end */
    for (double t = 2.35; t < 12.0; t += 0.37) {
      sph_paddle_displacement(&a, t, &Xa, &Ua);
      sph_paddle_displacement(&b, t, &X, &U);
      CU_ASSERT(X == Xa && U == Ua);
    }
    double Um;
    sph_paddle_displacement(&b, 2.35 * (1.0 - 1e-12), &X, &Um);
    sph_paddle_displacement(&b, 2.35, &X, &U);
    CU_ASSERT(fabs(U - Um) < 1e-9);
    /* during the ramp the amplitude is smaller */
    sph_paddle_displacement(&a, 1.0, &Xa, &Ua);
    sph_paddle_displacement(&b, 1.0, &X, &U);
    CU_ASSERT(fabs(X) < fabs(Xa));
    sph_paddle_angle(&a, 1.0, &th, &om);
    if (kind == SPH_PADDLE_PISTON) CU_ASSERT(th == 0.0 && om == 0.0);
  }
}

/* The flap crosses the still-water level at X(t) and rotates rigidly; the
 * piston translates. */
static void test_motion_geometry(void) {
  const sph_paddle f = paddle(SPH_PADDLE_FLAP, 4.7), p = paddle(SPH_PADDLE_PISTON, 4.7);
  double amax = 0.0;
  for (double t = 0.0; t < 15.0; t += 0.173) {
    double X, U, x, y, vx, vy, th, om;
    sph_paddle_displacement(&f, t, &X, &U);
    sph_paddle_angle(&f, t, &th, &om);
    if (fabs(th) > amax) amax = fabs(th);
    /* a point on the paddle plane at 2.5 m: the line hinge-point meets the
     * still-water level (4 m above the hinge) at hinge_x + X */
    sph_paddle_point(&f, t, f.hinge_x, f.hinge_y + 2.5, &x, &y, &vx, &vy);
    const double xs = f.hinge_x + (x - f.hinge_x) * 4.0 / (y - f.hinge_y);
    CU_ASSERT(fabs(xs - (f.hinge_x + X)) < 1e-12);
    CU_ASSERT(fabs(hypot(x - f.hinge_x, y - f.hinge_y) - 2.5) < 1e-12);
    /* off the plane: distance kept, velocity normal to the radius */
    sph_paddle_point(&f, t, f.hinge_x - 0.2, f.hinge_y + 1.0, &x, &y, &vx, &vy);
    CU_ASSERT(fabs(hypot(x - f.hinge_x, y - f.hinge_y) - hypot(0.2, 1.0)) < 1e-12);
    CU_ASSERT(fabs(vx * (x - f.hinge_x) + vy * (y - f.hinge_y)) < 1e-12);
    /* the hinge does not move */
    sph_paddle_point(&f, t, f.hinge_x, f.hinge_y, &x, &y, &vx, &vy);
    CU_ASSERT(x == f.hinge_x && y == f.hinge_y && vx == 0.0 && vy == 0.0);
    /* piston */
    sph_paddle_displacement(&p, t, &X, &U);
    sph_paddle_point(&p, t, 0.3, 2.0, &x, &y, &vx, &vy);
    CU_ASSERT(x == 0.3 + X && y == 2.0 && vx == U && vy == 0.0);
  }
  printf("\n  flap, S = 2.11 m, d = 4 m: angle amplitude %.4f rad (atan(S/2d) = %.4f) ", amax,
         atan(1.055 / 4.0));
  CU_ASSERT(amax <= atan(1.055 / 4.0) && amax > 0.99 * atan(1.055 / 4.0));
}

static void test_linear_elevation(void) {
  const double H = 1.02, k = 0.243, omega = 2.0 * SPH_PI / 4.7;
  /* crest at the paddle at t = 0 (paddle moving forward fastest), one
   * wavelength away too; trough half a period later */
  CU_ASSERT(rel(sph_wave_linear_elevation(H, k, omega, 0.0, 0.0), 0.51) < 1e-15);
  CU_ASSERT(rel(sph_wave_linear_elevation(H, k, omega, 2.0 * SPH_PI / k, 0.0), 0.51) < 1e-14);
  CU_ASSERT(rel(sph_wave_linear_elevation(H, k, omega, 0.0, 2.35), -0.51) < 1e-14);
  /* propagates in +x: the crest is at x = c t */
  const double c = omega / k;
  CU_ASSERT(rel(sph_wave_linear_elevation(H, k, omega, c * 3.1, 3.1), 0.51) < 1e-14);
}

static void test_names_and_errors(void) {
  sph_paddle_kind k;
  sph_error err;
  CU_ASSERT(sph_paddle_from_name("flap", &k, &err) == 0 && k == SPH_PADDLE_FLAP);
  CU_ASSERT(sph_paddle_from_name("piston", &k, &err) == 0 && k == SPH_PADDLE_PISTON);
  CU_ASSERT_STRING_EQUAL(sph_paddle_name(SPH_PADDLE_FLAP), "flap");
  CU_ASSERT_STRING_EQUAL(sph_paddle_name((sph_paddle_kind)5), "?");
  CU_ASSERT(sph_paddle_kind_names[2] == NULL);
  CU_ASSERT(sph_paddle_from_name("hinged", &k, &err) != 0);
  CU_ASSERT(strstr(err.msg, "hinged") && strstr(err.msg, "piston, flap"));
  double v = 7.0;
  CU_ASSERT(sph_wave_number(0.0, 1.0, G, &v, &err) != 0);
  CU_ASSERT(sph_wave_number(1.0, -1.0, G, &v, &err) != 0);
  CU_ASSERT(sph_wave_number(1.0, 1.0, NAN, &v, &err) != 0);
  CU_ASSERT(sph_wave_number(1e200, 1e200, G, &v, &err) != 0); /* omega^2 d / g overflows */
  CU_ASSERT(sph_wave_length(0.0, 1.0, G, &v, &err) != 0);
  CU_ASSERT(sph_paddle_stroke(SPH_PADDLE_FLAP, -1.0, 1.0, 1.0, G, &v, &err) != 0);
  CU_ASSERT(sph_paddle_stroke(SPH_PADDLE_FLAP, 1.0, 1.0, 0.0, G, &v, &err) != 0);
  CU_ASSERT(v == 7.0); /* untouched on error */
  sph_paddle pd = paddle(SPH_PADDLE_FLAP, 0.0);
  CU_ASSERT(sph_paddle_check(&pd, &err) == 0);
  pd.depth = 0.0;
  CU_ASSERT(sph_paddle_check(&pd, &err) != 0);
  pd.kind = SPH_PADDLE_PISTON; /* the piston does not need a depth */
  CU_ASSERT(sph_paddle_check(&pd, &err) == 0);
  pd.period = -1.0;
  CU_ASSERT(sph_paddle_check(&pd, &err) != 0);
  pd = paddle(SPH_PADDLE_PISTON, -1.0);
  CU_ASSERT(sph_paddle_check(&pd, &err) != 0);
  pd = paddle(SPH_PADDLE_PISTON, 0.0);
  pd.stroke = NAN;
  CU_ASSERT(sph_paddle_check(&pd, &err) != 0);
  pd = paddle((sph_paddle_kind)3, 0.0);
  CU_ASSERT(sph_paddle_check(&pd, &err) != 0);
}

int main(void) {
  CU_TestInfo tests[] = {
      {"dispersion relation residual, shallow to deep", test_dispersion_residual},
      {"dispersion limits", test_dispersion_limits},
      {"transfer functions: tabulated values", test_transfer_table},
      {"transfer functions: limits, no overflow", test_transfer_limits},
      {"paper B wave cases", test_paper_cases},
      {"paddle velocity = d/dt position", test_velocity_is_derivative},
      {"ramp-up", test_ramp},
      {"paddle geometry", test_motion_geometry},
      {"far-field linear wave", test_linear_elevation},
      {"names and errors", test_names_and_errors},
      CU_TEST_INFO_NULL,
  };
  return sph_test_main("wavemaker", tests);
}
