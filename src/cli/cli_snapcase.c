/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * cli_snapcase.c - the case a snapshot was run from, for the commands that
 * measure snapshots (sph profile, sph face)
 *
 * and for `sph run --restart SNAPSHOT` without a case file.
 *
 * Each snapshot written by `sph run` carries the text of its case file
 * (attribute case_text) and the run's --set overrides, one "key=value" per
 * line (attribute overrides); parsing both again with sph_case_parse gives
 * exactly the run's case.
 */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"

/* Splits the stored overrides ("k=v" lines) into a NULL-terminated array
 * of pointers into a private copy, with `extra` room for more; *n gets the
 * count. NULL on no memory. */
static char **split_overrides(const char *text, size_t extra, size_t *n, char **copy) {
  *n = 0;
  *copy = strdup(text ? text : "");
  if (!*copy) return NULL;
  size_t lines = 1;
  for (const char *q = *copy; *q; q++)
    lines += *q == '\n';
  char **v = calloc(lines + extra + 1, sizeof *v);
  if (!v) {
    free(*copy);
    *copy = NULL;
    return NULL;
  }
  char *s = *copy;
  while (*s) {
    char *nl = strchr(s, '\n');
    if (nl) *nl = '\0';
    if (*s) v[(*n)++] = s;
    if (!nl) break;
    s = nl + 1;
  }
  return v;
}

int sph_cli_snapshot_case_set(const sph_snapshot *s, const char *const *extra, size_t n_extra,
                              sph_case *c, sph_error *err) {
  const char *text = sph_snapshot_text(s, "case_text");
  if (!text || !*text)
    return sph_error_set(err, "%s: no case_text attribute (not written by sph run?)",
                         sph_snapshot_path(s));
  size_t n_set;
  char *copy;
  char **set = split_overrides(sph_snapshot_text(s, "overrides"), n_extra, &n_set, &copy);
  if (!set) return sph_error_set(err, "%s: out of memory", sph_snapshot_path(s));
  for (size_t k = 0; k < n_extra; k++)
    set[n_set++] = (char *)extra[k];
  char origin[4200];
  snprintf(origin, sizeof origin, "%s (case_text)", sph_snapshot_path(s));
  const int rc =
      sph_case_parse(text, strlen(text), origin, (const char *const *)set, n_set, c, err);
  free(set);
  free(copy);
  if (rc) sph_case_free(c);
  return rc ? -1 : 0;
}

int sph_cli_snapshot_case(const sph_snapshot *s, sph_case *c, sph_error *err) {
  return sph_cli_snapshot_case_set(s, NULL, 0, c, err);
}
