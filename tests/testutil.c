/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * testutil.c - file, process and CSV helpers shared by the test programs
 * (the CUnit runner is testmain.c).
 */
#include "config.h"

#include "testutil.h"

#include "io/csv.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

/* A ring of buffers, so that a few results can be used in one call. The
 * root is the environment's, else the directory the test started in (an
 * absolute path: a test may run a program after a cd). */
static const char *join(const char *env, const char *rel) {
  static char ring[8][8200], here[4096];
  static unsigned next;
  char *buf = ring[next++ % 8];
  const char *root = getenv(env);
  if (!root || !*root) {
    if (!here[0] && !getcwd(here, sizeof here)) snprintf(here, sizeof here, ".");
    root = here;
  }
  snprintf(buf, sizeof ring[0], "%s/%s", root, rel);
  return buf;
}

const char *sph_test_src(const char *rel) { return join("SPH_SRCDIR", rel); }
const char *sph_test_build(const char *rel) { return join("SPH_BUILDDIR", rel); }

char *sph_test_tmpdir(void) {
  const char *base = getenv("TMPDIR");
  if (!base || !*base) base = "/tmp";
  char tmpl[4096];
  snprintf(tmpl, sizeof tmpl, "%s/sphtest.XXXXXX", base);
  char *d = mkdtemp(tmpl);
  if (!d) {
    perror("mkdtemp");
    abort();
  }
  return strdup(d);
}

void sph_test_rmtree(const char *dir) {
  char cmd[4200];
  if (!dir || strncmp(dir, "/", 1) != 0 || strstr(dir, "sphtest.") == NULL) return;
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  if (system(cmd) != 0) fprintf(stderr, "warning: could not remove %s\n", dir);
}

int sph_test_system(const char *cmd) {
  int st = system(cmd);
  if (st == -1) return -1;
  if (WIFEXITED(st)) return WEXITSTATUS(st);
  return -1;
}

int sph_test_sph(const char *args, const char *dir, char *out, size_t len) {
  char cmd[40000];
  char log[4200];
  snprintf(log, sizeof log, "%s/sph.log", dir);
  snprintf(cmd, sizeof cmd, "'%s' %s >'%s' 2>&1", sph_test_build("src/sph"), args, log);
  const int st = sph_test_system(cmd);
  out[0] = 0;
  FILE *f = fopen(log, "r");
  if (f) {
    const size_t n = fread(out, 1, len - 1, f);
    out[n] = 0;
    fclose(f);
  }
  return st;
}

int sph_test_sph_ok(const char *args, const char *dir, char *out, size_t len) {
  const int st = sph_test_sph(args, dir, out, len);
  if (st) printf("\n  sph %s: exit %d\n%s\n", args, st, out);
  return st;
}

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

double sph_test_interp(const double *t, const double *x, size_t n, double at) {
  if (n == 0) return NAN;
  if (at <= t[0]) return x[0];
  for (size_t i = 1; i < n; i++)
    if (at <= t[i]) return x[i - 1] + (x[i] - x[i - 1]) * (at - t[i - 1]) / (t[i] - t[i - 1]);
  return x[n - 1];
}

double sph_test_median(const double *v, int n) {
  double *c = malloc((size_t)n * sizeof *c);
  if (!c) return NAN;
  memcpy(c, v, (size_t)n * sizeof *c);
  qsort(c, (size_t)n, sizeof *c, cmp_double);
  const double m = n % 2 ? c[n / 2] : 0.5 * (c[n / 2 - 1] + c[n / 2]);
  free(c);
  return m;
}

double sph_test_simpson(double (*f)(double), double a, double b, int m) {
  const double d = (b - a) / m;
  double acc = 0.0;
  for (int k = 0; k <= m; k++) {
    const double wgt = (k == 0 || k == m) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    acc += wgt * f(a + k * d);
  }
  return acc * d / 3.0;
}

char *sph_test_read_file(const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  size_t cap = 4096, n = 0;
  char *buf = malloc(cap);
  while (buf) {
    n += fread(buf + n, 1, cap - 1 - n, f);
    if (n < cap - 1) break;
    char *b = realloc(buf, 2 * cap);
    if (!b) {
      free(buf);
      buf = NULL;
      break;
    }
    buf = b;
    cap *= 2;
  }
  fclose(f);
  if (buf) buf[n] = '\0';
  if (buf && len) *len = n;
  return buf;
}

long sph_test_csv(const char *path, const char *names, double **out) {
  sph_csv t;
  sph_error err;
  if (sph_csv_read(path, &t, &err)) {
    printf("\n  %s\n", err.msg);
    return -1;
  }
  char buf[1024];
  snprintf(buf, sizeof buf, "%s", names);
  int k = 0;
  long rc = (long)t.nrow;
  for (char *save = NULL, *name = strtok_r(buf, ",", &save); name;
       name = strtok_r(NULL, ",", &save), k++) {
    int col = name[0] == '#' ? atoi(name + 1) : sph_csv_column(&t, name, &err);
    if (col < 0 || (size_t)col >= t.ncol) {
      printf("\n  %s: no column %s\n", path, name);
      rc = -1;
      out[k] = NULL;
      continue;
    }
    out[k] = malloc((t.nrow ? t.nrow : 1) * sizeof(double));
    for (size_t r = 0; r < t.nrow; r++)
      out[k][r] = t.data[r * t.ncol + (size_t)col];
  }
  sph_csv_free(&t);
  return rc;
}

size_t sph_test_csv2(const char *path, const char *names, double *a, double *b, size_t cap) {
  double *c[2] = {NULL, NULL};
  const long n = sph_test_csv(path, names, c);
  size_t k = 0;
  for (; n > 0 && k < (size_t)n && k < cap; k++) {
    a[k] = c[0][k];
    b[k] = c[1][k];
  }
  free(c[0]);
  free(c[1]);
  return k;
}

double sph_test_uniform(unsigned long long *s) {
  *s ^= *s << 13;
  *s ^= *s >> 7;
  *s ^= *s << 17;
  return (double)(*s >> 11) / 9007199254740992.0;
}

int sph_test_same_dirs(const char *a, const char *b) {
  char cmd[8300];
  snprintf(cmd, sizeof cmd, "diff -r '%s' '%s' >/dev/null", a, b);
  return sph_test_system(cmd) == 0;
}

int sph_test_restart_same(const char *cmd, const char *whole, const char *again, const char *what) {
  const int rc = sph_test_system(cmd);
  CU_ASSERT(rc == 0);
  char cmp[8400];
  snprintf(cmp, sizeof cmp, "cmp -s '%s/snap_0002.h5' '%s/snap_0002.h5'", whole, again);
  const int same = rc == 0 && sph_test_system(cmp) == 0;
  printf("\n  %s: %s", what, same ? "identical" : "DIFFERENT");
  return same;
}
