/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * freesurface.h - free-surface detection by uncovered arcs (paper A §7,
 * after Dilts). In 3-D the circle is a sphere and the discs balls: the
 * same detection with the covering test of sphere_cover.h.
 *
 * Every particle i is a circle of radius R_i = f h_i (f: the radius factor,
 * 1 in paper A). Fluid particle i is on the free surface if some arc of its
 * circle is not covered by the closed discs of radius R_j centred at its
 * neighbours r_j (fluid and wall alike). The covered arcs are computed
 * exactly (one closed angle interval per neighbour) and their union is
 * tested against the whole circle; nothing is sampled.
 *
 * Rules for the degenerate cases (d = |r_j - r_i|), so that the answer is
 * defined for every input:
 *   d >= R_i + R_j          disc j misses circle i or touches it in one point
 *                           (external tangency): covers nothing;
 *   R_i >= d + R_j          disc j lies inside circle i, touching it in at
 *                           most one point: covers nothing. With d = 0 this
 *                           includes a coincident particle of equal (or
 *                           smaller) radius: a duplicate carries no
 *                           direction, so it hides no part of the surface;
 *   R_j >= d + R_i          disc j contains circle i (internal tangency
 *                           included, and d = 0 with R_j > R_i): the whole
 *                           circle is covered;
 *   otherwise               the closed arc [theta - a, theta + a] with
 *                           theta = atan2(y_j - y_i, x_j - x_i) and
 *                           cos a = (R_i^2 + d^2 - R_j^2) / (2 R_i d).
 * The rules are tested in this order. Every particle in the store covers,
 * whatever its kind (fluid, wall, mirror); only fluid particles are flagged
 * (bit SPH_FLAG_FREE_SURFACE of particles.h). On a grid periodic in x,
 * r_j - r_i is the minimum image. Arcs are closed, so arcs that touch
 * join; an uncovered gap counts only if it is longer than
 * SPH_FREESURFACE_GAP_TOL radians (see there), so a circle covered in exact
 * arithmetic by touching arcs is covered in floating point too, whatever
 * the rounding of atan2 and acos.
 *
 * The answer for a particle depends only on the set of its neighbours'
 * positions and radii: not on the storage order, the neighbour order, or
 * the thread count.
 *
 * Two cheap certificates come first: most interior particles have, in
 * each of eight 45-degree cones, a neighbour whose disc covers the whole
 * cone (sph_freesurface_cones_cover); most surface particles have a point
 * of their circle, away from their neighbours, that no disc comes near
 * (sph_freesurface_point_open). They need no trigonometry and no sort,
 * and each gives the arc test's own answer (the argument is in
 * freesurface.c, the check in test_freesurface); on the rest the arc test
 * decides. The flags are therefore those of the arc test alone, bit for
 * bit.
 */
#ifndef SPH_FREESURFACE_H
#define SPH_FREESURFACE_H

#include <stddef.h>

#include "core/error.h"
#include "core/particles.h"
#include "neighbours/grid.h"

/* A gap between covered arcs no longer than this (radians) counts as
 * covered. Arc end points carry a rounding error of a few 1e-16 rad when
 * the half-width a is moderate, growing like 1e-16 / sin(a) for very narrow
 * or very wide arcs; 1e-10 rad absorbs that for every arc with
 * 1e-5 < a < pi - 1e-5, while a real gap of 1e-10 R is ten orders of
 * magnitude below the particle spacing and carries no physics. */
#define SPH_FREESURFACE_GAP_TOL 1e-10

/* Parameters of the detection. */
typedef struct sph_freesurface_params {
  double radius_factor; /* R_i = radius_factor * h_i; paper A: 1 */
  double period;        /* x period of a periodic grid (px1 - px0); 0 if the grid is not */
  int exact_only;       /* 1: the arc test on every particle, without the certificates (the
                           oracle of the tests; the flags are the same) */
  int scalar;           /* 1: the interior certificate one neighbour at a time even where the
                           processor has AVX2 (tests, SPH_TEST_LANES; the flags are the same) */
  int paxis;            /* the axis of the period: 0 (x); in 3-D also 1 (y) or 2 (z) */
} sph_freesurface_params;

/* Paper A: the circle of radius h_i; not periodic. */
#define SPH_FREESURFACE_DEFAULTS                                                                   \
  { .radius_factor = 1.0, .period = 0.0, .exact_only = 0, .scalar = 0, .paxis = 0 }

/* A closed arc [lo, hi] of a circle, angles in radians measured
 * counter-clockwise from +x. */
typedef struct sph_arc {
  double lo, hi;
} sph_arc;

/* What one disc covers of a circle (sph_freesurface_disc). */
enum { SPH_DISC_NONE = 0, SPH_DISC_ARC = 1, SPH_DISC_FULL = 2 };

/* The part of the circle of radius ri centred at the origin covered by the
 * closed disc of radius rj centred at (dx, dy) = r_j - r_i, by the rules
 * above. Returns SPH_DISC_NONE, SPH_DISC_FULL, or SPH_DISC_ARC with *arc
 * set (-2 pi <= lo <= hi <= 2 pi, hi - lo <= 2 pi). ri, rj > 0 and finite.
 * *arc is left untouched by the other results. */
int sph_freesurface_disc(double dx, double dy, double ri, double rj, sph_arc *arc);

/* Returns 1 if the union of the n closed arcs covers the whole circle (gaps
 * of at most SPH_FREESURFACE_GAP_TOL close), else 0; n = 0 gives 0. Each
 * arc needs -2 pi <= lo <= hi <= lo + 2 pi. The array is normalised
 * (lo moved into [0, 2 pi)) and sorted in place. The answer depends only
 * on the multiset of arcs, not on their order. */
int sph_freesurface_arcs_cover(sph_arc *arcs, size_t n);

/* The two certificates that spare most particles the arc test, for a
 * circle of radius ri centred at the origin and n discs (offsets
 * (dx[k], dy[k]), radii rj[k]); each is only sufficient (0 says nothing).
 * cones_cover: 1 if each of the eight 45-degree cones cut by the axes and
 * the diagonals holds the direction of a disc whose covered arc is at
 * least 90.001 degrees wide (or that contains the circle); then
 * sph_freesurface_arcs_cover of the discs' arcs is 1. point_open: 1 if
 * (px, py), a point of the circle, stands off every disc by a margin;
 * then the arcs leave a gap around it and arcs_cover is 0. Offsets closer
 * than 1e-3 ri, and radii more than a factor 1000 from ri, do not count
 * for cones_cover. */
/* The interior certificate as detection runs it for equal radii ri: the
 * candidates cand[0..m-1] of the positions x, y around (xi, yi) (x
 * periodic with period > 0), the bits of the cones held (bit c: cone c,
 * counter-clockwise from +x), 0xFF as soon as all eight are held; four
 * candidates at a time where the processor has AVX2 unless scalar (the
 * same bits; for the tests). */
unsigned sph_freesurface_cones_equal(const double *x, const double *y, const uint32_t *cand,
                                     size_t m, double xi, double yi, double period, double ri,
                                     int scalar);
int sph_freesurface_cones_cover(const double *dx, const double *dy, const double *rj, size_t n,
                                double ri);
int sph_freesurface_point_open(const double *dx, const double *dy, const double *rj, size_t n,
                               double ri, double px, double py);

/* Sets bit SPH_FLAG_FREE_SURFACE of p->flags for every fluid particle on
 * the free surface and clears it for every other particle (walls are never
 * flagged but do cover); other bits are kept. fp NULL means the defaults.
 * g must have been built on p's current positions (sph_grid_build, or
 * sph_grid_build_periodic with fp->period = its px1 - px0), with cells no
 * smaller than 2 * radius_factor * max h (then every pair whose discs can
 * overlap lies in neighbouring cells); a radius factor too large for the
 * cells is refused with an error, not searched by brute force: build the
 * grid with larger cells instead. Runs in parallel over particles (gather
 * form: each writes only its own flag). On success stores the number of
 * flagged particles in *count (if count is not NULL) and returns 0; on
 * error returns -1 with err set, flags unspecified. */
int sph_freesurface_detect(sph_particles *p, const sph_grid *g, const sph_freesurface_params *fp,
                           size_t *count, sph_error *err);

/* The same flags as sph_freesurface_detect, the candidates of each
 * particle taken from its row of the neighbour list l instead of a grid:
 * l must have been built on p in its current storage order and still be
 * complete (sph_nlist_fresh: a list with a skin after moves within it, or
 * any list before the first move) for a support of at least
 * 2 * radius_factor * max h, with the period fp->period. The solver's list
 * is: detection then needs neither a fresh grid nor a sorted store. */
int sph_freesurface_detect_list(sph_particles *p, const sph_nlist *l,
                                const sph_freesurface_params *fp, size_t *count, sph_error *err);

/* The option free_surface.h_factor: k (paper A §7, h* = k h, k = 2 in the
 * paper): h_i = k h0 for fluid particles flagged on the free surface, h0
 * for every other particle. The caller's grid must then have cells of at
 * least 2 k h0 (the kernel support of the enlarged particles); calling it
 * with k = 1 restores the uniform h0 (e.g. before detecting again, if the
 * detection is meant to use the base radius). */
void sph_freesurface_apply_h(sph_particles *p, double h0, double k);

#endif
