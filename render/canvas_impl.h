/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * canvas_impl.h - what the two kinds of canvas (canvas_gl.c, raster;
 * canvas_cairo.c, vector) provide to the dispatch in canvas.c. Private to
 * those three files.
 */
#ifndef SPH_RENDER_CANVAS_IMPL_H
#define SPH_RENDER_CANVAS_IMPL_H

#include "canvas.h"

typedef struct rcanvas_ops {
  void (*destroy)(rcanvas *c);
  void (*clear)(rcanvas *c, rcolor col);
  void (*clip)(rcanvas *c, const rrect *r);
  void (*rect)(rcanvas *c, rrect r, rcolor col);
  void (*disc)(rcanvas *c, double cx, double cy, double rad, rcolor col);
  void (*line)(rcanvas *c, double x0, double y0, double x1, double y1, double width, rcolor col);
  void (*triangle)(rcanvas *c, const double p[3][2], rcolor col);
  void (*image)(rcanvas *c, rrect r, int iw, int ih, const uint8_t *rgba);
  /* text whose pen starts at (x, y) on the baseline (vertical: reading
   * upwards from there); alignment already applied */
  void (*text)(rcanvas *c, double x, double y, const char *s, int scale, rcolor col, int vertical);
  int (*read_rgb)(rcanvas *c, uint8_t *rgb, sph_error *err); /* NULL: vector */
  int (*finish)(rcanvas *c, sph_error *err);                 /* NULL: raster */
  /* a polyline as one path; NULL: its segments one by one (rcanvas_polyline) */
  void (*polyline)(rcanvas *c, const double *xy, size_t n, int closed, double width, rcolor col);
} rcanvas_ops;

/* The common head of both kinds. */
struct rcanvas {
  const rcanvas_ops *ops;
  int w, h;
  int samples;   /* sub-pixels per pixel and axis (1 for vector) */
  sph_error err; /* the first drawing error (e.g. no font), reported at the end */
  int failed;
};

int rcanvas_gl_create(const rgl *gl, int width, int height, int samples, rcanvas **out,
                      sph_error *err);
int rcanvas_cairo_create(const char *path, int kind, int width, int height, rcanvas **out,
                         sph_error *err);

/* Records the first drawing error of c. */
void rcanvas_fail(rcanvas *c, const sph_error *err);

#endif
