/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * wall_velocity.c - the extrapolated (no-slip) velocity of wall particles
 * (see wall_velocity.h).
 */
#include "config.h"

#include "walls/wall_velocity.h"

#include "core/kernel_shape.h"
#include "core/lanes.h"
#include "core/linsolve.h"
#include "core/parallel.h"
#include "neighbours/grid.h"
#include "physics/kernel.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The most fields one fit serves (velocity: SPH_DIM), and the unknowns of
 * a field's linear fit (its value and its gradient). */
#define SPH_FIT_MAX SPH_DIM
#define FIT_N (SPH_DIM + 1)
/* The values a packed slot holds: the coordinates and h. */
#define PACK (SPH_DIM + 1)

void sph_wall_velocity_work_free(sph_wall_velocity_work *w) {
  free(w->start);
  free(w->idx);
  free(w->key);
  free(w->pack);
  *w = (sph_wall_velocity_work){0};
}

/* The cell layout: along each axis a, n[a] cells of width c[a], the cells
 * of one global grid (cell k holds floor(x / c[a]) = k, the grid's first
 * k0[a]), so that any subset of the particles (a rank's) bins each one into
 * the cell the whole set does and its fits sum in the whole set's order;
 * along the periodic axis (period > 0) the whole period from o. Cells are
 * numbered with x fastest, then y (then z). */
typedef struct layout {
  double o, c[SPH_DIM], period;
  double support; /* no particle farther than this from a point counts in its fit */
  long n[SPH_DIM], k0[SPH_DIM];
  int paxis;
} layout;

/* The unclamped cell along axis a of the coordinate x (not periodic). */
SPH_LANE_INLINE double cell_float(const layout *g, int a, double x) {
  return floor(x / g->c[a]) - (double)g->k0[a];
}

/* The cell along axis a of the coordinate x, clamped to the grid. */
SPH_LANE_INLINE long cell_along(const layout *g, int a, double x) {
  double f;
  if (a == g->paxis && g->period > 0.0) { /* into [0, period) */
    double u = fmod(x - g->o, g->period);
    if (u < 0.0) u += g->period;
    f = floor(u / g->c[a]);
  } else {
    f = cell_float(g, a, x);
  }
  return f < 0.0 ? 0 : f >= (double)g->n[a] ? g->n[a] - 1 : (long)f;
}

/* The cells along axis a within one cell of the coordinate x, in the
 * order the sums visit them, into cells[]; their count (0: none within
 * reach, the point is too far from the fluid). */
SPH_LANE_INLINE int cells_near(const layout *g, int a, double x, long cells[3]) {
  const long n = g->n[a];
  int nc = 0;
  if (a == g->paxis && g->period > 0.0) {
    const long c0 = cell_along(g, a, x);
    if (n <= 3) {
      for (long c = 0; c < n; c++)
        cells[nc++] = c; /* every cell, once */
    } else {
      cells[nc++] = (c0 + n - 1) % n;
      cells[nc++] = c0;
      cells[nc++] = (c0 + 1) % n;
    }
    return nc;
  }
  const double f = cell_float(g, a, x);
  if (f < -1.0 || f > (double)n) return 0;
  const long c0 = cell_along(g, a, x);
  for (long c = c0 - 1; c <= c0 + 1; c++)
    if (c >= 0 && c < n) cells[nc++] = c;
  return nc;
}

/* The squared distance along axis a from the coordinate x to cell c, less
 * 1e-9 of a cell's width for round-off (a particle binned to a cell lies
 * inside it to round-off); 0 along the periodic axis, whose cells are
 * reached through the period. */
SPH_LANE_INLINE double cell_gap2(const layout *g, int a, double x, long c) {
  if (a == g->paxis && g->period > 0.0) return 0.0;
  const double lo = (double)(g->k0[a] + c) * g->c[a], hi = lo + g->c[a];
  double gap = x < lo ? lo - x : x > hi ? x - hi : 0.0;
  gap -= 1e-9 * g->c[a];
  return gap > 0.0 ? gap * gap : 0.0;
}

/* The linear fit's solution from its moments: A (the symmetric moment
 * matrix, upper triangle used) and b[m] per field; into fit[FIT_N m ..]
 * where A is regular enough (det A above 1e-3 of the product of its
 * diagonal: fewer than SPH_DIM + 1 independent neighbours fail it). */
static void solve_fit(const double A[FIT_N][FIT_N], const double b[SPH_FIT_MAX][FIT_N], int nf,
                      double *fit) {
#if SPH_DIM == 2 /* Cramer's rule */
  const double sw = A[0][0], a01 = A[0][1], a02 = A[0][2], a11 = A[1][1], a12 = A[1][2],
               a22 = A[2][2];
  const double det =
      sw * (a11 * a22 - a12 * a12) - a01 * (a01 * a22 - a12 * a02) + a02 * (a01 * a12 - a11 * a02);
  const double scale = sw * a11 * a22;
  if (scale > 0.0 && fabs(det) > 1e-3 * scale) {
    const double c00 = a11 * a22 - a12 * a12, c01 = -(a01 * a22 - a02 * a12),
                 c02 = a01 * a12 - a02 * a11;
    const double c11 = sw * a22 - a02 * a02, c12 = -(sw * a12 - a01 * a02),
                 c22 = sw * a11 - a01 * a01;
    for (int m = 0; m < nf; m++) {
      fit[3 * m] = (c00 * b[m][0] + c01 * b[m][1] + c02 * b[m][2]) / det;
      fit[3 * m + 1] = (c01 * b[m][0] + c11 * b[m][1] + c12 * b[m][2]) / det;
      fit[3 * m + 2] = (c02 * b[m][0] + c12 * b[m][1] + c22 * b[m][2]) / det;
    }
  }
#else /* Gaussian elimination (core/linsolve.h), every field a column */
  double a[FIT_N][SPH_LINSOLVE_COLS];
  double scale = 1.0;
  for (int r = 0; r < FIT_N; r++) {
    scale *= A[r][r];
    for (int k = 0; k < FIT_N; k++)
      a[r][k] = r <= k ? A[r][k] : A[k][r];
    for (int m = 0; m < nf; m++)
      a[r][FIT_N + m] = b[m][r];
  }
  const double det = sph_linsolve_eliminate(FIT_N, FIT_N + nf, a);
  if (scale > 0.0 && fabs(det) > 1e-3 * scale)
    for (int m = 0; m < nf; m++)
      sph_linsolve_back(FIT_N, FIT_N + m, a, fit + FIT_N * m);
#endif
}

/* The candidates of a cell one fit takes at a time, and the slots of its
 * stack arrays: room for a full last vector of the widest flavour. */
#define FIT_CHUNK 64
#define FIT_SLOTS (FIT_CHUNK + 8)

/* The mirror point x + m of particle i. */
static void mirror_point(const sph_particles *p, size_t i, double x[SPH_DIM]) {
  for (int a = 0; a < SPH_DIM; a++)
    x[a] = p->pos[a][i] + p->mirror_offset[a][i];
}

/* Each flavour FL has take_FL(w, x, per, q, qe, qs, e, ws): of the
 * candidates in the slots [q, qe) of w (at most FIT_CHUNK), those within
 * reach of x, r^2 < (2 h_j)^2 (the nearest image over per; NULL: none
 * taken), their slots into qs[], in order, their offsets x_j - x into
 * e[a][] and their weights W(x - x_j, h_j) into ws[]; their count. Lane for
 * lane the same operations in every flavour (below the flavours' fit). */
SPH_LANE_INLINE int take_v2(const sph_wall_velocity_work *w, const double x[SPH_DIM],
                            const double per[SPH_DIM], size_t q, size_t qe, uint32_t *qs,
                            double e[SPH_DIM][FIT_SLOTS], double *ws);
#define FIT_FL v2
#define FIT_ATTR SPH_LANE_INLINE
#define FIT_ROWS static
#include "walls/wall_fit_body.h"
#undef FIT_FL
#undef FIT_ATTR
#undef FIT_ROWS

/* The candidate slots' coordinates along axis a (a = SPH_DIM: their h):
 * the packed arrays, one per value (bin_fluid). */
static inline const double *packed(const sph_wall_velocity_work *w, int a) {
  return w->pack + (size_t)a * w->cap_n;
}

/* Two lanes into out[0], out[1]. */
static inline void store2(double *out, v2 a) { memcpy(out, &a, 2 * sizeof *out); }

/* Two candidates at a time: those within reach without a branch, then
 * their weights (an odd count's last pair repeats its slot). */
SPH_LANE_INLINE int take_v2(const sph_wall_velocity_work *w, const double x[SPH_DIM],
                            const double per[SPH_DIM], size_t q, size_t qe, uint32_t *qs,
                            double e[SPH_DIM][FIT_SLOTS], double *ws) {
  const double *ph = packed(w, SPH_DIM);
  int k = 0;
  for (; q + 1 < qe; q += 2) {
    v2 r2 = v2_all(0.0);
    for (int a = 0; a < SPH_DIM; a++) {
      const double *pa = packed(w, a);
      const v2 d = sep_v2(x[a], v2_set(pa[q], pa[q + 1]), per, a);
      r2 = a ? v2_add(r2, v2_mul(d, d)) : v2_mul(d, d);
    }
    const v2 h = v2_set(ph[q], ph[q + 1]);
    const unsigned in =
        v2_bits2(v2_lt(r2, v2_mul(v2_mul(v2_all(SPH_CUBIC_SUPPORT * SPH_CUBIC_SUPPORT), h), h)));
    qs[k] = (uint32_t)q;
    k += (int)(in & 1u);
    qs[k] = (uint32_t)(q + 1);
    k += (int)(in >> 1);
  }
  if (q < qe) {
    double r2 = 0.0;
    for (int a = 0; a < SPH_DIM; a++) {
      const double xa = packed(w, a)[q];
      const double d = per ? sph_grid_min_image(x[a] - xa, per[a]) : x[a] - xa;
      r2 = a ? r2 + d * d : d * d;
    }
    qs[k] = (uint32_t)q;
    k += r2 < SPH_CUBIC_SUPPORT * SPH_CUBIC_SUPPORT * ph[q] * ph[q];
  }
  for (int t = 0; t < k; t += 2) {
    const uint32_t q0 = qs[t], q1 = qs[t + 1 < k ? t + 1 : t];
    v2 r2 = v2_all(0.0);
    for (int a = 0; a < SPH_DIM; a++) {
      const double *pa = packed(w, a);
      const v2 d = sep_v2(x[a], v2_set(pa[q0], pa[q1]), per, a);
      r2 = a ? v2_add(r2, v2_mul(d, d)) : v2_mul(d, d);
      store2(e[a] + t, v2_neg(d));
    }
    store2(ws + t, cubic_w_v2(v2_sqrt(r2), v2_set(ph[q0], ph[q1])));
  }
  return k;
}

#ifdef SPH_LANES_AVX512
SPH_AVX512 int take_v8z(const sph_wall_velocity_work *w, const double x[SPH_DIM],
                        const double per[SPH_DIM], size_t q, size_t qe, uint32_t *qs,
                        double e[SPH_DIM][FIT_SLOTS], double *ws);
#define FIT_FL v8z
#define FIT_ATTR SPH_AVX512
#define FIT_ROWS static __attribute__((target("avx512f")))
#include "walls/wall_fit_body.h"
#undef FIT_FL
#undef FIT_ATTR
#undef FIT_ROWS

/* Eight candidates at a time, read in a row (no gather: slow on some
 * processors), the last vector's lanes past qe masked off (not read; h 1
 * there, so that no lane divides by zero): those within reach packed to
 * the front (vcompresspd into a register, then stored whole: the arrays
 * have room for it) with their r^2 and h, then weighed eight at a time. */
SPH_AVX512 int take_v8z(const sph_wall_velocity_work *w, const double x[SPH_DIM],
                        const double per[SPH_DIM], size_t q, size_t qe, uint32_t *qs,
                        double e[SPH_DIM][FIT_SLOTS], double *ws) {
  const double *ph = packed(w, SPH_DIM);
  double r2s[FIT_SLOTS], hs[FIT_SLOTS];
  int k = 0;
  for (; q < qe; q += 8) {
    const __mmask8 lanes = qe - q >= 8 ? (__mmask8)0xff : (__mmask8)((1u << (qe - q)) - 1u);
    v8z d[SPH_DIM], r2 = v8z_all(0.0);
    for (int a = 0; a < SPH_DIM; a++) {
      d[a] = sep_v8z(x[a], _mm512_maskz_loadu_pd(lanes, packed(w, a) + q), per, a);
      r2 = a ? v8z_add(r2, v8z_mul(d[a], d[a])) : v8z_mul(d[a], d[a]);
    }
    const v8z h = _mm512_mask_loadu_pd(v8z_all(1.0), lanes, ph + q);
    const __mmask8 in =
        lanes & v8z_lt(r2, v8z_mul(v8z_mul(v8z_all(SPH_CUBIC_SUPPORT * SPH_CUBIC_SUPPORT), h), h));
    if (!in) continue;
    for (int a = 0; a < SPH_DIM; a++)
      _mm512_storeu_pd(e[a] + k, _mm512_maskz_compress_pd(in, v8z_neg(d[a])));
    _mm512_storeu_pd(r2s + k, _mm512_maskz_compress_pd(in, r2));
    _mm512_storeu_pd(hs + k, _mm512_mask_compress_pd(v8z_all(1.0), in, h));
    for (unsigned b = in; b; b &= b - 1u)
      qs[k++] = (uint32_t)(q + (size_t)__builtin_ctz(b));
  }
  /* the last vector's lanes past k: r^2 0 and h 1 (weighed, not read) */
  _mm512_storeu_pd(r2s + k, v8z_all(0.0));
  _mm512_storeu_pd(hs + k, v8z_all(1.0));
  for (int t = 0; t < k; t += 8)
    _mm512_storeu_pd(ws + t,
                     cubic_w_v8z(v8z_sqrt(_mm512_loadu_pd(r2s + t)), _mm512_loadu_pd(hs + t)));
  return k;
}
#endif

#ifdef SPH_LANES_AVX512
/* Whether this call's fits take eight lanes (AVX-512 here, and w not
 * narrow). */
static int wide(const sph_wall_velocity_work *w) { return !w->narrow && sph_cpu_has_avx512(); }
#endif

/* The fluid particles of p binned by cell into w (cells at least
 * `support` wide, and not many more than particles), the layout into *gp;
 * periodic along axis paxis over [px0, px0 + period) when period > 0.
 * 0, 1 when there is no fluid (nothing to fit), or -1 (err). */
static int bin_fluid(const sph_particles *p, double support, double px0, double period, int paxis,
                     layout *gp, sph_wall_velocity_work *w, sph_error *err) {
  const size_t n = p->n;
  double lo[SPH_DIM], hi[SPH_DIM];
  for (int a = 0; a < SPH_DIM; a++)
    lo[a] = INFINITY, hi[a] = -INFINITY;
  size_t nf = 0;
  for (size_t i = 0; i < n; i++) {
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    nf++;
    for (int a = 0; a < SPH_DIM; a++) {
      if (p->pos[a][i] < lo[a]) lo[a] = p->pos[a][i];
      if (p->pos[a][i] > hi[a]) hi[a] = p->pos[a][i];
    }
  }
  if (nf == 0) return 1; /* no fluid: nothing to fit */
  /* cells `support` wide (twice as wide while they would be far more than
   * the particles: fluid spread thin over a large domain) */
  double cell = support;
  layout g = {.period = period > 0.0 ? period : 0.0, .paxis = paxis, .support = support};
  for (;;) {
    double cells = 1.0;
    for (int a = 0; a < SPH_DIM; a++) {
      if (a == g.paxis && g.period > 0.0) {
        g.o = px0;
        g.n[a] = (long)floor(g.period / cell);
        if (g.n[a] < 1) g.n[a] = 1;
        g.c[a] = g.period / (double)g.n[a];
      } else {
        const double k0 = floor(lo[a] / cell);
        g.k0[a] = (long)k0;
        g.c[a] = cell;
        g.n[a] = (long)(floor(hi[a] / cell) - k0) + 1;
      }
      cells *= (double)g.n[a];
    }
    if (cells <= 64.0 * (double)nf + 1048576.0) break;
    cell *= 2.0;
  }
  size_t cells = 1;
  for (int a = 0; a < SPH_DIM; a++)
    cells *= (size_t)g.n[a];
  if (cells + 1 > w->cap_cells) {
    size_t *a = realloc(w->start, (cells + 1) * sizeof *a);
    if (!a) return sph_error_set(err, "wall velocity: out of memory for %zu cells", cells);
    w->start = a;
    w->cap_cells = cells + 1;
  }
  if (n > w->cap_n) {
    uint32_t *a = realloc(w->idx, n * sizeof *a);
    if (a) w->idx = a;
    size_t *b = a ? realloc(w->key, n * sizeof *b) : NULL;
    if (b) w->key = b;
    double *c = b ? realloc(w->pack, PACK * n * sizeof *c) : NULL;
    if (!c) return sph_error_set(err, "wall velocity: out of memory for %zu particles", n);
    w->pack = c;
    w->cap_n = n;
  }
  /* counting sort of the fluid particles by cell, stable */
  for (size_t c = 0; c <= cells; c++)
    w->start[c] = 0;
  for (size_t i = 0; i < n; i++) {
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    size_t key = 0;
    for (int a = SPH_DIM - 1; a >= 0; a--)
      key = key * (size_t)g.n[a] + (size_t)cell_along(&g, a, p->pos[a][i]);
    w->key[i] = key;
    w->start[key + 1]++;
  }
  for (size_t c = 0; c < cells; c++)
    w->start[c + 1] += w->start[c];
  for (size_t i = 0; i < n; i++)
    if (p->kind[i] == SPH_KIND_FLUID) w->idx[w->start[w->key[i]]++] = (uint32_t)i;
  for (size_t c = cells; c > 0; c--)
    w->start[c] = w->start[c - 1];
  w->start[0] = 0;
  for (size_t q = 0; q < nf; q++) { /* the candidates' coordinates and h in the cells' order */
    const size_t j = w->idx[q];
    for (int a = 0; a < SPH_DIM; a++)
      w->pack[(size_t)a * w->cap_n + q] = p->pos[a][j];
    w->pack[(size_t)SPH_DIM * w->cap_n + q] = p->h[j];
  }
  *gp = g;
  return 0;
}

int sph_wall_velocity(const sph_particles *p, double support, double px0, double period, int paxis,
                      double *const *gv, sph_wall_velocity_work *w, sph_error *err) {
  const size_t n = p->n;
  for (int a = 0; a < SPH_DIM; a++)
    for (size_t i = 0; i < n; i++)
      if (!(p->flags[i] & SPH_FLAG_ADAMI)) gv[a][i] = p->vel[a][i];
  layout g;
  const int rc = bin_fluid(p, support, px0, period, paxis, &g, w, err);
  if (rc) return rc < 0 ? -1 : 0;
#ifdef SPH_LANES_AVX512
  if (wide(w)) {
    velocity_rows_v8z(p, &g, w, gv);
    return 0;
  }
#endif
  velocity_rows_v2(p, &g, w, gv);
  return 0;
}

int sph_wall_mdbc_density(sph_particles *p, double support, double px0, double period, int paxis,
                          double rho0, const double head[SPH_DIM], sph_wall_velocity_work *w,
                          sph_error *err) {
  layout g;
  const int rc = bin_fluid(p, support, px0, period, paxis, &g, w, err);
  if (rc < 0) return -1;
#ifdef SPH_LANES_AVX512
  if (wide(w)) {
    mdbc_rows_v8z(p, &g, w, rc, rho0, head);
    return 0;
  }
#endif
  mdbc_rows_v2(p, &g, w, rc, rho0, head);
  return 0;
}
