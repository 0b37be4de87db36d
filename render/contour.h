/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * contour.h - the level line phi = 0 of a function sampled on a grid, as
 * straight segments (marching squares), for the free-surface outline.
 */
#ifndef SPH_RENDER_CONTOUR_H
#define SPH_RENDER_CONTOUR_H

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

#endif
