/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * slice.h - a plane through a 3-D snapshot (--slice y=0.5[,0.02]), drawn
 * as a 2-D snapshot is: the plane's two axes become the picture's (a
 * slice across y shows x to the right and z up; across x, y and z; across
 * z, x and y), and every 2-D view works on it.
 *
 * Discs show the particles of the slab within half the thickness of the
 * plane (default: one particle spacing thick). The interpolated view and
 * the outline are the 3-D SPH interpolation on the plane itself: the
 * slice keeps every particle within its support 2h of the plane with its
 * distance from it (rsnap.off), and interp.h sums them with the 3-D
 * kernel, so the outline is the cut of the 3-D free surface (surface.h)
 * by the plane.
 */
#ifndef SPH_RENDER_SLICE_H
#define SPH_RENDER_SLICE_H

#include "core/error.h"
#include "snapdata.h"

typedef struct rslice {
  int axis;         /* 0 x, 1 y, 2 z: the plane is axis = pos */
  double pos;       /* m */
  double thickness; /* m; 0: the snapshot's dx */
} rslice;

/* Parses "AXIS=POS" or "AXIS=POS,THICKNESS" (AXIS x, y or z; metres). */
int rslice_parse(const char *text, rslice *sl, sph_error *err);

/* The picture's horizontal (which 0) or vertical (1) axis of a slice
 * across axis: 0, 1 or 2. */
int rslice_axis(int axis, int which);

/* Turns a loaded 3-D snapshot (with its volumes if it is to be
 * interpolated) into the plane's 2-D picture: x and y become the plane's
 * axes, off each kept particle's distance from the plane, view the tank's
 * section (its box), slab half the thickness. */
int rslice_apply(const rslice *sl, rsnap *s, sph_error *err);

#endif
