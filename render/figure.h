/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * figure.h - draws snapshot panels on a canvas: particles as discs coloured
 * through a colour map (or the field interpolated on the pixels, with the
 * free surface as a line), walls in grey, axes with metre ticks, a label
 * line per panel (time, name), overlays of reference data, and the colour
 * bar.
 */
#ifndef SPH_RENDER_FIGURE_H
#define SPH_RENDER_FIGURE_H

#include <stddef.h>
#include <stdint.h>

#include "canvas.h"
#include "colormap.h"
#include "layout.h"
#include "snapdata.h"

enum { RWALLS_GREY, RWALLS_FIELD, RWALLS_NONE };

/* Reference points or a curve in world coordinates (metres), e.g. a
 * digitised free surface. With t set, a point shows only on panels whose
 * time is within the style's overlay_tol of its time. */
typedef struct roverlay {
  size_t n;
  double *x, *y, *t; /* t may be NULL */
  int line;          /* 1: connect the points; 0: markers */
  const char *label; /* legend text, or NULL */
} roverlay;

typedef struct rfigure_style {
  rcolor bg, fg, wall;
  const rcolormap *cmap;
  double lo, hi;         /* colour range */
  const char *bar_label; /* e.g. "speed (m/s)" */
  double disc_size;      /* disc diameter in metres; 0: each snapshot's dx */
  double disc_scale;     /* multiplies the diameter */
  int grow_small;        /* discs under 4 px grow to cover their cell (figure.c) */
  int walls;             /* RWALLS_* */
  int smooth;            /* the fluid as its SPH interpolation on the pixels (interp.h) */
  int outline;           /* the free surface as a line; both need rsnap_load_volumes */
  double raster;         /* samples of the interpolated field per canvas unit (0 or 1: one per
                            pixel; a PDF or SVG at --dpi: dpi / 72 per point) */
  const roverlay *overlays;
  int n_overlays;
  double overlay_tol;        /* seconds */
  const char *title;         /* NULL: none */
  const char *axis_label[2]; /* NULL: "x (m)", "y (m)" (a 3-D slice names its plane's axes) */
} rfigure_style;

typedef struct rpanel {
  const rsnap *snap;
  const uint8_t *image; /* a 3-D view drawn beforehand (scene3d.h): RGBA of the plot box's
                           pixels, iw x ih, drawn in place of discs and axes; NULL in 2-D */
  int iw, ih;
  char label[160]; /* left of the label line, e.g. "a) t = 0.156 s" */
  char note[160];  /* right of it, e.g. the case name; may be "" */
} rpanel;

/* "t = 0.156 s" */
void rfigure_time_label(double t, char *buf, size_t size);
/* The disc diameter in metres that style gives particles of snapshot s;
 * an error names the file if it has no spacing and none was given. */
int rfigure_disc_size(const rfigure_style *st, const rsnap *s, double *out, sph_error *err);
/* The factor by which a disc of d pixels grows (see figure.c). */
double rfigure_growth(double d);
/* The colour a field value maps to (the test oracle uses this too). */
void rfigure_color(const rfigure_style *st, double v, uint8_t rgb[3]);
/* Clears the canvas and draws n panels (n <= L->panels) with the style. */
int rfigure_draw(rcanvas *c, const rlayout *L, const rfigure_style *st, const rpanel *p, int n,
                 sph_error *err);

#endif
