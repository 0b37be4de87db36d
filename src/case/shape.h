/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * shape.h - the shapes of fluid blocks (case.h's sph_shape): which lattice
 * points a block keeps, its bounding box, its area or volume, and what
 * makes a polygon unusable. Internal to the library (case/, solver/, cli/).
 */
#ifndef SPH_SHAPE_H
#define SPH_SHAPE_H

#include <stddef.h>

#include "case/case.h"

/* 1 when the point x (SPH_DIM coordinates) is inside the block's shape
 * (strictly, for the box; a polygon by its winding number, nonzero inside:
 * a point on an edge falls on one side by the same arithmetic every run).
 * A 3-D polygon is a prism: x and z are tested, y is the box's. */
int sph_shape_inside(const sph_fluid_block *f, const double *x);
/* The winding number of a shape other than a box around x: 1 inside, 0 outside, and for a mesh
 * any other value where its surface crosses or overlaps itself (a shaped block's fill; a shaped
 * obstacle's, sph_obstacle's `inside`). */
int sph_shape_winding_of(const void *shape, const double *x);
/* A shaped obstacle's wall particle at x: its mirror offset m, twice its distance to the
 * shape's surface out along the surface's outward normal at the closest point (the normal
 * there when x lies on the surface): the walls' way out (sph_obstacle's `offset`). The parts
 * of the surface at or below `floor` (the height of the tank's first particles: a shape
 * standing on the floor) are no way out, as a box's bottom on the floor is not. A prism's
 * offsets point out through its side faces, never its two ends across y. */
void sph_shape_offset_of(const void *shape, const double *x, double floor, double *m);

/* The shape's bounding box along the axes it spans (a 3-D polygon: x and
 * z; lo[1], hi[1] are left as they are). */
void sph_shape_bounds(const sph_shape *s, double lo[SPH_DIM], double hi[SPH_DIM]);

/* 0 when the polygon of n vertices (x, up pairs) is simple: no repeated
 * consecutive vertex, a nonzero area, and no two edges that meet other
 * than adjacent ones at their common vertex. Otherwise -1 and the reason,
 * naming the vertices by index, in why. */
int sph_polygon_defect(const double *v, size_t n, char *why, size_t len);

/* The name of a shape for messages and listings ("box", "polygon",
 * "circle" or "sphere", "cylinder", "mesh"). */
const char *sph_shape_name(sph_shape_kind k);

#endif
