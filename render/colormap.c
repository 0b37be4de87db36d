/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * colormap.c - builds the colour tables of colormap.h.
 *
 * Each map is a few anchor colours at equal spacing, interpolated piecewise
 * linearly in the OKLab colour space (B. Ottosson, "A perceptual color space
 * for image processing", 2020: sRGB -> linear light -> LMS -> cube root ->
 * Lab, and back), so lightness changes evenly between anchors and no muddy
 * greys appear as they do when mixing in sRGB. Anchors:
 *  - viridis: the ten-colour sampling of viridis (S. van der Walt and
 *    N. Smith, matplotlib 1.5, 2015), a map of monotonically increasing
 *    lightness that stays readable in greyscale and for colour-blind viewers;
 *  - coolwarm: the end points and the neutral centre of K. Moreland's
 *    diverging cool-warm map ("Diverging color maps for scientific
 *    visualization", ISVC 2009); interpolated in OKLab rather than in his
 *    Msh space, so it is a close relative, not a copy;
 *  - gray: black to white.
 * Invariants: entry 0 and entry 255 are the first and last anchors exactly
 * (the round trip through OKLab is far below half an 8-bit step), and the
 * table depends only on the anchors, not on the order maps are built in.
 */
#include "config.h"

#include "colormap.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

typedef struct anchors {
  const char *name;
  int diverging;
  int n;
  uint32_t rgb[10]; /* 0xRRGGBB */
} anchors;

static const anchors maps[] = {
    {"viridis",
     0,
     10,
     {0x440154, 0x482878, 0x3e4a89, 0x31688e, 0x26828e, 0x1f9e89, 0x35b779, 0x6dcd59, 0xb4de2c,
      0xfde725}},
    {"coolwarm", 1, 3, {0x3b4cc0, 0xdddddd, 0xb40426}},
    {"gray", 0, 2, {0x000000, 0xffffff}},
};

const char *rcolormap_names(void) { return "viridis, coolwarm, gray"; }

static double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

static double linear_to_srgb(double c) {
  return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}

/* 0xRRGGBB -> OKLab (L, a, b). */
static void to_oklab(uint32_t rgb, double lab[3]) {
  double r = srgb_to_linear(((rgb >> 16) & 0xff) / 255.0);
  double g = srgb_to_linear(((rgb >> 8) & 0xff) / 255.0);
  double b = srgb_to_linear((rgb & 0xff) / 255.0);
  double l = cbrt(0.4122214708 * r + 0.5363325363 * g + 0.0514459929 * b);
  double m = cbrt(0.2119034982 * r + 0.6806995451 * g + 0.1073969566 * b);
  double s = cbrt(0.0883024619 * r + 0.2817188376 * g + 0.6299787005 * b);
  lab[0] = 0.2104542553 * l + 0.7936177850 * m - 0.0040720468 * s;
  lab[1] = 1.9779984951 * l - 2.4285922050 * m + 0.4505937099 * s;
  lab[2] = 0.0259040371 * l + 0.7827717662 * m - 0.8086757660 * s;
}

static uint8_t to_byte(double c) {
  c = linear_to_srgb(c < 0.0 ? 0.0 : c > 1.0 ? 1.0 : c);
  return (uint8_t)floor(c * 255.0 + 0.5);
}

/* OKLab -> 8-bit sRGB, clamped to the gamut. */
static void from_oklab(const double lab[3], uint8_t out[3]) {
  double l = lab[0] + 0.3963377774 * lab[1] + 0.2158037573 * lab[2];
  double m = lab[0] - 0.1055613458 * lab[1] - 0.0638541728 * lab[2];
  double s = lab[0] - 0.0894841775 * lab[1] - 1.2914855480 * lab[2];
  l = l * l * l;
  m = m * m * m;
  s = s * s * s;
  out[0] = to_byte(4.0767416621 * l - 3.3077115913 * m + 0.2309699292 * s);
  out[1] = to_byte(-1.2684380046 * l + 2.6097574011 * m - 0.3413193965 * s);
  out[2] = to_byte(-0.0041960863 * l - 0.7034186147 * m + 1.7076147010 * s);
}

int rcolormap_get(const char *name, rcolormap *out, sph_error *err) {
  const anchors *a = NULL;
  for (size_t i = 0; i < sizeof maps / sizeof maps[0]; i++)
    if (strcmp(maps[i].name, name) == 0) a = &maps[i];
  if (!a) return sph_error_set(err, "unknown colour map '%s' (valid: %s)", name, rcolormap_names());
  memset(out, 0, sizeof *out);
  snprintf(out->name, sizeof out->name, "%s", a->name);
  out->diverging = a->diverging;
  double lab[10][3];
  for (int k = 0; k < a->n; k++)
    to_oklab(a->rgb[k], lab[k]);
  for (int i = 0; i < RCMAP_SIZE; i++) {
    double pos = (double)i / (RCMAP_SIZE - 1) * (a->n - 1);
    int k = (int)floor(pos);
    if (k >= a->n - 1) k = a->n - 2;
    double u = pos - k, mix[3];
    for (int c = 0; c < 3; c++)
      mix[c] = (1.0 - u) * lab[k][c] + u * lab[k + 1][c];
    from_oklab(mix, out->lut[i]);
  }
  return 0;
}

int rcolormap_index(double t) {
  if (isnan(t)) return -1;
  if (t <= 0.0) return 0;
  if (t >= 1.0) return RCMAP_SIZE - 1;
  return (int)floor(t * (RCMAP_SIZE - 1) + 0.5);
}

void rcolormap_map(const rcolormap *m, double t, uint8_t rgb[3]) {
  int i = rcolormap_index(t);
  if (i < 0) {
    rgb[0] = 255;
    rgb[1] = 0;
    rgb[2] = 255;
    return;
  }
  memcpy(rgb, m->lut[i], 3);
}
