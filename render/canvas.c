/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * canvas.c - the calls of canvas.h, passed to the kind of canvas at hand
 * (canvas_impl.h), and what both kinds share: borders as four rectangles
 * and the placement of text by its anchor.
 *
 * Text placement: the text's box in its own frame has u along the text
 * and v down the glyphs; the pen starts at u0 = -w/2 * halign (w the
 * advance width of font.h), the capitals' top at v0 = -cap/2 * valign, and
 * the baseline is at v0 + cap. Horizontal text maps (u, v) to (x + u,
 * y + v); vertical text (a quarter turn counter-clockwise) to (x + v,
 * y - u).
 */
#include "config.h"

#include "canvas.h"

#include <ctype.h>
#include <string.h>

#include "canvas_impl.h"
#include "font.h"

int rcanvas_create(const rgl *gl, int width, int height, int samples, rcanvas **out,
                   sph_error *err) {
  if (samples < 1 || samples > RCANVAS_MAX_SAMPLES)
    return sph_error_set(err, "canvas: %d samples per axis (1 to %d)", samples,
                         RCANVAS_MAX_SAMPLES);
  return rcanvas_gl_create(gl, width, height, samples, out, err);
}

/* Whether path ends in ext, ignoring case. */
static int ends_with(const char *path, const char *ext) {
  size_t n = strlen(path), k = strlen(ext);
  if (n < k) return 0;
  for (size_t i = 0; i < k; i++)
    if (tolower((unsigned char)path[n - k + i]) != ext[i]) return 0;
  return 1;
}

int rcanvas_vector_kind(const char *path) {
  return ends_with(path, ".svg") ? 1 : ends_with(path, ".pdf") ? 2 : 0;
}

int rcanvas_create_vector(const char *path, int width, int height, rcanvas **out, sph_error *err) {
  int kind = rcanvas_vector_kind(path);
  if (!kind) return sph_error_set(err, "%s: a vector image is .svg or .pdf", path);
  return rcanvas_cairo_create(path, kind, width, height, out, err);
}

int rcanvas_finish(rcanvas *c, sph_error *err) {
  if (c->failed) {
    *err = c->err;
    return -1;
  }
  if (!c->ops->finish) return 0;
  return c->ops->finish(c, err);
}

void rcanvas_destroy(rcanvas *c) {
  if (c) c->ops->destroy(c);
}

int rcanvas_width(const rcanvas *c) { return c->w; }
int rcanvas_height(const rcanvas *c) { return c->h; }
int rcanvas_samples(const rcanvas *c) { return c->samples; }

void rcanvas_fail(rcanvas *c, const sph_error *err) {
  if (c->failed) return;
  c->failed = 1;
  c->err = *err;
}

void rcanvas_clear(rcanvas *c, rcolor col) { c->ops->clear(c, col); }
void rcanvas_clip(rcanvas *c, const rrect *r) { c->ops->clip(c, r); }

void rcanvas_rect(rcanvas *c, rrect r, rcolor col) {
  if (r.x1 <= r.x0 || r.y1 <= r.y0) return;
  c->ops->rect(c, r, col);
}

void rcanvas_border(rcanvas *c, rrect r, double w, rcolor col) {
  rcanvas_rect(c, (rrect){r.x0 - w, r.y0 - w, r.x1 + w, r.y0}, col);
  rcanvas_rect(c, (rrect){r.x0 - w, r.y1, r.x1 + w, r.y1 + w}, col);
  rcanvas_rect(c, (rrect){r.x0 - w, r.y0, r.x0, r.y1}, col);
  rcanvas_rect(c, (rrect){r.x1, r.y0, r.x1 + w, r.y1}, col);
}

void rcanvas_disc(rcanvas *c, double cx, double cy, double rad, rcolor col) {
  if (rad > 0.0) c->ops->disc(c, cx, cy, rad, col);
}

void rcanvas_line(rcanvas *c, double x0, double y0, double x1, double y1, double width,
                  rcolor col) {
  if (x0 == x1 && y0 == y1) return;
  c->ops->line(c, x0, y0, x1, y1, width, col);
}

void rcanvas_polyline(rcanvas *c, const double *xy, size_t n, int closed, double width,
                      rcolor col) {
  if (n < 2) return;
  if (c->ops->polyline) {
    c->ops->polyline(c, xy, n, closed, width, col);
    return;
  }
  for (size_t k = 0; k + 1 < n; k++)
    rcanvas_line(c, xy[2 * k], xy[2 * k + 1], xy[2 * k + 2], xy[2 * k + 3], width, col);
  if (closed) rcanvas_line(c, xy[2 * n - 2], xy[2 * n - 1], xy[0], xy[1], width, col);
}

void rcanvas_triangle(rcanvas *c, double x0, double y0, double x1, double y1, double x2, double y2,
                      rcolor col) {
  const double p[3][2] = {{x0, y0}, {x1, y1}, {x2, y2}};
  c->ops->triangle(c, p, col);
}

void rcanvas_image(rcanvas *c, rrect r, int iw, int ih, const uint8_t *rgba) {
  if (iw < 1 || ih < 1 || r.x1 <= r.x0 || r.y1 <= r.y0) return;
  c->ops->image(c, r, iw, ih, rgba);
}

void rcanvas_text(rcanvas *c, double x, double y, const char *s, int scale, rcolor col, int halign,
                  int valign, int vertical) {
  if (!s[0]) return;
  sph_error err;
  if (rfont_init(&err) != 0) {
    rcanvas_fail(c, &err);
    return;
  }
  if (scale < 1) scale = 1;
  double u0 = -0.5 * rfont_width(s, scale) * halign;
  double base = RFONT_CAP * scale * (1.0 - 0.5 * valign); /* v of the baseline */
  if (vertical)
    c->ops->text(c, x + base, y - u0, s, scale, col, 1);
  else
    c->ops->text(c, x + u0, y + base, s, scale, col, 0);
}

int rcanvas_read_rgb(rcanvas *c, uint8_t *rgb, sph_error *err) {
  if (c->failed) {
    *err = c->err;
    return -1;
  }
  if (!c->ops->read_rgb) return sph_error_set(err, "canvas: a vector canvas has no pixels");
  return c->ops->read_rgb(c, rgb, err);
}
