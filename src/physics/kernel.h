/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * kernel.h - the smoothing kernels as the solver uses them: by their kind
 * (sph_kernel_kind, numerics.kernel) and in the interaction loops' form.
 * The kernels themselves (shapes, support 2h, the normalisation per
 * dimension) are written once in src/core/kernel_shape.h, which the
 * renderer uses too.
 *
 * The cubic spline of Monaghan (paper A eq. (8); paper B §2.1), 2-D
 * normalisation sigma = 10/(7 pi h^2) (paper A writes the same function as
 * 15/(7 pi h^2) [2/3 - q^2 + q^3/2] ...). The Wendland C2 kernel (Wendland
 * 1995; numerics.kernel: wendland_c2), 2-D normalisation sigma =
 * 7/(4 pi h^2): positive definite in Fourier space, so it does not pair
 * particles up (the cubic spline does at h > 1.5 dx under compression); it
 * is smoother, needs a larger h for the same accuracy (h_factor 1.3 to 2
 * with dx) and its self-contribution W(0) = 7/(4 pi h^2) is 0.55 of the
 * cubic's at the same h.
 */
#ifndef SPH_KERNEL_H
#define SPH_KERNEL_H

#include "core/kernel_shape.h"
#include "physics/models.h"
#include "physics/pair_terms.h"

/* Support radius of the cubic spline (and of the Wendland kernel) in units of h. */
#define SPH_CUBIC_SUPPORT SPH_KERNEL_SUPPORT

/* W(r, h) and dW/dr for the cubic spline. r >= 0. */
static inline void sph_cubic_w_dw(double r, double h, double *w, double *dwdr) {
  sph_shape_cubic(r, h, w, dwdr);
}

/* W and F = (1/r) dW/dr together, for 0 < r < 2h, given 1/r and 1/h: the
 * interaction loops' branch-free form (F times r_ij is grad_i W_ij),
 * written once as cubic_w_f_FL in src/physics/pair_terms_body.h. Agrees
 * with sph_cubic_w_dw to round-off (tests/test_kernel.c). */
static inline void sph_cubic_w_f(double r, double inv_r, double inv_h, double *w, double *f) {
  const double sigma = sph_kernel_norm(SPH_SHAPE_CUBIC_SPLINE, inv_h);
  cubic_w_f_v1(r, inv_r, inv_h, sigma, sigma * inv_h, w, f);
}

/* The Wendland C2 kernel's W(r, h) and dW/dr, r >= 0. */
static inline void sph_wendland_w_dw(double r, double h, double *w, double *dwdr) {
  sph_shape_wendland_c2(r, h, w, dwdr);
}

/* The normalisation sigma of a kernel at 1/h (core/kernel_shape.h). */
static inline double sph_kernel_sigma(sph_kernel_kind k, double inv_h) {
  return sph_kernel_norm((int)k, inv_h);
}

/* W and dW/dr of the kernel k. */
static inline void sph_kernel_w_dw(sph_kernel_kind k, double r, double h, double *w, double *dwdr) {
  sph_shape_w_dw((int)k, r, h, w, dwdr);
}

/* W and F = (1/r) dW/dr of the kernel k in the loops' form, 0 < r < 2h. */
static inline void sph_kernel_w_f(sph_kernel_kind k, double r, double inv_r, double inv_h,
                                  double *w, double *f) {
  const double sigma = sph_kernel_sigma(k, inv_h);
  if (k == SPH_KERNEL_WENDLAND_C2)
    wendland_w_f_v1(r, inv_r, inv_h, sigma, sigma * inv_h, w, f);
  else
    cubic_w_f_v1(r, inv_r, inv_h, sigma, sigma * inv_h, w, f);
}

/* W alone (tests, filters). */
double sph_cubic_w(double r, double h);
/* W of the kernel k. */
double sph_kernel_w(sph_kernel_kind k, double r, double h);

#endif
