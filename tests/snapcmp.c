/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * snapcmp.c - snapshot comparison helpers of the tests (snapcmp.h), through
 * the library's own reader.
 */
#include "config.h"

#include "snapcmp.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/snapshot.h"

static int differ(const char *what, const char *msg, const char *field) {
  printf("\n  %s: %s%s%s\n", what, msg, field ? " " : "", field ? field : "");
  return 1;
}

static int same_array(const void *a, const void *b, size_t n, size_t size) {
  if (!a || !b) return a == b;
  return n == 0 || memcmp(a, b, n * size) == 0;
}

static int compare_restart(const char *what, const sph_snapshot *sa, const sph_snapshot *sb) {
  sph_snapshot_restart_data ra, rb;
  sph_error err;
  if (sph_snapshot_read_restart(sa, &ra, &err)) return differ(what, err.msg, NULL);
  if (sph_snapshot_read_restart(sb, &rb, &err)) {
    sph_snapshot_restart_free(&ra);
    return differ(what, err.msg, NULL);
  }
  int rc = 0;
  const size_t n = ra.count;
  if (ra.count != rb.count || ra.first_step != rb.first_step)
    rc = differ(what, "restart count or first_step differs", NULL);
  else if (memcmp(ra.ledger, rb.ledger, sizeof ra.ledger))
    rc = differ(what, "restart ledger differs", NULL);
  else if (ra.n_levels != rb.n_levels ||
           !same_array(ra.levels, rb.levels, ra.n_levels, sizeof(double)))
    rc = differ(what, "restart gauge levels differ", NULL);
  else if (!same_array(ra.order, rb.order, n, sizeof(int64_t)))
    rc = differ(what, "restart storage order differs", NULL);
  else if (!same_array(ra.vxh, rb.vxh, n, sizeof(double)) ||
           !same_array(ra.vyh, rb.vyh, n, sizeof(double)) ||
           !same_array(ra.rhoh, rb.rhoh, n, sizeof(double)) ||
           !same_array(ra.uh, rb.uh, n, sizeof(double)))
    rc = differ(what, "restart half-step values differ", NULL);
  sph_snapshot_restart_free(&ra);
  sph_snapshot_restart_free(&rb);
  return rc;
}

int snapcmp(const char *what, const char *a, const char *b, int restart) {
  sph_snapshot *sa = NULL, *sb = NULL;
  sph_error err;
  if (sph_snapshot_open(a, &sa, &err)) return differ(what, err.msg, NULL);
  if (sph_snapshot_open(b, &sb, &err)) {
    sph_snapshot_close(sa);
    return differ(what, err.msg, NULL);
  }
  int rc = 0;
  const double ta = sph_snapshot_time(sa), tb = sph_snapshot_time(sb);
  const double da = sph_snapshot_dt(sa), db = sph_snapshot_dt(sb);
  const size_t n = sph_snapshot_count(sa);
  if (memcmp(&ta, &tb, sizeof ta) || memcmp(&da, &db, sizeof da) ||
      sph_snapshot_step(sa) != sph_snapshot_step(sb))
    rc = differ(what, "time, dt or step differs", NULL);
  else if (n != sph_snapshot_count(sb) ||
           sph_snapshot_field_count(sa) != sph_snapshot_field_count(sb))
    rc = differ(what, "particle or field count differs", NULL);
  double *va = malloc((n ? n : 1) * sizeof *va), *vb = malloc((n ? n : 1) * sizeof *vb);
  for (size_t f = 0; rc == 0 && f < sph_snapshot_field_count(sa); f++) {
    const char *name = sph_snapshot_field_name(sa, f);
    if (strcmp(name, sph_snapshot_field_name(sb, f)))
      rc = differ(what, "field lists differ at", name);
    else if (sph_snapshot_read_field(sa, name, va, &err) ||
             sph_snapshot_read_field(sb, name, vb, &err))
      rc = differ(what, err.msg, NULL);
    else if (memcmp(va, vb, n * sizeof *va))
      rc = differ(what, "values differ in field", name);
  }
  free(va);
  free(vb);
  if (rc == 0 && restart) rc = compare_restart(what, sa, sb);
  sph_snapshot_close(sa);
  sph_snapshot_close(sb);
  return rc;
}

int snapcmp_complete(const char *path, size_t *np, double *tp) {
  sph_snapshot *s;
  sph_error err;
  if (sph_snapshot_open(path, &s, &err)) {
    printf("\n  %s\n", err.msg);
    return 0;
  }
  const size_t n = sph_snapshot_count(s);
  int ok = n > 0 && sph_snapshot_field_count(s) >= 11;
  if (!ok) printf("\n  %s: %zu particles, %zu fields\n", path, n, sph_snapshot_field_count(s));
  double *v = malloc((n ? n : 1) * sizeof *v);
  for (size_t f = 0; ok && f < sph_snapshot_field_count(s); f++) {
    const char *name = sph_snapshot_field_name(s, f);
    if (sph_snapshot_read_field(s, name, v, &err)) {
      printf("\n  %s\n", err.msg);
      ok = 0;
    }
    for (size_t i = 0; ok && i < n; i++)
      if (!isfinite(v[i])) {
        printf("\n  %s: field %s row %zu is not finite\n", path, name, i);
        ok = 0;
      }
  }
  free(v);
  if (np) *np = n;
  if (tp) *tp = sph_snapshot_time(s);
  sph_snapshot_close(s);
  return ok;
}

int snapcmp_files(const char *a, const char *b) {
  FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
  int rc = !fa || !fb;
  while (!rc) {
    const int ca = fa ? getc(fa) : EOF, cb = fb ? getc(fb) : EOF;
    if (ca != cb) rc = 1;
    if (ca == EOF || cb == EOF) break;
  }
  if (fa) fclose(fa);
  if (fb) fclose(fb);
  return rc;
}
