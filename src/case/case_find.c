/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * case_find.c - a case named by a user: a file, or one of the installed
 * example cases by name (see case.h, sph_case_find; `sph run` and the
 * Python module's sph.Case look cases up through it).
 *
 * `sph run martin_moyce` in a directory without such a file runs
 * ./cases/martin_moyce.yaml if there is one (the source tree), else
 * <datadir>/sph/cases/martin_moyce.yaml, the case `make install` put there;
 * SPH_CASES_DIR (environment) names another directory of cases. A path
 * that names a file always wins, so a case of one's own is never shadowed.
 */
#include "config.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "case/case.h"

const char *sph_case_cases_dir(void) {
  const char *e = getenv("SPH_CASES_DIR");
  return e && *e ? e : SPH_CASES_DIR;
}

/* Whether path names something (a file, or a device or directory the case
 * reader then refuses with its own message). */
static int exists(const char *path) {
  struct stat st;
  return stat(path, &st) == 0;
}

static int by_name(const void *a, const void *b) {
  return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* The installed cases' names, sorted and comma-separated, into out. */
static void list_cases(const char *dir, char *out, size_t n) {
  char *names[256];
  int k = 0;
  DIR *d = opendir(dir);
  out[0] = '\0';
  if (!d) return;
  for (struct dirent *e; (e = readdir(d)) && k < 256;) {
    const size_t len = strlen(e->d_name);
    if (len > 5 && !strcmp(e->d_name + len - 5, ".yaml") && (names[k] = strdup(e->d_name)))
      names[k++][len - 5] = '\0';
  }
  closedir(d);
  qsort(names, (size_t)k, sizeof names[0], by_name);
  size_t used = 0;
  for (int i = 0; i < k; i++) {
    const int w = snprintf(out + used, used < n ? n - used : 0, "%s%s", i ? ", " : "", names[i]);
    if (w > 0) used += (size_t)w;
    free(names[i]);
  }
}

/* dir/NAME.yaml (or dir/NAME if it ends in .yaml) into buf, if it exists. */
static int in_dir(const char *dir, const char *arg, char *buf, size_t n) {
  const size_t len = strlen(arg);
  const int has_ext = len > 5 && !strcmp(arg + len - 5, ".yaml");
  return snprintf(buf, n, "%s/%s%s", dir, arg, has_ext ? "" : ".yaml") < (int)n && exists(buf);
}

const char *sph_case_find(const char *arg, char *buf, size_t n, char *why, size_t nw) {
  if (exists(arg)) return arg;
  const char *dir = sph_case_cases_dir();
  /* a bare name: ./cases (a source tree, or a project laid out like it),
   * then the installed cases */
  if (!strchr(arg, '/') && (in_dir("cases", arg, buf, n) || in_dir(dir, arg, buf, n))) return buf;
  char cases[4096];
  list_cases(dir, cases, sizeof cases);
  if (strchr(arg, '/'))
    snprintf(why, nw, "%s: no such case file", arg);
  else
    snprintf(why, nw, "%s: no such case file here, no case of that name in ./cases or in %s (%s%s)",
             arg, dir, cases[0] ? "installed cases: " : "none installed there", cases);
  return NULL;
}
