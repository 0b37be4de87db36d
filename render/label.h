/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * label.h - axis and colour-bar labels with their units: "time (s)",
 * "density (kg/m³)". Units come from a snapshot's `units` attributes or,
 * for a CSV column, from its header (a name that carries its units, such
 * as "P1 (Pa)", is used as it is) or from the table of the columns sph
 * writes (sph_csv_units in io/csv.h).
 */
#ifndef SPH_RENDER_LABEL_H
#define SPH_RENDER_LABEL_H

#include <stddef.h>

/* "name (units)", with powers written as superscripts (m^3 -> m³,
 * s^-1 -> s⁻¹); just the name when units is NULL, "" or "1". */
void rlabel_with_units(const char *name, const char *units, char *buf, size_t size);
/* The label of a plot axis showing the column expression expr (a name or
 * names joined by '+') multiplied by scale: with units where they are
 * known and the values are not rescaled (scale 1) - a sum only if its
 * terms agree; "relative" marks (y - y0) / |y0|, which has none. */
void rlabel_column(const char *expr, double scale, int relative, char *buf, size_t size);

#endif
