/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * contour.h - the level line phi = 0 of a function sampled on a grid, as
 * straight segments (marching squares) or the polylines they join into,
 * for the free-surface outline.
 */
#ifndef SPH_RENDER_CONTOUR_H
#define SPH_RENDER_CONTOUR_H

#include <stddef.h>

/* Receives one segment, in grid coordinates: point (i, j) of the grid is
 * at (i + 1/2, j + 1/2). */
typedef void (*rcontour_segment)(void *ctx, double x0, double y0, double x1, double y1);

/* Visits the cells between four neighbouring points row by row and calls
 * seg for each piece of the line phi = 0 in them, its ends placed by
 * linear interpolation along the cell's edges. A NaN counts as negative.
 * keep (may be NULL: every cell) selects cells: a cell is drawn if keep
 * has bit 1 at one of its corners and bit 2 at none. A saddle (corners alternating in sign) is
 * split by the sign of the mean of its four corners. */
void rcontour(const double *phi, const unsigned char *keep, int nx, int ny, rcontour_segment seg,
              void *ctx);

/* Receives one polyline of n points (x, y pairs, grid coordinates);
 * closed: the last point joins the first. */
typedef void (*rcontour_polyline)(void *ctx, const double *xy, size_t n, int closed);
/* The same line as rcontour's segments joined into polylines where they
 * meet (an outline drawn as one path, not as pieces): 0, or -1 when out of
 * memory. rcontour stays as the tests' oracle for it. */
int rcontour_lines(const double *phi, const unsigned char *keep, int nx, int ny,
                   rcontour_polyline line, void *ctx);

#endif
