/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * plot.c - renders the plot mode of plot.h.
 *
 * Each series is a CSV file with two column expressions (csv.h: a name or
 * a sum of names), scaled by its factors, e.g. Z = front_x / a against
 * T = t sqrt(2 g / a) for the dam-break front of Martin & Moyce (1952); with
 * `relative` y becomes (y - y0) / |y0|, y0 its first finite value (the
 * relative energy deviation of paper A, eq. 28-30). Axis ranges default to
 * the data widened to nice tick multiples (ticks.c); a logarithmic axis
 * maps log10 of the value, leaves out values <= 0 (a line breaks there as
 * at a missing value) and defaults to whole decades. Lines are drawn in the
 * order given, then points on top, so measurements stay visible over the
 * curves. The margins follow the same font-scale rules as the snapshot
 * figures (layout.c); everything else is fixed by the inputs, so the PNG is
 * deterministic.
 */
#include "config.h"

#include "plot.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "canvas.h"
#include "font.h"
#include "gl_context.h"
#include "inputs.h"
#include "io/csv.h"
#include "label.h"
#include "layout.h"
#include "marks.h"
#include "png_out.h"
#include "ticks.h"

typedef struct series {
  size_t n;
  double *x, *y;
  char label[128];
  char xname[128], yname[128]; /* the column expressions read */
  int points;
} series;

static int load_series(const roptions *o, const rseries_opt *so, series *s, sph_error *err) {
  sph_csv t;
  if (sph_csv_read(so->path, &t, err) != 0) return -1;
  const char *xc = so->xcol ? so->xcol : o->xcol;
  const char *yc = so->ycol ? so->ycol : o->ycol;
  int rc = 0;
  if ((!xc || !yc) && t.ncol < 2)
    rc = sph_error_set(err, "%s: a series needs two columns (or --x and --y)", so->path);
  if (!xc && !rc) xc = t.names[0];
  if (!yc && !rc) yc = t.names[1];
  snprintf(s->xname, sizeof s->xname, "%s", xc ? xc : "x");
  snprintf(s->yname, sizeof s->yname, "%s", yc ? yc : "y");
  s->n = t.nrow;
  s->x = malloc((t.nrow + 1) * sizeof *s->x);
  s->y = malloc((t.nrow + 1) * sizeof *s->y);
  if (!rc && (!s->x || !s->y)) rc = sph_error_set(err, "out of memory");
  if (!rc) rc = sph_csv_eval(&t, xc, s->x, err);
  if (!rc) rc = sph_csv_eval(&t, yc, s->y, err);
  double y0 = NAN;
  for (size_t i = 0; !rc && i < s->n; i++) {
    s->x[i] *= so->xscale;
    s->y[i] *= so->yscale;
    if (isnan(y0) && isfinite(s->y[i])) y0 = s->y[i];
  }
  if (!rc && so->relative) {
    if (!(fabs(y0) > 0.0))
      rc = sph_error_set(err, "%s: --relative needs a non-zero first value of '%s'", so->path, yc);
    for (size_t i = 0; !rc && i < s->n; i++)
      s->y[i] = (s->y[i] - y0) / fabs(y0);
  }
  s->points = so->points;
  if (so->label) {
    snprintf(s->label, sizeof s->label, "%s", so->label);
  } else {
    /* the file's name, or its directory's for the solver's diagnostics.csv */
    char stem[128];
    rinputs_stem(so->path, stem, sizeof stem);
    if (strcmp(stem, "diagnostics") == 0) {
      char dir[1024];
      snprintf(dir, sizeof dir, "%s", so->path);
      char *slash = strrchr(dir, '/');
      if (slash) {
        *slash = '\0';
        rinputs_stem(dir, stem, sizeof stem);
      }
    }
    snprintf(s->label, sizeof s->label, "%s", stem);
  }
  sph_csv_free(&t);
  return rc;
}

/* The range of the finite values of an axis (only the positive ones on a
 * logarithmic axis); 0 when there is none. */
static int data_range(const series *s, int n, int axis, int log, double *lo, double *hi) {
  int any = 0;
  for (int k = 0; k < n; k++)
    for (size_t i = 0; i < s[k].n; i++) {
      double v = axis ? s[k].y[i] : s[k].x[i];
      if (!isfinite(v) || (log && !(v > 0.0))) continue;
      if (!any || v < *lo) *lo = v;
      if (!any || v > *hi) *hi = v;
      any = 1;
    }
  if (!any) {
    *lo = log ? 1.0 : 0.0;
    *hi = log ? 10.0 : 1.0;
  }
  return any;
}

static int label_width(const rticks *t, int s) {
  char buf[64];
  int w = 0;
  for (int i = 0; i < t->n; i++) {
    rticks_label(t, t->v[i], buf, sizeof buf);
    int lw = rfont_width(buf, s);
    if (lw > w) w = lw;
  }
  return w;
}

/* The axes' ranges in plotted coordinates: log10 of the value on a
 * logarithmic axis. */
typedef struct frame {
  rrect box;
  double x0, x1, y0, y1;
  int xlog, ylog;
} frame;

static double axis_value(int log, double v) { return log ? (v > 0.0 ? log10(v) : NAN) : v; }

static double map_x(const frame *f, double x) {
  return f->box.x0 + (axis_value(f->xlog, x) - f->x0) / (f->x1 - f->x0) * (f->box.x1 - f->box.x0);
}
static double map_y(const frame *f, double y) {
  return f->box.y1 - (axis_value(f->ylog, y) - f->y0) / (f->y1 - f->y0) * (f->box.y1 - f->box.y0);
}

/* An axis' range: given, or the data's widened to ticks (decades on a
 * logarithmic axis); in plotted coordinates. */
static void axis_range(const series *s, int n, int axis, int log, int have, const double given[2],
                       double *lo, double *hi) {
  if (have) {
    *lo = given[0];
    *hi = given[1];
  } else {
    data_range(s, n, axis, log, lo, hi);
    if (log)
      rticks_expand_log(lo, hi);
    else
      rticks_expand(lo, hi, 6);
  }
  if (log) {
    *lo = log10(*lo);
    *hi = log10(*hi);
  }
}

static void axis_ticks(int log, double lo, double hi, int target, rticks *t) {
  if (log)
    rticks_make_log(pow(10.0, lo), pow(10.0, hi), target, t);
  else
    rticks_make(lo, hi, target, t);
}

static void draw(rcanvas *c, const roptions *o, const series *s, int n, const char *xlabel,
                 const char *ylabel, int W, int H, int sc) {
  rcolor bg = o->bg;
  rcolor fg = rmark_ink(bg);
  rcolor grid = {(uint8_t)((bg.r * 7 + fg.r) / 8), (uint8_t)((bg.g * 7 + fg.g) / 8),
                 (uint8_t)((bg.b * 7 + fg.b) / 8), 255};
  frame f;
  f.xlog = o->xlog;
  f.ylog = o->ylog;
  axis_range(s, n, 0, f.xlog, o->have_xrange, o->xrange, &f.x0, &f.x1);
  axis_range(s, n, 1, f.ylog, o->have_yrange, o->yrange, &f.y0, &f.y1);
  int tick = 3 * sc, lw = sc > 2 ? sc / 2 : 1;
  double top = o->title ? 16 * sc : 10 * sc;
  double bottom = tick + 2 * sc + 9 * sc + 4 * sc + 9 * sc + 3 * sc;
  rticks xt, yt;
  /* two passes: the y labels' width sets the left margin (as in layout.c) */
  double left = 3 * sc + 9 * sc + 4 * sc + rfont_width("-0.00", sc) + 2 * sc + tick, right = 8 * sc;
  for (int pass = 0; pass < 2; pass++) {
    f.box = (rrect){floor(left), floor(top), floor(W - right), floor(H - bottom)};
    int tx = (int)((f.box.x1 - f.box.x0) / (60.0 * sc)) + 1;
    int ty = (int)((f.box.y1 - f.box.y0) / (40.0 * sc)) + 1;
    axis_ticks(f.xlog, f.x0, f.x1, tx < 2 ? 2 : tx, &xt);
    axis_ticks(f.ylog, f.y0, f.y1, ty < 2 ? 2 : ty, &yt);
    left = 3 * sc + 9 * sc + 4 * sc + label_width(&yt, sc) + 2 * sc + tick;
    double half = 0.5 * label_width(&xt, sc) + sc; /* the last label, centred on the edge */
    right = half > 8 * sc ? half : 8 * sc;
  }
  const rrect *b = &f.box;
  rcanvas_clear(c, bg);
  char buf[64];
  for (int i = 0; i < xt.n; i++) {
    double px = floor(map_x(&f, xt.v[i]));
    rcanvas_rect(c, (rrect){px, b->y0, px + lw, b->y1}, grid);
    rcanvas_rect(c, (rrect){px, b->y1 + lw, px + lw, b->y1 + lw + tick}, fg);
    rticks_label(&xt, xt.v[i], buf, sizeof buf);
    rcanvas_text(c, px + 0.5 * lw, b->y1 + lw + tick + 2 * sc, buf, sc, fg, RALIGN_CENTER,
                 RALIGN_TOP, 0);
  }
  for (int i = 0; i < yt.n; i++) {
    double py = floor(map_y(&f, yt.v[i]));
    rcanvas_rect(c, (rrect){b->x0, py, b->x1, py + lw}, grid);
    rcanvas_rect(c, (rrect){b->x0 - lw - tick, py, b->x0 - lw, py + lw}, fg);
    rticks_label(&yt, yt.v[i], buf, sizeof buf);
    rcanvas_text(c, b->x0 - lw - tick - 2 * sc, py + 0.5 * lw, buf, sc, fg, RALIGN_RIGHT,
                 RALIGN_MIDDLE, 0);
  }
  rcanvas_clip(c, b);
  double width = sc > 1 ? sc : 1.5;
  for (int pass = 0; pass < 2; pass++) { /* lines, then points */
    for (int k = 0; k < n; k++) {
      if (s[k].points != pass) continue;
      int have = 0;
      double qx = 0.0, qy = 0.0;
      for (size_t i = 0; i < s[k].n; i++) {
        double px = map_x(&f, s[k].x[i]), py = map_y(&f, s[k].y[i]);
        if (!isfinite(px) || !isfinite(py)) { /* missing, or <= 0 on a log axis */
          have = 0;
          continue;
        }
        if (s[k].points) {
          rmark_draw(c, k % RMARK_COUNT, px, py, 2.5 * sc, rmark_palette(k), fg, 1.0);
        } else {
          if (have) rcanvas_line(c, qx, qy, px, py, width, rmark_palette(k));
          have = 1;
          qx = px;
          qy = py;
        }
      }
    }
  }
  rcanvas_clip(c, NULL);
  rcanvas_border(c, *b, lw, fg);
  rcanvas_text(c, 0.5 * (b->x0 + b->x1), b->y1 + lw + tick + 2 * sc + 9 * sc + 4 * sc, xlabel, sc,
               fg, RALIGN_CENTER, RALIGN_TOP, 0);
  rcanvas_text(c, 3 * sc, 0.5 * (b->y0 + b->y1), ylabel, sc, fg, RALIGN_CENTER, RALIGN_TOP, 1);
  if (o->title) rcanvas_text(c, 0.5 * W, 8 * sc, o->title, sc, fg, RALIGN_CENTER, RALIGN_MIDDLE, 0);
  rlegend_entry e[ROPT_MAX_LIST];
  for (int k = 0; k < n; k++)
    e[k] = (rlegend_entry){s[k].label, rmark_palette(k), !s[k].points,
                           s[k].points ? k % RMARK_COUNT : -1};
  rlegend_draw(c, *b, o->legend, e, n, sc, bg, fg);
}

/* Draws the plot on a raster canvas and writes the PNG. */
static int write_png(const roptions *o, const series *s, int n, const char *xlabel,
                     const char *ylabel, int W, int H, int sc, sph_error *err) {
  rgl_context *gl = NULL;
  rcanvas *c = NULL;
  uint8_t *rgb = NULL;
  int rc = rgl_context_create(o->backend, &gl, err);
  if (rc == 0) rc = rcanvas_create(&gl->gl, W, H, o->samples, &c, err);
  if (rc == 0 && !(rgb = malloc((size_t)W * H * 3))) rc = sph_error_set(err, "out of memory");
  if (rc == 0) {
    draw(c, o, s, n, xlabel, ylabel, W, H, sc);
    rc = rcanvas_read_rgb(c, rgb, err);
  }
  if (rc == 0) rc = rpng_write(o->output, rgb, W, H, o->compression, err);
  free(rgb);
  rcanvas_destroy(c);
  rgl_context_destroy(gl);
  return rc;
}

/* Draws the plot on a vector canvas: the SVG or PDF file -o names. */
static int write_vector(const roptions *o, const series *s, int n, const char *xlabel,
                        const char *ylabel, int W, int H, int sc, sph_error *err) {
  rcanvas *c = NULL;
  int rc = rcanvas_create_vector(o->output, W, H, &c, err);
  if (rc == 0) {
    draw(c, o, s, n, xlabel, ylabel, W, H, sc);
    rc = rcanvas_finish(c, err);
  }
  rcanvas_destroy(c);
  return rc;
}

int rplot_run(const roptions *o, sph_error *err) {
  if (o->n_series == 0) return sph_error_set(err, "plot: no CSV file given");
  if (!rinputs_is_png(o->output) && !rcanvas_vector_kind(o->output))
    return sph_error_set(err, "plot: -o must name a .png, .svg or .pdf file, not '%s'", o->output);
  if (rfont_init(err) != 0) return -1;
  if ((o->have_xrange && !(o->xrange[1] > o->xrange[0])) ||
      (o->have_yrange && !(o->yrange[1] > o->yrange[0])))
    return sph_error_set(err, "plot: a range needs min < max");
  if ((o->xlog && o->have_xrange && !(o->xrange[0] > 0.0)) ||
      (o->ylog && o->have_yrange && !(o->yrange[0] > 0.0)))
    return sph_error_set(err, "plot: a logarithmic axis needs a range with min > 0");
  series s[ROPT_MAX_LIST];
  memset(s, 0, sizeof s);
  int rc = 0, n = o->n_series;
  for (int k = 0; k < n && rc == 0; k++)
    rc = load_series(o, &o->series[k], &s[k], err);
  for (int axis = 0; axis < 2 && rc == 0; axis++) {
    double lo, hi;
    if ((axis ? o->ylog : o->xlog) && !data_range(s, n, axis, 1, &lo, &hi))
      rc = sph_error_set(err, "plot: --%slog: no %s value is above 0", axis ? "y" : "x",
                         axis ? "y" : "x");
  }
  const rseries_opt *first = &o->series[0];
  const char *xc = first->xcol ? first->xcol : o->xcol, *yc = first->ycol ? first->ycol : o->ycol;
  char xlabel[256], ylabel[256];
  if (o->xlabel)
    snprintf(xlabel, sizeof xlabel, "%s", o->xlabel);
  else
    rlabel_column(xc ? xc : s[0].xname, first->xscale, 0, xlabel, sizeof xlabel);
  if (o->ylabel)
    snprintf(ylabel, sizeof ylabel, "%s", o->ylabel);
  else
    rlabel_column(yc ? yc : s[0].yname, first->yscale, first->relative, ylabel, sizeof ylabel);
  int W = o->width > 0 ? o->width : 960;
  int H = o->width > 0 && o->height > 0 ? o->height : o->width > 0 ? (W * 2 / 3) & ~1 : 640;
  int sc = o->font_scale;
  if (sc <= 0) sc = rlayout_auto_scale(W, H);
  if (rc == 0 && (W < 64 || H < 64 || W > 16384 || H > 16384))
    rc = sph_error_set(err, "plot: image size %dx%d: each side must be 64 to 16384", W, H);
  if (rc == 0)
    rc = rcanvas_vector_kind(o->output) ? write_vector(o, s, n, xlabel, ylabel, W, H, sc, err)
                                        : write_png(o, s, n, xlabel, ylabel, W, H, sc, err);
  for (int k = 0; k < n; k++) {
    free(s[k].x);
    free(s[k].y);
  }
  return rc;
}
