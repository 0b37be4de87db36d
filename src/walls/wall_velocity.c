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
static double cell_float(const layout *g, int a, double x) {
  return floor(x / g->c[a]) - (double)g->k0[a];
}

/* The cell along axis a of the coordinate x, clamped to the grid. */
static long cell_along(const layout *g, int a, double x) {
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
static int cells_near(const layout *g, int a, double x, long cells[3]) {
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
static double cell_gap2(const layout *g, int a, double x, long c) {
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

/* The candidates of a cell one fit takes at a time (its stack arrays). */
#define FIT_CHUNK 64

/* Two lanes into out[0], out[1]. */
static inline void store2(double *out, v2 a) { memcpy(out, &a, 2 * sizeof *out); }

/* The cubic spline's W(r, h) in two lanes: lane for lane the operations of
 * sph_cubic_w_dw (core/kernel_shape.h, sph_shape_cubic), so its bits. */
static inline v2 cubic_w2(v2 r, v2 h) {
  const v2 inv_h = v2_div(v2_all(1.0), h), q = v2_mul(r, inv_h);
  v2 sigma = v2_mul(v2_mul(v2_all(sph_kernel_c(SPH_SHAPE_CUBIC_SPLINE)), inv_h), inv_h);
  SPH_IF3(sigma = v2_mul(sigma, inv_h);)
  const v2 near = v2_mul(sigma, v2_add(v2_sub(v2_all(1.0), v2_mul(v2_mul(v2_all(1.5), q), q)),
                                       v2_mul(v2_mul(v2_mul(v2_all(0.75), q), q), q)));
  const v2 t = v2_sub(v2_all(2.0), q);
  const v2 far = v2_mul(v2_mul(v2_mul(v2_mul(sigma, v2_all(0.25)), t), t), t);
  return v2_sel(v2_lt(q, v2_all(1.0)), near, v2_sel(v2_lt(q, v2_all(2.0)), far, v2_all(0.0)));
}

/* The separations x - x_j of the packed slots p0 and p1 along axis a, in
 * two lanes: the nearest image over the period per[a] (per NULL: none
 * taken; a period of 0 leaves them as they are, bit for bit). */
static inline v2 sep2(const double x[SPH_DIM], const double *p0, const double *p1, int a,
                      const double per[SPH_DIM]) {
  const v2 d = v2_sub(v2_all(x[a]), v2_set(p0[a], p1[a]));
  if (!per) return d;
  const v2 vp = v2_all(per[a]), hp = v2_all(0.5 * per[a]), np = v2_all(-0.5 * per[a]);
  return SPH_LANE_MIN_IMAGE(v2, d, vp, hp, np);
}

/* The candidates in the slots [q, qe) of w (at most FIT_CHUNK) within
 * reach of x: their slots into qs[], in order; their count. Two at a time
 * without a branch: within reach is r^2 < (2 h_j)^2. */
static inline __attribute__((always_inline)) int within_reach(const sph_wall_velocity_work *w,
                                                              const double x[SPH_DIM],
                                                              const double per[SPH_DIM], size_t q,
                                                              size_t qe, uint32_t *qs) {
  int k = 0;
  for (; q + 1 < qe; q += 2) {
    const double *p0 = w->pack + PACK * q, *p1 = p0 + PACK;
    const v2 dx = sep2(x, p0, p1, 0, per), dy = sep2(x, p0, p1, 1, per);
    v2 r2 = v2_add(v2_mul(dx, dx), v2_mul(dy, dy));
    SPH_IF3(const v2 dz = sep2(x, p0, p1, 2, per); r2 = v2_add(r2, v2_mul(dz, dz));)
    const v2 h = v2_set(p0[SPH_DIM], p1[SPH_DIM]);
    const unsigned in =
        v2_bits2(v2_lt(r2, v2_mul(v2_mul(v2_all(SPH_CUBIC_SUPPORT * SPH_CUBIC_SUPPORT), h), h)));
    qs[k] = (uint32_t)q;
    k += (int)(in & 1u);
    qs[k] = (uint32_t)(q + 1);
    k += (int)(in >> 1);
  }
  if (q < qe) {
    const double *p0 = w->pack + PACK * q;
    double r2 = 0.0;
    for (int a = 0; a < SPH_DIM; a++) {
      const double d = per ? sph_grid_min_image(x[a] - p0[a], per[a]) : x[a] - p0[a];
      r2 = a ? r2 + d * d : d * d;
    }
    qs[k] = (uint32_t)q;
    k += r2 < SPH_CUBIC_SUPPORT * SPH_CUBIC_SUPPORT * p0[SPH_DIM] * p0[SPH_DIM];
  }
  return k;
}

/* The offsets x_j - x of the candidates in the slots qs[0..k) into e[a][],
 * their weights W(x - x_j, h_j) into ws[], two at a time. */
static inline __attribute__((always_inline)) void
weights(const sph_wall_velocity_work *w, const double x[SPH_DIM], const double per[SPH_DIM],
        const uint32_t *qs, int k, double e[SPH_DIM][FIT_CHUNK + 1], double *ws) {
  for (int t = 0; t < k; t += 2) { /* (an odd count's last pair repeats its slot) */
    const double *p0 = w->pack + PACK * qs[t], *p1 = w->pack + PACK * qs[t + 1 < k ? t + 1 : t];
    v2 r2 = v2_all(0.0);
    for (int a = 0; a < SPH_DIM; a++) {
      const v2 d = sep2(x, p0, p1, a, per);
      r2 = a ? v2_add(r2, v2_mul(d, d)) : v2_mul(d, d);
      store2(e[a] + t, v2_neg(d));
    }
    store2(ws + t, cubic_w2(v2_sqrt(r2), v2_set(p0[SPH_DIM], p1[SPH_DIM])));
  }
}

/* The linear moving-least-squares fit, at the point x, of nf fields f[k]
 * (per-particle arrays) over the fluid particles within reach of it:
 * f ~ c0 + c . (x_j - x), weights W(x - x_j, h_j) (exact for a linear
 * field, also where the kernel is cut by the wall or the surface). Fills
 * fit[FIT_N k ..] with (c0, c) per field; where the fit's moment matrix is
 * near singular (fewer than SPH_DIM + 1 independent neighbours) the
 * Shepard average sum W f / sum W with a zero gradient. fmax (NULL, or a
 * value set by the caller) is raised to the largest value of the first
 * field among those particles, and top set to the offset x_j - x of the
 * first particle in the sums' order that holds it. Returns 0 when no fluid
 * particle reaches the point, else 1.
 *
 * A cell's candidates go FIT_CHUNK at a time through within_reach and
 * weights (two lanes, lane for lane the scalar operations), then into the
 * sums one by one in their order: the bits of one scalar loop over them.
 * Always inlined, so that each caller's nf is a constant and the sums
 * stay in registers. */
static inline __attribute__((always_inline)) int
fit_at(const layout *g, const sph_wall_velocity_work *w, const double x[SPH_DIM],
       const double *const *f, int nf, double *fit, double *fmax, double top[SPH_DIM]) {
  long cells[SPH_DIM][3];
  int nc[3] = {1, 1, 1};
  for (int a = SPH_DIM - 1; a >= 0; a--) /* (the order of 2-D's first reach test: y, then x) */
    if ((nc[a] = cells_near(g, a, x[a], cells[a])) == 0) return 0;
  /* the squared gap along each axis between x and each cell: a cell whose
   * nearest point is beyond the support holds no particle the sums below
   * would take, so it is not visited (the same sums, in the same order) */
  double gap2[3][3] = {{0.0}};
  for (int a = 0; a < SPH_DIM; a++)
    for (int k = 0; k < nc[a]; k++)
      gap2[a][k] = cell_gap2(g, a, x[a], cells[a][k]);
  const double s2 = g->support * g->support;
  double per[SPH_DIM] = {0.0}; /* the period along each axis (0: none) */
  per[g->paxis] = g->period;
  /* linear MLS moments: A = sum W e e^T, b = sum W f e, e = (1, x_j - x), in
   * scalars (registers) */
  double sw = 0.0, a01 = 0.0, a02 = 0.0, a11 = 0.0, a12 = 0.0, a22 = 0.0;
  double sf[SPH_FIT_MAX] = {0.0}, b1[SPH_FIT_MAX] = {0.0}, b2[SPH_FIT_MAX] = {0.0};
  SPH_IF3(double a03 = 0.0, a13 = 0.0, a23 = 0.0, a33 = 0.0, b3[SPH_FIT_MAX] = {0.0};)
  uint32_t qs[FIT_CHUNK + 1];
  double e[SPH_DIM][FIT_CHUNK + 1], ws[FIT_CHUNK + 1];
  for (int kz = 0; kz < nc[2]; kz++)
    for (int ky = 0; ky < nc[1]; ky++)
      for (int kx = 0; kx < nc[0]; kx++) {
        if (gap2[0][kx] + gap2[1][ky] + gap2[2][kz] >= s2) continue;
        size_t cell = (size_t)(cells[1][ky] * g->n[0] + cells[0][kx]);
        SPH_IF3(cell += (size_t)(cells[2][kz] * g->n[0] * g->n[1]);)
        for (size_t q = w->start[cell], end = w->start[cell + 1]; q < end; q += FIT_CHUNK) {
          const size_t qe = end - q > FIT_CHUNK ? q + FIT_CHUNK : end;
          int k;
          if (g->period > 0.0) {
            k = within_reach(w, x, per, q, qe, qs);
            weights(w, x, per, qs, k, e, ws);
          } else { /* (no nearest image to take) */
            k = within_reach(w, x, NULL, q, qe, qs);
            weights(w, x, NULL, qs, k, e, ws);
          }
          for (int t = 0; t < k; t++) {
            const double wj = ws[t], ex = e[0][t], ey = e[1][t];
            SPH_IF3(const double ez = e[2][t];)
            sw += wj;
            a01 += wj * ex;
            a02 += wj * ey;
            a11 += wj * ex * ex;
            a12 += wj * ex * ey;
            a22 += wj * ey * ey;
            SPH_IF3(a03 += wj * ez; a13 += wj * ex * ez; a23 += wj * ey * ez; a33 += wj * ez * ez;)
            const size_t j = w->idx[qs[t]];
            if (fmax && f[0][j] > *fmax) {
              *fmax = f[0][j];
              top[0] = ex, top[1] = ey;
              SPH_IF3(top[2] = ez;)
            }
            for (int m = 0; m < nf; m++) {
              const double fj = f[m][j];
              sf[m] += wj * fj;
              b1[m] += wj * ex * fj;
              b2[m] += wj * ey * fj;
              SPH_IF3(b3[m] += wj * ez * fj;)
            }
          }
        }
      }
  if (!(sw > 0.0)) return 0;
  for (int m = 0; m < nf; m++) {
    fit[FIT_N * m] = sf[m] / sw;
    for (int r = 1; r < FIT_N; r++)
      fit[FIT_N * m + r] = 0.0;
  }
#if SPH_DIM == 2
  const double A[FIT_N][FIT_N] = {{sw, a01, a02}, {a01, a11, a12}, {a02, a12, a22}};
#else
  const double A[FIT_N][FIT_N] = {
      {sw, a01, a02, a03}, {a01, a11, a12, a13}, {a02, a12, a22, a23}, {a03, a13, a23, a33}};
#endif
  double b[SPH_FIT_MAX][FIT_N];
  for (int m = 0; m < nf; m++) {
    b[m][0] = sf[m], b[m][1] = b1[m], b[m][2] = b2[m];
    SPH_IF3(b[m][3] = b3[m];)
  }
  solve_fit(A, (const double(*)[FIT_N])b, nf, fit);
  return 1;
}

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
  for (size_t q = 0; q < nf; q++) { /* the candidates' coordinates in the cells' order */
    const size_t j = w->idx[q];
    for (int a = 0; a < SPH_DIM; a++)
      w->pack[PACK * q + a] = p->pos[a][j];
    w->pack[PACK * q + SPH_DIM] = p->h[j];
  }
  *gp = g;
  return 0;
}

/* The mirror point x + m of particle i. */
static void mirror_point(const sph_particles *p, size_t i, double x[SPH_DIM]) {
  for (int a = 0; a < SPH_DIM; a++)
    x[a] = p->pos[a][i] + p->mirror_offset[a][i];
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
  const double *const fields[SPH_DIM] = {SPH_XYZ(p->vx, p->vy, p->vz)};
  const long nl = (long)n;
#pragma omp parallel for schedule(dynamic, 256) if (nl > SPH_OMP_MIN)
  for (long li = 0; li < nl; li++) {
    const size_t i = (size_t)li;
    if (!(p->flags[i] & SPH_FLAG_NO_SLIP) || p->kind[i] != SPH_KIND_WALL) continue;
    double fit[FIT_N * SPH_DIM], x[SPH_DIM];
    mirror_point(p, i, x);
    if (fit_at(&g, w, x, fields, SPH_DIM, fit, NULL, NULL))
      for (int a = 0; a < SPH_DIM; a++)
        gv[a][i] = 2.0 * p->vel[a][i] - fit[FIT_N * a];
  }
  return 0;
}

int sph_wall_mdbc_density(sph_particles *p, double support, double px0, double period, int paxis,
                          double rho0, const double head[SPH_DIM], sph_wall_velocity_work *w,
                          sph_error *err) {
  layout g;
  const int rc = bin_fluid(p, support, px0, period, paxis, &g, w, err);
  if (rc < 0) return -1;
  const double *const fields[1] = {p->rho};
  const long nl = (long)p->n;
#pragma omp parallel for schedule(dynamic, 256) if (nl > SPH_OMP_MIN)
  for (long li = 0; li < nl; li++) {
    const size_t i = (size_t)li;
    if (!(p->flags[i] & SPH_FLAG_MDBC) || p->kind[i] != SPH_KIND_WALL) continue;
    double fit[FIT_N], x[SPH_DIM], top = -INFINITY, at[SPH_DIM] = {0.0}, rho = rho0;
    mirror_point(p, i, x);
    if (rc == 0 && fit_at(&g, w, x, fields, 1, fit, &top, at)) {
      /* the fit at the wall particle: rho_g - m . grad rho_g */
#if SPH_DIM == 2
      rho = fit[0] - (fit[1] * p->mx[i] + fit[2] * p->my[i]);
#else
      rho = fit[0] - (fit[1] * p->mx[i] + fit[2] * p->my[i] + fit[3] * p->mz[i]);
#endif
      /* no density the fluid around does not have, but for the weight of the fluid between
       * its densest particle (x + at, x the mirror point) and the wall particle (x - m):
       * head . ((x - m) - (x + at)) */
      double lift = 0.0;
      for (int a = 0; a < SPH_DIM; a++)
        lift -= head[a] * (p->mirror_offset[a][i] + at[a]);
      if (lift > 0.0) top += lift;
      if (rho > top) rho = top;
    }
    p->rho[i] = rho > rho0 ? rho : rho0; /* a wall pushes, never pulls */
  }
  return 0;
}
