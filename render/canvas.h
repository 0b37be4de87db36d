/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * canvas.h - a 2-D drawing surface of width x height pixels: rectangles,
 * discs, lines, triangles, images and text, in pixel coordinates with the
 * origin at the top-left corner and y down (the order of PNG rows).
 *
 * Two kinds: a raster canvas on an OpenGL framebuffer object (canvas_gl.c;
 * read back as RGB for a PNG) and a vector canvas that cairo writes as an
 * SVG or PDF file (canvas_cairo.c). Drawing code does not know which it has.
 *
 * Primitives are drawn in the order they were issued, with source-over
 * blending: later shapes cover earlier ones. The raster canvas draws every
 * pixel as the mean of samples x samples sub-pixels (supersampling: edges
 * and small discs are anti-aliased and a lattice of sub-pixel particles
 * does not beat into moire), and a colour with alpha 255 in the interior
 * of a shape is stored exactly (no rounding).
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

enum { RCANVAS_MAX_SAMPLES = 4, RCANVAS_DEFAULT_SAMPLES = 3 };

/* A raster canvas: the framebuffer (samples x samples sub-pixels per
 * pixel, 1 to RCANVAS_MAX_SAMPLES; fewer where the driver's size limit or
 * a 1 GiB bound on the framebuffer leaves no room), the shaders and the
 * vertex buffers in the current context of gl. Fails (naming the limit)
 * if the size itself exceeds the driver's. */
int rcanvas_create(const rgl *gl, int width, int height, int samples, rcanvas **out,
                   sph_error *err);
/* The vector format a file name asks for: 1 for .svg, 2 for .pdf (any
 * case), 0 for anything else. */
int rcanvas_vector_kind(const char *path);
/* A vector canvas writing path (.svg or .pdf, see rcanvas_vector_kind);
 * width x height pixels are points of the page (1/72 in). */
int rcanvas_create_vector(const char *path, int width, int height, rcanvas **out, sph_error *err);
/* Completes a vector canvas's file (atomically: written beside it and
 * renamed). */
int rcanvas_finish(rcanvas *c, sph_error *err);
void rcanvas_destroy(rcanvas *c);
/* The sub-pixels per pixel and axis of a raster canvas (1 for vector). */
int rcanvas_samples(const rcanvas *c);
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
/* A line through n points (x, y pairs; closed: back to the first): one
 * path on a vector canvas, its segments one by one on a raster one. */
void rcanvas_polyline(rcanvas *c, const double *xy, size_t n, int closed, double width, rcolor col);
void rcanvas_triangle(rcanvas *c, double x0, double y0, double x1, double y1, double x2, double y2,
                      rcolor col);
/* An image of iw x ih RGBA pixels (top row first, straight alpha) drawn
 * over r, each pixel a flat rectangle (no filtering between them). */
void rcanvas_image(rcanvas *c, rrect r, int iw, int ih, const uint8_t *rgba);
/* Draws UTF-8 text s with the font of font.h at font scale `scale`.
 * (x, y) is the anchor; halign picks which end or the middle of the text
 * sits on it, valign the top, middle or bottom of the capital letters.
 * vertical rotates the text a quarter turn counter-clockwise (reading
 * upwards); alignment then applies in the rotated frame. */
void rcanvas_text(rcanvas *c, double x, double y, const char *s, int scale, rcolor col, int halign,
                  int valign, int vertical);

/* Raster canvas: draws everything pending, waits for the driver
 * (glFinish) and copies the image into rgb (width * height * 3 bytes, top
 * row first), each pixel the rounded mean of its sub-pixels. An error on a
 * vector canvas. */
int rcanvas_read_rgb(rcanvas *c, uint8_t *rgb, sph_error *err);

#endif
