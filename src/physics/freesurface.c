/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * freesurface.c - free-surface detection by uncovered arcs (paper A §7,
 * after Dilts; the rules are stated in freesurface.h).
 *
 * Per fluid particle i: every neighbour candidate j of the grid's 3x3 cell
 * block contributes nothing, the whole circle (which ends the search), or
 * one closed arc [theta - a, theta + a] of circle i. The arcs are then
 * moved to start in [0, 2 pi), sorted by (start, end) and swept once:
 * `reach` is how far from angle 0 the circle is known to be covered, seeded
 * with the part of arcs that wrap past 2 pi and so cover [0, hi - 2 pi];
 * the circle is uncovered as soon as an arc starts more than
 * SPH_FREESURFACE_GAP_TOL beyond `reach`, covered if the sweep ends with
 * `reach` at 2 pi (within the same tolerance). The sweep uses only
 * comparisons and max on the arc end points, so its answer is a function of
 * the multiset of arcs: the storage order, the neighbour order and the
 * thread count cannot change a flag. Each arc end point depends only on the
 * pair (r_i, R_i, r_j, R_j), computed the same way whoever asks.
 *
 * Invariants: the grid's cells are at least 2 max R, so every pair whose
 * discs overlap lies in neighbouring cells (across the seam of a periodic
 * grid too, where the pair is taken as its minimum image: a period holds
 * at least 2 cells, so only one image can overlap); each particle writes
 * only its own flag (gather form); the arc scratch is private to each
 * thread.
 */
#include "config.h"

#include "core/parallel.h"

#include "physics/freesurface.h"

#include <math.h>
#include <stdlib.h>

#include "core/lanes.h"
#include "physics/kernel.h"
#include "physics/sphere_cover.h"

#define TWO_PI (2.0 * SPH_PI)

int sph_freesurface_disc(double dx, double dy, double ri, double rj, sph_arc *arc) {
  const double d = sqrt(dx * dx + dy * dy);
  if (d >= ri + rj) return SPH_DISC_NONE; /* apart, or tangent in one point */
  if (ri >= d + rj) return SPH_DISC_NONE; /* inside circle i (d = 0, rj <= ri too) */
  if (rj >= d + ri) return SPH_DISC_FULL; /* contains circle i */
  /* here d > 0: law of cosines for the angle at i between r_j - r_i and an
   * intersection point; (ri - rj)(ri + rj) vanishes exactly for equal radii,
   * leaving c = d / (2 ri) with one rounding */
  double c = 0.5 * (d + (ri - rj) * (ri + rj) / d) / ri;
  if (c > 1.0) c = 1.0;
  if (c < -1.0) c = -1.0;
  const double a = acos(c), theta = atan2(dy, dx);
  arc->lo = theta - a;
  arc->hi = theta + a;
  return SPH_DISC_ARC;
}

static int cmp_arc(const void *pa, const void *pb) {
  const sph_arc *a = pa, *b = pb;
  if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
  return (a->hi > b->hi) - (a->hi < b->hi);
}

/* Shifts an arc by whole turns so that lo lies in [0, 2 pi). */
static void normalise(sph_arc *a) {
  if (a->lo < 0.0) {
    a->lo += TWO_PI;
    a->hi += TWO_PI;
  }
  if (a->lo >= TWO_PI) { /* lo was >= 2 pi, or -tiny rounded up to 2 pi */
    a->lo -= TWO_PI;
    a->hi -= TWO_PI;
  }
}

int sph_freesurface_arcs_cover(sph_arc *arcs, size_t n) {
  if (n == 0) return 0;
  for (size_t k = 0; k < n; k++)
    if (arcs[k].hi - arcs[k].lo >= TWO_PI - SPH_FREESURFACE_GAP_TOL) return 1;
  for (size_t k = 0; k < n; k++)
    normalise(&arcs[k]);
  qsort(arcs, n, sizeof *arcs, cmp_arc);
  double reach = -INFINITY; /* [0, reach] is covered by arcs wrapping past 2 pi */
  for (size_t k = 0; k < n; k++)
    if (arcs[k].hi - TWO_PI > reach) reach = arcs[k].hi - TWO_PI;
  for (size_t k = 0; k < n; k++) {
    if (arcs[k].lo > reach + SPH_FREESURFACE_GAP_TOL) return 0;
    if (arcs[k].hi > reach) reach = arcs[k].hi;
  }
  return reach >= TWO_PI - SPH_FREESURFACE_GAP_TOL;
}

/* ---- two cheap certificates -------------------------------------------------
 *
 * Interior: eight closed cones of 45 degrees (cone_of below) share out
 * the directions around particle i. A neighbour j
 * whose covered arc is at least 2 (45 + 0.00055) degrees wide, i.e. with
 * c_j = cos a_j = (R_i^2 + d^2 - R_j^2) / (2 R_i d) <= GAMMA = 0.7071 (or
 * whose disc contains circle i), covers the whole cone its direction
 * theta_j lies in, with a margin of 9.6e-6 rad at both ends: the arc
 * [theta_j - a_j, theta_j + a_j] is centred in that cone. When each of
 * the eight cones holds such a neighbour, the circle is covered with
 * overlaps of at least 2e-5 rad. The test needs no square root:
 * A = R_i^2 + d^2 - R_j^2 <= 2 GAMMA R_i d holds if A <= 0, otherwise iff
 * A^2 <= 4 GAMMA^2 R_i^2 d^2. c_j <= GAMMA < 1 also puts d below R_i + R_j
 * and disc j not inside circle i (both need c_j >= 1), so the arc test
 * takes the same neighbour as an arc (with sin a_j >= 0.7 its end points
 * are within 1e-15 rad of exact) or as containing the circle: it says
 * "covered" too. Offsets closer than D_MIN R_i (a duplicate carries no
 * direction) and radii more than RATIO apart are passed over, so that
 * the rounding of A (1e-16 (R_i^2 + d^2 + R_j^2)) stays far below the
 * margin (2e-5 R_i d).
 *
 * Surface: a point P on circle i (the direction away from the sum of the
 * offsets r_j - r_i, where a surface particle's open side mostly is) that
 * lies outside every other disc, |P - r_j|^2 >= R_j^2 + ETA R_i (R_i +
 * R_j), is at least ETA / 2 rad from every covered arc (the squared
 * distance changes at most 2 R_i d per radian along the circle, and
 * d < R_i + R_j for a disc that covers anything), far more than the
 * arcs' rounding (at most 1.5e-8 rad, for a disc that barely touches) and
 * SPH_FREESURFACE_GAP_TOL: the arc test finds the gap around P.
 *
 * So each certificate gives the arc test's answer, whatever its order of
 * sums; where neither holds the arc test decides. The flags are those of
 * the arc test alone, bit for bit (test_freesurface compares them with
 * exact_only on lattices, disordered clouds and near-tangent cases). */
#define GAMMA 0.7071
#define D_MIN 1e-3
#define RATIO 1e3
#define ETA 1e-6

/* The cones, numbered counter-clockwise from the one around +x, are
 * centred on the axes and the diagonals (so that the neighbours of a
 * square lattice lie inside them, not on their edges); their edges are
 * the lines |dy| = t |dx| and |dx| = t |dy|, t = tan(22.5 degrees) (to
 * 1e-16 rad: inside the margin). cone_of is indexed by [near the x axis,
 * near the y axis, dx < 0, dy < 0]; both "near" bits hold only at d = 0,
 * which cone_held does not use. */
#define TAN_22_5 0.41421356237309505
static const unsigned char cone_of[16] = {1, 0, 2, 0, 3, 4, 2, 4, 7, 0, 6, 0, 5, 4, 6, 4};

/* The bit of the cone of offset (dx, dy), if `held`. */
static inline unsigned cone_bit(double dx, double dy, int held) {
  const double ax = fabs(dx), ay = fabs(dy);
  const unsigned k = (unsigned)(ay <= TAN_22_5 * ax) | (unsigned)(ax <= TAN_22_5 * ay) << 1 |
                     (unsigned)(dx < 0.0) << 2 | (unsigned)(dy < 0.0) << 3;
  return (unsigned)held << cone_of[k];
}

/* The bit of the cone of offset (dx, dy) if disc j covers that cone. */
static inline unsigned cone_held(double dx, double dy, double ri, double rj) {
  const double d2 = dx * dx + dy * dy;
  const double A = ri * ri + d2 - rj * rj;
  const int wide = A <= 0.0 || A * A <= (4.0 * GAMMA * GAMMA) * (ri * ri) * d2;
  const int usable = d2 >= (D_MIN * D_MIN) * (ri * ri) && rj <= RATIO * ri && ri <= RATIO * rj;
  return cone_bit(dx, dy, wide & usable);
}

/* The same for equal radii, R_j = R_i: A = d^2, so the disc is wide iff
 * d^2 <= 4 GAMMA^2 R_i^2 (a bound lo2 <= d^2 <= hi2 passed in). */
static inline unsigned cone_held_equal(double dx, double dy, double lo2, double hi2) {
  const double d2 = dx * dx + dy * dy;
  return cone_bit(dx, dy, (d2 >= lo2) & (d2 <= hi2));
}

/* 1 if the point (px, py) (offsets from particle i) stands off disc j with
 * the margin. */
static inline int stands_off(double px, double py, double dx, double dy, double ri, double rj) {
  const double ex = px - dx, ey = py - dy;
  return ex * ex + ey * ey >= rj * rj + ETA * ri * (ri + rj);
}

int sph_freesurface_cones_cover(const double *dx, const double *dy, const double *rj, size_t n,
                                double ri) {
  unsigned held = 0;
  for (size_t k = 0; k < n; k++)
    held |= cone_held(dx[k], dy[k], ri, rj[k]);
  return held == 0xFFu;
}

int sph_freesurface_point_open(const double *dx, const double *dy, const double *rj, size_t n,
                               double ri, double px, double py) {
  for (size_t k = 0; k < n; k++)
    if (!stands_off(px, py, dx[k], dy[k], ri, rj[k])) return 0;
  return 1;
}

#ifdef SPH_LANES_AVX
/* The interior certificate for equal radii (cone_held_equal over the
 * candidates), four neighbours at a time with AVX2: the held cones' bits
 * (0xFF as soon as all eight are held). Each lane forms d^2, |dy| <= t |dx|, ... with the scalar
 * operations (no fused multiply-add), so every neighbour holds the cone it
 * holds there; the held set is an OR, the same in any order, and so are
 * the flags (test_freesurface runs both). The cone of a lane is picked by
 * blends from the four tests (cone_of's table as selections). */
__attribute__((target("avx2"))) static unsigned
cones_held_equal_avx2(const double *restrict x, const double *restrict y,
                      const uint32_t *restrict cand, size_t m, double xi, double yi, double period,
                      double lo2, double hi2) {
  const __m256d vxi = _mm256_set1_pd(xi), vyi = _mm256_set1_pd(yi);
  const __m256d vlo = _mm256_set1_pd(lo2), vhi = _mm256_set1_pd(hi2);
  const __m256d tan = _mm256_set1_pd(TAN_22_5), zero = _mm256_setzero_pd();
  const __m256d sign = _mm256_set1_pd(-0.0);
  const __m256d per = _mm256_set1_pd(period), hp = _mm256_set1_pd(0.5 * period);
  const __m256d nhp = _mm256_set1_pd(-0.5 * period);
#define CONE(c) _mm256_castsi256_pd(_mm256_set1_epi64x(c))
  const __m256d c0 = CONE(0), c1 = CONE(1), c2 = CONE(2), c3 = CONE(3), c4 = CONE(4);
  const __m256d c5 = CONE(5), c6 = CONE(6), c7 = CONE(7);
#undef CONE
  const __m256i one = _mm256_set1_epi64x(1);
  __m256i acc = _mm256_setzero_si256();
  unsigned held = 0;
  size_t k = 0;
  for (; k + 4 <= m; k += 4) {
    const uint32_t j0 = cand[k], j1 = cand[k + 1], j2 = cand[k + 2], j3 = cand[k + 3];
    __m256d dx = _mm256_sub_pd(_mm256_set_pd(x[j3], x[j2], x[j1], x[j0]), vxi);
    if (period > 0.0) /* the minimum image, as sph_grid_min_image */
      dx = _mm256_blendv_pd(
          _mm256_blendv_pd(dx, _mm256_add_pd(dx, per), _mm256_cmp_pd(dx, nhp, _CMP_LT_OQ)),
          _mm256_sub_pd(dx, per), _mm256_cmp_pd(dx, hp, _CMP_GT_OQ));
    const __m256d dy = _mm256_sub_pd(_mm256_set_pd(y[j3], y[j2], y[j1], y[j0]), vyi);
    const __m256d d2 = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
    const __m256d wide =
        _mm256_and_pd(_mm256_cmp_pd(d2, vlo, _CMP_GE_OQ), _mm256_cmp_pd(d2, vhi, _CMP_LE_OQ));
    const __m256d ax = _mm256_andnot_pd(sign, dx), ay = _mm256_andnot_pd(sign, dy);
    const __m256d nx = _mm256_cmp_pd(ay, _mm256_mul_pd(tan, ax), _CMP_LE_OQ);
    const __m256d ny = _mm256_cmp_pd(ax, _mm256_mul_pd(tan, ay), _CMP_LE_OQ);
    const __m256d sx = _mm256_cmp_pd(dx, zero, _CMP_LT_OQ),
                  sy = _mm256_cmp_pd(dy, zero, _CMP_LT_OQ);
    /* cone_of: near the x axis 0 or 4 (by dx < 0), else near the y axis 2
     * or 6 (by dy < 0), else the diagonals 1, 3, 7, 5 */
    const __m256d diag =
        _mm256_blendv_pd(_mm256_blendv_pd(c1, c7, sy), _mm256_blendv_pd(c3, c5, sy), sx);
    const __m256d cone = _mm256_blendv_pd(_mm256_blendv_pd(diag, _mm256_blendv_pd(c2, c6, sy), ny),
                                          _mm256_blendv_pd(c0, c4, sx), nx);
    const __m256i bits = _mm256_sllv_epi64(one, _mm256_castpd_si256(cone));
    acc = _mm256_or_si256(acc, _mm256_and_si256(bits, _mm256_castpd_si256(wide)));
    const __m128i h2 = _mm_or_si128(_mm256_castsi256_si128(acc), _mm256_extracti128_si256(acc, 1));
    held = (unsigned)_mm_cvtsi128_si64(_mm_or_si128(h2, _mm_unpackhi_epi64(h2, h2)));
    if (held == 0xFFu) return held;
  }
  for (; k < m; k++) {
    const size_t j = cand[k];
    held |= cone_held_equal(sph_grid_min_image(x[j] - xi, period), y[j] - yi, lo2, hi2);
  }
  return held;
}

#endif

/* Whether the interior certificate runs four neighbours at a time: AVX2
 * here, and not asked to scan one at a time. */
static int use_simd(int scalar) {
#ifdef SPH_LANES_AVX
  return !scalar && sph_cpu_has_avx2();
#else
  (void)scalar;
  return 0;
#endif
}

/* The interior certificate for equal radii over the candidates cand[]
 * (positions x, y; particle i at xi, yi, radius ri): the held cones' bits,
 * 0xFF as soon as all eight are held; four neighbours at a time if simd. */
static unsigned cones_equal(const double *x, const double *y, const uint32_t *cand, size_t m,
                            double xi, double yi, double period, double ri, int simd) {
  const double lo2 = (D_MIN * D_MIN) * (ri * ri), hi2 = (4.0 * GAMMA * GAMMA) * (ri * ri);
#ifdef SPH_LANES_AVX
  if (simd) return cones_held_equal_avx2(x, y, cand, m, xi, yi, period, lo2, hi2);
#else
  (void)simd;
#endif
  unsigned held = 0;
  for (size_t k = 0; k < m && held != 0xFFu; k++) {
    const size_t j = cand[k];
    held |= cone_held_equal(sph_grid_min_image(x[j] - xi, period), y[j] - yi, lo2, hi2);
  }
  return held;
}

unsigned sph_freesurface_cones_equal(const double *x, const double *y, const uint32_t *cand,
                                     size_t m, double xi, double yi, double period, double ri,
                                     int scalar) {
  return cones_equal(x, y, cand, m, xi, yi, period, ri, use_simd(scalar));
}

/* ---- one particle ------------------------------------------------------------ */

#if SPH_DIM == 2
/* 1 if some arc of the circle of particle i is uncovered, over the m
 * candidates cand[] (every particle whose disc can overlap circle i; i
 * itself may be among them): the two certificates first, unless
 * exact_only, then the arc test. buf holds at least m arcs. */
static int uncovered(const sph_particles *p, size_t i, const uint32_t *cand, size_t m, double f,
                     double period, int exact_only, int equal_h, int simd, sph_arc *buf) {
  const double xi = p->x[i], yi = p->y[i], ri = f * p->h[i];
  if (!exact_only) {
    if (equal_h) { /* every particle has this h: no radius to load */
      if (cones_equal(p->x, p->y, cand, m, xi, yi, period, ri, simd) == 0xFFu) return 0;
    } else {
      unsigned held = 0;
      for (size_t k = 0; k < m; k++) {
        const size_t j = cand[k];
        held |= cone_held(sph_grid_min_image(p->x[j] - xi, period), p->y[j] - yi, ri, f * p->h[j]);
        if (held == 0xFFu) return 0;
      }
    }
    double sx = 0.0, sy = 0.0;
    for (size_t k = 0; k < m; k++) {
      const size_t j = cand[k];
      sx += sph_grid_min_image(p->x[j] - xi, period);
      sy += p->y[j] - yi;
    }
    const double s2 = sx * sx + sy * sy;
    if (s2 > 0.0) {
      const double scale = -ri / sqrt(s2), px = scale * sx, py = scale * sy;
      int open = 1;
      for (size_t k = 0; k < m && open; k++) {
        const size_t j = cand[k];
        if (j == i) continue;
        open = stands_off(px, py, sph_grid_min_image(p->x[j] - xi, period), p->y[j] - yi, ri,
                          f * p->h[j]);
      }
      if (open) return 1;
    }
  }
  size_t a = 0;
  for (size_t k = 0; k < m; k++) {
    const size_t j = cand[k];
    if (j == i) continue;
    const double dx = sph_grid_min_image(p->x[j] - xi, period), dy = p->y[j] - yi;
    const int r = sph_freesurface_disc(dx, dy, ri, f * p->h[j], &buf[a]);
    if (r == SPH_DISC_FULL) return 0;
    if (r == SPH_DISC_ARC) a++;
  }
  return !sph_freesurface_arcs_cover(buf, a);
}
#endif

#if SPH_DIM == 3
/* Per-thread scratch of the 3-D test, m candidates' worth. */
typedef struct scratch3 {
  sph_cap *caps;
  double *off, *rad;
} scratch3;

/* The 3-D form of uncovered(): 1 if some part of the sphere of particle i
 * is uncovered (sphere_cover.h), over the candidates cand[] (the minimum
 * image along axis paxis when period > 0). Unless exact_only, the
 * certificates first: the interior one by each cap's nearest direction
 * as the caps are made (most interior particles stop there), the surface
 * one, then the interior one by every direction each cap holds; the exact
 * test decides the rest. */
static int uncovered_3d(const sph_particles *p, size_t i, const uint32_t *cand, size_t m, double f,
                        double period, int paxis, int exact_only, scratch3 *w, sph_arc *arcs) {
  const double ri = f * p->h[i];
  size_t nb = 0, nc = 0;
  unsigned long held = 0; /* the interior certificate's directions, as the caps come */
  double sum[3] = {0.0, 0.0, 0.0};
  for (size_t k = 0; k < m; k++) {
    const size_t j = cand[k];
    if (j == i) continue;
    double *d = w->off + 3 * nb;
    for (int a = 0; a < 3; a++) {
      const double e = p->pos[a][j] - p->pos[a][i];
      d[a] = a == paxis ? sph_grid_min_image(e, period) : e;
      sum[a] += d[a];
    }
    w->rad[nb] = f * p->h[j];
    const int r = sph_sphere_cap(d, ri, w->rad[nb], &w->caps[nc]);
    if (r == SPH_DISC_FULL) return 0;
    if (r == SPH_DISC_ARC && !exact_only) {
      held |= sph_sphere_dir_near(&w->caps[nc]);
      if (held == SPH_SPHERE_DIRS_ALL) return 0; /* covered, whatever the others */
    }
    nc += r == SPH_DISC_ARC;
    nb++;
  }
  if (!exact_only) {
    const double s2 = sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2];
    if (s2 > 0.0) {
      const double scale = -ri / sqrt(s2);
      const double q[3] = {scale * sum[0], scale * sum[1], scale * sum[2]};
      if (sph_sphere_point_open(w->off, w->rad, nb, ri, q)) return 1;
    }
    if (sph_sphere_dirs_cover(w->caps, nc)) return 0; /* every direction each cap holds */
  }
  return !sph_sphere_caps_cover(w->caps, nc, arcs);
}
#endif

/* Cheap argument checks shared by both searches: the factor, the period
 * and every h; the smallest and largest h in *hmin, *hmax. */
static int check_particles(const sph_particles *p, double f, double period, double *hmin,
                           double *hmax, sph_error *err) {
  if (!(f > 0.0) || !isfinite(f))
    return sph_error_set(err, "free surface: radius factor must be positive and finite, got %g", f);
  if (!(period >= 0.0) || !isfinite(period))
    return sph_error_set(err, "free surface: period must be 0 or positive, got %g", period);
  if (p->n > UINT32_MAX) return sph_error_set(err, "free surface: %zu particles is too many", p->n);
  *hmin = INFINITY;
  *hmax = 0.0;
  for (size_t i = 0; i < p->n; i++) {
    if (!(p->h[i] > 0.0) || !isfinite(p->h[i]))
      return sph_error_set(err, "free surface: particle %lld has smoothing length %g",
                           (long long)p->id[i], p->h[i]);
    if (p->h[i] < *hmin) *hmin = p->h[i];
    if (p->h[i] > *hmax) *hmax = p->h[i];
  }
  return 0;
}

/* A grid that belongs to p, has cells large enough for the largest pair of
 * discs and, if periodic, the period given. */
static int check_grid(const sph_particles *p, const sph_grid *g, double f, double period,
                      int period_axis, double hmax, sph_error *err) {
  if (!g->start || !g->cell_of[0] || g->ncell[0] <= 0 || g->start[sph_grid_cells(g)] != p->n)
    return sph_error_set(err, "free surface: the grid was not built on these %zu particles", p->n);
  if (g->periodic && g->periodic != 1 + period_axis)
    return sph_error_set(err, "free surface: the grid is periodic along axis %d, not %d",
                         g->periodic - 1, period_axis);
  if (g->periodic && !(fabs(period - sph_grid_period(g)) <= 1e-9 * period))
    return sph_error_set(err, "free surface: the grid is periodic over %g, the period given is %g",
                         sph_grid_period(g), period);
  if (!g->periodic && period != 0.0)
    return sph_error_set(err, "free surface: a period (%g) is given but the grid is not periodic",
                         period);
  if (2.0 * (f * hmax) > g->cell)
    return sph_error_set(err,
                         "free surface: radius factor %g with h up to %g needs grid cells of at "
                         "least %g, the grid has %g (build it with larger cells)",
                         f, hmax, 2.0 * (f * hmax), g->cell);
  return 0;
}

/* A list built on p, still complete (sph_nlist_fresh) for a support that
 * holds the largest pair of discs, with the period given. */
static int check_list(const sph_particles *p, const sph_nlist *l, double f, double period,
                      int period_axis, double hmax, sph_error *err) {
  if (!l->valid || l->n != p->n || !sph_nlist_fresh(l, p))
    return sph_error_set(err,
                         "free surface: the neighbour list is not complete for these %zu "
                         "particles (build it again)",
                         p->n);
  if (!(fabs(l->period - period) <= 1e-9 * period))
    return sph_error_set(err, "free surface: the list's period is %g, the period given is %g",
                         l->period, period);
  if (period > 0.0 && l->paxis != period_axis)
    return sph_error_set(err, "free surface: the list is periodic along axis %d, not %d", l->paxis,
                         period_axis);
  if (2.0 * (f * hmax) > l->radius - l->skin)
    return sph_error_set(err,
                         "free surface: radius factor %g with h up to %g needs a list support of "
                         "at least %g, the list has %g",
                         f, hmax, 2.0 * (f * hmax), l->radius - l->skin);
  return 0;
}

/* The flags of every particle from the candidates the grid g (or, if g is
 * NULL, the list l) gives each; equal_h: every particle has the same h;
 * scalar: the interior certificate one neighbour at a time even with AVX2. */
static int detect(sph_particles *p, const sph_grid *g, const sph_nlist *l, double f, double period,
                  int paxis, int exact_only, int equal_h, int scalar, size_t *count,
                  sph_error *err) {
  (void)paxis; /* (2-D: the period is along x) */
  const long n = (long)p->n;
  const int simd = use_simd(scalar); /* the interior certificate four at a time */
  size_t flagged = 0;
  int oom = 0;
#pragma omp parallel if (n > SPH_OMP_MIN) reduction(+ : flagged) reduction(| : oom)
  {
    sph_arc *buf = NULL;
    uint32_t *cand = NULL;
    size_t cap = 0;
#if SPH_DIM == 3
    scratch3 w3 = {NULL, NULL, NULL};
#endif
#pragma omp for schedule(dynamic, 256)
    for (long li = 0; li < n; li++) {
      const size_t i = (size_t)li;
      unsigned bit = 0;
      if (p->kind[i] == SPH_KIND_FLUID) {
        size_t lo[SPH_GRID_RANGES], hi[SPH_GRID_RANGES], need = 0;
        if (g) {
          sph_grid_ranges_all(g, i, lo, hi);
          for (int k = 0; k < SPH_GRID_RANGES; k++)
            need += hi[k] - lo[k];
        } else {
          need = l->count[i];
        }
        if (need > cap) { /* arcs, and with a grid the candidates' indices */
          const size_t c = need + need / 2 + 16;
          sph_arc *b = realloc(buf, c * sizeof *b);
          if (b) buf = b;
          uint32_t *q = g ? realloc(cand, c * sizeof *q) : NULL;
          if (q) cand = q;
          int more = b && (q || !g);
#if SPH_DIM == 3 /* the caps, offsets and radii of the 3-D test */
          sph_cap *cp = more ? realloc(w3.caps, c * sizeof *cp) : NULL;
          if (cp) w3.caps = cp;
          double *op = cp ? realloc(w3.off, 3 * c * sizeof *op) : NULL;
          if (op) w3.off = op;
          double *rp = op ? realloc(w3.rad, c * sizeof *rp) : NULL;
          if (rp) w3.rad = rp;
          more = rp != NULL;
#endif
          if (more) cap = c;
        }
        if (need > cap) {
          oom = 1;
        } else {
          size_t got = need;
          const uint32_t *row = l ? sph_nlist_row(l, i, &got) : cand;
          if (g) {
            size_t m = 0;
            for (int k = 0; k < SPH_GRID_RANGES; k++)
              for (size_t j = lo[k]; j < hi[k]; j++)
                cand[m++] = (uint32_t)j;
          }
#if SPH_DIM == 2
          bit = uncovered(p, i, row, need, f, period, exact_only, equal_h, simd, buf)
                    ? SPH_FLAG_FREE_SURFACE
                    : 0u;
#else
          (void)equal_h, (void)simd;
          bit = uncovered_3d(p, i, row, need, f, period, paxis, exact_only, &w3, buf)
                    ? SPH_FLAG_FREE_SURFACE
                    : 0u;
#endif
        }
      }
      p->flags[i] = (uint8_t)((p->flags[i] & ~SPH_FLAG_FREE_SURFACE) | bit);
      flagged += bit ? 1u : 0u;
    }
    free(buf);
    free(cand);
#if SPH_DIM == 3
    free(w3.caps);
    free(w3.off);
    free(w3.rad);
#endif
  }
  if (oom) return sph_error_set(err, "free surface: out of memory for the arc scratch");
  if (count) *count = flagged;
  return 0;
}

/* The checks, then detection from the grid g or, if g is NULL, the list l. */
static int detect_checked(sph_particles *p, const sph_grid *g, const sph_nlist *l,
                          const sph_freesurface_params *fp, size_t *count, sph_error *err) {
  const sph_freesurface_params defaults = SPH_FREESURFACE_DEFAULTS;
  if (!fp) fp = &defaults;
  const double f = fp->radius_factor, period = fp->period;
  double hmin = 0.0, hmax = 0.0;
  if (check_particles(p, f, period, &hmin, &hmax, err)) return -1;
  if (p->n == 0) return count ? (*count = 0, 0) : 0;
  if (!(fp->paxis >= 0 && fp->paxis < SPH_DIM && (SPH_DIM == 3 || fp->paxis == 0)))
    return sph_error_set(err, "free surface: no periodic axis %d in %d-D", fp->paxis, SPH_DIM);
  if (g ? check_grid(p, g, f, period, fp->paxis, hmax, err)
        : check_list(p, l, f, period, fp->paxis, hmax, err))
    return -1;
  return detect(p, g, l, f, period, fp->paxis, fp->exact_only, hmin == hmax, fp->scalar, count,
                err);
}

int sph_freesurface_detect(sph_particles *p, const sph_grid *g, const sph_freesurface_params *fp,
                           size_t *count, sph_error *err) {
  return detect_checked(p, g, NULL, fp, count, err);
}

int sph_freesurface_detect_list(sph_particles *p, const sph_nlist *l,
                                const sph_freesurface_params *fp, size_t *count, sph_error *err) {
  return detect_checked(p, NULL, l, fp, count, err);
}

void sph_freesurface_apply_h(sph_particles *p, double h0, double k) {
  const long n = (long)p->n;
  const double hs = k * h0;
#pragma omp parallel for schedule(static) if (n > SPH_OMP_MIN)
  for (long l = 0; l < n; l++) {
    const size_t i = (size_t)l;
    const int surface = p->kind[i] == SPH_KIND_FLUID && (p->flags[i] & SPH_FLAG_FREE_SURFACE);
    p->h[i] = surface ? hs : h0;
  }
}
