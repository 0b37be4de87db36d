/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * marks.h - what identifies a data series: a colour from a fixed
 * colour-blind-safe palette, a marker shape, and the legend that names
 * series by showing their mark next to their label.
 */
#ifndef SPH_RENDER_MARKS_H
#define SPH_RENDER_MARKS_H

#include "canvas.h"

enum {
  RMARK_CIRCLE,
  RMARK_SQUARE,
  RMARK_TRIANGLE,
  RMARK_DIAMOND,
  RMARK_TRIANGLE_DOWN,
  RMARK_COUNT
};
enum {
  RLEGEND_TOP_LEFT,
  RLEGEND_TOP_RIGHT,
  RLEGEND_BOTTOM_LEFT,
  RLEGEND_BOTTOM_RIGHT,
  RLEGEND_NONE
};

/* The colour of text, axes and outlines on background bg: near-black on
 * light backgrounds, near-white on dark ones. */
rcolor rmark_ink(rcolor bg);
/* Series colour i (cycles through the palette). */
rcolor rmark_palette(int i);
/* A marker of the given shape and size (half-width in pixels), filled
 * with fill and outlined with edge (edge_w pixels). */
void rmark_draw(rcanvas *c, int shape, double x, double y, double size, rcolor fill, rcolor edge,
                double edge_w);

typedef struct rlegend_entry {
  const char *label;
  rcolor color;
  int line;   /* show a line sample */
  int marker; /* RMARK_* shape, or -1 for none */
} rlegend_entry;

/* Draws a legend box in the given corner of area (RLEGEND_NONE: nothing). */
void rlegend_draw(rcanvas *c, rrect area, int corner, const rlegend_entry *e, int n, int scale,
                  rcolor bg, rcolor fg);
/* Parses "top-left" ... "bottom-right" or "none"; -1 if unknown. */
int rlegend_corner(const char *name);

#endif
