/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * canvas.h - a 2-D drawing surface of width x height pixels on an OpenGL
 * framebuffer object: rectangles, discs, lines, triangles and bitmap text,
 * in pixel coordinates with the origin at the top-left corner and y down
 * (the order of PNG rows).
 *
 * Primitives are batched and drawn in the order they were issued, with
 * source-over blending: later shapes cover earlier ones. A colour with
 * alpha 255 in the interior of a shape is stored exactly (no rounding).
 */
#ifndef SPH_RENDER_CANVAS_H
#define SPH_RENDER_CANVAS_H

#include <stddef.h>
#include <stdint.h>

#include "core/error.h"
#include "gl_api.h"

typedef struct rcolor {
  uint8_t r, g, b, a;
} rcolor;

typedef struct rrect {
  double x0, y0, x1, y1; /* x0 <= x1, y0 <= y1; pixel edges */
} rrect;

enum { RALIGN_LEFT = 0, RALIGN_CENTER = 1, RALIGN_RIGHT = 2 }; /* along the text */
enum { RALIGN_TOP = 0, RALIGN_MIDDLE = 1, RALIGN_BOTTOM = 2 }; /* across: cap height */

typedef struct rcanvas rcanvas;

/* Creates the framebuffer, the shader and the vertex buffers in the current
 * context of gl. Fails (naming the limit) if the size exceeds the driver's. */
int rcanvas_create(const rgl *gl, int width, int height, rcanvas **out, sph_error *err);
void rcanvas_destroy(rcanvas *c);
int rcanvas_width(const rcanvas *c);
int rcanvas_height(const rcanvas *c);

/* Fills the whole canvas (ignores the clip rectangle). */
void rcanvas_clear(rcanvas *c, rcolor col);
/* Restricts drawing to r (rounded to whole pixels), or lifts it (NULL). */
void rcanvas_clip(rcanvas *c, const rrect *r);

void rcanvas_rect(rcanvas *c, rrect r, rcolor col);
/* A border of the given width just outside r. */
void rcanvas_border(rcanvas *c, rrect r, double width, rcolor col);
/* A disc of radius rad (pixels) with a one-pixel anti-aliased rim. */
void rcanvas_disc(rcanvas *c, double cx, double cy, double rad, rcolor col);
/* A segment of the given width with anti-aliased long edges. */
void rcanvas_line(rcanvas *c, double x0, double y0, double x1, double y1, double width, rcolor col);
void rcanvas_triangle(rcanvas *c, double x0, double y0, double x1, double y1, double x2, double y2,
                      rcolor col);
/* Draws s with the built-in font at an integer scale. (x, y) is the anchor;
 * halign picks which end or the middle of the text sits on it, valign the
 * top, middle or bottom of the capital letters. vertical rotates the text a
 * quarter turn counter-clockwise (reading upwards); alignment then applies
 * in the rotated frame. */
void rcanvas_text(rcanvas *c, double x, double y, const char *s, int scale, rcolor col, int halign,
                  int valign, int vertical);

/* Draws everything pending, waits for the driver (glFinish) and copies the
 * image into rgb (width * height * 3 bytes, top row first). */
int rcanvas_read_rgb(rcanvas *c, uint8_t *rgb, sph_error *err);

#endif
