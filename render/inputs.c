/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * inputs.c - snapshot lists from the command line (see inputs.h).
 *
 * A directory stands for the run written into it: its snap_*.h5 files in
 * strcmp order, which is time order because the solver zero-pads the
 * number (snap_0000.h5, snap_0001.h5, ...). Files named explicitly keep
 * the user's order. Nothing depends on readdir's order, which varies
 * between file systems.
 */
#include "config.h"

#include "inputs.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "snapdata.h"

static int push(rinputs *l, const char *path, sph_error *err) {
  if (l->n == l->cap) {
    size_t cap = l->cap ? 2 * l->cap : 64;
    rinput *v = realloc(l->v, cap * sizeof *v);
    if (!v) return sph_error_set(err, "out of memory");
    l->v = v;
    l->cap = cap;
  }
  l->v[l->n].path = strdup(path);
  if (!l->v[l->n].path) return sph_error_set(err, "out of memory");
  l->v[l->n].time = NAN;
  l->n++;
  return 0;
}

static int ends_with(const char *s, const char *suffix) {
  size_t n = strlen(s), k = strlen(suffix);
  return n >= k && strcmp(s + n - k, suffix) == 0;
}

static int cmp_str(const void *a, const void *b) {
  return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Collects the names in dir that match (prefix "snap_" or not) and end in .h5. */
static int scan(const char *dir, int want_snap, char ***names, size_t *count, sph_error *err) {
  DIR *d = opendir(dir);
  if (!d) return sph_error_set(err, "%s: cannot read directory: %s", dir, strerror(errno));
  size_t n = 0, cap = 0;
  char **v = NULL;
  struct dirent *e;
  int rc = 0;
  while ((e = readdir(d)) != NULL) {
    if (!ends_with(e->d_name, ".h5")) continue;
    if (want_snap && strncmp(e->d_name, "snap_", 5) != 0) continue;
    if (n == cap) {
      cap = cap ? 2 * cap : 64;
      char **nv = realloc(v, cap * sizeof *nv);
      if (!nv) {
        rc = sph_error_set(err, "out of memory");
        break;
      }
      v = nv;
    }
    v[n] = strdup(e->d_name);
    if (!v[n]) {
      rc = sph_error_set(err, "out of memory");
      break;
    }
    n++;
  }
  closedir(d);
  if (rc) {
    for (size_t i = 0; i < n; i++)
      free(v[i]);
    free(v);
    return rc;
  }
  qsort(v, n, sizeof *v, cmp_str);
  *names = v;
  *count = n;
  return 0;
}

int rinputs_add(rinputs *l, const char *arg, sph_error *err) {
  struct stat st;
  if (stat(arg, &st) != 0) return sph_error_set(err, "%s: %s", arg, strerror(errno));
  if (!S_ISDIR(st.st_mode)) return push(l, arg, err);
  char **names = NULL;
  size_t n = 0;
  if (scan(arg, 1, &names, &n, err) != 0) return -1;
  if (n == 0) {
    free(names);
    if (scan(arg, 0, &names, &n, err) != 0) return -1;
  }
  int rc = 0;
  if (n == 0) rc = sph_error_set(err, "%s: no snapshots (snap_*.h5) in this directory", arg);
  for (size_t i = 0; i < n; i++) {
    if (rc == 0) {
      size_t len = strlen(arg) + strlen(names[i]) + 2;
      char *p = malloc(len);
      if (!p) {
        rc = sph_error_set(err, "out of memory");
      } else {
        snprintf(p, len, "%s%s%s", arg, ends_with(arg, "/") ? "" : "/", names[i]);
        rc = push(l, p, err);
        free(p);
      }
    }
    free(names[i]);
  }
  free(names);
  return rc;
}

int rinputs_times(rinputs *l, sph_error *err) {
  for (size_t i = 0; i < l->n; i++)
    if (isnan(l->v[i].time) && rsnap_peek(l->v[i].path, &l->v[i].time, NULL, err) != 0) return -1;
  return 0;
}

void rinputs_free(rinputs *l) {
  for (size_t i = 0; i < l->n; i++)
    free(l->v[i].path);
  free(l->v);
  memset(l, 0, sizeof *l);
}

size_t rinputs_nearest(const rinputs *l, double t) {
  size_t best = 0;
  for (size_t i = 1; i < l->n; i++)
    if (fabs(l->v[i].time - t) < fabs(l->v[best].time - t)) best = i;
  return best;
}

double rinputs_min_spacing(const rinputs *l) {
  double m = INFINITY;
  for (size_t i = 1; i < l->n; i++) {
    double d = fabs(l->v[i].time - l->v[i - 1].time);
    if (d > 0.0 && d < m) m = d;
  }
  return m;
}

void rinputs_stem(const char *path, char *buf, size_t size) {
  char tmp[4096];
  snprintf(tmp, sizeof tmp, "%s", path);
  size_t n = strlen(tmp);
  while (n > 1 && tmp[n - 1] == '/')
    tmp[--n] = '\0'; /* "out/run/" names "run" */
  const char *base = strrchr(tmp, '/');
  base = base && base[1] ? base + 1 : tmp;
  snprintf(buf, size, "%s", base);
  char *dot = strrchr(buf, '.');
  if (dot && dot != buf) *dot = '\0';
}

void rinputs_number(const char *path, char *buf, size_t size) {
  char stem[1024];
  rinputs_stem(path, stem, sizeof stem);
  size_t n = strlen(stem), k = n;
  while (k > 0 && stem[k - 1] >= '0' && stem[k - 1] <= '9')
    k--;
  snprintf(buf, size, "%s", stem + k);
}

int rinputs_is_png(const char *path) {
  size_t n = strlen(path);
  return n >= 4 && strcasecmp(path + n - 4, ".png") == 0;
}

int rinputs_mkdirs(const char *dir, sph_error *err) {
  char buf[4096];
  if (snprintf(buf, sizeof buf, "%s", dir) >= (int)sizeof buf)
    return sph_error_set(err, "%s: path too long", dir);
  for (char *p = buf + 1;; p++) {
    char c = *p;
    if (c == '/' || c == '\0') {
      *p = '\0';
      if (mkdir(buf, 0777) != 0 && errno != EEXIST)
        return sph_error_set(err, "%s: cannot create directory: %s", buf, strerror(errno));
      *p = c;
    }
    if (c == '\0') break;
  }
  struct stat st;
  if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode))
    return sph_error_set(err, "%s: exists and is not a directory", dir);
  return 0;
}
