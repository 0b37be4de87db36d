/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_freesurface_run.c - free-surface detection (paper A §7) inside a
 * real run: issue 3, free-surface test (4).
 *
 * 1. The coarse Martin & Moyce dam break (cases/martin_moyce_coarse.yaml,
 *    --set output.free_surface=true --set time.end=0.1) is run through the
 *    `sph` program with 2 threads and every loop parallel (SPH_TEST_OMP_MIN=0).
 *    In its snapshot at t = 0.1 s the ids of the fluid particles whose
 *    free_surface flag is set must equal golden/freesurface/
 *    dam_break_coarse_t0.1.csv exactly (written from a 1-thread run, so the
 *    comparison also says the flags do not depend on the thread count); no
 *    wall particle is flagged. diagnostics.csv has the n_free_surface
 *    column, and its value at t = 0.1 s is the number of flagged fluid
 *    particles in the snapshot.
 * 2. free_surface.h_factor=2 (h* = 2h on surface particles): the run works
 *    and the h field of its last snapshot holds exactly two values, h (the
 *    snapshot's "h" attribute) and 2h, with 2h on exactly the flagged fluid
 *    particles.
 *
 * 3. numerics.smoothing_length=variable (paper B, h = h0 sqrt(rho0/rho)) with
 *    the flags in the output: detection leaves the smoothing lengths alone
 *    (it once reset them to h0, and to 0 on surface particles, so the MLS
 *    filter refused the state): every particle's h in the last snapshot
 *    is h0 sqrt(rho0/rho) of its density, and surface particles are flagged.
 *
 * `test_freesurface_run --regen` (SPH_SRCDIR, SPH_BUILDDIR set, as `make
 * golden` does through tests/regen_golden.sh) rewrites the golden file
 * from a 1-thread run instead of testing.
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/particles.h"
#include "core/version.h"
#include "io/snapshot.h"
#include "testutil.h"

#define GOLDEN "golden/freesurface/dam_break_coarse_t0.1.csv"
#define T_OUT 0.1
#define RUN_ARGS "--set output.free_surface=true --set time.end=0.1"

static char *tmpdir;

/* Runs the coarse dam break with RUN_ARGS and `extra` into dir. */
static int run_sph(const char *dir, int threads, const char *extra) {
  char cmd[12000];
  snprintf(cmd, sizeof cmd, "SPH_TEST_OMP_MIN=0 '%s' run --quiet --threads %d '%s' -o '%s' %s %s",
           sph_test_build("src/sph"), threads, sph_test_src("cases/martin_moyce_coarse.yaml"), dir,
           RUN_ARGS, extra);
  return sph_test_system(cmd);
}

/* The path of the last snapshot snap_NNNN.h5 in dir (the run's end). */
static int last_snapshot(const char *dir, char *path, size_t len) {
  int found = -1;
  for (int k = 0; k < 10000; k++) {
    char p[4200];
    snprintf(p, sizeof p, "%s/snap_%04d.h5", dir, k);
    FILE *f = fopen(p, "rb");
    if (!f) break;
    fclose(f);
    found = k;
  }
  if (found < 0) return -1;
  snprintf(path, len, "%s/snap_%04d.h5", dir, found);
  return 0;
}

typedef struct flagged {
  size_t n, cap;
  long long *id; /* ascending */
  size_t wall_flagged;
  double time;
} flagged;

static int cmp_ll(const void *a, const void *b) {
  const long long x = *(const long long *)a, y = *(const long long *)b;
  return (x > y) - (x < y);
}

static void push(flagged *f, long long id) {
  if (f->n == f->cap) {
    f->cap = f->cap ? 2 * f->cap : 64;
    f->id = realloc(f->id, f->cap * sizeof *f->id);
    if (!f->id) abort();
  }
  f->id[f->n++] = id;
}

/* Reads the flagged particle ids of a snapshot through the reading API and
 * the "h" attribute into h0. When h_out is not NULL, h_out, kind_out and
 * fs_out receive malloc'ed copies of the fields h, kind and free_surface
 * (n_out values). */
static int read_flags(const char *path, flagged *f, double **h_out, double **kind_out,
                      double **fs_out, size_t *n_out, double *h0) {
  sph_snapshot *s;
  sph_error err;
  memset(f, 0, sizeof *f);
  if (sph_snapshot_open(path, &s, &err)) {
    printf("\n%s\n", err.msg);
    return -1;
  }
  const size_t n = sph_snapshot_count(s);
  double *id = malloc(n * sizeof *id), *kind = malloc(n * sizeof *kind),
         *fs = malloc(n * sizeof *fs), *h = malloc(n * sizeof *h);
  int rc = (!id || !kind || !fs || !h) ? -1 : 0;
  if (rc == 0 && !sph_snapshot_has_field(s, "free_surface")) {
    printf("\n%s: no free_surface field\n", path);
    rc = -1;
  }
  if (rc == 0)
    rc = sph_snapshot_read_field(s, "id", id, &err) ||
         sph_snapshot_read_field(s, "kind", kind, &err) ||
         sph_snapshot_read_field(s, "free_surface", fs, &err) ||
         sph_snapshot_read_field(s, "h", h, &err) || sph_snapshot_number(s, "h", h0, 1, &err);
  if (rc) printf("\n%s\n", err.msg);
  f->time = sph_snapshot_time(s);
  for (size_t i = 0; rc == 0 && i < n; i++) {
    if (fs[i] == 0.0) continue;
    if (kind[i] == SPH_KIND_FLUID)
      push(f, (long long)id[i]);
    else
      f->wall_flagged++;
  }
  if (f->n) qsort(f->id, f->n, sizeof *f->id, cmp_ll);
  sph_snapshot_close(s);
  free(id);
  if (rc == 0 && h_out) {
    *h_out = h;
    *kind_out = kind;
    *fs_out = fs;
    *n_out = n;
  } else {
    free(h);
    free(kind);
    free(fs);
  }
  return rc ? -1 : 0;
}

/* Ids from the golden CSV: '#' lines and the "id" header skipped. */
static int read_golden(const char *path, flagged *f) {
  memset(f, 0, sizeof *f);
  double *c[1] = {NULL};
  const long n = sph_test_csv(path, "id", c);
  for (long i = 0; i < n; i++)
    push(f, (long long)c[0][i]);
  free(c[0]);
  if (f->n) qsort(f->id, f->n, sizeof *f->id, cmp_ll);
  return f->n ? 0 : -1;
}

/* The n_free_surface of the diagnostics row at time t (-1 if absent). */
static long diag_surface_count(const char *path, double t) {
  double *c[2] = {NULL, NULL};
  const long n = sph_test_csv(path, "time,n_free_surface", c);
  long found = -1;
  for (long i = 0; i < n; i++)
    if (fabs(c[0][i] - t) < 1e-12) found = (long)c[1][i];
  free(c[0]);
  free(c[1]);
  return found;
}

static void test_flags_match_golden(void) {
  char dir[4200], snap[4300], diag[4300];
  snprintf(dir, sizeof dir, "%s/run", tmpdir);
  CU_ASSERT_FATAL(run_sph(dir, 2, "") == 0);
  CU_ASSERT_FATAL(last_snapshot(dir, snap, sizeof snap) == 0);
  flagged run, gold;
  double h0;
  CU_ASSERT_FATAL(read_flags(snap, &run, NULL, NULL, NULL, NULL, &h0) == 0);
  CU_ASSERT_DOUBLE_EQUAL(run.time, T_OUT, 1e-12);
  CU_ASSERT_EQUAL(run.wall_flagged, 0);
  CU_ASSERT_FATAL(read_golden(sph_test_src(GOLDEN), &gold) == 0);
  size_t only_run = 0, only_gold = 0, i = 0, j = 0;
  while (i < run.n || j < gold.n) {
    if (j == gold.n || (i < run.n && run.id[i] < gold.id[j])) {
      printf("\n  flagged in the run, not in the golden file: id %lld", run.id[i]);
      only_run++;
      i++;
    } else if (i == run.n || gold.id[j] < run.id[i]) {
      printf("\n  flagged in the golden file, not in the run: id %lld", gold.id[j]);
      only_gold++;
      j++;
    } else {
      i++;
      j++;
    }
  }
  printf("\n  t = %.9g s: %zu fluid particles flagged (golden %zu)\n", run.time, run.n, gold.n);
  CU_ASSERT_EQUAL(only_run, 0);
  CU_ASSERT_EQUAL(only_gold, 0);
  CU_ASSERT(run.n > 20);
  snprintf(diag, sizeof diag, "%s/diagnostics.csv", dir);
  const long n_diag = diag_surface_count(diag, run.time);
  printf("  diagnostics.csv n_free_surface at t = %.9g s: %ld\n", run.time, n_diag);
  CU_ASSERT_EQUAL(n_diag, (long)run.n);
  free(run.id);
  free(gold.id);
}

static void test_h_factor(void) {
  char dir[4200], snap[4300];
  snprintf(dir, sizeof dir, "%s/h2", tmpdir);
  CU_ASSERT_FATAL(run_sph(dir, 2, "--set free_surface.h_factor=2") == 0);
  CU_ASSERT_FATAL(last_snapshot(dir, snap, sizeof snap) == 0);
  flagged f;
  double *h = NULL, *kind = NULL, *fs = NULL, h0 = 0.0;
  size_t n = 0;
  CU_ASSERT_FATAL(read_flags(snap, &f, &h, &kind, &fs, &n, &h0) == 0);
  CU_ASSERT_DOUBLE_EQUAL(f.time, T_OUT, 1e-12);
  size_t n_h = 0, n_2h = 0, other = 0, misplaced = 0;
  for (size_t i = 0; i < n; i++) {
    const int surface = kind[i] == SPH_KIND_FLUID && fs[i] != 0.0;
    if (h[i] == h0)
      n_h++;
    else if (h[i] == 2.0 * h0)
      n_2h++;
    else
      other++;
    if ((h[i] == 2.0 * h0) != surface) misplaced++;
  }
  printf("\n  h* = 2h: %zu particles with h, %zu with 2h (flagged fluid: %zu), %zu other, "
         "%zu misplaced\n",
         n_h, n_2h, f.n, other, misplaced);
  CU_ASSERT(n_h > 0);
  CU_ASSERT(n_2h > 0);
  CU_ASSERT_EQUAL(other, 0);
  CU_ASSERT_EQUAL(misplaced, 0);
  CU_ASSERT_EQUAL(n_2h, f.n);
  free(h);
  free(kind);
  free(fs);
  free(f.id);
}

static void test_variable_h(void) {
  char dir[4200], snap[4300];
  snprintf(dir, sizeof dir, "%s/varh", tmpdir);
  CU_ASSERT_FATAL(run_sph(dir, 2,
                          "--set numerics.smoothing_length=variable "
                          "--set numerics.density_filter.kind=mls") == 0);
  CU_ASSERT_FATAL(last_snapshot(dir, snap, sizeof snap) == 0);
  sph_snapshot *s;
  sph_error err;
  CU_ASSERT_FATAL(sph_snapshot_open(snap, &s, &err) == 0);
  sph_particles p;
  CU_ASSERT_FATAL(sph_snapshot_read_particles(s, &p, &err) == 0);
  double h0 = 0.0;
  CU_ASSERT_FATAL(sph_snapshot_number(s, "h", &h0, 1, &err) == 0);
  sph_snapshot_close(s);
  size_t bad = 0, surface = 0, distinct = 0;
  double worst = 0.0;
  for (size_t i = 0; i < p.n; i++) {
    const double want = h0 * sqrt(1000.0 / p.rho[i]);
    const double e = fabs(p.h[i] - want) / want;
    if (e > worst) worst = e;
    bad += e > 1e-12;
    distinct += p.h[i] != h0;
    surface += p.kind[i] == SPH_KIND_FLUID && (p.flags[i] & SPH_FLAG_FREE_SURFACE);
  }
  printf("\n  variable h: %zu particles, %zu flagged on the surface, %zu with h != h0, "
         "worst |h - h0 sqrt(rho0/rho)| / h %.2e\n",
         p.n, surface, distinct, worst);
  CU_ASSERT_EQUAL(bad, 0);
  CU_ASSERT(surface > 50);
  CU_ASSERT(distinct > p.n / 2);
  sph_particles_free(&p);
}

/* --regen: a 1-thread run, its flags written to the golden file. */
static int regenerate(void) {
  char dir[4200], snap[4300], out[4300];
  snprintf(dir, sizeof dir, "%s/regen", tmpdir);
  if (run_sph(dir, 1, "") != 0 || last_snapshot(dir, snap, sizeof snap)) {
    fprintf(stderr, "test_freesurface_run --regen: the run failed\n");
    return 1;
  }
  flagged f;
  double h0;
  if (read_flags(snap, &f, NULL, NULL, NULL, NULL, &h0) || fabs(f.time - T_OUT) > 1e-12) {
    fprintf(stderr, "test_freesurface_run --regen: cannot read %s at t = %g\n", snap, T_OUT);
    return 1;
  }
  snprintf(out, sizeof out, "%s", sph_test_src(GOLDEN));
  char tmp[4400];
  snprintf(tmp, sizeof tmp, "%s.tmp", out);
  FILE *o = fopen(tmp, "w");
  if (!o) {
    perror(tmp);
    return 1;
  }
  fprintf(o, "# golden: ids of the fluid particles flagged on the free surface (paper A §7) in\n"
             "# the snapshot at t = 0.1 s of the coarse dam break, issue 3 free-surface test (4).\n"
             "# command: sph run --threads 1 cases/martin_moyce_coarse.yaml " RUN_ARGS "\n");
  fprintf(o, "# made by: tests/test_freesurface_run --regen (make golden), %s\n", sph_version());
  fprintf(o,
          "# why: the flags of a real run must not change unnoticed; tests/test_freesurface_run\n"
          "# compares the set exactly (its 2-thread run must give the same ids).\n"
          "id\n");
  for (size_t i = 0; i < f.n; i++)
    fprintf(o, "%lld\n", f.id[i]);
  free(f.id);
  if (fclose(o) || rename(tmp, out)) {
    perror(out);
    return 1;
  }
  printf("wrote %s (%zu ids)\n", out, f.n);
  return 0;
}

int main(int argc, char **argv) {
  tmpdir = sph_test_tmpdir();
  int rc;
  if (argc > 1 && !strcmp(argv[1], "--regen")) {
    rc = regenerate();
  } else {
    CU_TestInfo tests[] = {
        {"dam break at t = 0.1 s: flags equal the golden ids, diagnostics agree",
         test_flags_match_golden},
        {"free_surface.h_factor=2: h on the interior, 2h on flagged fluid", test_h_factor},
        {"variable h with the flags: h = h0 sqrt(rho0/rho) everywhere", test_variable_h},
        CU_TEST_INFO_NULL};
    rc = sph_test_main("freesurface_run", tests);
  }
  sph_test_rmtree(tmpdir);
  free(tmpdir);
  return rc;
}
