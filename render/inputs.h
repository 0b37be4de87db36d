/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * inputs.h - turns command-line inputs into lists of snapshot files, names
 * output files after them, and matches snapshots by time.
 */
#ifndef SPH_RENDER_INPUTS_H
#define SPH_RENDER_INPUTS_H

#include <stddef.h>

#include "core/error.h"

typedef struct rinput {
  char *path;
  double time; /* NaN until rinputs_times */
} rinput;

typedef struct rinputs {
  size_t n, cap;
  rinput *v;
} rinputs;

/* Appends arg: a snapshot file as given, or a directory's snap_*.h5 files
 * (all *.h5 if there is no snap_*.h5) in name order. A missing path or a
 * directory without snapshots is an error naming it. */
int rinputs_add(rinputs *l, const char *arg, sph_error *err);
/* Reads every snapshot's time (only the header). */
int rinputs_times(rinputs *l, sph_error *err);
void rinputs_free(rinputs *l);

/* Index of the snapshot whose time is nearest t (the first of equals);
 * the list must have times and at least one entry. */
size_t rinputs_nearest(const rinputs *l, double t);
/* Smallest positive spacing between consecutive times (Inf if none). */
double rinputs_min_spacing(const rinputs *l);

/* The trailing digits of a file's base name without extension
 * ("out/snap_0012.h5" -> "0012"); "" if it has none. */
void rinputs_number(const char *path, char *buf, size_t size);
/* The base name of path without directories and extension. */
void rinputs_stem(const char *path, char *buf, size_t size);
/* Non-zero if path ends in ".png" (any case). */
int rinputs_is_png(const char *path);
/* Creates directory dir and its parents (like mkdir -p). */
int rinputs_mkdirs(const char *dir, sph_error *err);

#endif
