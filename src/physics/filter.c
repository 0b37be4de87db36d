/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * filter.c - density re-initialisation filters (see filter.h).
 *
 * MLS (paper B §2.8, its ref. [15]; the form SPHysics uses, after Colagrossi
 * & Landrini 2003): for each filtered particle a, with x_ab = x_a - x_b and
 * V_b = m_b / rho_b,
 *   A_a = sum_b V_b W_ab P_ab P_ab^T,  P_ab = (1, x_ab, y_ab)^T,
 *   beta_a = A_a^-1 (1, 0, 0)^T,
 *   rho_a <- sum_b m_b W_ab P_ab . beta_a = beta_a . M_a,  M_a = sum_b m_b W_ab P_ab.
 * Why it is exact for linear fields: if rho_b = P_ab . c for all b (a linear
 * field, c_0 its value at x_a), then M_a = sum_b V_b W_ab P_ab P_ab^T c =
 * A_a c and beta_a . A_a c = e_0^T A_a^-1 A_a c = c_0, since A_a is
 * symmetric. Nothing else is needed: any positive volumes V_b, any
 * neighbourhood (one-sided at a boundary too) as long as A_a is regular,
 * any positive pair weights W_ab (so the pair-mean h of the variable-h mode
 * keeps the property).
 *
 * Only beta_a . M_a is needed, so the 3x3 system is not solved as such:
 * beta_a is the first column of A_a^-1, i.e. the first row of cofactors
 * over det A_a. Positions are taken in units of h_a, so the entries of A_a
 * are all O(1) and det(A_a) / (tr(A_a)/3)^3, which lies in [0, 1] for the
 * positive semi-definite A_a (ratio of the geometric to the arithmetic
 * mean of its eigenvalues, cubed), measures how close A_a is to singular,
 * whatever h and the scale of the volumes. Below mls_det_min (default
 * 1e-3: an isolated particle, one neighbour, collinear neighbours, or a
 * single-file line of particles scattered across it by a few per cent of h
 * or less; a jittered lattice, corners included, stays above 0.07) the
 * particle gets the Shepard value M_0 / A_00 instead, which is always
 * defined because the particle's own term V_a W(0) > 0 is in A_00.
 *
 * Shepard: rho_a <- M_0 / A_00 = sum_b m_b W_ab / sum_b V_b W_ab, exact for
 * constant fields only.
 *
 * Determinism: a gather over the grid's fixed neighbour order reads the old
 * densities and writes the new ones to scratch; only when every particle is
 * done is scratch copied into rho, so no particle sees a partly updated
 * field. Each particle writes only its own slot: the result is bitwise
 * independent of the thread count. A new storage order changes the order of
 * the sums and so the result by rounding only.
 *
 * The loop body is one always-inline function whose switches (MLS or
 * Shepard, constant or variable h) are constants at each call site, as in
 * forces.c.
 */
#include "config.h"

#include "core/linsolve.h"
#include "core/parallel.h"

#include "physics/filter.h"

#include <math.h>
#include <string.h>

#include "physics/kernel.h"

const char *const sph_filter_kind_names[] = {"none", "mls", "shepard", NULL};

const char *sph_filter_name(sph_filter_kind k) {
  if ((int)k < 0 || (int)k > (int)SPH_FILTER_SHEPARD) return "?";
  return sph_filter_kind_names[k];
}

int sph_filter_from_name(const char *name, sph_filter_kind *k, sph_error *err) {
  for (int i = 0; sph_filter_kind_names[i]; i++)
    if (name && strcmp(name, sph_filter_kind_names[i]) == 0) {
      *k = (sph_filter_kind)i;
      return 0;
    }
  return sph_error_set(err, "density filter: unknown choice '%s' (valid: none, mls, shepard)",
                       name ? name : "(null)");
}

void sph_filter_params_default(sph_filter_params *fp, double h) {
  fp->h = h;
  fp->filter_walls = 0;
  fp->same_kind_only = 0;
  fp->mls_det_min = SPH_FILTER_MLS_DET_MIN;
  fp->kernel = SPH_KERNEL_CUBIC_SPLINE;
}

/* Neighbour candidates of particle i (up to SPH_GRID_RANGES ranges: a
 * periodic grid wraps around), and the period of the grid (0 if none). */
#define NRANGES SPH_GRID_RANGES
static inline void neighbour_ranges(const sph_grid *g, size_t i, size_t *lo, size_t *hi) {
  sph_grid_ranges_all(g, i, lo, hi);
}
static inline double grid_period(const sph_grid *g) { return sph_grid_period(g); }

/* The kernel moments of one particle: A (upper triangle, positions in
 * units of h_a) and M = sum m_b W_ab P_ab. The Shepard filter uses a00 and
 * m0 only. */
typedef struct moments {
  double a00, a01, a02, a11, a12, a22;
  double m0, m1, m2;
#if SPH_DIM == 3 /* the z row of A (a03, a13, a23, a33) and M's m3 */
  double a03, a13, a23, a33, m3;
#endif
} moments;

/* beta . M with beta = A^-1 e_0 (first row of cofactors over det A); on a
 * near-singular A (see the header comment) the Shepard value, and *fell
 * is set. */
#if SPH_DIM == 3
/* The 3-D form: A is 4x4; beta = A^-1 e_0 by Gaussian elimination with
 * partial pivoting on a copy, and the test det(A) / (tr(A)/4)^4 < det_min
 * (the same measure: the eigenvalues' geometric over arithmetic mean, to
 * the fourth). */
static double mls_value(const moments *s, double det_min, int *fell) {
  double a[4][SPH_LINSOLVE_COLS] = {{s->a00, s->a01, s->a02, s->a03, 1.0},
                                    {s->a01, s->a11, s->a12, s->a13, 0.0},
                                    {s->a02, s->a12, s->a22, s->a23, 0.0},
                                    {s->a03, s->a13, s->a23, s->a33, 0.0}};
  const double t = (s->a00 + s->a11 + s->a22 + s->a33) / 4.0;
  const double det = sph_linsolve_eliminate(4, 5, a);
  if (!(det > det_min * t * t * t * t)) {
    *fell = 1;
    return s->m0 / s->a00;
  }
  double beta[4];
  sph_linsolve_back(4, 4, a, beta);
  return ((beta[0] * s->m0 + beta[1] * s->m1) + beta[2] * s->m2) + beta[3] * s->m3;
}
#else
static double mls_value(const moments *s, double det_min, int *fell) {
  const double c00 = s->a11 * s->a22 - s->a12 * s->a12;
  const double c01 = s->a02 * s->a12 - s->a01 * s->a22;
  const double c02 = s->a01 * s->a12 - s->a11 * s->a02;
  const double det = s->a00 * c00 + s->a01 * c01 + s->a02 * c02;
  const double t = (s->a00 + s->a11 + s->a22) / 3.0;
  if (!(det > det_min * t * t * t)) {
    *fell = 1;
    return s->m0 / s->a00;
  }
  return (c00 * s->m0 + c01 * s->m1 + c02 * s->m2) / det;
}
#endif

/* The new density of particle a. MLS and VARH are constants at each call
 * site; *fell is set when MLS falls back to Shepard. */
static inline __attribute__((always_inline)) double
filter_one(const sph_particles *restrict p, const sph_grid *restrict g,
           const sph_filter_params *restrict fp, const double per[SPH_DIM], size_t a, const int MLS,
           const int VARH, int *fell) {
  const double *restrict x = p->x, *restrict y = p->y;
  const double *restrict m = p->mass, *restrict rho = p->rho, *restrict hh = p->h;
  const int32_t *restrict kind = p->kind;
  const int same = fp->same_kind_only;
  const double xa = x[a], ya = y[a];
  SPH_IF3(const double *restrict z = p->z; const double za = z[a];)
  const double ha = VARH ? hh[a] : fp->h;
  const double inv_ha = 1.0 / ha;
  const double s2 = (SPH_CUBIC_SUPPORT * ha) * (SPH_CUBIC_SUPPORT * ha);
  moments s;
  memset(&s, 0, sizeof s);
  size_t lo[NRANGES], hi[NRANGES];
  neighbour_ranges(g, a, lo, hi);
  for (int k = 0; k < NRANGES; k++) {
    for (size_t b = lo[k]; b < hi[k]; b++) {
      if (same && kind[b] != kind[a]) continue;
      const double dx = sph_grid_min_image(xa - x[b], per[0]);
#if SPH_DIM == 2
      const double dy = ya - y[b];
#else
      const double dy = sph_grid_min_image(ya - y[b], per[1]);
      const double dz = sph_grid_min_image(za - z[b], per[2]);
#endif
      const double r2 = SPH_NORM2(dx, dy, dz);
      const double hab = VARH ? 0.5 * (ha + hh[b]) : ha;
      if (VARH) {
        const double sab = SPH_CUBIC_SUPPORT * hab;
        if (r2 >= sab * sab) continue;
      } else if (r2 >= s2) {
        continue;
      }
      double w, dw;
      sph_kernel_w_dw(fp->kernel, sqrt(r2), hab, &w, &dw);
      const double mw = m[b] * w, vw = m[b] / rho[b] * w;
      s.a00 += vw;
      s.m0 += mw;
      if (MLS) {
        const double u = dx * inv_ha, v = dy * inv_ha;
        s.a01 += vw * u;
        s.a02 += vw * v;
        s.a11 += vw * u * u;
        s.a12 += vw * u * v;
        s.a22 += vw * v * v;
        s.m1 += mw * u;
        s.m2 += mw * v;
        SPH_IF3(const double q = dz * inv_ha; s.a03 += vw * q; s.a13 += vw * u * q;
                s.a23 += vw * v * q; s.a33 += vw * q * q; s.m3 += mw * q;)
      }
    }
  }
  if (MLS) return mls_value(&s, fp->mls_det_min, fell);
  return s.m0 / s.a00;
}

/* One pass over all particles into scratch, then the copy; returns the
 * number of MLS fallbacks. */
static size_t filter_all(sph_particles *p, const sph_grid *g, const sph_filter_params *fp,
                         double *scratch, const int MLS, const int VARH) {
  const long n = (long)p->n;
  double per[SPH_DIM]; /* the period along each axis: 0 but on the grid's periodic one */
  for (int d = 0; d < SPH_DIM; d++)
    per[d] = g->periodic == d + 1 ? grid_period(g) : 0.0;
  const int walls_too = fp->filter_walls;
  size_t fallbacks = 0;
#pragma omp parallel for schedule(dynamic, 256) if (n > SPH_OMP_MIN) reduction(+ : fallbacks)
  for (long i = 0; i < n; i++) {
    const int32_t kind = p->kind[i];
    if (kind != SPH_KIND_FLUID && !(walls_too && kind == SPH_KIND_WALL)) {
      scratch[i] = p->rho[i];
      continue;
    }
    int fell = 0;
    scratch[i] = filter_one(p, g, fp, per, (size_t)i, MLS, VARH, &fell);
    fallbacks += (size_t)fell;
  }
#pragma omp parallel for schedule(static) if (n > SPH_OMP_MIN)
  for (long i = 0; i < n; i++)
    p->rho[i] = scratch[i];
  return fallbacks;
}

/* Cheap argument checks, including the grid's cell against the support. */
static int check_args(const char *name, const sph_particles *p, const sph_grid *g,
                      const sph_filter_params *fp, const double *scratch, sph_error *err) {
  if (!p || !g || !fp)
    return sph_error_set(err, "%s filter: particles, grid and parameters are required", name);
  if (p->n > 0 && !scratch)
    return sph_error_set(err, "%s filter: scratch of %zu doubles is required", name, p->n);
  if (!(fp->h >= 0.0) || !isfinite(fp->h))
    return sph_error_set(err, "%s filter: h must be > 0 (or 0 for variable h), got %g", name,
                         fp->h);
  if (!(fp->mls_det_min >= 0.0 && fp->mls_det_min < 1.0))
    return sph_error_set(err, "%s filter: mls_det_min must be in [0, 1), got %g", name,
                         fp->mls_det_min);
  double hmax = fp->h;
  if (fp->h == 0.0) {
    for (size_t i = 0; i < p->n; i++) {
      if (!(p->h[i] > 0.0) || !isfinite(p->h[i]))
        return sph_error_set(err, "%s filter: particle %lld has smoothing length %g", name,
                             (long long)p->id[i], p->h[i]);
      if (p->h[i] > hmax) hmax = p->h[i];
    }
  }
  if (p->n > 0 && !(g->cell >= SPH_CUBIC_SUPPORT * hmax))
    return sph_error_set(err, "%s filter: grid cells of %g are smaller than the support %g", name,
                         g->cell, SPH_CUBIC_SUPPORT * hmax);
  return 0;
}

int sph_filter_mls(sph_particles *p, const sph_grid *g, const sph_filter_params *fp,
                   double *scratch, size_t *fallbacks, sph_error *err) {
  if (check_args("MLS", p, g, fp, scratch, err)) return -1;
  const size_t fb =
      fp->h > 0.0 ? filter_all(p, g, fp, scratch, 1, 0) : filter_all(p, g, fp, scratch, 1, 1);
  if (fallbacks) *fallbacks = fb;
  return 0;
}

int sph_filter_shepard(sph_particles *p, const sph_grid *g, const sph_filter_params *fp,
                       double *scratch, size_t *fallbacks, sph_error *err) {
  if (check_args("Shepard", p, g, fp, scratch, err)) return -1;
  if (fp->h > 0.0)
    filter_all(p, g, fp, scratch, 0, 0);
  else
    filter_all(p, g, fp, scratch, 0, 1);
  if (fallbacks) *fallbacks = 0;
  return 0;
}

int sph_filter_apply(sph_filter_kind k, sph_particles *p, const sph_grid *g,
                     const sph_filter_params *fp, double *scratch, size_t *fallbacks,
                     sph_error *err) {
  switch (k) {
  case SPH_FILTER_NONE:
    if (fallbacks) *fallbacks = 0;
    return 0;
  case SPH_FILTER_MLS: return sph_filter_mls(p, g, fp, scratch, fallbacks, err);
  case SPH_FILTER_SHEPARD: return sph_filter_shepard(p, g, fp, scratch, fallbacks, err);
  }
  return sph_error_set(err, "density filter: unknown kind %d", (int)k);
}
