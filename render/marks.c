/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * marks.c - series colours, marker shapes and the legend (see marks.h).
 *
 * Colours: the palette of M. Okabe and K. Ito ("Color Universal Design",
 * 2008), chosen to stay distinguishable for the common kinds of colour
 * blindness; yellow is left out because it vanishes on white. Markers are
 * drawn as an outline shape with the fill shape on top, so overlapping
 * markers stay separate. The legend sizes itself from its labels and the
 * font scale and sits inside the given area, a small margin from the
 * chosen corner.
 */
#include "config.h"

#include "marks.h"

#include <string.h>

#include "font.h"

static const rcolor palette[] = {
    {0x00, 0x72, 0xb2, 255}, /* blue */
    {0xd5, 0x5e, 0x00, 255}, /* vermillion */
    {0x00, 0x9e, 0x73, 255}, /* bluish green */
    {0xcc, 0x79, 0xa7, 255}, /* reddish purple */
    {0xe6, 0x9f, 0x00, 255}, /* orange */
    {0x56, 0xb4, 0xe9, 255}, /* sky blue */
    {0x00, 0x00, 0x00, 255}, /* black */
};

rcolor rmark_ink(rcolor bg) {
  double luminance = 0.2126 * bg.r + 0.7152 * bg.g + 0.0722 * bg.b; /* Rec. 709 weights */
  return luminance > 128.0 ? (rcolor){26, 26, 26, 255} : (rcolor){235, 235, 235, 255};
}

rcolor rmark_palette(int i) {
  int n = (int)(sizeof palette / sizeof palette[0]);
  return palette[((i % n) + n) % n];
}

static void shape(rcanvas *c, int kind, double x, double y, double r, rcolor col) {
  switch (kind) {
  case RMARK_SQUARE:
    r *= 0.85; /* same visual weight as the circle */
    rcanvas_rect(c, (rrect){x - r, y - r, x + r, y + r}, col);
    break;
  case RMARK_TRIANGLE:
    rcanvas_triangle(c, x, y - 1.15 * r, x + 1.1 * r, y + 0.75 * r, x - 1.1 * r, y + 0.75 * r, col);
    break;
  case RMARK_TRIANGLE_DOWN:
    rcanvas_triangle(c, x, y + 1.15 * r, x - 1.1 * r, y - 0.75 * r, x + 1.1 * r, y - 0.75 * r, col);
    break;
  case RMARK_DIAMOND:
    r *= 1.2;
    rcanvas_triangle(c, x, y - r, x + r, y, x, y + r, col);
    rcanvas_triangle(c, x, y - r, x, y + r, x - r, y, col);
    break;
  default: rcanvas_disc(c, x, y, r, col); break;
  }
}

void rmark_draw(rcanvas *c, int kind, double x, double y, double size, rcolor fill, rcolor edge,
                double edge_w) {
  double grow = kind == RMARK_TRIANGLE || kind == RMARK_TRIANGLE_DOWN ? 2.0 * edge_w : edge_w;
  if (edge_w > 0.0) shape(c, kind, x, y, size + grow, edge);
  shape(c, kind, x, y, size, fill);
}

int rlegend_corner(const char *name) {
  static const char *names[] = {"top-left", "top-right", "bottom-left", "bottom-right", "none"};
  for (int i = 0; i < 5; i++)
    if (strcmp(name, names[i]) == 0) return i;
  return -1;
}

void rlegend_draw(rcanvas *c, rrect area, int corner, const rlegend_entry *e, int n, int s,
                  rcolor bg, rcolor fg) {
  if (corner == RLEGEND_NONE || n <= 0) return;
  int text_w = 0;
  for (int i = 0; i < n; i++) {
    int w = rfont_width(e[i].label, s);
    if (w > text_w) text_w = w;
  }
  double pad = 4 * s, sample = 18 * s, row = 12 * s;
  double w = pad + sample + 4 * s + text_w + pad, h = pad + n * row + pad - 3 * s;
  double margin = 6 * s;
  double x0 = (corner == RLEGEND_TOP_LEFT || corner == RLEGEND_BOTTOM_LEFT) ? area.x0 + margin
                                                                            : area.x1 - margin - w;
  double y0 = (corner == RLEGEND_TOP_LEFT || corner == RLEGEND_TOP_RIGHT) ? area.y0 + margin
                                                                          : area.y1 - margin - h;
  rrect box = {x0, y0, x0 + w, y0 + h};
  rcanvas_rect(c, box, bg);
  rcanvas_border(c, box, 1.0, fg);
  for (int i = 0; i < n; i++) {
    double cy = y0 + pad + i * row + 3.5 * s;
    double sx0 = x0 + pad, sx1 = sx0 + sample;
    if (e[i].line) rcanvas_line(c, sx0, cy, sx1, cy, s > 1 ? s : 1.5, e[i].color);
    if (e[i].marker >= 0)
      rmark_draw(c, e[i].marker, 0.5 * (sx0 + sx1), cy, 2.5 * s, e[i].color, fg, 1.0);
    rcanvas_text(c, sx1 + 4 * s, cy, e[i].label, s, fg, RALIGN_LEFT, RALIGN_MIDDLE, 0);
  }
}
