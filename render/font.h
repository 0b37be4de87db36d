/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * font.h - text through FreeType with one TrueType font: DejaVu Sans from
 * Debian's fonts-dejavu-core unless configure's SPH_FONT_FILE or the
 * environment's SPH_RENDER_FONT names another.
 *
 * Text sizes are an integer font scale s, as in the layout's margins: the
 * capital letters are RFONT_CAP * s pixels tall (the em is set so), the
 * descenders reach about 2 s below the baseline, and a line of text takes
 * RFONT_ROWS * s pixels. Widths come from the font's unhinted advances,
 * so the same string has the same width in a PNG (rasterised here) and in
 * an SVG or PDF (drawn by cairo from the same face).
 *
 * The face is loaded once per process (rfont_init); a process that draws
 * text without it gets a box-width estimate and rfont_init's error.
 */
#ifndef SPH_RENDER_FONT_H
#define SPH_RENDER_FONT_H

#include <stddef.h>
#include <stdint.h>

#include "core/error.h"

enum {
  RFONT_CAP = 7, /* cap height in units of the font scale */
  RFONT_ROWS = 9 /* a text line: cap height plus descenders */
};

/* Loads the font (once; later calls return the first result). An error
 * names the file and the package that provides it. */
int rfont_init(sph_error *err);
/* The font file in use (after rfont_init). */
const char *rfont_path(void);
/* The FreeType face (an FT_Face) for cairo; NULL before rfont_init. */
void *rfont_face(void);
/* The em size in pixels for font scale s times a factor (supersampling). */
double rfont_em(double s);
/* Width in pixels of UTF-8 text s at font scale `scale` (rounded up). */
int rfont_width(const char *s, int scale);

/* A string's coverage bitmap: w x h bytes (0 transparent .. 255 ink), top
 * row first; the pen starts at column ox and the baseline is row oy. */
typedef struct rfont_bitmap {
  int w, h;
  int ox, oy;
  uint8_t *a;
} rfont_bitmap;

/* Rasterises UTF-8 text s at em size em (pixels), anti-aliased, the pen
 * starting at the fractional x offset frac (0 <= frac < 1) of a pixel. */
int rfont_raster(const char *s, double em, double frac, rfont_bitmap *out, sph_error *err);
void rfont_bitmap_free(rfont_bitmap *b);

/* The next code point of UTF-8 text at *p (advancing *p); invalid bytes
 * give U+FFFD. */
uint32_t rfont_utf8_next(const char **p);

#endif
