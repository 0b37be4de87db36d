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
 * at least 3 cells, so only one image can overlap); each particle writes
 * only its own flag (gather form); the arc scratch is private to each
 * thread.
 */
#include "config.h"

#include "core/parallel.h"

#include "physics/freesurface.h"

#include <math.h>
#include <stdlib.h>

#include "physics/kernel.h"

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

/* Number of neighbour candidates of particle i (an upper bound on its arcs). */
static size_t candidates(const sph_grid *g, size_t i) {
  size_t lo[SPH_GRID_RANGES], hi[SPH_GRID_RANGES], m = 0;
  sph_grid_ranges_all(g, i, lo, hi);
  for (int k = 0; k < SPH_GRID_RANGES; k++)
    m += hi[k] - lo[k];
  return m;
}

/* 1 if some arc of the circle of particle i is uncovered. buf holds at
 * least candidates(g, i) arcs. */
static int uncovered(const sph_particles *p, const sph_grid *g, size_t i, double f, double period,
                     sph_arc *buf) {
  const double xi = p->x[i], yi = p->y[i], ri = f * p->h[i];
  size_t lo[SPH_GRID_RANGES], hi[SPH_GRID_RANGES], m = 0;
  sph_grid_ranges_all(g, i, lo, hi);
  for (int k = 0; k < SPH_GRID_RANGES; k++)
    for (size_t j = lo[k]; j < hi[k]; j++) {
      if (j == i) continue;
      const double dx = sph_grid_min_image(p->x[j] - xi, period), dy = p->y[j] - yi;
      const int r = sph_freesurface_disc(dx, dy, ri, f * p->h[j], &buf[m]);
      if (r == SPH_DISC_FULL) return 0;
      if (r == SPH_DISC_ARC) m++;
    }
  return !sph_freesurface_arcs_cover(buf, m);
}

/* Cheap argument checks: the factor, every h, and a grid that belongs to p,
 * has cells large enough for the largest pair of discs and, if periodic,
 * the period given. */
static int check_inputs(const sph_particles *p, const sph_grid *g, double f, double period,
                        sph_error *err) {
  if (!(f > 0.0) || !isfinite(f))
    return sph_error_set(err, "free surface: radius factor must be positive and finite, got %g", f);
  if (!(period >= 0.0) || !isfinite(period))
    return sph_error_set(err, "free surface: period must be 0 or positive, got %g", period);
  double hmax = 0.0;
  for (size_t i = 0; i < p->n; i++) {
    if (!(p->h[i] > 0.0) || !isfinite(p->h[i]))
      return sph_error_set(err, "free surface: particle %lld has smoothing length %g",
                           (long long)p->id[i], p->h[i]);
    if (p->h[i] > hmax) hmax = p->h[i];
  }
  if (p->n == 0) return 0;
  if (!g->start || !g->cx || !g->cy || g->nx <= 0 || g->ny <= 0 ||
      g->start[(size_t)g->nx * (size_t)g->ny] != p->n)
    return sph_error_set(err, "free surface: the grid was not built on these %zu particles", p->n);
  if (g->periodic && !(fabs(period - g->cellx * (double)g->nx) <= 1e-9 * period))
    return sph_error_set(err, "free surface: the grid is periodic over %g, the period given is %g",
                         g->cellx * (double)g->nx, period);
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

int sph_freesurface_detect(sph_particles *p, const sph_grid *g, const sph_freesurface_params *fp,
                           size_t *count, sph_error *err) {
  const sph_freesurface_params defaults = SPH_FREESURFACE_DEFAULTS;
  if (!fp) fp = &defaults;
  const double f = fp->radius_factor, period = fp->period;
  if (check_inputs(p, g, f, period, err)) return -1;
  const long n = (long)p->n;
  size_t flagged = 0;
  int oom = 0;
#pragma omp parallel if (n > SPH_OMP_MIN) reduction(+ : flagged) reduction(| : oom)
  {
    sph_arc *buf = NULL;
    size_t cap = 0;
#pragma omp for schedule(dynamic, 256)
    for (long l = 0; l < n; l++) {
      const size_t i = (size_t)l;
      unsigned bit = 0;
      if (p->kind[i] == SPH_KIND_FLUID) {
        const size_t need = candidates(g, i);
        if (need > cap) {
          sph_arc *b = realloc(buf, (need + need / 2 + 16) * sizeof *b);
          if (b) {
            buf = b;
            cap = need + need / 2 + 16;
          }
        }
        if (need > cap)
          oom = 1;
        else
          bit = uncovered(p, g, i, f, period, buf) ? SPH_FLAG_FREE_SURFACE : 0u;
      }
      p->flags[i] = (uint8_t)((p->flags[i] & ~SPH_FLAG_FREE_SURFACE) | bit);
      flagged += bit ? 1u : 0u;
    }
    free(buf);
  }
  if (oom) return sph_error_set(err, "free surface: out of memory for the arc scratch");
  if (count) *count = flagged;
  return 0;
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
