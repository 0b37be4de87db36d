/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * canvas_cairo.c - the vector canvas of canvas.h: cairo's SVG and PDF
 * surfaces, one pixel of the canvas a point (1/72 in) of the page.
 *
 * Shapes become paths (rectangles, arcs, strokes with butt caps like the
 * raster canvas's lines), text is set with the FreeType face of font.h
 * (cairo embeds the glyphs it uses: as outlines in SVG, as a font subset
 * in PDF), unhinted and with unhinted metrics so widths match font.c's.
 * Clipping is a rectangle, reset on every change.
 *
 * The file is written beside the target (NAME.tmp) and renamed over it
 * when complete, so a failed plot leaves no partial file. To make the
 * bytes depend only on the drawing, the PDF's creation date is fixed
 * (SOURCE_DATE_EPOCH if set, else 2000-01-01) and cairo is asked for no
 * other metadata; SVG carries none.
 */
#include "config.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <cairo-ft.h>
#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>

#include "canvas_impl.h"
#include "font.h"

typedef struct vcanvas {
  struct rcanvas base;
  cairo_surface_t *surface;
  cairo_t *cr;
  cairo_font_face_t *face;
  char *path, *tmp;
} vcanvas;

static void set_color(cairo_t *cr, rcolor col) {
  cairo_set_source_rgba(cr, col.r / 255.0, col.g / 255.0, col.b / 255.0, col.a / 255.0);
}

static void v_destroy(rcanvas *base) {
  vcanvas *c = (vcanvas *)base;
  if (c->cr) cairo_destroy(c->cr);
  if (c->surface) {
    cairo_surface_finish(c->surface);
    cairo_surface_destroy(c->surface);
  }
  if (c->face) cairo_font_face_destroy(c->face);
  if (c->tmp) remove(c->tmp); /* not finished: no partial file */
  free(c->tmp);
  free(c->path);
  free(c);
}

static void v_clear(rcanvas *base, rcolor col) {
  vcanvas *c = (vcanvas *)base;
  cairo_save(c->cr);
  cairo_reset_clip(c->cr);
  set_color(c->cr, (rcolor){col.r, col.g, col.b, 255});
  cairo_paint(c->cr);
  cairo_restore(c->cr);
}

static void v_clip(rcanvas *base, const rrect *r) {
  vcanvas *c = (vcanvas *)base;
  cairo_reset_clip(c->cr);
  if (!r) return;
  cairo_rectangle(c->cr, floor(r->x0 + 0.5), floor(r->y0 + 0.5),
                  floor(r->x1 + 0.5) - floor(r->x0 + 0.5), floor(r->y1 + 0.5) - floor(r->y0 + 0.5));
  cairo_clip(c->cr);
}

static void v_rect(rcanvas *base, rrect r, rcolor col) {
  vcanvas *c = (vcanvas *)base;
  set_color(c->cr, col);
  cairo_rectangle(c->cr, r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0);
  cairo_fill(c->cr);
}

static void v_disc(rcanvas *base, double cx, double cy, double rad, rcolor col) {
  vcanvas *c = (vcanvas *)base;
  set_color(c->cr, col);
  cairo_new_sub_path(c->cr);
  cairo_arc(c->cr, cx, cy, rad, 0.0, 2.0 * M_PI);
  cairo_fill(c->cr);
}

static void v_line(rcanvas *base, double x0, double y0, double x1, double y1, double width,
                   rcolor col) {
  vcanvas *c = (vcanvas *)base;
  set_color(c->cr, col);
  cairo_set_line_width(c->cr, width);
  cairo_set_line_cap(c->cr, CAIRO_LINE_CAP_BUTT);
  cairo_move_to(c->cr, x0, y0);
  cairo_line_to(c->cr, x1, y1);
  cairo_stroke(c->cr);
}

/* One path through the points, round joins (and caps on an open line), so
 * a curve sampled finely reads as a curve at any zoom. */
static void v_polyline(rcanvas *base, const double *xy, size_t n, int closed, double width,
                       rcolor col) {
  vcanvas *c = (vcanvas *)base;
  cairo_save(c->cr);
  set_color(c->cr, col);
  cairo_set_line_width(c->cr, width);
  cairo_set_line_join(c->cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(c->cr, CAIRO_LINE_CAP_ROUND);
  cairo_move_to(c->cr, xy[0], xy[1]);
  for (size_t k = 1; k < n; k++)
    cairo_line_to(c->cr, xy[2 * k], xy[2 * k + 1]);
  if (closed) cairo_close_path(c->cr);
  cairo_stroke(c->cr);
  cairo_restore(c->cr);
}

static void v_triangle(rcanvas *base, const double p[3][2], rcolor col) {
  vcanvas *c = (vcanvas *)base;
  set_color(c->cr, col);
  cairo_move_to(c->cr, p[0][0], p[0][1]);
  cairo_line_to(c->cr, p[1][0], p[1][1]);
  cairo_line_to(c->cr, p[2][0], p[2][1]);
  cairo_close_path(c->cr);
  cairo_fill(c->cr);
}

static void v_image(rcanvas *base, rrect r, int iw, int ih, const uint8_t *rgba) {
  vcanvas *c = (vcanvas *)base;
  cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, iw, ih);
  if (cairo_surface_status(img) != CAIRO_STATUS_SUCCESS) {
    sph_error e;
    sph_error_set(&e, "cairo: no memory for a %dx%d image", iw, ih);
    rcanvas_fail(base, &e);
    cairo_surface_destroy(img);
    return;
  }
  cairo_surface_flush(img);
  unsigned char *d = cairo_image_surface_get_data(img);
  int stride = cairo_image_surface_get_stride(img);
  for (int y = 0; y < ih; y++) { /* premultiplied native-endian ARGB */
    uint32_t *row = (uint32_t *)(d + (size_t)y * stride);
    for (int x = 0; x < iw; x++) {
      const uint8_t *s = rgba + 4 * ((size_t)y * iw + x);
      uint32_t a = s[3];
      uint32_t r8 = (s[0] * a + 127) / 255, g8 = (s[1] * a + 127) / 255,
               b8 = (s[2] * a + 127) / 255;
      row[x] = a << 24 | r8 << 16 | g8 << 8 | b8;
    }
  }
  cairo_surface_mark_dirty(img);
  cairo_save(c->cr);
  cairo_translate(c->cr, r.x0, r.y0);
  cairo_scale(c->cr, (r.x1 - r.x0) / iw, (r.y1 - r.y0) / ih);
  cairo_set_source_surface(c->cr, img, 0, 0);
  cairo_pattern_set_filter(cairo_get_source(c->cr), CAIRO_FILTER_NEAREST);
  cairo_rectangle(c->cr, 0, 0, iw, ih);
  cairo_fill(c->cr);
  cairo_restore(c->cr);
  cairo_surface_destroy(img);
}

static void v_text(rcanvas *base, double x, double y, const char *s, int scale, rcolor col,
                   int vertical) {
  vcanvas *c = (vcanvas *)base;
  cairo_save(c->cr);
  cairo_set_font_face(c->cr, c->face);
  cairo_set_font_size(c->cr, rfont_em(scale));
  cairo_font_options_t *fo = cairo_font_options_create();
  cairo_font_options_set_hint_style(fo, CAIRO_HINT_STYLE_NONE);
  cairo_font_options_set_hint_metrics(fo, CAIRO_HINT_METRICS_OFF);
  cairo_set_font_options(c->cr, fo);
  cairo_font_options_destroy(fo);
  set_color(c->cr, col);
  cairo_translate(c->cr, x, y);
  if (vertical) cairo_rotate(c->cr, -0.5 * M_PI);
  cairo_move_to(c->cr, 0, 0);
  cairo_show_text(c->cr, s);
  cairo_restore(c->cr);
}

static int v_finish(rcanvas *base, sph_error *err) {
  vcanvas *c = (vcanvas *)base;
  cairo_destroy(c->cr);
  c->cr = NULL;
  cairo_surface_finish(c->surface);
  cairo_status_t st = cairo_surface_status(c->surface);
  cairo_surface_destroy(c->surface);
  c->surface = NULL;
  if (st != CAIRO_STATUS_SUCCESS)
    return sph_error_set(err, "%s: cairo cannot write it: %s", c->path, cairo_status_to_string(st));
  if (rename(c->tmp, c->path) != 0)
    return sph_error_set(err, "%s: cannot rename %s to it: %s", c->path, c->tmp, strerror(errno));
  free(c->tmp);
  c->tmp = NULL;
  return 0;
}

static const rcanvas_ops v_ops = {v_destroy,  v_clear, v_clip, v_rect, v_disc,   v_line,
                                  v_triangle, v_image, v_text, NULL,   v_finish, v_polyline};

/* The PDF's creation date: SOURCE_DATE_EPOCH (reproducible builds) or a
 * fixed date, never the clock. */
static void creation_date(char *buf, size_t size) {
  const char *e = getenv("SOURCE_DATE_EPOCH");
  time_t t = 946684800; /* 2000-01-01T00:00:00Z */
  if (e && *e) {
    char *end;
    long long v = strtoll(e, &end, 10);
    if (*end == '\0' && v >= 0) t = (time_t)v;
  }
  struct tm tm;
  gmtime_r(&t, &tm);
  strftime(buf, size, "%Y-%m-%dT%H:%M:%SZ", &tm);
}

int rcanvas_cairo_create(const char *path, int kind, int width, int height, rcanvas **out,
                         sph_error *err) {
  *out = NULL;
  if (width < 1 || height < 1) return sph_error_set(err, "canvas: bad size %dx%d", width, height);
  if (rfont_init(err) != 0) return -1;
  vcanvas *c = calloc(1, sizeof *c);
  if (!c) return sph_error_set(err, "out of memory");
  c->base.ops = &v_ops;
  c->base.w = width;
  c->base.h = height;
  c->base.samples = 1;
  size_t len = strlen(path) + 8;
  c->path = strdup(path);
  c->tmp = malloc(len);
  if (!c->path || !c->tmp) {
    v_destroy(&c->base);
    return sph_error_set(err, "out of memory");
  }
  snprintf(c->tmp, len, "%s.tmp", path);
  if (kind == 1) {
    c->surface = cairo_svg_surface_create(c->tmp, width, height);
    cairo_svg_surface_restrict_to_version(c->surface, CAIRO_SVG_VERSION_1_1);
  } else {
    c->surface = cairo_pdf_surface_create(c->tmp, width, height);
    char date[32];
    creation_date(date, sizeof date);
    cairo_pdf_surface_set_metadata(c->surface, CAIRO_PDF_METADATA_CREATE_DATE, date);
    cairo_pdf_surface_set_metadata(c->surface, CAIRO_PDF_METADATA_CREATOR, "sph-render");
  }
  if (cairo_surface_status(c->surface) != CAIRO_STATUS_SUCCESS) {
    int rc = sph_error_set(err, "%s: cannot create: %s", c->tmp,
                           cairo_status_to_string(cairo_surface_status(c->surface)));
    v_destroy(&c->base);
    return rc;
  }
  c->cr = cairo_create(c->surface);
  c->face = cairo_ft_font_face_create_for_ft_face(rfont_face(), FT_LOAD_NO_HINTING);
  cairo_ft_font_face_set_synthesize(c->face, 0);
  *out = &c->base;
  return 0;
}
