/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * font.c - text metrics and anti-aliased glyph rasters from FreeType (see
 * font.h).
 *
 * Scale: the em is set so that the capital H is RFONT_CAP pixels tall at
 * font scale 1 (DejaVu Sans: H is 0.729 em, so the em is 9.6 s pixels).
 * Advances are taken in font units (FT_LOAD_NO_SCALE) and scaled in double
 * precision, so a width does not depend on the size FreeType was last set
 * to, and a string is laid out with fractional pen positions: each glyph's
 * outline is shifted by the pen's fraction of a pixel (in 1/64 pixel)
 * before it is rendered. Outlines are not hinted (FT_LOAD_NO_HINTING):
 * hinting would move stems to whole pixels and change widths with the
 * size. FreeType's rasteriser computes exact coverage in fixed point, so
 * the bitmap of a string is the same on every run.
 */
#include "config.h"

#include "font.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_OUTLINE_H

static struct {
  int tried, ok;
  FT_Library lib;
  FT_Face face;
  double cap_ratio; /* height of H / em */
  char path[1024];
  sph_error err;
} F;

uint32_t rfont_utf8_next(const char **p) {
  const unsigned char *s = (const unsigned char *)*p;
  uint32_t c = s[0];
  int n = c < 0x80             ? 0
          : (c & 0xE0) == 0xC0 ? 1
          : (c & 0xF0) == 0xE0 ? 2
          : (c & 0xF8) == 0xF0 ? 3
                               : -1;
  if (n < 0) {
    *p += 1;
    return 0xFFFD;
  }
  if (n > 0) c &= 0x3Fu >> n;
  for (int k = 1; k <= n; k++) {
    if ((s[k] & 0xC0) != 0x80) { /* truncated sequence */
      *p += k;
      return 0xFFFD;
    }
    c = c << 6 | (s[k] & 0x3F);
  }
  *p += n + 1;
  return c;
}

int rfont_init(sph_error *err) {
  if (F.tried) {
    if (!F.ok && err) *err = F.err;
    return F.ok ? 0 : -1;
  }
  F.tried = 1;
  const char *env = getenv("SPH_RENDER_FONT");
  snprintf(F.path, sizeof F.path, "%s", env && env[0] ? env : SPH_FONT_FILE);
  if (FT_Init_FreeType(&F.lib) != 0) {
    sph_error_set(&F.err, "cannot start FreeType");
  } else if (FT_New_Face(F.lib, F.path, 0, &F.face) != 0) {
    sph_error_set(&F.err,
                  "cannot load the font %s: install it (apt-get install fonts-dejavu-core) "
                  "or name a TrueType font in SPH_RENDER_FONT",
                  F.path);
  } else if (!FT_IS_SCALABLE(F.face) ||
             FT_Load_Char(F.face, 'H', FT_LOAD_NO_SCALE | FT_LOAD_NO_HINTING) != 0 ||
             F.face->glyph->metrics.height <= 0) {
    sph_error_set(&F.err, "%s: not a scalable font with a capital H", F.path);
  } else {
    F.cap_ratio = (double)F.face->glyph->metrics.height / F.face->units_per_EM;
    F.ok = 1;
  }
  if (!F.ok && err) *err = F.err;
  return F.ok ? 0 : -1;
}

const char *rfont_path(void) { return F.path; }

void *rfont_face(void) { return F.ok ? (void *)F.face : NULL; }

double rfont_em(double s) {
  double ratio = F.ok ? F.cap_ratio : 0.729;
  return RFONT_CAP * s / ratio;
}

/* The advance of code point c in font units; 0 for a missing font. */
static long advance_units(uint32_t c) {
  FT_UInt g = FT_Get_Char_Index(F.face, c);
  if (FT_Load_Glyph(F.face, g, FT_LOAD_NO_SCALE | FT_LOAD_NO_HINTING) != 0) return 0;
  return F.face->glyph->advance.x;
}

/* The unrounded width of s at em size em. */
static double width_em(const char *s, double em) {
  if (rfont_init(NULL) != 0) return 0.62 * em * (double)strlen(s);
  long units = 0;
  for (const char *p = s; *p;)
    units += advance_units(rfont_utf8_next(&p));
  return (double)units * em / F.face->units_per_EM;
}

int rfont_width(const char *s, int scale) { return (int)ceil(width_em(s, rfont_em(scale)) - 1e-9); }

void rfont_bitmap_free(rfont_bitmap *b) {
  free(b->a);
  memset(b, 0, sizeof *b);
}

int rfont_raster(const char *s, double em, double frac, rfont_bitmap *out, sph_error *err) {
  memset(out, 0, sizeof *out);
  if (rfont_init(err) != 0) return -1;
  if (!(em > 0.0) || em > 4096.0) return sph_error_set(err, "font: bad size %g pixels", em);
  if (FT_Set_Char_Size(F.face, 0, (FT_F26Dot6)lround(em * 64.0), 72, 72) != 0)
    return sph_error_set(err, "font: cannot set the size %g pixels", em);
  /* a box with room for accents above and descenders below */
  const int above = (int)ceil(1.2 * em), below = (int)ceil(0.5 * em), side = (int)ceil(0.3 * em);
  out->ox = side;
  out->oy = above;
  out->w = (int)ceil(width_em(s, em) + frac) + 2 * side + 1;
  out->h = above + below;
  out->a = calloc((size_t)out->w * (size_t)out->h, 1);
  if (!out->a) return sph_error_set(err, "font: out of memory");
  double pen = out->ox + frac;
  for (const char *p = s; *p;) {
    uint32_t c = rfont_utf8_next(&p);
    long adv = advance_units(c); /* leaves the glyph slot unscaled: reload below */
    FT_UInt g = FT_Get_Char_Index(F.face, c);
    if (FT_Load_Glyph(F.face, g, FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP) == 0 &&
        F.face->glyph->format == FT_GLYPH_FORMAT_OUTLINE) {
      double whole = floor(pen);
      FT_Outline_Translate(&F.face->glyph->outline, (FT_Pos)lround((pen - whole) * 64.0), 0);
      if (FT_Render_Glyph(F.face->glyph, FT_RENDER_MODE_NORMAL) == 0) {
        const FT_Bitmap *b = &F.face->glyph->bitmap;
        int x0 = (int)whole + F.face->glyph->bitmap_left;
        int y0 = out->oy - F.face->glyph->bitmap_top;
        for (unsigned r = 0; r < b->rows; r++) {
          int y = y0 + (int)r;
          if (y < 0 || y >= out->h) continue;
          const unsigned char *src = b->buffer + (long)r * b->pitch;
          for (unsigned k = 0; k < b->width; k++) {
            int x = x0 + (int)k;
            if (x < 0 || x >= out->w) continue;
            uint8_t *d = &out->a[(size_t)y * out->w + x];
            if (src[k] > *d) *d = src[k]; /* overlapping glyphs: the larger coverage */
          }
        }
      }
    }
    pen += (double)adv * em / F.face->units_per_EM;
  }
  return 0;
}
