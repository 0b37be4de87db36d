/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * probes.c - the readings of pressure, level and velocity probes (see
 * probes.h).
 */
#include "config.h"

#include "analysis/probe_terms.h"
#include "analysis/probes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/kernel_shape.h"
#include "core/lanes.h"
#include "physics/kernel.h"

int sph_probe_columns(const sph_probe *q) {
  return q->kind == SPH_PROBE_VELOCITY ? SPH_DIM : sph_probe_filtered(q) ? 2 : 1;
}

double sph_probe_low_pass(double y, double x, double dt, double cutoff) {
  const double a = -expm1(-2.0 * SPH_PI * cutoff * dt);
  return y + a * (x - y);
}

void sph_probe_header(const sph_probe *q, char *buf, size_t len) {
  switch (q->kind) {
  case SPH_PROBE_PRESSURE:
    if (sph_probe_filtered(q))
      snprintf(buf, len, ",%s (Pa),%s_low_pass (Pa)", q->name, q->name);
    else
      snprintf(buf, len, ",%s (Pa)", q->name);
    break;
  case SPH_PROBE_LEVEL: snprintf(buf, len, ",%s (m)", q->name); break;
  case SPH_PROBE_VELOCITY:
#if SPH_DIM == 2
    snprintf(buf, len, ",%s_vx (m/s),%s_vy (m/s)", q->name, q->name);
#else
    snprintf(buf, len, ",%s_vx (m/s),%s_vy (m/s),%s_vz (m/s)", q->name, q->name, q->name);
#endif
    break;
  }
}

/* K(rho) = the integral of W(sqrt(rho^2 + s^2), h) over s: the kernel's weight along a line at
 * distance rho < 2h from its centre (Simpson's rule, 64 intervals over the chord). The
 * integrand is even in s: the chord's half from s = 0 is summed and doubled (33 kernel values
 * instead of 65: a wire gauge reads it for every fluid particle near its line, every step). */
static double line_weight(sph_kernel_kind kernel, double rho, double h) {
  const double half = sqrt(fmax(4.0 * h * h - rho * rho, 0.0));
  if (!(half > 0.0)) return 0.0;
  const int n = 32; /* intervals over the half chord */
  const double ds = half / n;
  double w, dw, sum = 0.0;
  for (int k = 1; k <= n; k++) {
    const double s = k * ds, r = sqrt(rho * rho + s * s);
    sph_kernel_w_dw(kernel, r, h, &w, &dw);
    sum += (k == n ? 1.0 : (k % 2 ? 4.0 : 2.0)) * w;
  }
  sph_kernel_w_dw(kernel, rho, h, &w, &dw); /* s = 0, the middle point: weight 2 of the whole */
  return (2.0 * sum + 2.0 * w) * ds / 3.0;
}

/* A probe's sums, which its terms (sph_probe_term, probe_terms.h) add to
 * in the store's order: a pressure or velocity probe's Shepard sums at each
 * point (the kernel sum, then the weighted pressure and velocity), a wire
 * gauge's wetted length, a level probe's highest fluid centre. */
struct acc {
  double s[SPH_PROBE_MAX_POINTS][2 + SPH_DIM];
  double top;
};

static void acc_init(struct acc *a) {
  memset(a->s, 0, sizeof a->s);
  a->top = -INFINITY;
}

/* One term: its point k and its values, added as the serial reading adds
 * them (a level probe's top a maximum). */
static inline void acc_add(struct acc *a, sph_probe_kind kind, int wetted,
                           const sph_probe_term *t) {
  if (kind == SPH_PROBE_LEVEL) {
    if (wetted)
      a->s[0][0] += t->v[0];
    else if (t->v[0] > a->top)
      a->top = t->v[0];
    return;
  }
  double *sk = a->s[t->k];
  for (int m = 0; m < 2 + SPH_DIM; m++)
    sk[m] += t->v[m];
}

/* Where a probe's terms go: straight into its sums (one process reading
 * the whole store), or appended to a list (a share of the store, whose
 * lists the processes merge in storage order). */
typedef struct sink {
  struct acc *acc;
  sph_probe_kind kind;
  int wetted;
  sph_probe_term *t; /* the list: n of cap */
  size_t n, cap;
  int failed; /* out of memory */
} sink;

static void emit(sink *o, int k, const double *v, int nv) {
  sph_probe_term t;
  memset(&t, 0, sizeof t); /* (its padding too: the processes send terms as bytes) */
  t.k = k;
  for (int m = 0; m < nv; m++)
    t.v[m] = v[m];
  if (o->acc) {
    acc_add(o->acc, o->kind, o->wetted, &t);
    return;
  }
  if (o->failed) return;
  if (o->n == o->cap) {
    const size_t cap = o->cap ? 2 * o->cap : 256;
    sph_probe_term *g = realloc(o->t, cap * sizeof *g);
    if (!g) {
      o->failed = 1;
      return;
    }
    o->t = g, o->cap = cap;
  }
  o->t[o->n++] = t;
}

/* The particles a probe reads go by in blocks of SPH_PROBE_BLOCK in storage
 * order: a block with no particle strictly between lo and hi along x (a test
 * in lanes, with no branch a particle) is passed over whole. The store is
 * sorted by cell, so the few particles near a probe fill few blocks; those
 * blocks are read particle by particle, in storage order, with every test the
 * reading makes (lo and hi wider than they are): the same terms in the same
 * order. On SPHERIC Test 2 (12 probes) it leaves a reading a third of its
 * instructions. */
#define SPH_PROBE_BLOCK 64

static inline size_t block_end(size_t b, size_t to) {
  return to - b > SPH_PROBE_BLOCK ? b + SPH_PROBE_BLOCK : to;
}

/* How many of x[b, e) lie strictly between lo and hi: a count in doubles,
 * so that the loop runs in lanes (four with AVX2, where the processor has
 * it: the same count). */
SPH_AVX2_TWIN(double, count_within, (const double *x, size_t b, size_t e, double lo, double hi),
              (x, b, e, lo, hi), {
                double k = 0.0;
                _Pragma("omp simd reduction(+ : k)") for (size_t j = b; j < e; j++) k +=
                    (x[j] > lo) & (x[j] < hi) ? 1.0 : 0.0;
                return k;
              })

/* The first block from particle b on (b, b + SPH_PROBE_BLOCK, ... up to
 * to) with a particle strictly between lo and hi along x, or to. */
static size_t next_block(const double *x, size_t b, size_t to, double lo, double hi) {
  for (; b < to; b += SPH_PROBE_BLOCK)
    if (count_within(x, b, block_end(b, to), lo, hi) != 0.0) return b;
  return to;
}

/* A wire gauge's wetted length along the vertical line of a level probe:
 * sum_j V_j K(rho_j) over the liquid's particles within 2h of the line, in storage order (a term
 * a particle: particles [from, to)). */
static void wetted_length(const sph_probe *q, const sph_particles *p, size_t from, size_t to,
                          sph_kernel_kind kernel, double h, sink *o) {
  /* (past this along x, a particle is past the reach below: its square alone exceeds it) */
  const double far = 2.001 * h, lo = q->x - 1.01 * far, hi = q->x + 1.01 * far;
  for (size_t b = next_block(p->x, from, to, lo, hi); b < to;
       b = next_block(p->x, b + SPH_PROBE_BLOCK, to, lo, hi)) {
    for (size_t j = b, e = block_end(b, to); j < e; j++) {
      const double ex = p->x[j] - q->x;
      if (!(fabs(ex) < far) || !sph_particles_liquid(p, j)) continue; /* (not the air) */
#if SPH_DIM == 2
      const double rho = fabs(ex);
#else
      /* hypot only within the reach: a sum of squares 1e-9 above (2h)^2
       * puts hypot's correctly rounded distance past 2h too */
      const double ey = p->y[j] - q->y;
      if (ex * ex + ey * ey >= 4.0 * h * h * (1.0 + 1e-9)) continue;
      const double rho = hypot(ex, ey);
#endif
      if (rho < 2.0 * h) {
        const double v = p->mass[j] / p->rho[j] * line_weight(kernel, rho, h);
        emit(o, 0, &v, 1);
      }
    }
  }
}

/* How a probe interpolates (probes.h): the defaults, or a pressure
 * sensor's own. */
typedef struct interp {
  double h;   /* the kernel's smoothing length */
  double wet; /* the kernel sum below which a point is dry */
  int clip;   /* negative pressures read as 0 */
  int carry;  /* pressures carried along g */
} interp;

static interp interp_of(const sph_probe *q, double h) {
  interp o = {h, SPH_PROBE_WET_SUM, 0, 1};
  if (q->kind != SPH_PROBE_PRESSURE) return o;
  if (q->smoothing > 0.0) o.h = q->smoothing * h;
  if (q->wet_sum > 0.0) o.wet = q->wet_sum;
  o.clip = q->clip_negative;
  o.carry = !q->no_carry;
  return o;
}

/* The Shepard sums of the pressure (carried along g) and the velocity at
 * each of the n points x[k] (n <= SPH_PROBE_MAX_POINTS), in one pass over
 * particles [from, to): a term for each particle and point within reach,
 * the kernel sum, then the weighted pressure and velocity. Each point's
 * sums run over the particles in storage order, as they would alone. */
static void shepard_terms(const sph_particles *p, size_t from, size_t to, sph_kernel_kind kernel,
                          int n, const double x[][SPH_DIM], const interp *o,
                          const double g[SPH_DIM], sink *out) {
  const double h = o->h, reach = 2.0 * h;
  double lo[SPH_DIM], hi[SPH_DIM]; /* the box every point's reach lies in */
  for (int d = 0; d < SPH_DIM; d++) {
    lo[d] = hi[d] = x[0][d];
    for (int k = 1; k < n; k++)
      lo[d] = fmin(lo[d], x[k][d]), hi[d] = fmax(hi[d], x[k][d]);
    lo[d] -= 1.001 * reach, hi[d] += 1.001 * reach; /* never tighter than the test below */
  }
  const double *px = p->x;
  for (size_t b = next_block(px, from, to, lo[0], hi[0]); b < to;
       b = next_block(px, b + SPH_PROBE_BLOCK, to, lo[0], hi[0])) {
    for (size_t j = b, e = block_end(b, to); j < e; j++) {
      /* the box along x, the other axes, then the kind */
      if (!(px[j] > lo[0] && px[j] < hi[0])) continue;
      const double xj[SPH_DIM] = {SPH_XYZ(px[j], p->y[j], p->z[j])};
      int in = 1;
      for (int d = 1; d < SPH_DIM; d++)
        in &= xj[d] > lo[d] && xj[d] < hi[d];
      if (!in || p->kind[j] != SPH_KIND_FLUID) continue;
      for (int k = 0; k < n; k++) {
        const double dx = x[k][0] - xj[0], dy = x[k][1] - xj[1];
        if (fabs(dx) >= reach || fabs(dy) >= reach) continue;
#if SPH_DIM == 2
        const double r = sqrt(dx * dx + dy * dy), gd = g[0] * dx + g[1] * dy;
#else
        const double dz = x[k][2] - xj[2];
        if (fabs(dz) >= reach) continue;
        const double r = sqrt(dx * dx + dy * dy + dz * dz), gd = g[0] * dx + g[1] * dy + g[2] * dz;
#endif
        const double w = sph_kernel_w(kernel, r, h) * (p->mass[j] / p->rho[j]);
        const double pj = o->clip && !(p->p[j] > 0.0) ? 0.0 : p->p[j];
        const double v[2 + SPH_DIM] = {w, w * (o->carry ? pj + p->rho[j] * gd : pj), w * p->vx[j],
                                       w * p->vy[j] SPH_IF3(, w * p->vz[j])};
        emit(out, k, v, 2 + SPH_DIM);
      }
    }
  }
}

/* The Shepard-normalised pressure and velocity at each point from its
 * sums: out[k][0] the pressure, out[k][1 ..] the velocity; wet[k] 0 where
 * dry (out[k] then unset). */
static void shepard_of(const struct acc *a, int n, const interp *o, double out[][1 + SPH_DIM],
                       int *wet) {
  for (int k = 0; k < n; k++) {
    wet[k] = a->s[k][0] >= o->wet;
    if (!wet[k]) continue;
    for (int m = 0; m < 1 + SPH_DIM; m++)
      out[k][m] = a->s[k][1 + m] / a->s[k][0];
  }
}

#if SPH_DIM == 3
/* Two unit vectors across the unit normal n, and n's: a right-handed set. */
static void across(const double n[3], double t1[3], double t2[3]) {
  const double a[3] = {fabs(n[0]) < 0.9 ? 1.0 : 0.0, fabs(n[0]) < 0.9 ? 0.0 : 1.0, 0.0};
  t1[0] = a[1] * n[2] - a[2] * n[1]; /* a x n */
  t1[1] = a[2] * n[0] - a[0] * n[2];
  t1[2] = a[0] * n[1] - a[1] * n[0];
  const double l = sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
  for (int d = 0; d < 3; d++)
    t1[d] /= l;
  t2[0] = n[1] * t1[2] - n[2] * t1[1]; /* n x t1 */
  t2[1] = n[2] * t1[0] - n[0] * t1[2];
  t2[2] = n[0] * t1[1] - n[1] * t1[0];
}
#endif

/* The k-th of a pressure sensor's n face points (n = 1: its centre). */
static void face_point(const sph_probe *q, int k, int n, double x[SPH_DIM]) {
#if SPH_DIM == 2
  const double s = n > 1 ? ((double)k / (n - 1) - 0.5) * q->diameter : 0.0;
  x[0] = q->x + (q->along_x ? s : 0.0);
  x[1] = q->y + (q->along_x ? 0.0 : s);
#else
  double t1[3], t2[3];
  across(q->normal, t1, t2);
  const double r = 0.5 * q->diameter / sqrt(2.0);
  const double a = k == 0 || n == 1 ? 0.0 : (k % 2 ? r : -r);
  const double *t = k <= 2 ? t1 : t2;
  const double c[3] = {q->x, q->y, q->z};
  for (int d = 0; d < 3; d++)
    x[d] = c[d] + a * t[d];
#endif
}

/* A pressure probe's points: its face's (probes.h), or its centre. */
static int points_of(const sph_probe *q, double at[][SPH_DIM]) {
  const int n = q->kind == SPH_PROBE_PRESSURE && q->diameter > 0.0
                    ? (q->points > 0 ? q->points : SPH_PROBE_FACE_POINTS)
                    : 1;
  if (q->kind == SPH_PROBE_PRESSURE)
    for (int k = 0; k < n; k++)
      face_point(q, k, n, at[k]);
  else
    for (int d = 0; d < SPH_DIM; d++)
      at[0][d] = (double[]){SPH_XYZ(q->x, q->y, q->z)}[d];
  return n;
}

/* Probe q's terms among particles [from, to) of p, into o. */
static void terms_of(const sph_probe *q, const sph_particles *p, size_t from, size_t to,
                     sph_kernel_kind kernel, double h, double dx, const double g[SPH_DIM],
                     sink *o) {
  switch (q->kind) {
  case SPH_PROBE_PRESSURE:
  case SPH_PROBE_VELOCITY: {
    double at[SPH_PROBE_MAX_POINTS][SPH_DIM];
    const int n = points_of(q, at);
    const interp in = interp_of(q, h);
    shepard_terms(p, from, to, kernel, n, at, &in, g, o);
    break;
  }
  case SPH_PROBE_LEVEL: {
    if (q->wetted) {
      wetted_length(q, p, from, to, kernel, h, o);
      break;
    }
    const double *up = p->pos[SPH_UP];
    const double lo = q->x - 1.01 * dx, hi = q->x + 1.01 * dx;
    for (size_t b = next_block(p->x, from, to, lo, hi); b < to;
         b = next_block(p->x, b + SPH_PROBE_BLOCK, to, lo, hi)) {
      for (size_t j = b, e = block_end(b, to); j < e; j++) {
        const double ex = p->x[j] - q->x;
        if (!(fabs(ex) < dx) || !sph_particles_liquid(p, j)) continue;
#if SPH_DIM == 2
        const int near = 1;
#else
        const double ey = p->y[j] - q->y;
        const int near = ex * ex + ey * ey < dx * dx;
#endif
        if (near) emit(o, 0, &up[j], 1);
      }
    }
    break;
  }
  }
}

/* The reading from its sums. */
static void reading_of(const sph_probe *q, const struct acc *a, double h, double dx, double floor_y,
                       double *out) {
  switch (q->kind) {
  case SPH_PROBE_PRESSURE: {
    double at[SPH_PROBE_MAX_POINTS][SPH_DIM], v[SPH_PROBE_MAX_POINTS][1 + SPH_DIM];
    int wet[SPH_PROBE_MAX_POINTS];
    const int n = points_of(q, at);
    const interp o = interp_of(q, h);
    shepard_of(a, n, &o, v, wet);
    double sum = 0.0;
    for (int k = 0; k < n; k++)
      if (wet[k]) sum += v[k][0];
    out[0] = sum / n;
    break;
  }
  case SPH_PROBE_LEVEL: {
    if (q->wetted) {
      out[0] = a->s[0][0];
      break;
    }
    const double depth = a->top + 0.5 * dx - floor_y;
    out[0] = isfinite(depth) && depth > 0.0 ? depth : 0.0;
    break;
  }
  case SPH_PROBE_VELOCITY: {
    double v[1][1 + SPH_DIM];
    int wet;
    const interp o = interp_of(q, h);
    for (int d = 0; d < SPH_DIM; d++)
      out[d] = 0.0;
    shepard_of(a, 1, &o, v, &wet);
    if (wet)
      for (int d = 0; d < SPH_DIM; d++)
        out[d] = v[0][1 + d];
    break;
  }
  }
}

void sph_probe_read(const sph_probe *q, const sph_particles *p, sph_kernel_kind kernel, double h,
                    double dx, double floor_y, const double g[SPH_DIM], double *out) {
  struct acc a;
  acc_init(&a);
  sink o = {&a, q->kind, q->wetted, NULL, 0, 0, 0};
  terms_of(q, p, 0, p->n, kernel, h, dx, g, &o);
  reading_of(q, &a, h, dx, floor_y, out);
}

int sph_probe_terms(const sph_probe *q, const sph_particles *p, size_t from, size_t to,
                    sph_kernel_kind kernel, double h, double dx, const double g[SPH_DIM],
                    sph_probe_term **t, size_t *n, size_t *cap) {
  sink o = {NULL, q->kind, q->wetted, *t, *n, *cap, 0};
  terms_of(q, p, from, to, kernel, h, dx, g, &o);
  *t = o.t, *n = o.n, *cap = o.cap;
  return o.failed ? -1 : 0;
}

void sph_probe_fold(const sph_probe *q, const sph_probe_term *const *pieces, const size_t *counts,
                    int n_pieces, double h, double dx, double floor_y, double *out) {
  struct acc a;
  acc_init(&a);
  for (int r = 0; r < n_pieces; r++)
    for (size_t i = 0; i < counts[r]; i++)
      acc_add(&a, q->kind, q->wetted, &pieces[r][i]);
  reading_of(q, &a, h, dx, floor_y, out);
}
