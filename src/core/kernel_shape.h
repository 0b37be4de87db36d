/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * kernel_shape.h - the smoothing kernels, written once: their shapes W(q)
 * and dW/dq with q = r / h, and their normalisation constant for each
 * dimension (the pattern of SWIFT's kernel_hydro.h). Everything that evaluates
 * a kernel takes it from here: the solver's passes and probes through
 * src/physics/kernel.h, the renderer's interpolation (render/interp.c),
 * and, for the normalisation, the interaction loops, whose branch-free
 * form of the same shapes is src/physics/pair_terms_body.h (cubic_w_f,
 * wendland_w_f; tests/test_kernel.c holds the two forms to each other).
 *
 * Both kernels have support 2h (the smoothing radius of GOST R 57700.6
 * 3.4.2) and W = sigma_d w(q), sigma_d = C_d / h^d:
 *   cubic spline (Monaghan; paper A eq. 8, paper B §2.1)
 *     w(q) = 1 - 3/2 q^2 + 3/4 q^3   0 <= q < 1
 *          = (2 - q)^3 / 4           1 <= q < 2,   C_2 = 10/(7 pi), C_3 = 1/pi
 *   Wendland C2 (Wendland 1995)
 *     w(q) = (1 - q/2)^4 (2q + 1)    0 <= q < 2,   C_2 = 7/(4 pi),  C_3 = 21/(16 pi)
 * (the Wendland C2 function of 2-D and 3-D; 1-D would take another).
 * The values are kept in the operation order the results were first
 * written with: sigma = C_d (1/h) (1/h) ..., then the shape.
 */
#ifndef SPH_KERNEL_SHAPE_H
#define SPH_KERNEL_SHAPE_H

#include <string.h>

#include "core/dim.h"

#define SPH_PI 3.14159265358979323846

/* The kernels, in the order of sph_kernel_kind (physics/models.h). */
enum { SPH_SHAPE_CUBIC_SPLINE = 0, SPH_SHAPE_WENDLAND_C2 = 1 };

/* Support radius in units of h. */
#define SPH_KERNEL_SUPPORT 2.0

/* C_d of each kernel for d = 2 and 3, and the one of this build's dimension. */
#define SPH_CUBIC_C2 (10.0 / (7.0 * SPH_PI))
#define SPH_CUBIC_C3 (1.0 / SPH_PI)
#define SPH_WENDLAND_C2_C2 (7.0 / (4.0 * SPH_PI))
#define SPH_WENDLAND_C2_C3 (21.0 / (16.0 * SPH_PI))
static inline double sph_kernel_c(int kind) {
#if SPH_DIM == 2
  return kind == SPH_SHAPE_WENDLAND_C2 ? SPH_WENDLAND_C2_C2 : SPH_CUBIC_C2;
#else
  return kind == SPH_SHAPE_WENDLAND_C2 ? SPH_WENDLAND_C2_C3 : SPH_CUBIC_C3;
#endif
}

/* sigma_d = C_d / h^d at 1/h. */
static inline double sph_kernel_norm(int kind, double inv_h) {
  return sph_pow_dim(sph_kernel_c(kind), inv_h);
}

/* W(r, h) and dW/dr of the cubic spline, r >= 0. */
static inline void sph_shape_cubic(double r, double h, double *w, double *dwdr) {
  const double inv_h = 1.0 / h;
  const double q = r * inv_h;
  const double sigma = sph_kernel_norm(SPH_SHAPE_CUBIC_SPLINE, inv_h);
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

/* W(r, h) and dW/dr of the Wendland C2 kernel, r >= 0. */
static inline void sph_shape_wendland_c2(double r, double h, double *w, double *dwdr) {
  const double inv_h = 1.0 / h, q = r * inv_h;
  const double sigma = sph_kernel_norm(SPH_SHAPE_WENDLAND_C2, inv_h);
  if (q < 2.0) {
    const double t = 1.0 - 0.5 * q, t3 = t * t * t;
    *w = sigma * t3 * t * (2.0 * q + 1.0);
    *dwdr = -5.0 * sigma * inv_h * q * t3;
  } else {
    *w = 0.0;
    *dwdr = 0.0;
  }
}

/* W and dW/dr of the kernel kind. */
static inline void sph_shape_w_dw(int kind, double r, double h, double *w, double *dwdr) {
  if (kind == SPH_SHAPE_WENDLAND_C2)
    sph_shape_wendland_c2(r, h, w, dwdr);
  else
    sph_shape_cubic(r, h, w, dwdr);
}

/* The kernel named (case files' and snapshots' numerics.kernel), or -1. */
static inline int sph_shape_of_name(const char *name) {
  static const char *const names[] = {"cubic_spline", "wendland_c2"};
  for (int k = 0; name && k < 2; k++)
    if (strcmp(name, names[k]) == 0) return k;
  return -1;
}

#endif
