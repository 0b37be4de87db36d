/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * figure.c - draws the snapshot panels of figure.h into a layout.
 *
 * Particles: each is a disc of diameter dx * disc_scale (dx, the initial
 * particle spacing, is stored on every snapshot) centred on its position.
 * Discs smaller than 4 pixels grow (unless the user set their size): to
 * sqrt(2) dx below 2 pixels, enough to cover the square cell of a lattice,
 * shrinking linearly to dx at 4 pixels. A lattice finer than 2 pixels
 * (above the image's Nyquist frequency) would otherwise show its gaps as
 * moire beats that no pixel filter removes; covered, it shows the field.
 * Walls are drawn first and fluid on top, each in file (id) order, so the
 * picture is a pure function of the snapshot; particles outside the plot
 * box are skipped and the rest are clipped to it. A value v maps to the
 * colour table at t = (v - lo) / (hi - lo), the same entries the colour bar
 * shows: the bar's row i (top = 0) shows t = 1 - i / (rows - 1) and its
 * ticks sit on the centres of the rows whose t they label.
 * Text, ticks and frames use the foreground colour; their sizes scale with
 * the layout's font scale.
 */
#include "config.h"

#include "figure.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contour.h"
#include "font.h"
#include "interp.h"
#include "marks.h"

void rfigure_time_label(double t, char *buf, size_t size) {
  if (t != 0.0 && fabs(t) < 0.01)
    snprintf(buf, size, "t = %.3g s", t);
  else
    snprintf(buf, size, "t = %.3f s", t);
}

int rfigure_disc_size(const rfigure_style *st, const rsnap *s, double *out, sph_error *err) {
  double d = st->disc_size > 0.0 ? st->disc_size : s->dx;
  if (!(d > 0.0) || !isfinite(d))
    return sph_error_set(err, "%s: no particle spacing (attribute 'dx'); give --disc-size",
                         s->path);
  *out = d * st->disc_scale;
  return 0;
}

double rfigure_growth(double d) {
  if (d <= 2.0) return M_SQRT2;
  if (d >= 4.0) return 1.0;
  return M_SQRT2 + (1.0 - M_SQRT2) * 0.5 * (d - 2.0);
}

void rfigure_color(const rfigure_style *st, double v, uint8_t rgb[3]) {
  double t = st->hi > st->lo ? (v - st->lo) / (st->hi - st->lo) : 0.5;
  rcolormap_map(st->cmap, isnan(v) ? NAN : t, rgb);
}

static rcolor opaque(const uint8_t rgb[3]) { return (rcolor){rgb[0], rgb[1], rgb[2], 255}; }

/* The particles of one kind (walls if walls, else fluid) as discs. */
static void draw_discs(rcanvas *c, const rlayout *L, int k, const rfigure_style *st, const rsnap *s,
                       double r, int walls) {
  const rrect *box = &L->panel[k].plot;
  for (size_t i = 0; i < s->n; i++) {
    if (s->wall[i] != walls || (s->off && !(fabs(s->off[i]) <= s->slab))) continue;
    double px, py;
    rlayout_to_px(L, k, s->x[i], s->y[i], &px, &py);
    if (px + r + 1 < box->x0 || px - r - 1 > box->x1 || py + r + 1 < box->y0 ||
        py - r - 1 > box->y1)
      continue;
    rcolor col = st->wall;
    if (!walls || st->walls == RWALLS_FIELD) {
      uint8_t rgb[3];
      rfigure_color(st, s->val[i], rgb);
      col = opaque(rgb);
    }
    rcanvas_disc(c, px, py, r, col);
  }
}

typedef struct outline_ctx {
  rcanvas *c;
  double x0, y0, per, width; /* the box's corner; grid samples per canvas unit */
  rcolor col;
} outline_ctx;

/* A polyline of the outline from grid to canvas coordinates, drawn as one
 * line (one path in a PDF or SVG). */
static void outline_polyline(void *ctx, const double *xy, size_t n, int closed) {
  const outline_ctx *o = ctx;
  double *q = (double *)xy; /* rcontour_lines' own buffer, free to rewrite */
  for (size_t k = 0; k < n; k++) {
    q[2 * k] = o->x0 + xy[2 * k] / o->per;
    q[2 * k + 1] = o->y0 + xy[2 * k + 1] / o->per;
  }
  rcanvas_polyline(o->c, q, n, closed, o->width, o->col);
}

/* The fluid of panel k as the SPH interpolation of the field at the
 * centres of a grid over the plot box (interp.h), blank outside the fluid,
 * and/or the free surface as a line: the level 1/2 of the kernel sum. The
 * grid has one point per pixel, or for a PDF or SVG st->raster per point
 * (the --dpi of the page): the field as an image at that resolution, the
 * outline traced on it and joined into polylines. */
static int draw_smooth(rcanvas *c, const rlayout *L, int k, const rfigure_style *st, const rsnap *s,
                       sph_error *err) {
  const rrect *box = &L->panel[k].plot;
  const double per = st->raster > 1.0 ? st->raster : 1.0;
  int nx = (int)floor((box->x1 - box->x0) * per + 0.5),
      ny = (int)floor((box->y1 - box->y0) * per + 0.5);
  if (nx < 2 || ny < 2) return 0;
  if (!s->h || !s->vol)
    return sph_error_set(err, "%s: the interpolated view needs the particle volumes", s->path);
  size_t np = (size_t)nx * ny;
  double *f = malloc(np * sizeof *f), *sf = malloc(np * sizeof *sf), *sw = malloc(np * sizeof *sw);
  double *phi = malloc(np * sizeof *phi);
  uint8_t *rgba = malloc(np * 4), *keep = malloc(np);
  int rc = 0;
  if (!f || !sf || !sw || !phi || !rgba || !keep)
    rc = sph_error_set(err, "%s: out of memory for a %dx%d interpolated view", s->path, nx, ny);
  rinterp_in in = {s->n, s->x, s->y, s->h, s->vol, s->val, s->wall, s->kernel, s->off};
  /* the world point of the box's top-left corner (the inverse of rlayout_to_px) */
  double wx0, wy1, cx, cy;
  rlayout_to_px(L, k, 0.0, 0.0, &cx, &cy);
  wx0 = (box->x0 - cx) / L->px_per_m;
  wy1 = (cy - box->y0) / L->px_per_m;
  rinterp_grid g = {nx, ny, wx0, wy1, (box->x1 - box->x0) / nx / L->px_per_m};
  if (!rc) rc = rinterp_field(&in, &g, f, sf, sw, err);
  for (size_t q = 0; !rc && q < np; q++) {
    int fluid = rinterp_is_fluid(sf[q]);
    keep[q] = (uint8_t)(fluid ? 1 : 0) | (uint8_t)(sw[q] >= RINTERP_WALL_NEAR ? 2 : 0);
    phi[q] = sf[q] - 0.5;
    uint8_t rgb[3] = {0, 0, 0};
    if (fluid) rfigure_color(st, f[q], rgb);
    memcpy(rgba + 4 * q, rgb, 3);
    rgba[4 * q + 3] = fluid ? 255 : 0;
  }
  if (!rc && st->smooth) rcanvas_image(c, *box, nx, ny, rgba);
  if (!rc && st->outline) {
    /* 1.5 pixels (the line's rim antialiased); on a page the layout's line, 1 pt at 9 pt text */
    const double lw = per > 1.0 || rlayout_line_width(L) > 1 ? rlayout_line_width(L) : 1.5;
    outline_ctx o = {c, box->x0, box->y0, nx / (box->x1 - box->x0), lw, st->fg};
    if (rcontour_lines(phi, keep, nx, ny, outline_polyline, &o) != 0)
      rc = sph_error_set(err, "%s: out of memory for the outline", s->path);
  }
  free(f);
  free(sf);
  free(sw);
  free(phi);
  free(rgba);
  free(keep);
  return rc;
}

/* Walls, then fluid (as discs, or interpolated), in file (id) order. */
static int draw_particles(rcanvas *c, const rlayout *L, int k, const rfigure_style *st,
                          const rsnap *s, double diameter, sph_error *err) {
  double r = 0.5 * diameter * L->px_per_m;
  if (st->grow_small) r *= rfigure_growth(2.0 * r);
  if (r < 0.5) r = 0.5; /* keep sub-pixel particles visible */
  if (st->walls != RWALLS_NONE) draw_discs(c, L, k, st, s, r, 1);
  if (!st->smooth) draw_discs(c, L, k, st, s, r, 0);
  if (st->smooth || st->outline) return draw_smooth(c, L, k, st, s, err);
  return 0;
}

static void draw_overlays(rcanvas *c, const rlayout *L, int k, const rfigure_style *st,
                          double time) {
  int s = L->scale;
  for (int o = 0; o < st->n_overlays; o++) {
    const roverlay *ov = &st->overlays[o];
    rcolor col = rmark_palette(o + 1); /* vermillion first: stands out on viridis */
    int have_prev = 0;
    double qx = 0.0, qy = 0.0;
    for (size_t i = 0; i < ov->n; i++) {
      int shown = isfinite(ov->x[i]) && isfinite(ov->y[i]) &&
                  (!ov->t || fabs(ov->t[i] - time) <= st->overlay_tol);
      if (!shown) {
        have_prev = 0;
        continue;
      }
      double px, py;
      rlayout_to_px(L, k, ov->x[i], ov->y[i], &px, &py);
      if (ov->line) {
        if (have_prev) rcanvas_line(c, qx, qy, px, py, s > 1 ? s : 1.5, col);
        have_prev = 1;
        qx = px;
        qy = py;
      } else {
        rmark_draw(c, o % RMARK_COUNT, px, py, 2.5 * s, col, st->fg, 1.0);
      }
    }
  }
}

static void draw_legend(rcanvas *c, const rlayout *L, const rfigure_style *st) {
  rlegend_entry e[16];
  int n = 0;
  for (int o = 0; o < st->n_overlays && n < 16; o++) {
    if (!st->overlays[o].label) continue;
    e[n++] = (rlegend_entry){st->overlays[o].label, rmark_palette(o + 1), st->overlays[o].line,
                             st->overlays[o].line ? -1 : o % RMARK_COUNT};
  }
  rlegend_draw(c, L->panel[0].plot, RLEGEND_TOP_RIGHT, e, n, L->scale, st->bg, st->fg);
}

static void draw_axes(rcanvas *c, const rlayout *L, int k, const rfigure_style *st) {
  const rrect *b = &L->panel[k].plot;
  int s = L->scale, lw = rlayout_line_width(L), tick = rlayout_tick_len(L);
  char buf[64];
  rcanvas_border(c, *b, lw, st->fg);
  for (int i = 0; i < L->xt.n; i++) {
    double px, py;
    rlayout_to_px(L, k, L->xt.v[i], L->view[2], &px, &py);
    px = floor(px);
    rcanvas_rect(c, (rrect){px, b->y1 + lw, px + lw, b->y1 + lw + tick}, st->fg);
    rticks_label(&L->xt, L->xt.v[i], buf, sizeof buf);
    rcanvas_text(c, px + 0.5 * lw, b->y1 + lw + tick + 2 * s, buf, s, st->fg, RALIGN_CENTER,
                 RALIGN_TOP, 0);
  }
  for (int i = 0; i < L->yt.n; i++) {
    double px, py;
    rlayout_to_px(L, k, L->view[0], L->yt.v[i], &px, &py);
    py = floor(py);
    rcanvas_rect(c, (rrect){b->x0 - lw - tick, py, b->x0 - lw, py + lw}, st->fg);
    rticks_label(&L->yt, L->yt.v[i], buf, sizeof buf);
    rcanvas_text(c, b->x0 - lw - tick - 2 * s, py + 0.5 * lw, buf, s, st->fg, RALIGN_RIGHT,
                 RALIGN_MIDDLE, 0);
  }
  rcanvas_text(c, 0.5 * (b->x0 + b->x1), b->y1 + lw + tick + 2 * s + 9 * s + 4 * s,
               st->axis_label[0] ? st->axis_label[0] : "x (m)", s, st->fg, RALIGN_CENTER,
               RALIGN_TOP, 0);
  rcanvas_text(c, L->panel[k].cell.x0 + 3 * s, 0.5 * (b->y0 + b->y1),
               st->axis_label[1] ? st->axis_label[1] : "y (m)", s, st->fg, RALIGN_CENTER,
               RALIGN_TOP, 1);
}

static void draw_colorbar(rcanvas *c, const rlayout *L, const rfigure_style *st) {
  const rrect *b = &L->bar;
  int s = L->scale, lw = rlayout_line_width(L), tick = rlayout_tick_len(L);
  int rows = (int)(b->y1 - b->y0);
  if (rows < 1 || b->x1 <= b->x0) return;
  for (int i = 0; i < rows; i++) {
    double t = rows > 1 ? 1.0 - (double)i / (rows - 1) : 1.0;
    uint8_t rgb[3];
    rcolormap_map(st->cmap, t, rgb);
    rcanvas_rect(c, (rrect){b->x0, b->y0 + i, b->x1, b->y0 + i + 1}, opaque(rgb));
  }
  rcanvas_border(c, *b, lw, st->fg);
  double label_w = 0;
  char buf[64];
  for (int i = 0; i < L->bt.n; i++) {
    double v = L->bt.v[i];
    double t = st->hi > st->lo ? (v - st->lo) / (st->hi - st->lo) : 0.5;
    if (t < -1e-9 || t > 1.0 + 1e-9) continue;
    double y = floor(b->y0 + 0.5 + (1.0 - t) * (rows - 1) - 0.5 * lw + 0.5);
    rcanvas_rect(c, (rrect){b->x1 + lw, y, b->x1 + lw + tick, y + lw}, st->fg);
    rticks_label(&L->bt, v, buf, sizeof buf);
    rcanvas_text(c, b->x1 + lw + tick + 2 * s, y + 0.5 * lw, buf, s, st->fg, RALIGN_LEFT,
                 RALIGN_MIDDLE, 0);
    double w = rfont_width(buf, s);
    if (w > label_w) label_w = w;
  }
  if (st->bar_label)
    rcanvas_text(c, b->x1 + lw + tick + 2 * s + label_w + 4 * s, 0.5 * (b->y0 + b->y1),
                 st->bar_label, s, st->fg, RALIGN_CENTER, RALIGN_TOP, 1);
}

int rfigure_draw(rcanvas *c, const rlayout *L, const rfigure_style *st, const rpanel *p, int n,
                 sph_error *err) {
  if (n > L->panels) return sph_error_set(err, "%d snapshots for %d panels", n, L->panels);
  rcanvas_clear(c, st->bg);
  int s = L->scale;
  for (int k = 0; k < n; k++) {
    if (p[k].image) { /* a 3-D view: its image, without axes */
      rcanvas_image(c, L->panel[k].plot, p[k].iw, p[k].ih, p[k].image);
      if (L->bare) continue;
    } else {
      double diameter;
      if (rfigure_disc_size(st, p[k].snap, &diameter, err) != 0) return -1;
      rcanvas_clip(c, &L->panel[k].plot);
      if (draw_particles(c, L, k, st, p[k].snap, diameter, err) != 0) {
        rcanvas_clip(c, NULL);
        return -1;
      }
      draw_overlays(c, L, k, st, p[k].snap->time);
      rcanvas_clip(c, NULL);
      if (L->bare) continue;
      if (!L->no_axes) draw_axes(c, L, k, st);
    }
    const rrect *b = &L->panel[k].plot;
    rcanvas_text(c, b->x0, L->panel[k].label_y, p[k].label, s, st->fg, RALIGN_LEFT, RALIGN_TOP, 0);
    /* the note (the case's name) where it fits beside the label, else none */
    if (p[k].note[0] &&
        rfont_width(p[k].label, s) + 4 * s + rfont_width(p[k].note, s) <= b->x1 - b->x0)
      rcanvas_text(c, b->x1, L->panel[k].label_y, p[k].note, s, st->fg, RALIGN_RIGHT, RALIGN_TOP,
                   0);
  }
  if (!L->bare) {
    draw_legend(c, L, st);
    draw_colorbar(c, L, st);
    if (st->title && L->title.y1 > L->title.y0)
      rcanvas_text(c, 0.5 * L->width, 0.5 * (L->title.y0 + L->title.y1), st->title, s, st->fg,
                   RALIGN_CENTER, RALIGN_MIDDLE, 0);
  }
  return 0;
}
