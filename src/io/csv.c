/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * csv.c - reads the numeric CSV tables of csv.h.
 *
 * One pass over the lines: comments ('#' as the first non-blank character)
 * and blank lines are skipped, the first other line is the header, and
 * every later line must have exactly as many comma-separated cells. Cells
 * are trimmed of spaces and of one pair of double quotes (no embedded
 * commas: the diagnostics and the experimental tables have none). Numbers
 * are parsed with strtod in the C locale the program runs in. CR before LF
 * is ignored, so files saved on Windows read the same.
 */
#include "config.h"

#include "io/csv.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Trims spaces and one pair of quotes in place; returns the start. */
static char *trim(char *s) {
  while (*s && isspace((unsigned char)*s))
    s++;
  size_t n = strlen(s);
  while (n > 0 && isspace((unsigned char)s[n - 1]))
    s[--n] = '\0';
  if (n >= 2 && s[0] == '"' && s[n - 1] == '"') {
    s[n - 1] = '\0';
    s++;
  }
  return s;
}

/* Splits line at commas into at most max cells; returns the count (which
 * may exceed max: then only max were stored). */
static size_t split(char *line, char **cells, size_t max) {
  size_t n = 0;
  char *p = line;
  for (;;) {
    char *comma = strchr(p, ',');
    if (comma) *comma = '\0';
    if (n < max) cells[n] = trim(p);
    n++;
    if (!comma) break;
    p = comma + 1;
  }
  return n;
}

static int is_skipped(const char *line) {
  while (*line && isspace((unsigned char)*line))
    line++;
  return *line == '\0' || *line == '#';
}

/* Reads one line of any length into *buf; 0 at end of file. */
/* One line into *buf (grown as needed), without its newline (or \r\n):
 * 1, 0 at the end of the file, -1 out of memory, -2 a line longer than
 * SPH_CSV_MAX_LINE. *total counts the bytes read. */
static int read_line(FILE *fp, char **buf, size_t *cap, size_t *total) {
  size_t n = 0;
  int c;
  while ((c = fgetc(fp)) != EOF && c != '\n') {
    if (n >= SPH_CSV_MAX_LINE) return -2;
    (*total)++;
    if (n + 2 > *cap) {
      size_t nc = *cap ? 2 * *cap : 256;
      char *b = realloc(*buf, nc);
      if (!b) return -1;
      *buf = b;
      *cap = nc;
    }
    (*buf)[n++] = (char)c;
  }
  if (c == EOF && n == 0) return 0;
  if (!*buf) {
    *buf = malloc(1);
    if (!*buf) return -1;
    *cap = 1;
  }
  if (n > 0 && (*buf)[n - 1] == '\r') n--;
  (*buf)[n] = '\0';
  return 1;
}

static int parse_cell(const char *s, double *out) {
  if (*s == '\0' || strcmp(s, "nan") == 0 || strcmp(s, "NaN") == 0) {
    *out = NAN;
    return 0;
  }
  char *end;
  errno = 0;
  double v = strtod(s, &end);
  if (end == s || *end != '\0') return -1;
  *out = v;
  return 0;
}

int sph_csv_read(const char *path, sph_csv *t, sph_error *err) {
  memset(t, 0, sizeof *t);
  FILE *fp = fopen(path, "r");
  if (!fp) return sph_error_set(err, "%s: cannot open: %s", path, strerror(errno));
  t->path = strdup(path);
  char *line = NULL, **cells = NULL;
  size_t cap = 0, rows_cap = 0, total = 0;
  long lineno = 0;
  int rc = 0, got;
  while ((got = read_line(fp, &line, &cap, &total)) > 0) {
    lineno++;
    if ((total += 1) > SPH_CSV_MAX_BYTES) { /* the newline */
      rc = sph_error_set(err, "%s:%ld: larger than %u MiB: not a table this reader takes", path,
                         lineno, SPH_CSV_MAX_BYTES >> 20);
      break;
    }
    if (is_skipped(line)) continue;
    if (!t->names) {
      /* the header: count the cells first, then keep their names */
      char *copy = strdup(line);
      if (!copy) {
        rc = sph_error_set(err, "%s: out of memory", path);
        break;
      }
      t->ncol = split(copy, NULL, 0);
      free(copy);
      t->names = calloc(t->ncol, sizeof *t->names);
      cells = calloc(t->ncol, sizeof *cells);
      if (!t->names || !cells) {
        rc = sph_error_set(err, "%s: out of memory", path);
        break;
      }
      split(line, cells, t->ncol);
      for (size_t k = 0; k < t->ncol; k++) {
        if (!*cells[k]) {
          rc = sph_error_set(err, "%s:%ld: column %zu of the header has no name", path, lineno,
                             k + 1);
          break;
        }
        t->names[k] = strdup(cells[k]);
      }
      if (rc) break;
      continue;
    }
    size_t n = split(line, cells, t->ncol);
    if (n != t->ncol) {
      rc = sph_error_set(err, "%s:%ld: %zu cells, but the header names %zu columns", path, lineno,
                         n, t->ncol);
      break;
    }
    if ((t->nrow + 1) * t->ncol > SPH_CSV_MAX_CELLS) {
      rc = sph_error_set(err, "%s:%ld: more than %u cells: not a table this reader takes", path,
                         lineno, SPH_CSV_MAX_CELLS);
      break;
    }
    if (t->nrow == rows_cap) {
      rows_cap = rows_cap ? 2 * rows_cap : 64;
      if (rows_cap * t->ncol > SPH_CSV_MAX_CELLS) rows_cap = SPH_CSV_MAX_CELLS / t->ncol;
      double *d = realloc(t->data, rows_cap * t->ncol * sizeof *d);
      if (!d) {
        rc = sph_error_set(err, "%s: out of memory", path);
        break;
      }
      t->data = d;
    }
    for (size_t k = 0; k < t->ncol; k++) {
      if (parse_cell(cells[k], &t->data[t->nrow * t->ncol + k]) != 0) {
        rc = sph_error_set(err, "%s:%ld: column '%s': '%s' is not a number", path, lineno,
                           t->names[k], cells[k]);
        break;
      }
    }
    if (rc) break;
    t->nrow++;
  }
  if (got == -2 && !rc)
    rc = sph_error_set(err, "%s:%ld: a line longer than %u KiB: not a table this reader takes",
                       path, lineno + 1, SPH_CSV_MAX_LINE >> 10);
  if (got == -1 && !rc) rc = sph_error_set(err, "%s: out of memory", path);
  if (!rc && ferror(fp)) rc = sph_error_set(err, "%s: read error", path);
  if (!rc && !t->names) rc = sph_error_set(err, "%s: no header row (the file is empty)", path);
  fclose(fp);
  free(line);
  free(cells);
  if (rc) sph_csv_free(t);
  return rc;
}

void sph_csv_free(sph_csv *t) {
  if (!t) return;
  if (t->names)
    for (size_t k = 0; k < t->ncol; k++)
      free(t->names[k]);
  free(t->names);
  free(t->data);
  free(t->path);
  memset(t, 0, sizeof *t);
}

size_t sph_csv_bare_length(const char *column, size_t len) {
  if (len < 4 || column[len - 1] != ')') return len;
  for (size_t k = 1; k + 2 < len; k++)
    if (column[k] == ' ' && column[k + 1] == '(') return k;
  return len;
}

int sph_csv_column(const sph_csv *t, const char *name, sph_error *err) {
  /* the column of that exact name; else the one whose name before its
   * units is name ("kinetic" for "kinetic (J/m)"); two of either kind are
   * ambiguous, never one picked silently (issue 61, E10) */
  for (int pass = 0; pass < 2; pass++) {
    const size_t n = strlen(name);
    int found = -1, again = -1;
    for (size_t k = 0; k < t->ncol; k++) {
      const char *c = t->names[k];
      const size_t len = strlen(c);
      const int hit = pass == 0 ? strcmp(c, name) == 0
                                : n > 0 && n < len && sph_csv_bare_length(c, len) == n &&
                                      strncmp(c, name, n) == 0;
      if (!hit) continue;
      if (found < 0)
        found = (int)k;
      else if (again < 0)
        again = (int)k;
    }
    if (found >= 0 && again < 0) return found;
    if (again >= 0) {
      sph_error_set(err, "%s: '%s' names columns %d ('%s') and %d ('%s'): ambiguous", t->path, name,
                    found + 1, t->names[found], again + 1, t->names[again]);
      return -1;
    }
  }
  char list[512] = "";
  size_t used = 0;
  for (size_t k = 0; k < t->ncol && used + 4 < sizeof list; k++) {
    int w = snprintf(list + used, sizeof list - used, "%s%s", k ? ", " : "", t->names[k]);
    if (w < 0) break;
    used += (size_t)w;
  }
  sph_error_set(err, "%s: no column '%s' (columns: %s)", t->path, name, list);
  return -1;
}

int sph_csv_eval(const sph_csv *t, const char *expr, double *out, sph_error *err) {
  for (size_t r = 0; r < t->nrow; r++)
    out[r] = 0.0;
  const char *p = expr;
  for (;;) {
    const char *plus = strchr(p, '+');
    size_t len = plus ? (size_t)(plus - p) : strlen(p);
    char name[256];
    if (len == 0 || len >= sizeof name)
      return sph_error_set(err, "%s: bad column expression '%s'", t->path, expr);
    memcpy(name, p, len);
    name[len] = '\0';
    int k = sph_csv_column(t, trim(name), err);
    if (k < 0) return -1;
    for (size_t r = 0; r < t->nrow; r++)
      out[r] += t->data[r * t->ncol + (size_t)k];
    if (!plus) break;
    p = plus + 1;
  }
  return 0;
}
