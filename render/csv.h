/*
 * csv.h - numeric tables from CSV files: a header row of column names, then
 * rows of numbers. Lines starting with '#' (comments, e.g. a data source)
 * and blank lines are skipped anywhere.
 */
#ifndef SPH_RENDER_CSV_H
#define SPH_RENDER_CSV_H

#include <stddef.h>

#include "core/error.h"

typedef struct rcsv {
  char *path;
  size_t ncol, nrow;
  char **names; /* ncol column names */
  double *data; /* nrow * ncol values, row-major; an empty cell or "nan" is NaN */
} rcsv;

/* Reads path. Errors name the file and line (and the column for a cell
 * that is not a number). */
int rcsv_read(const char *path, rcsv *out, sph_error *err);
void rcsv_free(rcsv *t);
/* Index of the named column, or -1 with an error listing the columns. */
int rcsv_column(const rcsv *t, const char *name, sph_error *err);
/* Fills out (nrow values) with a column expression: a column name, or
 * several joined by '+' (their sum, e.g. "kinetic+potential"). */
int rcsv_eval(const rcsv *t, const char *expr, double *out, sph_error *err);

#endif
