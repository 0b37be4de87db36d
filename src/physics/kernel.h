/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * kernel.h - smoothing kernels W and their radial derivative dW/dr.
 *
 * The cubic spline of Monaghan (paper A eq. (8); paper B §2.1), 2-D
 * normalisation sigma = 10/(7 pi h^2), smoothing radius (GOST R 57700.6
 * 3.4.2) 2h:
 *   W(q) = sigma [1 - 3/2 q^2 + 3/4 q^3]  0 <= q < 1
 *        = sigma [(2 - q)^3 / 4]          1 <= q < 2
 *        = 0                              q >= 2,      q = r / h
 * (Paper A writes the same function as 15/(7 pi h^2) [2/3 - q^2 + q^3/2] ...)
 *
 * The Wendland C2 kernel (Wendland 1995; numerics.kernel: wendland_c2),
 * 2-D normalisation sigma = 7/(4 pi h^2), support 2h:
 *   W(q) = sigma (1 - q/2)^4 (2q + 1)   0 <= q < 2,  0 beyond,
 * positive definite in Fourier space, so it does not pair particles up
 * (the cubic spline does at h > 1.5 dx under compression); it is smoother,
 * needs a larger h for the same accuracy (h_factor 1.3 to 2 with dx) and
 * its self-contribution W(0) = 7/(4 pi h^2) is 0.55 of the cubic's at the
 * same h.
 * One evaluator returns W and dW/dr together; powers are multiplications.
 */
#ifndef SPH_KERNEL_H
#define SPH_KERNEL_H

#include "physics/models.h"
#include "physics/pair_terms.h"

#define SPH_PI 3.14159265358979323846

/* Support radius of the cubic spline in units of h. */
#define SPH_CUBIC_SUPPORT 2.0

/* W(r, h) and dW/dr for the 2-D cubic spline. r >= 0. */
static inline void sph_cubic_w_dw(double r, double h, double *w, double *dwdr) {
  const double inv_h = 1.0 / h;
  const double q = r * inv_h;
  const double sigma = 10.0 / (7.0 * SPH_PI) * inv_h * inv_h;
  if (q < 1.0) {
    *w = sigma * (1.0 - 1.5 * q * q + 0.75 * q * q * q);
    *dwdr = sigma * inv_h * (-3.0 * q + 2.25 * q * q);
  } else if (q < 2.0) {
    const double t = 2.0 - q;
    *w = sigma * 0.25 * t * t * t;
    *dwdr = sigma * inv_h * (-0.75 * t * t);
  } else {
    *w = 0.0;
    *dwdr = 0.0;
  }
}

/* W and F = (1/r) dW/dr together, for 0 < r < 2h, given 1/r and 1/h: the
 * interaction loops' branch-free form (F times r_ij is grad_i W_ij),
 * written once as cubic_w_f_FL in src/physics/pair_terms_body.h. Agrees
 * with sph_cubic_w_dw to round-off (tests/test_kernel.c). */
static inline void sph_cubic_w_f(double r, double inv_r, double inv_h, double *w, double *f) {
  const double sigma = (10.0 / (7.0 * SPH_PI)) * inv_h * inv_h;
  cubic_w_f_v1(r, inv_r, inv_h, sigma, sigma * inv_h, w, f);
}

/* The Wendland C2 kernel's W(r, h) and dW/dr, r >= 0. */
static inline void sph_wendland_w_dw(double r, double h, double *w, double *dwdr) {
  const double inv_h = 1.0 / h, q = r * inv_h;
  const double sigma = 7.0 / (4.0 * SPH_PI) * inv_h * inv_h;
  if (q < 2.0) {
    const double t = 1.0 - 0.5 * q, t3 = t * t * t;
    *w = sigma * t3 * t * (2.0 * q + 1.0);
    *dwdr = -5.0 * sigma * inv_h * q * t3;
  } else {
    *w = 0.0;
    *dwdr = 0.0;
  }
}

/* The 2-D normalisation sigma of a kernel at 1/h. */
static inline double sph_kernel_sigma(sph_kernel_kind k, double inv_h) {
  return (k == SPH_KERNEL_WENDLAND_C2 ? 7.0 / (4.0 * SPH_PI) : 10.0 / (7.0 * SPH_PI)) * inv_h *
         inv_h;
}

/* W and dW/dr of the kernel k. */
static inline void sph_kernel_w_dw(sph_kernel_kind k, double r, double h, double *w, double *dwdr) {
  if (k == SPH_KERNEL_WENDLAND_C2)
    sph_wendland_w_dw(r, h, w, dwdr);
  else
    sph_cubic_w_dw(r, h, w, dwdr);
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
/* The gradient of W_ij with respect to x_i: (dW/dr) (x_i - x_j)/r; zero at
 * r = 0. Antisymmetric in the pair by construction: swapping i and j negates
 * dx and dy exactly. */
void sph_cubic_grad(double dx, double dy, double h, double *gx, double *gy);

#endif
