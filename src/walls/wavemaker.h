/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * wavemaker.h - linear wavemaker theory and paddle motion laws (paper B
 * §4.2).
 *
 * A paddle at the end of a flume of still-water depth d moves with period
 * T (omega = 2 pi / T) and stroke S; far from it (a few depths) linear
 * theory predicts a progressive wave of height H = S * (H/S)(kd), with k
 * the wave number of the dispersion relation omega^2 = g k tanh(kd). Two
 * paddle types (`paddle: piston | flap`):
 *
 *   piston  the whole paddle translates: X(t) = (S/2) sin(omega t);
 *           H/S = 2 (cosh 2kd - 1) / (sinh 2kd + 2kd);
 *   flap    the paddle rotates about a hinge on the bed so that it crosses
 *           the still-water level at X(t) = (S/2) sin(omega t);
 *           H/S = 4 (sinh kd / kd) (kd sinh kd - cosh kd + 1) / (sinh 2kd + 2kd)
 *           (the formula paper B prints).
 *
 * An optional ramp multiplies X(t) by 0.5 (1 - cos(pi t / T_ramp)) for
 * 0 <= t < T_ramp, so that the paddle starts from rest without the start-up
 * shock; every velocity here is the exact time derivative of the position,
 * ramp included. Before t = 0 the paddle is at rest at X = 0.
 */
#ifndef SPH_WAVEMAKER_H
#define SPH_WAVEMAKER_H

#include "core/error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sph_paddle_kind { SPH_PADDLE_PISTON = 0, SPH_PADDLE_FLAP = 1 } sph_paddle_kind;

/* Names in enum order, NULL-terminated: {"piston", "flap", NULL}. */
extern const char *const sph_paddle_kind_names[];
/* "piston", "flap"; "?" for a value outside the enum. */
const char *sph_paddle_name(sph_paddle_kind k);
/* The kind named `name`; an unknown name is an error listing the valid ones. */
int sph_paddle_from_name(const char *name, sph_paddle_kind *k, sph_error *err);

/* ---- linear theory ---------------------------------------------------------- */

/* The wave number k > 0 with omega^2 = g k tanh(k d), by Newton's method
 * from the Fenton & McKee (1990) approximation, to rounding (relative
 * residual of the equation below 1e-13 for any depth). omega, d, g > 0. */
int sph_wave_number(double omega, double d, double g, double *k, sph_error *err);
/* The frequency of wave number k: omega = sqrt(g k tanh(kd)). */
double sph_wave_frequency(double k, double d, double g);
/* The wavelength L = 2 pi / k of the period T in depth d. */
int sph_wave_length(double T, double d, double g, double *L, sph_error *err);

/* H/S of the paddle at relative depth kd >= 0 (paper B §4.2 for the flap).
 * Evaluated in forms without overflow or cancellation: piston -> kd for
 * kd -> 0 and -> 2 for kd -> inf; flap -> kd/2 and -> 2. NaN for kd < 0. */
double sph_paddle_transfer(sph_paddle_kind kind, double kd);

/* The stroke S that makes waves of height H with period T in depth d. */
int sph_paddle_stroke(sph_paddle_kind kind, double H, double T, double d, double g, double *S,
                      sph_error *err);

/* The far-field linear wave of height H: eta(x, t) = (H/2) cos(k x - omega t),
 * x from the paddle's mean position. It is in phase with the paddle
 * velocity (crest at the paddle when it moves forward fastest), ignores the
 * evanescent modes near the paddle and the ramp, and assumes the wave has
 * arrived (x < c_g t). */
double sph_wave_linear_elevation(double H, double k, double omega, double x, double t);

/* ---- paddle motion ------------------------------------------------------------ */

typedef struct sph_paddle {
  sph_paddle_kind kind;
  double stroke;  /* S (m): full excursion at the still-water level */
  double period;  /* T (s) */
  double depth;   /* d (m): still-water level above the hinge (flap; unused by the piston) */
  double ramp;    /* T_ramp (s); 0: no ramp */
  double hinge_x; /* flap: the hinge (x of the paddle plane at rest, bed level) */
  double hinge_y;
} sph_paddle;

/* Validates a filled-in paddle: stroke >= 0, period > 0, ramp >= 0, and
 * for a flap depth > 0; all finite. */
int sph_paddle_check(const sph_paddle *pd, sph_error *err);

/* The displacement X(t) of the paddle at the still-water level, ramp
 * included, and its rate dX/dt. */
void sph_paddle_displacement(const sph_paddle *pd, double t, double *X, double *U);

/* The flap angle from the vertical, theta(t) = atan(X(t) / d) (positive:
 * top towards +x), and dtheta/dt. For a piston both are 0. */
void sph_paddle_angle(const sph_paddle *pd, double t, double *theta, double *omega_t);

/* Position and velocity at time t of the paddle point (a wall particle)
 * whose rest position is (xr, yr). Piston: translated by X(t). Flap:
 * rotated rigidly about the hinge by theta(t), so a point keeps its
 * distance from the hinge and v = theta' x (r - r_hinge). */
void sph_paddle_point(const sph_paddle *pd, double t, double xr, double yr, double *x, double *y,
                      double *vx, double *vy);

#ifdef __cplusplus
}
#endif

#endif
