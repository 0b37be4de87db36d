/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * wavemaker.c - linear wavemaker theory and paddle motion (see wavemaker.h).
 *
 * Dispersion. With y = kd and x = omega^2 d / g (the deep-water k0 d) the
 * relation omega^2 = g k tanh(kd) reads f(y) = y tanh y - x = 0, which has
 * one positive root for every x > 0 (f increases from -x). Newton's method
 * starts from the explicit approximation of Fenton & McKee (1990),
 * y0 = x / tanh(x^(3/4))^(2/3), within 1.7 % of the root at every depth
 * (it has the right shallow, y -> sqrt(x), and deep, y -> x, limits), so a
 * handful of quadratically converging steps reach rounding. f' = tanh y +
 * y / cosh^2 y stays >= tanh y > 0; in deep water tanh y is 1 to rounding
 * and the first step lands on y = x.
 *
 * Transfer functions (paper B §4.2 for the flap; Dean & Dalrymple,
 * "Water wave mechanics for engineers and scientists", ch. 6, for both).
 * Dividing numerator and denominator by sinh 2kd gives forms that neither
 * overflow (kd up to infinity) nor cancel (kd down to the smallest double):
 *   piston  H/S = 2 tanh y / (1 + 2y / sinh 2y)
 *   flap    H/S = 2 (tanh y - (1 - 1/cosh y)/y) / (1 + 2y / sinh 2y)
 * with 1 - 1/cosh y = 2 sinh^2(y/2) / cosh y for y <= 1.
 *
 * Motion. The piston translates by X(t) = r(t) (S/2) sin(omega t), r the
 * ramp factor. The flap rotates about its hinge on the bed by
 * theta = atan(X/d): the paddle line then crosses the still-water level
 * exactly at X(t), which is what a flap stroke means in linear theory and
 * in a laboratory (the stroke measured at the still-water level). The other
 * reading, the material point at rest height d displaced horizontally by X
 * (theta = asin(X/d)), differs at third order in X/d: for paper B §4.2
 * (S/2 = 1.055 m, d = 4 m) the angle amplitudes differ by 3.5 % (with atan
 * that material point moves by d sin(theta) = 1.020 m, not 1.055 m; linear
 * theory cannot tell the two apart). Velocities
 * are exact derivatives: U = r' A sin + r A omega cos, theta' = d U / (d^2 +
 * X^2), and a rigid rotation gives v = theta' (y - y_h, -(x - x_h)).
 */
#include "config.h"

#include "walls/wavemaker.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include "physics/kernel.h" /* SPH_PI */

const char *const sph_paddle_kind_names[] = {"piston", "flap", NULL};

const char *sph_paddle_name(sph_paddle_kind k) {
  if ((int)k < 0 || (int)k > (int)SPH_PADDLE_FLAP) return "?";
  return sph_paddle_kind_names[k];
}

int sph_paddle_from_name(const char *name, sph_paddle_kind *k, sph_error *err) {
  for (int i = 0; sph_paddle_kind_names[i]; i++)
    if (name && strcmp(name, sph_paddle_kind_names[i]) == 0) {
      *k = (sph_paddle_kind)i;
      return 0;
    }
  return sph_error_set(err, "paddle: unknown choice '%s' (valid: piston, flap)",
                       name ? name : "(null)");
}

/* ---- linear theory ---------------------------------------------------------- */

static int positive(double v) { return v > 0.0 && isfinite(v); }

/* The root y of y tanh y = x (x > 0, finite). */
static double dispersion_root(double x) {
  double y = x / pow(tanh(pow(x, 0.75)), 2.0 / 3.0);
  for (int it = 0; it < 50; it++) {
    const double t = tanh(y), c = cosh(y);
    const double step = (y * t - x) / (t + y / (c * c));
    y -= step;
    if (fabs(step) <= 4.0 * DBL_EPSILON * y) break;
  }
  return y;
}

int sph_wave_number(double omega, double d, double g, double *k, sph_error *err) {
  if (!positive(omega) || !positive(d) || !positive(g))
    return sph_error_set(err, "dispersion: omega, depth and g must be positive, got %g, %g, %g",
                         omega, d, g);
  const double x = omega * omega * d / g;
  if (!positive(x)) return sph_error_set(err, "dispersion: omega^2 d / g = %g is out of range", x);
  const double y = dispersion_root(x);
  if (!positive(y) || fabs(y * tanh(y) - x) > 1e-13 * x)
    return sph_error_set(err, "dispersion: no convergence for omega %g, depth %g", omega, d);
  *k = y / d;
  return 0;
}

double sph_wave_frequency(double k, double d, double g) { return sqrt(g * k * tanh(k * d)); }

int sph_wave_length(double T, double d, double g, double *L, sph_error *err) {
  if (!positive(T)) return sph_error_set(err, "dispersion: period must be positive, got %g", T);
  double k;
  if (sph_wave_number(2.0 * SPH_PI / T, d, g, &k, err)) return -1;
  *L = 2.0 * SPH_PI / k;
  return 0;
}

/* 1 + 2y / sinh 2y, the common denominator (-> 2 for y -> 0, 1 for y -> inf). */
static double denominator(double y) { return 1.0 + 2.0 * y / sinh(2.0 * y); }

static double piston_hs(double y) { return 2.0 * tanh(y) / denominator(y); }

static double flap_hs(double y) {
  const double c = cosh(y);
  const double s = sinh(0.5 * y);
  const double one_minus_sech = y <= 1.0 ? 2.0 * s * s / c : 1.0 - 1.0 / c;
  return 2.0 * (tanh(y) - one_minus_sech / y) / denominator(y);
}

double sph_paddle_transfer(sph_paddle_kind kind, double kd) {
  if (!(kd >= 0.0)) return NAN;
  if (kd == 0.0) return 0.0;
  if (isinf(kd)) return 2.0;
  return kind == SPH_PADDLE_FLAP ? flap_hs(kd) : piston_hs(kd);
}

int sph_paddle_stroke(sph_paddle_kind kind, double H, double T, double d, double g, double *S,
                      sph_error *err) {
  if (!positive(H) || !positive(T))
    return sph_error_set(err, "paddle stroke: H and T must be positive, got %g, %g", H, T);
  double k;
  if (sph_wave_number(2.0 * SPH_PI / T, d, g, &k, err)) return -1;
  *S = H / sph_paddle_transfer(kind, k * d);
  return 0;
}

double sph_wave_linear_elevation(double H, double k, double omega, double x, double t) {
  return 0.5 * H * cos(k * x - omega * t);
}

/* ---- paddle motion ------------------------------------------------------------ */

int sph_paddle_check(const sph_paddle *pd, sph_error *err) {
  if ((int)pd->kind < 0 || (int)pd->kind > (int)SPH_PADDLE_FLAP)
    return sph_error_set(err, "paddle: unknown kind %d", (int)pd->kind);
  if (!(pd->stroke >= 0.0) || !isfinite(pd->stroke))
    return sph_error_set(err, "paddle: stroke must be >= 0, got %g", pd->stroke);
  if (!positive(pd->period))
    return sph_error_set(err, "paddle: period must be positive, got %g", pd->period);
  if (!(pd->ramp >= 0.0) || !isfinite(pd->ramp))
    return sph_error_set(err, "paddle: ramp time must be >= 0, got %g", pd->ramp);
  if (pd->kind == SPH_PADDLE_FLAP) {
    if (!positive(pd->depth))
      return sph_error_set(err, "paddle: flap depth must be positive, got %g", pd->depth);
    if (!isfinite(pd->hinge_x) || !isfinite(pd->hinge_y))
      return sph_error_set(err, "paddle: flap hinge is not finite");
  }
  return 0;
}

/* The ramp factor r(t) and dr/dt. */
static void ramp_factor(double ramp, double t, double *r, double *dr) {
  if (ramp > 0.0 && t < ramp) {
    const double a = SPH_PI / ramp;
    *r = 0.5 * (1.0 - cos(a * t));
    *dr = 0.5 * a * sin(a * t);
  } else {
    *r = 1.0;
    *dr = 0.0;
  }
}

void sph_paddle_displacement(const sph_paddle *pd, double t, double *X, double *U) {
  if (t < 0.0) { /* at rest before the start */
    *X = *U = 0.0;
    return;
  }
  const double omega = 2.0 * SPH_PI / pd->period, amp = 0.5 * pd->stroke;
  double r, dr;
  ramp_factor(pd->ramp, t, &r, &dr);
  const double s = sin(omega * t), c = cos(omega * t);
  *X = r * amp * s;
  *U = dr * amp * s + r * amp * omega * c;
}

void sph_paddle_angle(const sph_paddle *pd, double t, double *theta, double *omega_t) {
  if (pd->kind != SPH_PADDLE_FLAP) {
    *theta = *omega_t = 0.0;
    return;
  }
  double X, U;
  sph_paddle_displacement(pd, t, &X, &U);
  const double d = pd->depth;
  *theta = atan(X / d);
  *omega_t = d * U / (d * d + X * X);
}

void sph_paddle_point(const sph_paddle *pd, double t, double xr, double yr, double *x, double *y,
                      double *vx, double *vy) {
  if (pd->kind != SPH_PADDLE_FLAP) {
    double X, U;
    sph_paddle_displacement(pd, t, &X, &U);
    *x = xr + X;
    *y = yr;
    *vx = U;
    *vy = 0.0;
    return;
  }
  double th, om;
  sph_paddle_angle(pd, t, &th, &om);
  const double c = cos(th), s = sin(th);
  const double rx = xr - pd->hinge_x, ry = yr - pd->hinge_y;
  const double px = rx * c + ry * s, py = -rx * s + ry * c;
  *x = pd->hinge_x + px;
  *y = pd->hinge_y + py;
  *vx = om * py;
  *vy = -om * px;
}
