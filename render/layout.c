/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * layout.c - computes the figure layout of layout.h.
 *
 * All margins are multiples of the font scale s (glyphs are 5s x 7s):
 *   label line above each plot   14s
 *   left margin                  3s + 9s (y label) + 4s + widest y tick label + 2s + tick
 *   bottom margin                tick + 2s + 9s (tick labels) + 4s + 9s (x label) + 3s
 *   right margin                 half the widest x tick label, at least 6s
 *   colour bar column            10s gap + 10s bar + tick + 2s + widest label + 4s + 9s + 4s
 *   title line                   16s
 * Without axes (a 3-D view) the left, right and bottom margins are 3s.
 * The tick labels set the margins but depend on the plot size, which
 * depends on the margins: the layout is recomputed until the label widths
 * (and the colour bar's tick count) stop changing - after the first guess
 * they may only grow, so at most four passes settle it.
 * Plot boxes start and end on whole pixels and the world window maps onto
 * them with one scale for both axes; cells are packed around their plots
 * and the group is centred in the image. With an automatic height the
 * image height is rounded up to an even number (video codecs want even
 * sizes).
 */
#include "config.h"

#include "layout.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "font.h"

static int ticks_width(const rticks *t, int s) {
  int w = 0;
  char buf[64];
  for (int i = 0; i < t->n; i++) {
    rticks_label(t, t->v[i], buf, sizeof buf);
    int lw = rfont_width(buf, s);
    if (lw > w) w = lw;
  }
  return w;
}

/* The ticks of an axis len units long over [lo, hi]: about target of them
 * (rticks_make), and where that leaves fewer than three, finer steps
 * (1-2-5) towards three, as long as their labels stay apart: along x by
 * the widest label and 3s, across (y, the colour bar) by the cap height
 * and 2s, 9s. A journal-size panel (8.5 cm, 7 pt capitals) thus reads its
 * scale off three labels where two or one fitted the coarser target. */
static void axis_ticks(double lo, double hi, double len, int target, int along_x, int s,
                       rticks *t) {
  rticks_make(lo, hi, target < 2 ? 2 : target, t);
  rticks c = *t;
  for (int k = 0; k < 6 && t->n < 3 && hi > lo; k++) {
    rticks_make_step(lo, hi, rticks_finer(c.step), &c);
    const double gap = c.step / (hi - lo) * len;
    if (gap < (along_x ? ticks_width(&c, s) + 3 * s : 9 * s)) break;
    if (c.n > t->n) *t = c;
  }
}

int rlayout_tick_len(const rlayout *L) { return 3 * L->scale; }
int rlayout_line_width(const rlayout *L) { return L->scale > 2 ? L->scale / 2 : 1; }

/* Text sized for the whole image as it will be looked at (shrunk to fit a
 * screen or a page): scale 1 below about 0.55 megapixel, 2 for 1280x720 and
 * figures up to about 1.5 megapixels, 3 for 1920x1080. */
int rlayout_auto_scale(double width, double height) {
  int s = (int)floor(sqrt(width * height) / 500.0 + 0.5);
  return s < 1 ? 1 : s > 8 ? 8 : s;
}

int rlayout_figure(const rlayout_in *in, rlayout *L, sph_error *err) {
  memset(L, 0, sizeof *L);
  if (in->rows < 1 || in->cols < 1 || in->rows * in->cols > RLAYOUT_MAX_PANELS)
    return sph_error_set(err, "panel grid %dx%d: need 1 to %d panels", in->cols, in->rows,
                         RLAYOUT_MAX_PANELS);
  if (in->width < 16 || in->width > RLAYOUT_MAX_SIZE || in->height < 0 ||
      (in->height > 0 && in->height < 16) || in->height > RLAYOUT_MAX_SIZE)
    return sph_error_set(err, "image size %dx%d: each side must be 16 to %d pixels", in->width,
                         in->height, RLAYOUT_MAX_SIZE);
  double vw = in->view[1] - in->view[0], vh = in->view[3] - in->view[2];
  if (!(vw > 0.0) || !(vh > 0.0) || !isfinite(vw) || !isfinite(vh))
    return sph_error_set(err, "view %g:%g:%g:%g: need x0 < x1 and y0 < y1", in->view[0],
                         in->view[1], in->view[2], in->view[3]);
  int s = in->scale > 0
              ? in->scale
              : rlayout_auto_scale(
                    in->width, in->height > 0 ? in->height : 0.6 * in->width * in->rows / in->cols);
  L->scale = s;
  L->rows = in->rows;
  L->cols = in->cols;
  L->bare = in->bare;
  L->no_axes = in->no_axes && !in->bare;
  L->panels = in->rows * in->cols;
  memcpy(L->view, in->view, sizeof L->view);

  int tick = 3 * s;
  int label_h = 0, bottom = 0, left = 0, right = 0, bar_col = 0, title_h = 0;
  if (!in->bare) {
    label_h = 14 * s;
    bottom = L->no_axes ? 3 * s : tick + 2 * s + 9 * s + 4 * s + 9 * s + 3 * s;
    if (in->title) title_h = 16 * s;
  }
  double W = in->width;
  double plot_w = 0.0, plot_h = 0.0, cell_w = 0.0, cell_h = 0.0, H = in->height;
  int yw = rfont_width("-0.00", s), xw = 0, bar_ticks = 5;
  double bar_len = 0.0; /* the colour bar's length, once known (0: the target alone) */
  for (int pass = 0; pass < 4; pass++) {
    if (!in->bare) {
      left = L->no_axes ? 3 * s : 3 * s + 9 * s + 4 * s + yw + 2 * s + tick;
      right = L->no_axes ? 3 * s : xw / 2 > 6 * s ? xw / 2 : 6 * s;
      if (in->colorbar) {
        axis_ticks(in->lo, in->hi, bar_len, bar_ticks, 0, s, &L->bt);
        bar_col = 10 * s + 10 * s + tick + 2 * s + ticks_width(&L->bt, s) + 4 * s + 9 * s + 4 * s;
      }
    }
    cell_w = (W - bar_col) / in->cols;
    double avail_w = cell_w - left - right;
    if (in->height > 0) {
      cell_h = (H - title_h) / in->rows;
    } else {
      cell_h = label_h + avail_w * vh / vw + bottom;
      H = title_h + in->rows * cell_h;
      H = 2.0 * ceil(H / 2.0);
      if (H > RLAYOUT_MAX_SIZE) H = RLAYOUT_MAX_SIZE;
      cell_h = (H - title_h) / in->rows;
    }
    double avail_h = cell_h - label_h - bottom;
    if (avail_w < 8.0 || avail_h < 8.0)
      return sph_error_set(err, "image size %dx%d is too small for %dx%d panels at font scale %d",
                           in->width, (int)H, in->cols, in->rows, s);
    L->px_per_m = fmin(avail_w / vw, avail_h / vh);
    plot_w = fmin(floor(vw * L->px_per_m + 0.5), floor(avail_w));
    plot_h = fmin(floor(vh * L->px_per_m + 0.5), floor(avail_h));
    if (in->bare) break;
    /* the bar spans from the first plot's top to the last one's bottom */
    const double bl = (in->rows - 1) * cell_h + plot_h;
    int nb = (int)(bl / (60.0 * s)) + 1; /* a bar's labels one per 60s, as along x */
    if (nb < 2) nb = 2;
    if (L->no_axes) { /* only the colour bar's ticks, from its height */
      if (nb == bar_ticks && bl == bar_len) break;
      bar_ticks = nb;
      bar_len = bl;
      continue;
    }
    int tx = (int)(plot_w / (60.0 * s)) + 1, ty = (int)(plot_h / (40.0 * s)) + 1;
    axis_ticks(in->view[0], in->view[1], plot_w, tx, 1, s, &L->xt);
    axis_ticks(in->view[2], in->view[3], plot_h, ty, 0, s, &L->yt);
    int ny = ticks_width(&L->yt, s), nx = ticks_width(&L->xt, s);
    if (ny == yw && nx == xw && nb == bar_ticks && bl == bar_len)
      break; /* the margins fit the labels */
    /* after the first guess widths only grow, so the passes settle */
    yw = pass == 0 || ny > yw ? ny : yw;
    xw = pass == 0 || nx > xw ? nx : xw;
    bar_ticks = nb;
    bar_len = bl;
  }
  L->width = in->width;
  L->height = (int)H;
  /* Cells are packed tightly around their plots and the whole group
   * (title, panels, colour bar) is centred in the image, so the axis labels
   * and the bar stay next to the plots whatever the view's aspect. */
  double cw = left + plot_w + right, chh = label_h + plot_h + bottom;
  double ox = floor(0.5 * (W - (in->cols * cw + bar_col)));
  double oy = floor(0.5 * (H - (title_h + in->rows * chh)));
  if (ox < 0) ox = 0;
  if (oy < 0) oy = 0;
  if (title_h) L->title = (rrect){ox, oy, ox + in->cols * cw + bar_col, oy + title_h};
  for (int r = 0; r < in->rows; r++) {
    for (int c = 0; c < in->cols; c++) {
      rpanel_box *p = &L->panel[r * in->cols + c];
      double x0 = ox + c * cw, y0 = oy + title_h + r * chh;
      p->cell = (rrect){x0, y0, x0 + cw, y0 + chh};
      p->plot = (rrect){x0 + left, y0 + label_h, x0 + left + plot_w, y0 + label_h + plot_h};
      p->label_y = y0 + 3 * s;
    }
  }
  if (!in->bare && in->colorbar) {
    const rrect *first = &L->panel[0].plot, *last = &L->panel[L->panels - 1].plot;
    double bx = ox + in->cols * cw + 10 * s;
    L->bar = (rrect){bx, first->y0, bx + 10 * s, last->y1};
  }
  return 0;
}

void rlayout_to_px(const rlayout *L, int k, double wx, double wy, double *px, double *py) {
  const rrect *p = &L->panel[k].plot;
  double cx = 0.5 * (p->x0 + p->x1), cy = 0.5 * (p->y0 + p->y1);
  double wcx = 0.5 * (L->view[0] + L->view[1]), wcy = 0.5 * (L->view[2] + L->view[3]);
  *px = cx + (wx - wcx) * L->px_per_m;
  *py = cy - (wy - wcy) * L->px_per_m;
}

/* "0, 0.5, 1" into buf (at most size bytes). */
static void tick_list(const rticks *t, char *buf, size_t size) {
  size_t used = 0;
  buf[0] = '\0';
  for (int i = 0; i < t->n && used < size; i++) {
    char v[64];
    rticks_label(t, t->v[i], v, sizeof v);
    const int w = snprintf(buf + used, size - used, "%s%s", i ? ", " : "", v);
    if (w < 0) break;
    used += (size_t)w;
  }
}

void rlayout_describe_ticks(const rlayout *L, char *buf, size_t size) {
  char x[512] = "", y[512] = "", b[512] = "";
  if (!L->no_axes && !L->bare) {
    tick_list(&L->xt, x, sizeof x);
    tick_list(&L->yt, y, sizeof y);
  }
  if (L->bar.x1 > L->bar.x0) tick_list(&L->bt, b, sizeof b);
  snprintf(buf, size, "x ticks [%s], y ticks [%s], colour bar ticks [%s]", x, y, b);
}
