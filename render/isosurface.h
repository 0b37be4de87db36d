/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * isosurface.h - the level set of a field sampled on a lattice
 * (interp3d.h) as a triangle mesh: marching cubes (Lorensen & Cline
 * 1987), each cube cut into six tetrahedra along its main diagonal (Doi &
 * Koide 1991; references in doc/render.md).
 *
 * A point is inside where its value is >= the level. Every cube of eight
 * lattice points is split the same way (the six tetrahedra 0, e_a,
 * e_a + e_b, e_a + e_b + e_c for the orders (a, b, c) of the axes), so
 * neighbouring cubes cut their common face along the same diagonal and the
 * mesh has no cracks and no ambiguous cases: a level set that does not
 * touch the lattice's faces gives a closed, consistently oriented surface.
 * A tetrahedron with one corner on the other side gives a triangle, one
 * with two on each side a quadrilateral (two triangles). Vertices lie on
 * lattice edges (the cube's edges, its faces' diagonals and its main
 * diagonal) where the linear interpolation between the two ends reaches
 * the level, and are shared by every triangle on that edge. A vertex's
 * normal is minus the field's gradient (central differences at the ends,
 * one-sided on the lattice's faces, interpolated as the position is),
 * normalised: it points out of the inside. Triangles are wound
 * counter-clockwise seen from outside.
 */
#ifndef SPH_RENDER_ISOSURFACE_H
#define SPH_RENDER_ISOSURFACE_H

#include <stddef.h>
#include <stdint.h>

#include "core/error.h"
#include "interp3d.h"

typedef struct rmesh {
  size_t nv, nt;
  float *p;      /* 3 nv: positions (m) */
  float *normal; /* 3 nv: unit outward normals */
  float *val;    /* nv: the second field at the vertices, or NULL */
  uint32_t *tri; /* 3 nt: vertex indices, counter-clockwise from outside */
} rmesh;

/* The level set s = level of the lattice g's values s (rgrid3_points
 * values); if f is not NULL, f interpolated to the vertices as the
 * positions are (where one end of an edge is NaN, the other end's value).
 * Deterministic: vertices and triangles come in lattice order. */
int rmesh_isosurface(const rgrid3 *g, const double *s, const double *f, double level, rmesh *m,
                     sph_error *err);
void rmesh_free(rmesh *m);

/* The volume enclosed (divergence theorem; positive for a closed outward
 * mesh) and the area of a mesh. */
double rmesh_volume(const rmesh *m);
double rmesh_area(const rmesh *m);

#endif
