/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * label.c - labels with units (see label.h).
 */
#include "config.h"

#include "label.h"

#include <stdio.h>
#include <string.h>

#include "io/csv.h"

/* UTF-8 superscripts of '0'..'9' and '-'. */
static const char *superscript(char c) {
  static const char *digits[10] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  if (c >= '0' && c <= '9') return digits[c - '0'];
  return c == '-' ? "⁻" : NULL;
}

void rlabel_with_units(const char *name, const char *units, char *buf, size_t size) {
  if (!units || !units[0] || strcmp(units, "1") == 0) {
    snprintf(buf, size, "%s", name);
    return;
  }
  char u[128];
  size_t k = 0;
  for (const char *p = units; *p && k + 8 < sizeof u; p++) {
    if (*p == '^' && superscript(p[1])) {
      for (p++; *p && superscript(*p) && k + 8 < sizeof u; p++) {
        const char *s = superscript(*p);
        memcpy(u + k, s, strlen(s));
        k += strlen(s);
      }
      p--;
      continue;
    }
    u[k++] = *p;
  }
  u[k] = '\0';
  snprintf(buf, size, "%s (%s)", name, u);
}

/* The units of one column name: NULL if unknown or carried in the name. */
static const char *column_units(const char *name) {
  size_t n = strlen(name);
  if (n > 0 && (name[n - 1] == ')' || name[n - 1] == ']')) return NULL; /* "P1 (Pa)" */
  return sph_csv_units(name);
}

void rlabel_column(const char *expr, double scale, int relative, char *buf, size_t size) {
  if (relative) {
    snprintf(buf, size, "%s, relative change", expr);
    return;
  }
  const char *units = NULL;
  int agree = scale == 1.0;
  char term[256];
  for (const char *p = expr; agree;) {
    const char *plus = strchr(p, '+');
    size_t len = plus ? (size_t)(plus - p) : strlen(p);
    while (len > 0 && *p == ' ')
      p++, len--;
    while (len > 0 && p[len - 1] == ' ')
      len--;
    if (len >= sizeof term) {
      agree = 0;
      break;
    }
    memcpy(term, p, len);
    term[len] = '\0';
    const char *u = column_units(term);
    if (!u || (units && strcmp(u, units) != 0)) agree = 0;
    units = u;
    if (!plus) break;
    p = plus + 1;
  }
  rlabel_with_units(expr, agree ? units : NULL, buf, size);
}
