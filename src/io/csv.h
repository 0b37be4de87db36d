/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * csv.h - numeric tables from CSV files: a header row of column names, then
 * rows of numbers (diagnostics.csv, gauges.csv, audit.csv, the experimental
 * tables; the one reader of sph-render and the tests). Lines starting with '#' (comments, e.g. a
 * data source) and blank lines are skipped anywhere.
 */
#ifndef SPH_CSV_H
#define SPH_CSV_H

#include <stddef.h>
#include <stdio.h>

#include "core/error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sph_csv {
  char *path;
  size_t ncol, nrow;
  char **names; /* ncol column names */
  double *data; /* nrow * ncol values, row-major; an empty cell or "nan" is NaN */
} sph_csv;

/* The reader's bounds (a stream without newlines, /dev/zero, or without
 * end must not fill the memory): a line of at most 1 MiB, a file of at
 * most 1 GiB and a table of at most 2^25 cells (256 MiB of values; a
 * diagnostics.csv of a million steps holds about 2 10^7). */
#define SPH_CSV_MAX_LINE (1u << 20)
#define SPH_CSV_MAX_BYTES (1u << 30)
#define SPH_CSV_MAX_CELLS (1u << 25)

/* Reads path. Errors name the file and line (and the column for a cell
 * that is not a number, or the bound a file exceeds). */
int sph_csv_read(const char *path, sph_csv *out, sph_error *err);
void sph_csv_free(sph_csv *t);
/* Index of the named column, or -1 with an error listing the columns. A
 * column whose header carries its units matches its bare name too:
 * "kinetic" finds "kinetic (J/m)" (an exact match comes first). */
int sph_csv_column(const sph_csv *t, const char *name, sph_error *err);
/* The units of a column of the CSV files sph writes (diagnostics.csv,
 * gauges.csv, probes.csv, audit.csv), as their documentation gives them:
 * "s", "m", "J/m", ..., "" for counts and ratios, NULL for a name it does
 * not know. The bare name: a header's "P1 (Pa)" is not looked up, the
 * units are in it. */
const char *sph_csv_units(const char *column);
/* Writes one column of a header sph writes, after a comma unless first:
 * "name (units)" with the units of sph_csv_units, the bare name for counts
 * and ratios (units "") and names it does not know. Every CSV file sph
 * writes follows this one convention, as probes.csv's "P1 (Pa)" does;
 * 0, or -1 on a write error. */
int sph_csv_put_column(FILE *f, const char *name, int first);
/* sph_csv_put_column for each name of a NULL-terminated list, the first
 * after a comma unless first; 0, or -1 on a write error. */
int sph_csv_put_columns(FILE *f, const char *const *names, int first);
/* The length of a header column's name (the column is len bytes) without
 * the units it carries: "kinetic (J/m)" -> 7; len for a column without. */
size_t sph_csv_bare_length(const char *column, size_t len);
/* Fills out (nrow values) with a column expression: a column name, or
 * several joined by '+' (their sum, e.g. "kinetic+potential"). */
int sph_csv_eval(const sph_csv *t, const char *expr, double *out, sph_error *err);

#ifdef __cplusplus
}
#endif

#endif
