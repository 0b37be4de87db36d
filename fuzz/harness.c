/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * harness.c - the fuzz targets (harness.h).
 *
 * Both targets exercise only the public API, the way `sph run` and
 * `sph info` (and the renderer) use it, and then check what the API
 * promises; they never print.
 */
#include "config.h"

#include "harness.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "case/case.h"
#include "io/csv.h"
#include "io/snapshot.h"

#define MAX_SETS 8

static void check(int ok) {
  if (!ok) abort();
}

int sph_fuzz_case(const uint8_t *data, size_t len) {
  char *text = malloc(len + 1);
  check(text != NULL);
  memcpy(text, data, len);
  text[len] = 0;
  /* "#set KEY=VALUE" lines become overrides (copied: NUL-terminated) */
  char *sets[MAX_SETS];
  size_t n_set = 0;
  for (size_t i = 0; i + 5 <= len && n_set < MAX_SETS; i++) {
    if ((i > 0 && text[i - 1] != '\n') || memcmp(text + i, "#set ", 5)) continue;
    const char *v = text + i + 5;
    const size_t n = strcspn(v, "\n");
    if (!memchr(v, '=', n)) continue; /* the CLI rejects these before parsing */
    sets[n_set] = malloc(n + 1);
    check(sets[n_set] != NULL);
    memcpy(sets[n_set], v, n);
    sets[n_set][n] = 0;
    n_set++;
  }
  sph_case c, c2;
  sph_error err, err2;
  memset(&err, 0, sizeof err);
  memset(&err2, 0, sizeof err2);
  const int rc = sph_case_parse(text, len, "fuzz.yaml", (const char *const *)sets, n_set, &c, &err);
  const int rc2 =
      sph_case_parse(text, len, "fuzz.yaml", (const char *const *)sets, n_set, &c2, &err2);
  check((rc == 0) == (rc2 == 0));
  if (rc) {
    /* a clear error: one line, naming where (the file or an override) */
    check(err.msg[0] != 0 && memchr(err.msg, 0, sizeof err.msg) != NULL);
    check(strstr(err.msg, "fuzz.yaml") != NULL || strstr(err.msg, "--set") != NULL ||
          strstr(err.msg, "out of memory") != NULL);
    check(strcmp(err.msg, err2.msg) == 0);
  } else {
    char *d = sph_case_describe(&c), *d2 = sph_case_describe(&c2);
    check(d && d2 && d[0] && strcmp(d, d2) == 0);
    check(c.name && c.name[0] && c.dx > 0.0 && c.h > 0.0 && c.t_end > 0.0 && c.n_fluid >= 1);
    free(d);
    free(d2);
  }
  sph_case_free(&c);
  sph_case_free(&c2);
  for (size_t i = 0; i < n_set; i++)
    free(sets[i]);
  free(text);
  return 0;
}

int sph_fuzz_snapshot(const uint8_t *data, size_t len, const char *scratch) {
  FILE *f = fopen(scratch, "wb");
  check(f != NULL);
  check(fwrite(data, 1, len, f) == len || len == 0);
  check(fclose(f) == 0);
  sph_snapshot *s;
  sph_error err;
  memset(&err, 0, sizeof err);
  if (sph_snapshot_open(scratch, &s, &err)) {
    check(strstr(err.msg, scratch) != NULL);
    return 0;
  }
  const size_t n = sph_snapshot_count(s);
  (void)sph_snapshot_time(s);
  (void)sph_snapshot_dt(s);
  (void)sph_snapshot_step(s);
  check(sph_snapshot_text(s, "case_name") != NULL);
  const char *names[] = {"case_text", "overrides",      "parameters",
                         "version",   "configure_args", "compiler"};
  for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
    (void)sph_snapshot_text(s, names[i]);
  double view[4], one;
  if (sph_snapshot_number(s, "view", view, 4, &err)) check(strstr(err.msg, scratch) != NULL);
  if (sph_snapshot_number(s, "dx", &one, 1, &err)) check(strstr(err.msg, scratch) != NULL);
  /* every field, as sph info and the renderer read them; a huge count
   * that the file cannot back is refused by the reads, not allocated */
  if (n <= (size_t)1 << 24) {
    double *v = malloc((n ? n : 1) * sizeof *v);
    check(v != NULL);
    for (size_t i = 0; i < sph_snapshot_field_count(s); i++) {
      const char *name = sph_snapshot_field_name(s, i);
      check(name != NULL && sph_snapshot_has_field(s, name));
      if (sph_snapshot_read_field(s, name, v, &err)) check(strstr(err.msg, scratch) != NULL);
    }
    free(v);
    sph_particles p;
    if (sph_snapshot_read_particles(s, &p, &err) == 0) {
      check(p.n == n);
      for (size_t i = 0; i < n; i++)
        check(p.id[i] == (int64_t)i);
      sph_particles_free(&p);
    } else {
      check(strstr(err.msg, scratch) != NULL);
    }
    sph_snapshot_restart_data r;
    if (sph_snapshot_read_restart(s, &r, &err) == 0) {
      check(r.count == n);
      unsigned char *seen = calloc(n ? n : 1, 1);
      check(seen != NULL);
      for (size_t k = 0; k < n; k++) {
        check(r.order[k] >= 0 && (size_t)r.order[k] < n && !seen[r.order[k]]);
        seen[r.order[k]] = 1;
      }
      free(seen);
      sph_snapshot_restart_free(&r);
    } else {
      check(strstr(err.msg, scratch) != NULL);
    }
    /* the geometry group: read whole, absent, or refused naming the file */
    sph_snapshot_geometry g;
    const int gr = sph_snapshot_read_geometry(s, &g, &err);
    if (gr == 0) {
      check(g.dim == 2 || g.dim == 3);
      for (size_t k = 0; k < g.n_probes; k++)
        check(memchr(g.probe_name[k], 0, SPH_GEOMETRY_NAME) != NULL);
      sph_snapshot_geometry_free(&g);
    } else if (gr < 0) {
      check(strstr(err.msg, scratch) != NULL);
    }
  }
  sph_snapshot_close(s);
  return 0;
}

int sph_fuzz_csv(const uint8_t *data, size_t len, const char *scratch) {
  FILE *f = fopen(scratch, "wb");
  check(f != NULL);
  check(fwrite(data, 1, len, f) == len || len == 0);
  check(fclose(f) == 0);
  sph_csv t;
  sph_error err;
  memset(&err, 0, sizeof err);
  if (sph_csv_read(scratch, &t, &err)) {
    check(strstr(err.msg, scratch) != NULL && strchr(err.msg, '\n') == NULL);
    return 0;
  }
  check(t.ncol > 0 && t.names != NULL);
  check(t.nrow == 0 || t.data != NULL);
  double sum = 0.0;
  for (size_t k = 0; k < t.nrow * t.ncol; k++)
    sum += t.data[k] == t.data[k] ? 0.0 : 1.0; /* every value is read */
  (void)sum;
  for (size_t c = 0; c < t.ncol; c++) {
    check(t.names[c] != NULL);
    size_t same = 0; /* columns of exactly this name */
    for (size_t k = 0; k < t.ncol; k++)
      same += strcmp(t.names[k], t.names[c]) == 0;
    const int found = sph_csv_column(&t, t.names[c], &err);
    /* a name of one column finds it; a name twice is ambiguous (issue 61, E10) */
    check(same == 1 ? found == (int)c : found == -1);
  }
  sph_csv_free(&t);
  return 0;
}
