/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * sphere_cover.h - the 3-D free-surface test: whether a particle's sphere
 * is covered by its neighbours' balls (paper A §7's covering test, after
 * Dilts, one dimension up; Haque and Dilts 2007 give the 3-D form).
 *
 * Particle i is a sphere of radius R_i; neighbour j a closed ball of
 * radius R_j at offset r_j - r_i, distance d. The ball covers a closed cap
 * of the sphere, by the 2-D rules (freesurface.h) with the circle read as
 * the sphere: nothing if d >= R_i + R_j or R_i >= d + R_j (outside, tangent,
 * or inside the sphere: a duplicate carries no direction), the whole sphere
 * if R_j >= d + R_i, else the cap of unit-sphere points v with v . u >= c,
 * u = (r_j - r_i) / d and c = cos a = (R_i^2 + d^2 - R_j^2) / (2 R_i d).
 *
 * The exact test. The caps cover the sphere iff, for every cap j, the
 * other caps cover its boundary circle C_j: if some point of C_j lies in
 * no other (closed) cap, the points just outside cap j beside it lie in
 * none, so the sphere is not covered; and if the sphere is not covered,
 * the uncovered region (open, not the whole sphere when there is a cap) is
 * bounded by arcs of cap circles whose inner points lie in no other cap.
 * So each C_j is tested as a circle covered by arcs (one closed arc per
 * other cap, its angle around u_j), with the 2-D sweep
 * (sph_freesurface_arcs_cover: gaps of at most SPH_FREESURFACE_GAP_TOL
 * close). No cap at all: not covered. Two caps with the same axis and
 * cosine (coincident neighbours of equal radius) count once: neither
 * covers the other's circle.
 *
 * Two certificates spare most particles the O(n^2) exact test, each only
 * sufficient and each giving the exact test's answer:
 * - interior: every one of the 26 directions of the cube's faces, edges
 *   and corners lies within a_j - rho of some cap's axis u_j, with rho =
 *   27.58 degrees, above the 26 directions' covering radius (27.5693
 *   degrees: every unit vector lies within it of one of them); by the
 *   triangle inequality the caps then cover the sphere with a margin;
 * - surface: the point of the sphere opposite the sum of the offsets
 *   stands off every ball by a margin (as in 2-D): the uncovered region
 *   around it holds a disc, and its boundary arcs are far longer than the
 *   sweep's tolerance.
 */
#ifndef SPH_SPHERE_COVER_H
#define SPH_SPHERE_COVER_H

#include <stddef.h>

#include "physics/freesurface.h"

/* A closed cap of the unit sphere: the points v with v . u >= c (u a unit
 * vector, -1 < c < 1 the cosine of its half-angle a, s = sin a). */
typedef struct sph_cap {
  double u[3], c, s;
} sph_cap;

/* What the closed ball of radius rj at offset d (from the centre of the
 * sphere of radius ri) covers of that sphere: SPH_DISC_NONE, SPH_DISC_FULL
 * or SPH_DISC_ARC (a cap, into *cap). ri, rj > 0 and finite. */
int sph_sphere_cap(const double d[3], double ri, double rj, sph_cap *cap);

/* 1 if the n caps cover the whole unit sphere, by the exact test above
 * (arcs: scratch room for n - 1 arcs); n = 0 gives 0. */
int sph_sphere_caps_cover(const sph_cap *caps, size_t n, sph_arc *arcs);

/* The interior certificate: the bits (26 of them, SPH_SPHERE_DIRS_ALL) of
 * the directions that lie within a - rho of the cap's axis; when the caps
 * of a particle together hold all 26, sph_sphere_caps_cover is 1 for them.
 * sph_sphere_dir_near: the bit of the one direction nearest the cap's axis
 * (by its components' signs), if the cap holds it: cheaper, and enough on
 * a lattice and in most disordered interiors. sph_sphere_dirs_cover: 1 if
 * the n caps hold all 26; 0 says nothing. */
#define SPH_SPHERE_DIRS_ALL (((1ul << 27) - 1ul) & ~(1ul << 13))
unsigned long sph_sphere_dirs_held(const sph_cap *cap);
unsigned long sph_sphere_dir_near(const sph_cap *cap);
int sph_sphere_dirs_cover(const sph_cap *caps, size_t n);

/* The surface certificate: 1 if the point q (a point of the sphere of
 * radius ri, as an offset from its centre) stands off each of the n balls
 * (offsets d[3 k ..], radii rj[k]) by the margin (then the caps leave it
 * uncovered); 0 says nothing. */
int sph_sphere_point_open(const double *d, const double *rj, size_t n, double ri,
                          const double q[3]);

#endif
