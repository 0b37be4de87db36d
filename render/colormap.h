/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * colormap.h - colour maps: a value in [0, 1] to an 8-bit sRGB colour.
 *
 * Maps by name: "viridis" (perceptual, sequential; the default), "coolwarm"
 * (diverging, for signed fields such as vx, vy), "gray". Each map is a
 * 256-entry table built once; a value t is looked up at index
 * round(t * 255) after clamping to [0, 1], so the colour of a particle and
 * the colour bar come from the same table entries.
 */
#ifndef SPH_RENDER_COLORMAP_H
#define SPH_RENDER_COLORMAP_H

#include <stdint.h>

#include "core/error.h"

enum { RCMAP_SIZE = 256 };

typedef struct rcolormap {
  char name[16];
  int diverging;              /* centred on zero: automatic ranges are symmetric */
  uint8_t lut[RCMAP_SIZE][3]; /* sRGB */
} rcolormap;

/* "viridis, coolwarm, gray" */
const char *rcolormap_names(void);
/* Builds the named map. An unknown name is an error listing the valid ones. */
int rcolormap_get(const char *name, rcolormap *out, sph_error *err);
/* The colour of t (clamped to [0, 1]); NaN maps to magenta, which no map contains. */
void rcolormap_map(const rcolormap *m, double t, uint8_t rgb[3]);
/* The table index that t maps to (0..255), or -1 for NaN. */
int rcolormap_index(double t);

#endif
