/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * layout.h - where everything goes in a figure of snapshot panels: a grid
 * of rows x cols panels (one for a single frame), each with a label line,
 * a plot box in world coordinates and its axes, a shared colour bar on the
 * right, and an optional title line. Pure arithmetic on pixel rectangles,
 * so tests can find a particle's pixel or the colour bar's ends.
 *
 * Both axes of a plot box use the same scale (pixels per metre), so discs
 * stay round; the box is the largest that fits its cell, centred in it.
 */
#ifndef SPH_RENDER_LAYOUT_H
#define SPH_RENDER_LAYOUT_H

#include "canvas.h"
#include "core/error.h"
#include "ticks.h"

enum { RLAYOUT_MAX_PANELS = 64, RLAYOUT_MAX_SIZE = 16384 };

typedef struct rlayout_in {
  int width, height; /* pixels; height 0: from the view's aspect ratio */
  int rows, cols;
  double view[4]; /* x0, x1, y0, y1 of the world window */
  int scale;      /* font scale, 0: automatic */
  int bare;       /* nothing but the particles: no margins, axes, labels, bar */
  int no_axes;    /* no axes (a 3-D view): the label line, the bar and thin margins */
  int colorbar;   /* reserve room for the colour bar (ignored if bare) */
  int title;      /* reserve a title line (ignored if bare) */
  double lo, hi;  /* colour range, for the colour bar's tick labels */
} rlayout_in;

typedef struct rpanel_box {
  rrect cell;     /* the panel's share of the image */
  rrect plot;     /* the world window's pixels (edges on whole pixels) */
  double label_y; /* top of the label line's text */
} rpanel_box;

typedef struct rlayout {
  int width, height, scale, rows, cols, bare, no_axes;
  double view[4];
  double px_per_m;   /* pixels per metre, both axes */
  rrect title;       /* empty if none */
  rrect bar;         /* empty if none */
  rticks xt, yt, bt; /* x axis, y axis and colour bar ticks */
  int panels;
  rpanel_box panel[RLAYOUT_MAX_PANELS];
} rlayout;

/* Computes the layout; errors for a bad size, grid or view. */
int rlayout_figure(const rlayout_in *in, rlayout *out, sph_error *err);
/* World point -> pixel (centre) of panel k. */
void rlayout_to_px(const rlayout *L, int k, double wx, double wy, double *px, double *py);
/* The font scale for an image of about width x height pixels, sized for
 * the image as it is looked at (shrunk to fit a screen or a page). */
int rlayout_auto_scale(double width, double height);
/* Sizes in pixels derived from the font scale. */
int rlayout_tick_len(const rlayout *L);
/* The tick labels of the layout's axes and colour bar, as
 * "x ticks [0, 1, 2], y ticks [0.0, 0.1], colour bar ticks [0, 0.5, 1]"
 * (empty brackets for what the figure does not have), for -v. */
void rlayout_describe_ticks(const rlayout *L, char *buf, size_t size);
int rlayout_line_width(const rlayout *L);

#endif
