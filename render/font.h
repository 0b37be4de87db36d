/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * font.h - the built-in bitmap font: 5x7 glyphs (cap height 7, two rows of
 * descender) for printable ASCII, so no font file is needed.
 *
 * A glyph is RFONT_ROWS row masks; bit (RFONT_COLS - 1 - c) is column c,
 * counted from the left. Text advances RFONT_ADVANCE columns per character.
 * All sizes scale by an integer factor when drawn.
 */
#ifndef SPH_RENDER_FONT_H
#define SPH_RENDER_FONT_H

#include <stdint.h>

enum {
  RFONT_COLS = 5,   /* glyph width */
  RFONT_CAP = 7,    /* rows above the baseline */
  RFONT_ROWS = 9,   /* rows including the descender */
  RFONT_ADVANCE = 6 /* glyph width plus one column of spacing */
};

/* The rows of byte c; a character outside printable ASCII gives a box. */
void rfont_glyph(unsigned char c, uint8_t rows[RFONT_ROWS]);
/* Width in pixels of s drawn at the given scale (no trailing spacing). */
int rfont_width(const char *s, int scale);
/* 0 if the glyph table is well formed (see font.c), -1 otherwise. */
int rfont_check(void);

#endif
