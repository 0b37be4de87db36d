/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * cli_info.c - `sph info [--help] SNAPSHOT...`: what a snapshot holds.
 *
 * Prototype (declared in src/cli/cli.h):
 *   int sph_cli_info(int argc, char **argv);
 * argv[0] is "info". For each file, in the order given, prints the path,
 * the case name, time, step, dt, the particle count with the count of each
 * kind (0 fluid, 1 wall), the version that wrote it, and a table of every
 * field with its minimum, maximum and mean (%.9g). Files are separated by a
 * blank line.
 *
 * Invariants: uses only the reading API of snapshot.h, so it shows what any
 * other reader would see; the statistics are sums in file (id) order, so the
 * output is the same on every run; a NaN anywhere in a field makes all three
 * statistics of that field "nan". A file that fails is reported on stderr as
 * "sph info: <message>" and the others are still shown; the exit status is
 * 0 if all were shown, 1 if any failed, 2 for a usage error.
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "sph.h"

static const char USAGE[] =
    "usage: sph info [--help] SNAPSHOT...\n"
    "Prints the header of each HDF5 snapshot (case, time, step, dt, particle\n"
    "counts, version) and the minimum, maximum and mean of every field.\n";

typedef struct field_stats {
  double min, max, mean;
  int nan; /* a NaN was seen */
} field_stats;

/* The compensated (Neumaier) sum of v[0..n-1] / scale. */
static double sum_of(const double *v, size_t n, double scale) {
  double sum = 0.0, carry = 0.0;
  for (size_t i = 0; i < n; i++) {
    const double x = v[i] / scale, t = sum + x;
    carry += fabs(sum) >= fabs(x) ? (sum - t) + x : (x - t) + sum;
    sum = t;
  }
  return sum + carry;
}

/* min, max and mean of v[0..n-1]; the sum is compensated (Neumaier), and
 * scaled by the largest magnitude where it would overflow (finite values
 * near 1e308: issue 39, D8). */
static field_stats stats_of(const double *v, size_t n) {
  field_stats st = {0.0, 0.0, 0.0, 0};
  for (size_t i = 0; i < n; i++) {
    const double x = v[i];
    if (isnan(x)) {
      st.nan = 1;
      return st;
    }
    if (i == 0 || x < st.min) st.min = x;
    if (i == 0 || x > st.max) st.max = x;
  }
  if (!n) return st;
  const double sum = sum_of(v, n, 1.0);
  const double big = fmax(fabs(st.min), fabs(st.max));
  if (isfinite(sum) || !isfinite(big))
    st.mean = sum / (double)n;
  else
    st.mean = sum_of(v, n, big) / (double)n * big;
  return st;
}

static void print_stats(const char *name, field_stats st, size_t n) {
  if (n == 0)
    printf("  %-14s %16s %16s %16s\n", name, "-", "-", "-");
  else if (st.nan)
    printf("  %-14s %16s %16s %16s\n", name, "nan", "nan", "nan");
  else
    printf("  %-14s %16.9g %16.9g %16.9g\n", name, st.min, st.max, st.mean);
}

/* "1000 (fluid 800, wall 200)" from the kind field, when there is one. */
static int print_counts(const sph_snapshot *s, double *buf, sph_error *err) {
  size_t n = sph_snapshot_count(s);
  printf("particles:   %zu", n);
  if (!sph_snapshot_has_field(s, "kind")) {
    printf(" (no kind field)\n");
    return 0;
  }
  if (sph_snapshot_read_field(s, "kind", buf, err)) {
    printf("\n");
    return -1;
  }
  size_t fluid = 0, wall = 0;
  for (size_t i = 0; i < n; i++) {
    fluid += buf[i] == SPH_KIND_FLUID;
    wall += buf[i] == SPH_KIND_WALL;
  }
  printf(" (fluid %zu, wall %zu", fluid, wall);
  if (fluid + wall < n) printf(", other %zu", n - fluid - wall);
  printf(")");
  /* a two-phase run's (physics.air): its fluid by phase */
  if (sph_snapshot_has_field(s, "phase")) {
    double *ph = malloc((n ? n : 1) * sizeof *ph);
    if (!ph) return sph_error_set(err, "out of memory for %zu particles", n);
    if (sph_snapshot_read_field(s, "phase", ph, err)) {
      free(ph);
      printf("\n");
      return -1;
    }
    size_t air = 0;
    for (size_t i = 0; i < n; i++)
      air += buf[i] == SPH_KIND_FLUID && ph[i] == 1.0;
    free(ph);
    printf(": liquid %zu, air %zu", fluid - air, air);
  }
  printf("\n");
  return 0;
}

static void print_header(const sph_snapshot *s) {
  printf("path:        %s\n", sph_snapshot_path(s));
  printf("case:        %s\n", sph_snapshot_text(s, "case_name"));
  printf("time:        %.9g s\n", sph_snapshot_time(s));
  printf("step:        %lld\n", (long long)sph_snapshot_step(s));
  printf("dt:          %.9g s\n", sph_snapshot_dt(s));
}

static void print_version(const sph_snapshot *s) {
  const char *version = sph_snapshot_text(s, "version");
  printf("version:     %s\n", version ? version : "(unknown)");
}

/* A box of the geometry group's as "x [x0, x1] y [y0, y1] (z [z0, z1])". */
static void print_box(const double *b, int dim) {
  static const char axes[3] = {'x', 'y', 'z'};
  for (int a = 0; a < dim; a++)
    printf("%s%c [%.9g, %.9g]", a ? " " : "", axes[a], b[2 * a], b[2 * a + 1]);
}

/* The snapshot's geometry (its group /geometry; a line saying so for a
 * snapshot written before it existed): 0, or -1 with err. */
static int print_geometry(const sph_snapshot *s, sph_error *err) {
  sph_snapshot_geometry g;
  const int rc = sph_snapshot_read_geometry(s, &g, err);
  if (rc < 0) return -1;
  if (rc > 0) {
    printf("geometry:    (not recorded: a snapshot of an earlier build)\n");
    return 0;
  }
  printf("geometry:    tank ");
  if (g.has_tank)
    print_box(g.tank, g.dim);
  else
    printf("none");
  printf("; %zu obstacle%s, %zu wall%s, %zu probe%s\n", g.n_obstacles,
         g.n_obstacles == 1 ? "" : "s", g.n_walls, g.n_walls == 1 ? "" : "s", g.n_probes,
         g.n_probes == 1 ? "" : "s");
  for (size_t k = 0; k < g.n_obstacles; k++) {
    printf("  obstacle %zu: ", k);
    print_box(g.obstacles[k], g.dim);
    printf("\n");
  }
  for (size_t k = 0; k < g.n_probes; k++) {
    const double *q = g.probe_position[k];
    printf("  probe %s (%s) at (%.9g, %.9g", g.probe_name[k], g.probe_kind[k], q[0], q[1]);
    if (g.dim == 3) printf(", %.9g", q[2]);
    printf(")\n");
  }
  sph_snapshot_geometry_free(&g);
  return 0;
}

/* Prints one snapshot, after a blank line if *printed (set here once
 * anything is printed); returns 0, or -1 with err. */
static int show(const char *path, int *printed, sph_error *err) {
  sph_snapshot *s;
  if (sph_snapshot_open(path, &s, err)) return -1;
  if (*printed) printf("\n");
  *printed = 1;
  size_t n = sph_snapshot_count(s);
  double *buf = malloc((n ? n : 1) * sizeof *buf);
  if (!buf) {
    sph_snapshot_close(s);
    return sph_error_set(err, "%s: out of memory for %zu values", path, n);
  }
  print_header(s);
  int rc = print_counts(s, buf, err);
  if (rc == 0) print_version(s);
  if (rc == 0) rc = print_geometry(s, err);
  if (rc == 0) printf("  %-14s %16s %16s %16s\n", "field", "min", "max", "mean");
  for (size_t i = 0; rc == 0 && i < sph_snapshot_field_count(s); i++) {
    const char *name = sph_snapshot_field_name(s, i);
    rc = sph_snapshot_read_field(s, name, buf, err);
    if (rc == 0) print_stats(name, stats_of(buf, n), n);
  }
  free(buf);
  sph_snapshot_close(s);
  return rc;
}

static int show_one(const char *path, void *printed, sph_error *err) {
  return show(path, (int *)printed, err);
}

int sph_cli_info(int argc, char **argv) {
  int n_files;
  int rc = sph_cli_snapshot_args("info", USAGE, argc, argv, &n_files);
  if (rc != 0) return rc < 0 ? 0 : rc;
  int printed = 0;
  return sph_cli_each_snapshot("info", argc, argv, show_one, &printed);
}
