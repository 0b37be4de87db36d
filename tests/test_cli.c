/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_cli.c - the `sph` program as a user meets it: help and version, and
 * bad input (missing case file, unknown key, wrong type, bad option, bad
 * --set) gives a non-zero exit status and a message naming the file, line
 * and key. Also a short good run followed by `sph info` on its snapshot.
 */
#include "config.h"

#include <hdf5.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/particles.h"
#include "io/snapshot.h"
#include "testutil.h"

static char *tmp;

/* Runs `sph ARGS` (output in tmp/sph.log, returned in out). */
static int sph(const char *args, char *out, size_t len) {
  return sph_test_sph(args, tmp, out, len);
}
/* The same for a run that should succeed (its output printed if not). */
static int sph_ok(const char *args, char *out, size_t len) {
  return sph_test_sph_ok(args, tmp, out, len);
}

static void write_file(const char *name, const char *text) {
  char path[4096];
  snprintf(path, sizeof path, "%s/%s", tmp, name);
  FILE *f = fopen(path, "w");
  CU_ASSERT_FATAL(f != NULL);
  fputs(text, f);
  fclose(f);
}

static const char *GOOD = "name: tiny\n"
                          "physics:\n"
                          "  sound_speed: 10\n"
                          "  artificial_viscosity: {alpha: 0.1}\n"
                          "numerics:\n"
                          "  dx: 0.01\n"
                          "time:\n"
                          "  end: 0.002\n"
                          "  output_interval: 0.001\n"
                          "geometry:\n"
                          "  tank: {x: [0, 0.1], y: [0, 0.1]}\n"
                          "  fluid:\n"
                          "    - {x: [0, 0.05], y: [0, 0.05]}\n";

static void test_help_and_version(void) {
  char out[65536];
  CU_ASSERT_EQUAL(sph("--help", out, sizeof out), 0);
  CU_ASSERT(strstr(out, "run CASE") != NULL && strstr(out, "info SNAPSHOT") != NULL);
  CU_ASSERT_EQUAL(sph("run --help", out, sizeof out), 0);
  CU_ASSERT(strstr(out, "--threads") != NULL && strstr(out, "--set") != NULL);
  CU_ASSERT_EQUAL(sph("--version", out, sizeof out), 0);
  CU_ASSERT(strstr(out, "sph ") != NULL);
  CU_ASSERT_EQUAL(sph("", out, sizeof out), 2);
  CU_ASSERT_EQUAL(sph("frobnicate", out, sizeof out), 2);
  CU_ASSERT(strstr(out, "unknown command") != NULL);
}

static void test_bad_input(void) {
  char out[65536], args[8192];
  /* missing file */
  snprintf(args, sizeof args, "run '%s/nope.yaml' -o '%s/o1'", tmp, tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 1);
  CU_ASSERT(strstr(out, "nope.yaml") != NULL);
  /* a bare name: ./cases/NAME.yaml, as in the source tree (issue 39, D11) */
  char cmd[16384];
  write_file("byname.yaml", GOOD);
  snprintf(cmd, sizeof cmd,
           "cd '%s' && mkdir -p cases && mv byname.yaml cases/ && '%s' run -q byname -o o_byname "
           "> byname.log 2>&1",
           tmp, sph_test_build("src/sph"));
  CU_ASSERT_EQUAL(sph_test_system(cmd), 0);
  snprintf(cmd, sizeof cmd, "cd '%s' && '%s' run -q no_such_name > byname2.log 2>&1", tmp,
           sph_test_build("src/sph"));
  CU_ASSERT_EQUAL(sph_test_system(cmd), 1);
  snprintf(cmd, sizeof cmd,
           "grep -q 'no_such_name: no such case file here, no case of that name in ./cases or in' "
           "'%s/byname2.log'",
           tmp);
  CU_ASSERT_EQUAL(sph_test_system(cmd), 0);
  /* unknown key, on line 3 */
  write_file("badkey.yaml", "name: x\nphysics:\n  sound_sped: 10\n");
  snprintf(args, sizeof args, "run '%s/badkey.yaml' -o '%s/o2'", tmp, tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 1);
  CU_ASSERT(strstr(out, "badkey.yaml:3") != NULL);
  CU_ASSERT(strstr(out, "sound_sped") != NULL);
  /* wrong type */
  write_file("good.yaml", GOOD);
  snprintf(args, sizeof args, "run '%s/good.yaml' -o '%s/o3' --set numerics.dx=abc", tmp, tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 1);
  CU_ASSERT(strstr(out, "numerics.dx") != NULL);
  /* bad options */
  snprintf(args, sizeof args, "run '%s/good.yaml' --threads 0", tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 2);
  /* bounds are named (issue 39, D8) */
  snprintf(args, sizeof args, "run '%s/good.yaml' --threads 100000", tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 2);
  CU_ASSERT(strstr(out, "--threads: expected a whole number from 1 to 4096, got '100000'") != NULL);
  char many[512] = "";
  for (int k = 0; k < 35; k++)
    snprintf(many + strlen(many), sizeof many - strlen(many), "%s%d", k ? "," : "", 100 + k);
  snprintf(args, sizeof args, "audit '%s/good.yaml' --particles %s", tmp, many);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 2);
  CU_ASSERT(strstr(out, "--particles: expected 1 to 32 whole numbers") != NULL);
  snprintf(args, sizeof args, "run '%s/good.yaml' --bogus", tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 2);
  snprintf(args, sizeof args, "run '%s/good.yaml' --set novalue", tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 2);
  CU_ASSERT_EQUAL(sph("run", out, sizeof out), 2);
  /* info on a directory: one line, no HDF5 timestamp or address (issue 21, D10) */
  snprintf(args, sizeof args, "info '%s'", tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 1);
  CU_ASSERT(strstr(out, "Is a directory") != NULL);
  CU_ASSERT(strchr(out, '\n') == out + strlen(out) - 1);
  CU_ASSERT(strstr(out, "time =") == NULL && strstr(out, "0x") == NULL);
  /* info on a missing snapshot */
  snprintf(args, sizeof args, "info '%s/missing.h5'", tmp);
  CU_ASSERT_NOT_EQUAL(sph(args, out, sizeof out), 0);
  CU_ASSERT(strstr(out, "missing.h5") != NULL);
}

static int dir_exists(const char *name) {
  char path[4200];
  snprintf(path, sizeof path, "%s/%s", tmp, name);
  FILE *f = fopen(path, "r");
  if (f) fclose(f);
  return f != NULL;
}

/* The particle count is bounded before any particle is made (issue 21,
 * D3, D4): a tiny dx, a denormal dx, a wall 2000 km long and a bound asked
 * for are refused at once with exit 1, naming numerics.dx, and nothing is
 * written; a bad --max-particles is a usage error. */
static void test_resource_bound(void) {
  char out[65536], args[8192];
  write_file("good.yaml", GOOD);
  const char *sets[] = {"--set numerics.dx=1e-7", "--set numerics.dx=4.9e-324",
                        "--set 'geometry.walls=[{from: [0, 0], to: [2e6, 0]}]'",
                        "--max-particles 100"};
  for (int k = 0; k < 4; k++) {
    snprintf(args, sizeof args, "run '%s/good.yaml' -o '%s/big%d' %s", tmp, tmp, k, sets[k]);
    const int st = sph(args, out, sizeof out);
    CU_ASSERT_EQUAL(st, 1);
    CU_ASSERT(strstr(out, "numerics.dx") != NULL && strstr(out, "particles") != NULL &&
              strstr(out, "--max-particles") != NULL);
    if (st != 1 || !strstr(out, "numerics.dx")) printf("\n  %s\n  -> %d: %s", sets[k], st, out);
    char name[32];
    snprintf(name, sizeof name, "big%d", k);
    CU_ASSERT(!dir_exists(name));
  }
  CU_ASSERT(strstr(out, "good.yaml:6: numerics.dx: 0.01 makes about") != NULL);
  /* sph audit has the bound too, the option its message names (issue 39, D8) */
  snprintf(args, sizeof args,
           "audit '%s/good.yaml' -q -o '%s/big_audit' -p 1000 --max-particles 100", tmp, tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 1);
  CU_ASSERT(strstr(out, "the bound asked for; --max-particles N changes it") != NULL);
  snprintf(args, sizeof args, "audit --help");
  CU_ASSERT_EQUAL(sph_ok(args, out, sizeof out), 0);
  CU_ASSERT(strstr(out, "--max-particles N") != NULL);
  snprintf(args, sizeof args, "run '%s/good.yaml' --max-particles 0", tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 2);
  snprintf(args, sizeof args, "run '%s/good.yaml' --max-particles 1e12", tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 2);
  /* the listing states the memory and the bound */
  snprintf(args, sizeof args, "run '%s/good.yaml' -o '%s/ok' --max-particles 10000", tmp, tmp);
  CU_ASSERT_EQUAL(sph_ok(args, out, sizeof out), 0);
  CU_ASSERT(strstr(out, "at most 10000 particles allowed") != NULL);
  /* the count and the memory come before the set-up, the particles made after it */
  const char *plan = strstr(out, "setting up about "), *made = strstr(out, "  particles ");
  CU_ASSERT(plan != NULL && made != NULL && plan < made);
  CU_ASSERT(plan != NULL && strstr(plan, "memory about") != NULL);
  /* in the unit that reads (issue 39, D11): GB, not 2.4e+05 MB */
  snprintf(args, sizeof args,
           "run '%s/good.yaml' -o '%s/gb' --max-particles 100 --set numerics.dx=0.000025", tmp,
           tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 1); /* refused after the plan, before the set-up */
  const char *gb = strstr(out, "memory about ");
  double amount = 0.0;
  char unit[3] = "";
  CU_ASSERT(gb != NULL && sscanf(gb, "memory about %lf %2s", &amount, unit) == 2);
  CU_ASSERT(amount > 4.0 && amount < 5.0 && strcmp(unit, "GB") == 0);
  if (strcmp(unit, "GB")) printf("\n  %s", out);
  /* a blow-up at a fixed step names the step the rule would have taken */
  snprintf(args, sizeof args,
           "run '%s/good.yaml' -o '%s/fixed' --set numerics.time_step.rule=fixed "
           "--set numerics.time_step.dt=0.01 --set time.end=0.5 --set time.output_interval=0.1",
           tmp, tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 3);
  CU_ASSERT(strstr(out, "the fixed time step 0.01 s is") != NULL &&
            strstr(out, "paper B's rule (time_step.rule: paper_b, factor 0.3)") != NULL);
}

static void test_good_run_and_info(void) {
  char out[65536], args[8192], path_huge[4200];
  write_file("good.yaml", GOOD);
  snprintf(args, sizeof args, "run '%s/good.yaml' -o '%s/run' --set time.end=0.003", tmp, tmp);
  CU_ASSERT_EQUAL_FATAL(sph_ok(args, out, sizeof out), 0);
  CU_ASSERT(strstr(out, "particles") != NULL);
  snprintf(args, sizeof args, "info '%s/run/snap_0003.h5'", tmp);
  CU_ASSERT_EQUAL(sph_ok(args, out, sizeof out), 0);
  CU_ASSERT(strstr(out, "tiny") != NULL);
  CU_ASSERT(strstr(out, "rho") != NULL);
  /* the mean of finite values near 1e308 is finite (issue 39, D8) */
  {
    sph_particles p;
    sph_error err;
    CU_ASSERT_FATAL(sph_particles_init(&p, 4, &err) == 0);
    const double xs[3] = {1e308, 1.5e308, 1.7e308};
    for (int k = 0; k < 3; k++)
      CU_ASSERT_FATAL(sph_particles_add(&p, xs[k], 0, 0, 0, 1000, 0.1, 0.013, 0, &err) == k);
    sph_snapshot_meta m;
    memset(&m, 0, sizeof m);
    m.case_name = "huge";
    snprintf(path_huge, sizeof path_huge, "%s/huge.h5", tmp);
    CU_ASSERT_FATAL(sph_snapshot_write(path_huge, &m, &p, &err) == 0);
    sph_particles_free(&p);
    snprintf(args, sizeof args, "info '%s'", path_huge);
    CU_ASSERT_EQUAL(sph_ok(args, out, sizeof out), 0);
    const char *x = strstr(out, "\n  x ");
    double lo = 0, hi = 0, mean = 0;
    CU_ASSERT(x != NULL && sscanf(x, " x %lf %lf %lf", &lo, &hi, &mean) == 3);
    CU_ASSERT(lo == 1e308 && hi == 1.7e308 && fabs(mean / 1.4e308 - 1.0) < 1e-9);
    if (!x || !(fabs(mean / 1.4e308 - 1.0) < 1e-9)) printf("\n%s", out);
  }
  /* diagnostics: a header and one row per output time (0, 1, 2, 3 ms) */
  char path[4096];
  snprintf(path, sizeof path, "%s/run/diagnostics.csv", tmp);
  FILE *f = fopen(path, "r");
  CU_ASSERT_FATAL(f != NULL);
  char line[4096];
  int lines = 0;
  CU_ASSERT(fgets(line, sizeof line, f) != NULL);
  CU_ASSERT_STRING_EQUAL(line, "time (s),step,dt (s),n_fluid,front_x (m),mass (kg/m),momentum_x "
                               "(kg/s),momentum_y (kg/s),kinetic (J/m),potential (J/m)\n");
  while (fgets(line, sizeof line, f))
    lines++;
  fclose(f);
  CU_ASSERT_EQUAL(lines, 4);
}

/* A listed output time that is also a multiple of the interval up to
 * rounding (3 * 0.0077 = 0.023100000000000002, listed 0.0231) is one
 * output: 0, 0.0077, 0.0154, 0.0231, 0.03 give five snapshots and five
 * diagnostics rows, not a sixth after a step of 2e-18 s. */
static void test_output_times_merge(void) {
  char out[65536], args[8192];
  write_file("good.yaml", GOOD);
  snprintf(args, sizeof args,
           "run '%s/good.yaml' -o '%s/merge' --set time.end=0.03 "
           "--set time.output_interval=0.0077 --set 'time.output_times=[0.0231]'",
           tmp, tmp);
  CU_ASSERT_EQUAL_FATAL(sph_ok(args, out, sizeof out), 0);
  snprintf(args, sizeof args,
           "test -s '%s/merge/snap_0004.h5' && ! test -e '%s/merge/snap_0005.h5'", tmp, tmp);
  CU_ASSERT_EQUAL(sph_test_system(args), 0);
  char path[4096], line[4096];
  snprintf(path, sizeof path, "%s/merge/diagnostics.csv", tmp);
  FILE *f = fopen(path, "r");
  CU_ASSERT_FATAL(f != NULL);
  int lines = 0;
  double last = -1.0, t;
  int increasing = 1;
  CU_ASSERT(fgets(line, sizeof line, f) != NULL);
  while (fgets(line, sizeof line, f)) {
    lines++;
    if (sscanf(line, "%lf", &t) == 1) {
      if (!(t > last)) increasing = 0;
      last = t;
    }
  }
  fclose(f);
  CU_ASSERT_EQUAL(lines, 5);
  CU_ASSERT(increasing);
  CU_ASSERT_DOUBLE_EQUAL(last, 0.03, 1e-15);
}

/* A case that must blow up: fluid dropped onto the floor with a sound
 * speed far too low for the impact, and a strict density limit. */
/* numerics.scheme is its keys: a run with `scheme: riemann` (the default)
 * and one with delta_sph write the same diagnostics, byte for byte, as the
 * same case with all eleven of the scheme's keys written out (src/case/presets.c);
 * the start-up listing names the scheme's keys a case gives itself. */
static void test_scheme_is_its_keys(void) {
  static const struct {
    const char *scheme, *physics, *numerics, *tank;
  } cases[] = {
      {"riemann",
       "  riemann: {limiter: 3}\n  artificial_viscosity: {alpha: 0}\n  xsph: 0\n"
       "  viscosity: {model: none}\n  negative_pressure: false\n",
       "  density_diffusion: {model: none}\n  kernel: wendland_c2\n  h_factor: 2\n"
       "  time_step: {rule: cfl}\n  integrator: leapfrog\n",
       "adami"},
      {"delta_sph",
       "  riemann: off\n  artificial_viscosity: {alpha: 0.02}\n  xsph: 0\n"
       "  viscosity: {model: morris, mu: 0.001}\n  negative_pressure: true\n",
       "  density_diffusion: {model: antuono, delta: 0.1}\n  kernel: cubic_spline\n"
       "  h_factor: 1.3\n  time_step: {rule: paper_b}\n  integrator: predictor_corrector\n",
       "mdbc"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    char text[2048], out[65536], args[8192], a[4200], b[4200];
    snprintf(text, sizeof text,
             "name: s\nphysics:\n  sound_speed: 10\nnumerics:\n  scheme: %s\n  dx: 0.01\n"
             "time:\n  end: 0.01\n  output_interval: 0.005\ngeometry:\n"
             "  tank: {x: [0, 0.1], y: [0, 0.1]}\n  fluid:\n    - {x: [0, 0.05], y: [0, 0.05]}\n",
             cases[k].scheme);
    write_file("scheme.yaml", text);
    snprintf(text, sizeof text,
             "name: s\nphysics:\n  sound_speed: 10\n%snumerics:\n  dx: 0.01\n%s"
             "time:\n  end: 0.01\n  output_interval: 0.005\ngeometry:\n"
             "  tank: {x: [0, 0.1], y: [0, 0.1], boundary: %s}\n  fluid:\n"
             "    - {x: [0, 0.05], y: [0, 0.05]}\n",
             cases[k].physics, cases[k].numerics, cases[k].tank);
    write_file("keys.yaml", text);
    snprintf(args, sizeof args, "run -q '%s/scheme.yaml' -o '%s/scheme_%zu'", tmp, tmp, k);
    CU_ASSERT_EQUAL(sph_ok(args, out, sizeof out), 0);
    snprintf(args, sizeof args, "run -q '%s/keys.yaml' -o '%s/keys_%zu'", tmp, tmp, k);
    CU_ASSERT_EQUAL(sph_ok(args, out, sizeof out), 0);
    snprintf(a, sizeof a, "%s/scheme_%zu/diagnostics.csv", tmp, k);
    snprintf(b, sizeof b, "%s/keys_%zu/diagnostics.csv", tmp, k);
    size_t la = 0, lb = 0;
    char *da = sph_test_read_file(a, &la), *db = sph_test_read_file(b, &lb);
    CU_ASSERT_FATAL(da != NULL && db != NULL);
    CU_ASSERT(la > 100 && la == lb && memcmp(da, db, la) == 0);
    if (!(la == lb && memcmp(da, db, la) == 0))
      printf("\n  %s: %s and %s differ", cases[k].scheme, a, b);
    free(da);
    free(db);
  }
  /* a case with its own numerics under a scheme: the listing says which keys it keeps */
  write_file("good.yaml", GOOD);
  char out[65536], args[8192];
  snprintf(args, sizeof args, "run '%s/good.yaml' -o '%s/mixed' --set numerics.scheme=riemann", tmp,
           tmp);
  CU_ASSERT_EQUAL(sph_ok(args, out, sizeof out), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(out, "numerics.scheme riemann: the case gives its own "
                                     "physics.artificial_viscosity.alpha (kept"));
}

/* One program, both dimensions: a case with dimension: 3 is handed to the
 * 3-D build (sph-3d) with the same command line; its run writes 3-D
 * snapshots (z, v_z, XYZ) and 3-D diagnostics; sph info hands a 3-D
 * snapshot over the same way; without the 3-D program the run says so. */
/* The last "progress: t = T / END s (P%)" line of out: 1 and T, END, P,
 * or 0 when out has none. */
static int last_progress(const char *out, double *t, double *end, double *pct) {
  const char *at = NULL;
  for (const char *p = strstr(out, "progress: t = "); p; p = strstr(p + 1, "progress: t = "))
    at = p;
  return at && sscanf(at, "progress: t = %lf / %lf s (%lf%%)", t, end, pct) == 3;
}

/* Progress in a log: with standard error not a terminal (here a file),
 * one line every --progress seconds of wall time, none from a run shorter
 * than the default minute, none under --quiet; the 3-D program takes the
 * option through the hand-over; a bad value is refused by name. */
static void test_progress_in_a_log(void) {
  char out[65536], args[8192];
  write_file("progress.yaml", GOOD);
  double t, end, pct;
  snprintf(args, sizeof args,
           "run '%s/progress.yaml' -o '%s/prog' --set time.end=0.05 --progress 0.001", tmp, tmp);
  CU_ASSERT_EQUAL_FATAL(sph_ok(args, out, sizeof out), 0);
  CU_ASSERT(last_progress(out, &t, &end, &pct));
  CU_ASSERT(t > 0.0 && t <= end && end == 0.05 && fabs(pct - 100.0 * t / end) < 0.051);
  CU_ASSERT(strstr(out, " steps/s, ") != NULL && strstr(out, " elapsed, ETA ") != NULL);
  CU_ASSERT(strchr(out, '\r') == NULL); /* no bar in a log */
  /* the default: a line a minute, so none from this run; none when quiet */
  snprintf(args, sizeof args, "run '%s/progress.yaml' -o '%s/prog' --set time.end=0.05", tmp, tmp);
  CU_ASSERT_EQUAL(sph_ok(args, out, sizeof out), 0);
  CU_ASSERT(strstr(out, "progress:") == NULL);
  snprintf(args, sizeof args, "run -q '%s/progress.yaml' -o '%s/prog' --progress 0.001", tmp, tmp);
  CU_ASSERT_EQUAL(sph_ok(args, out, sizeof out), 0);
  CU_ASSERT(strstr(out, "progress:") == NULL);
  /* 3-D: through sph to sph-3d */
  snprintf(args, sizeof args,
           "run '%s' -o '%s/prog3' --set time.end=0.004 --set time.output_interval=0.004 "
           "--set output.probe_interval=0.004 --progress 0.001",
           sph_test_src("cases/hydrostatic_3d.yaml"), tmp);
  CU_ASSERT_EQUAL(sph_ok(args, out, sizeof out), 0);
  CU_ASSERT(last_progress(out, &t, &end, &pct) && end == 0.004);
  /* bad values */
  static const char *const bad[] = {"abc", "-1", "1e99", ""};
  for (int k = 0; k < 4; k++) {
    snprintf(args, sizeof args, "run '%s/progress.yaml' -o '%s/prog' --progress '%s'", tmp, tmp,
             bad[k]);
    CU_ASSERT_EQUAL(sph(args, out, sizeof out), 2);
    CU_ASSERT(strstr(out, "sph run: --progress: expected seconds between progress lines") != NULL);
  }
}

static void test_three_dimensions(void) {
  char out[65536], args[8192], path[4200];
  CU_ASSERT_EQUAL(sph("--version", out, sizeof out), 0);
  CU_ASSERT(strstr(out, "dimensions: 2 (this program), 3 (") != NULL);
  CU_ASSERT(strstr(out, "not found") == NULL);
  snprintf(args, sizeof args,
           "run '%s' -o '%s/run3' --set time.end=0.004 --set time.output_interval=0.002 "
           "--set output.probe_interval=0.002",
           sph_test_src("cases/hydrostatic_3d.yaml"), tmp);
  CU_ASSERT_EQUAL_FATAL(sph_ok(args, out, sizeof out), 0);
  CU_ASSERT(strstr(out, "dimension: 3") != NULL &&
            strstr(out, "geometry.tank.z: [0, 0.15]") != NULL);
  snprintf(args, sizeof args, "info '%s/run3/snap_0002.h5'", tmp);
  CU_ASSERT_EQUAL(sph_ok(args, out, sizeof out), 0);
  CU_ASSERT(strstr(out, "\n  z ") != NULL && strstr(out, "\n  vz ") != NULL);
  CU_ASSERT(strstr(out, "(fluid 2000, wall 6576)") != NULL); /* adami walls: 4 layers */
  snprintf(path, sizeof path, "%s/run3/diagnostics.csv", tmp);
  char *d = sph_test_read_file(path, NULL);
  CU_ASSERT_PTR_NOT_NULL(d && strstr(d, "momentum_y (kg m/s),momentum_z (kg m/s),kinetic (J),"));
  free(d);
  snprintf(path, sizeof path, "%s/run3/probes.csv", tmp);
  d = sph_test_read_file(path, NULL);
  CU_ASSERT_PTR_NOT_NULL(d && strstr(d, "P_centre (Pa),P_corner (Pa),H_centre (m),V_mid_vx (m/s),"
                                        "V_mid_vy (m/s),V_mid_vz (m/s)\n"));
  free(d);
  snprintf(path, sizeof path, "%s/run3/snapshots.xmf", tmp);
  d = sph_test_read_file(path, NULL);
  CU_ASSERT_PTR_NOT_NULL(d && strstr(d, "GeometryType=\"XYZ\""));
  free(d);
  /* no 3-D program: one line that says so */
  snprintf(args, sizeof args, "run '%s' -o '%s/run3b'", sph_test_src("cases/hydrostatic_3d.yaml"),
           tmp);
  setenv("SPH_TWIN", "/nonexistent/sph-3d", 1);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 1);
  unsetenv("SPH_TWIN");
  CU_ASSERT(strstr(out, "is a 3-D case and the 3-D program (sph-3d) is not installed") != NULL);
  /* SPH_TWIN naming a program of this dimension: handed over once, then
   * refused, never back and forth (issue 61, E2; timeout: the old loop) */
  char cmd[16384];
  snprintf(cmd, sizeof cmd,
           "SPH_TWIN='%s' timeout 60 '%s' run '%s' -o '%s/run3c' >'%s/twin.log' 2>&1",
           sph_test_build("src/sph"), sph_test_build("src/sph"),
           sph_test_src("cases/hydrostatic_3d.yaml"), tmp, tmp);
  CU_ASSERT_EQUAL(sph_test_system(cmd), 1);
  snprintf(path, sizeof path, "%s/twin.log", tmp);
  d = sph_test_read_file(path, NULL);
  if (!(d && strstr(d, "not handed back (is SPH_TWIN set to a program of the wrong dimension?)")))
    printf("\n  %s\n", d ? d : "(no log)");
  CU_ASSERT_PTR_NOT_NULL(
      d && strstr(d, "not handed back (is SPH_TWIN set to a program of the wrong dimension?)"));
  free(d);
  /* a snapshot whose dimension attribute is neither 2 nor 3: refused by
   * the first program, not handed over */
  for (int k = 0; k < 3; k++) {
    const long long bad[3] = {0, 4, -1};
    snprintf(cmd, sizeof cmd, "cp '%s/run3/snap_0002.h5' '%s/dim.h5'", tmp, tmp);
    CU_ASSERT_EQUAL_FATAL(sph_test_system(cmd), 0);
    snprintf(path, sizeof path, "%s/dim.h5", tmp);
    const hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    CU_ASSERT_FATAL(f >= 0);
    const hid_t a = H5Aopen(f, "dimension", H5P_DEFAULT);
    CU_ASSERT_FATAL(a >= 0);
    const int64_t v = bad[k];
    CU_ASSERT(H5Awrite(a, H5T_NATIVE_INT64, &v) >= 0);
    H5Aclose(a);
    H5Fclose(f);
    for (int r = 0; r < 2; r++) {
      snprintf(cmd, sizeof cmd,
               r ? "timeout 60 '%s' run --restart '%s/dim.h5' -o '%s/dimrun' >'%s/dim.log' 2>&1"
                 : "timeout 60 '%s' info '%s/dim.h5' >'%s/dim.log' 2>&1",
               sph_test_build("src/sph"), tmp, tmp, tmp);
      const int st = sph_test_system(cmd);
      CU_ASSERT(st != 0 && st != 124);
      snprintf(path, sizeof path, "%s/dim.log", tmp);
      d = sph_test_read_file(path, NULL);
      char want[96];
      snprintf(want, sizeof want, "attribute \"dimension\" is %lld, expected 2 or 3", bad[k]);
      if (!(d && strstr(d, want))) printf("\n  exit %d: %s\n", st, d ? d : "(no log)");
      CU_ASSERT_PTR_NOT_NULL(d && strstr(d, want));
      free(d);
    }
  }
}

/* A signal while sph hands a 3-D run to sph-3d (between the two programs'
 * handlers; the test hook SPH_TEST_HANDOVER_SIGNAL raises SIGTERM there) is
 * held across the exec and reported by sph-3d as a set-up interruption:
 * exit 4, nothing written (it was lost, and the run went on to the end). */
static void test_signal_in_hand_over(void) {
  char cmd[16384], path[4400];
  snprintf(cmd, sizeof cmd,
           "SPH_TEST_HANDOVER_SIGNAL=1 timeout 120 '%s' run '%s' -o '%s/handsig' "
           "--set time.end=0.002 --set time.output_interval=0.002 "
           "--set output.probe_interval=0.002 >'%s/handsig.log' 2>&1",
           sph_test_build("src/sph"), sph_test_src("cases/hydrostatic_3d.yaml"), tmp, tmp);
  const int st = sph_test_system(cmd);
  snprintf(path, sizeof path, "%s/handsig.log", tmp);
  char *log = sph_test_read_file(path, NULL);
  if (st != 4) printf("\n  exit %d: %s\n", st, log ? log : "");
  CU_ASSERT_EQUAL(st, 4);
  CU_ASSERT_PTR_NOT_NULL(log &&
                         strstr(log, "interrupted by SIGTERM during set-up; nothing written"));
  free(log);
  snprintf(cmd, sizeof cmd, "test -e '%s/handsig'", tmp);
  CU_ASSERT_NOT_EQUAL(sph_test_system(cmd), 0);
}

/* A case file that can be read once (issue 61, E4): a named FIFO, /dev/stdin
 * and a pipe run the case, 2-D and 3-D (the 3-D one handed over with a copy
 * of its text), and give the same diagnostics as the file itself. The
 * timeouts: the old second open of a FIFO hung. */
static void test_case_read_once(void) {
  char cmd[40000], path[4400];
  write_file("good.yaml", GOOD);
  const char *sph_prog = sph_test_build("src/sph");
  const char *three = sph_test_src("cases/hydrostatic_3d.yaml");
  const char *sets3 = "--set time.end=0.002 --set time.output_interval=0.002 "
                      "--set output.probe_interval=0.002";
  /* the references, from the files */
  snprintf(cmd, sizeof cmd, "'%s' run -q '%s/good.yaml' -o '%s/once_ref2' --set time.end=0.01",
           sph_prog, tmp, tmp);
  CU_ASSERT_EQUAL_FATAL(sph_test_system(cmd), 0);
  snprintf(cmd, sizeof cmd, "'%s' run -q '%s' -o '%s/once_ref3' %s", sph_prog, three, tmp, sets3);
  CU_ASSERT_EQUAL_FATAL(sph_test_system(cmd), 0);
  for (int d = 2; d <= 3; d++) {
    char src[4200], ref[4200], sets[256];
    if (d == 2)
      snprintf(src, sizeof src, "%s/good.yaml", tmp);
    else
      snprintf(src, sizeof src, "%s", three);
    snprintf(ref, sizeof ref, "%s/once_ref%d/diagnostics.csv", tmp, d);
    snprintf(sets, sizeof sets, "%s", d == 2 ? "--set time.end=0.01" : sets3);
    const char *how[3] = {"fifo", "stdin", "pipe"};
    for (int k = 0; k < 3; k++) {
      char dir[4300];
      snprintf(dir, sizeof dir, "%s/once_%s%d", tmp, how[k], d);
      if (k == 0)
        snprintf(cmd, sizeof cmd,
                 "rm -f '%s.fifo' && mkfifo '%s.fifo' && (cat '%s' > '%s.fifo' &) && "
                 "timeout 120 '%s' run -q '%s.fifo' -o '%s' %s >'%s.log' 2>&1",
                 dir, dir, src, dir, sph_prog, dir, dir, sets, dir);
      else if (k == 1)
        snprintf(cmd, sizeof cmd,
                 "timeout 120 '%s' run -q /dev/stdin -o '%s' %s <'%s' >'%s.log' 2>&1", sph_prog,
                 dir, sets, src, dir);
      else
        snprintf(cmd, sizeof cmd,
                 "cat '%s' | timeout 120 '%s' run -q /dev/stdin -o '%s' %s >'%s.log' 2>&1", src,
                 sph_prog, dir, sets, dir);
      const int st = sph_test_system(cmd);
      snprintf(path, sizeof path, "%s.log", dir);
      char *log = sph_test_read_file(path, NULL);
      if (st != 0) printf("\n  %d-D %s: exit %d: %s\n", d, how[k], st, log ? log : "");
      free(log);
      CU_ASSERT_EQUAL(st, 0);
      snprintf(cmd, sizeof cmd, "cmp '%s' '%s/diagnostics.csv'", ref, dir);
      CU_ASSERT_EQUAL(sph_test_system(cmd), 0);
    }
  }
}

/* A fluid block drawn through a box obstacle (a wet bed with a box standing
 * in it): the box's inside is solid, so none of the block's particles are
 * made there, and the run says how many (issue 61, E1), 2-D and 3-D. */
static void test_fluid_through_obstacle(void) {
  char out[65536], args[8192];
  write_file("good.yaml", GOOD);
  /* 2-D: the bed x [0, 0.1] y [0, 0.05] at dx 0.01 (50 particles), the box
   * x [0.03, 0.07] covers 4 of its 10 columns */
  snprintf(args, sizeof args,
           "run '%s/good.yaml' -o '%s/bed2' --set 'geometry.fluid=[{x: [0, 0.1], y: [0, 0.05]}]' "
           "--set 'geometry.obstacles=[{x: [0.03, 0.07], y: [0, 0.08]}]'",
           tmp, tmp);
  CU_ASSERT_EQUAL_FATAL(sph_ok(args, out, sizeof out), 0);
  CU_ASSERT(strstr(out, "20 fluid particles not made: inside an obstacle box") != NULL);
  snprintf(args, sizeof args, "info '%s/bed2/snap_0000.h5'", tmp);
  CU_ASSERT_EQUAL(sph_ok(args, out, sizeof out), 0);
  CU_ASSERT(strstr(out, "(fluid 30, ") != NULL);
  /* 3-D: the bed of cases/hydrostatic_3d.yaml (20 x 10 x 10), a box
   * x [0.05, 0.1] y [0, 0.1] z [0, 0.12] takes 5 x 10 x 10 of it */
  snprintf(args, sizeof args,
           "run '%s' -o '%s/bed3' --set time.end=0.002 --set time.output_interval=0.002 "
           "--set output.probe_interval=0.002 "
           "--set 'geometry.obstacles=[{x: [0.05, 0.1], y: [0, 0.1], z: [0, 0.12]}]'",
           sph_test_src("cases/hydrostatic_3d.yaml"), tmp);
  CU_ASSERT_EQUAL_FATAL(sph_ok(args, out, sizeof out), 0);
  CU_ASSERT(strstr(out, "500 fluid particles not made: inside an obstacle box") != NULL);
  snprintf(args, sizeof args, "info '%s/bed3/snap_0000.h5'", tmp);
  CU_ASSERT_EQUAL(sph_ok(args, out, sizeof out), 0);
  CU_ASSERT(strstr(out, "(fluid 1500, ") != NULL);
}

/* sph face on a 3-D snapshot reads heights along z (issue 61, E9): water
 * 0.06 m deep in a tank 0.1 m across y has its crest at z = 0.055 m (the
 * top layer's centre), not at the y extent's 0.095 m. */
static void test_face_3d(void) {
  char out[65536], args[8192];
  snprintf(args, sizeof args,
           "run '%s' -o '%s/face3' --set time.end=0.002 --set time.output_interval=0.002 "
           "--set output.probe_interval=0.002 "
           "--set 'geometry.fluid=[{x: [0, 0.2], y: [0, 0.1], z: [0, 0.06]}]'",
           sph_test_src("cases/hydrostatic_3d.yaml"), tmp);
  CU_ASSERT_EQUAL_FATAL(sph_ok(args, out, sizeof out), 0);
  snprintf(args, sizeof args, "face '%s/face3/snap_0000.h5'", tmp);
  CU_ASSERT_EQUAL_FATAL(sph_ok(args, out, sizeof out), 0);
  double t = -1, cx = 0, cy = 0;
  const char *line = strstr(out, "0 ");
  CU_ASSERT_FATAL(line != NULL);
  CU_ASSERT_EQUAL(sscanf(line, "%lf %lf %lf", &t, &cx, &cy), 3);
  if (!(fabs(cy - 0.055) < 1e-3)) printf("\n  %s\n", out);
  CU_ASSERT(fabs(cy - 0.055) < 1e-3);
  CU_ASSERT(strstr(out, "# first vertical: not reached") != NULL); /* still water: no face */
  /* sph info lists the snapshot's geometry (its /geometry group) */
  snprintf(args, sizeof args, "info '%s/face3/snap_0000.h5'", tmp);
  CU_ASSERT_EQUAL_FATAL(sph_ok(args, out, sizeof out), 0);
  if (!strstr(out, "geometry:    tank x [0, 0.2] y [0, 0.1] z [0, 0.15]; 0 obstacles, 0 walls, "
                   "4 probes\n"))
    printf("\n  %s\n", out);
  CU_ASSERT(strstr(out, "geometry:    tank x [0, 0.2] y [0, 0.1] z [0, 0.15]; 0 obstacles, 0 "
                        "walls, 4 probes\n") != NULL);
  CU_ASSERT(strstr(out, "  probe P_centre (pressure) at (0.1, 0.05, 0)\n") != NULL);
  CU_ASSERT(strstr(out, "  probe H_centre (level) at (0.1, 0.05, 0)\n") != NULL);
  /* a snapshot of an earlier build has none, and says so */
  snprintf(args, sizeof args, "info '%s'", sph_test_src("tests/data/snapshot_unchecked_v0.h5"));
  CU_ASSERT_EQUAL(sph_ok(args, out, sizeof out), 0);
  CU_ASSERT(strstr(out, "geometry:    (not recorded: a snapshot of an earlier build)") != NULL);
}

/* sph profile on a 3-D snapshot measures heights along z: water 0.06 m
 * deep (six layers, 0.1 m across y) at rest under a body force along x
 * reads, against v(z) = (g/nu)(L - z/2) z with L = 0.06 m, max = the top
 * layer's v / v_max (99.31 %) and L2 = the RMS over the layers; heights
 * along y (0.1 m of them) would give 99.75 % and another L2. */
static void test_profile_3d(void) {
  char out[65536], args[8192];
  snprintf(args, sizeof args,
           "run -q '%s' -o '%s/profile3' --set time.end=0.001 --set time.output_interval=0.001 "
           "--set output.probe_interval=0.001 --set 'physics.gravity=[1.0e-4, 0, 0]' "
           "--set physics.viscosity.model=morris --set physics.viscosity.mu=1.0e-3 "
           "--set 'geometry.fluid=[{x: [0, 0.2], y: [0, 0.1], z: [0, 0.06]}]'",
           sph_test_src("cases/hydrostatic_3d.yaml"), tmp);
  CU_ASSERT_EQUAL_FATAL(sph_ok(args, out, sizeof out), 0);
  snprintf(args, sizeof args, "profile '%s/profile3/snap_0000.h5'", tmp);
  CU_ASSERT_EQUAL_FATAL(sph_ok(args, out, sizeof out), 0);
  const double L = 0.06, dz = 0.01;
  double want_max = 0.0, sum = 0.0;
  for (int k = 0; k < 6; k++) {
    const double z = (k + 0.5) * dz, f = (2.0 * L - z) * z / (L * L);
    want_max = fmax(want_max, f);
    sum += f * f;
  }
  double t = -1, emax = 0, el2 = 0;
  const char *line = strstr(out, "\n0 ");
  CU_ASSERT_FATAL(line != NULL);
  CU_ASSERT_EQUAL(sscanf(line + 1, "%lf %lf %lf", &t, &emax, &el2), 3);
  if (!(fabs(emax - 100.0 * want_max) < 1e-6 && fabs(el2 - 100.0 * sqrt(sum / 6)) < 1e-6))
    printf("\n  want %.9g %.9g: %s\n", 100.0 * want_max, 100.0 * sqrt(sum / 6), out);
  CU_ASSERT(fabs(emax - 100.0 * want_max) < 1e-6);
  CU_ASSERT(fabs(el2 - 100.0 * sqrt(sum / 6)) < 1e-6);
}

/* 3-D messages give every component (issue 61, E12): a probe below the
 * domain is outside its z range, a blow-up names z and vz. */
static void test_messages_3d(void) {
  char out[65536], args[8192];
  snprintf(args, sizeof args,
           "run -q '%s' -o '%s/msg3a' "
           "--set 'output.probes=[{name: a, kind: pressure, at: [0.1, 0.05, -0.5]}]'",
           sph_test_src("cases/hydrostatic_3d.yaml"), tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 1);
  CU_ASSERT(strstr(out, "(0.1, 0.05, -0.5) is outside the domain, x [-0.18, 0.38] y [-0.18, "
                        "0.28] z [-0.18, 0.63]") != NULL);
  snprintf(args, sizeof args,
           "run -q '%s' -o '%s/msg3b' --set time.end=0.05 --set time.output_interval=0.01 "
           "--set output.probe_interval=0 --set numerics.density_limit=0.01 "
           "--set 'geometry.fluid=[{x: [0, 0.05], y: [0, 0.05], z: [0.02, 0.07], "
           "velocity: [0, 0, -3]}]'",
           sph_test_src("cases/hydrostatic_3d.yaml"), tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 3);
  if (!strstr(out, ", vz = ")) printf("\n  %s\n", out);
  CU_ASSERT(strstr(out, "blow-up at step") != NULL && strstr(out, ", z = ") != NULL &&
            strstr(out, ", vz = ") != NULL && strstr(out, "] z [-0.25, 0.735])") != NULL);
  /* a 3-D plate thinner than dx across the flume is one row: refused (E11) */
  snprintf(args, sizeof args,
           "run -q '%s' -o '%s/msg3c' "
           "--set 'geometry.walls=[{from: [0.1, 0], to: [0.1, 0.05], y: [0.05, 0.050000000001]}]'",
           sph_test_src("cases/hydrostatic_3d.yaml"), tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 1);
  CU_ASSERT(strstr(out, "geometry.walls[0].y: expected a range at least numerics.dx = 0.01 m "
                        "wide across the flume") != NULL);
}

/* A case far from the origin (UTM-like coordinates) makes the particles it
 * makes at the origin (issue 61, E8: x + 1e6 m lost a layer of fluid, 1900
 * of 2000 in 3-D), and one so far that doubles cannot hold the lattice is
 * refused before any particle is made. */
static void test_far_from_origin(void) {
  char out[65536], args[8192], text[2048];
  const char *offs[] = {"0", "1000000", "123456.789"};
  for (int d = 2; d <= 3; d++)
    for (int k = 0; k < 4; k++) {
      const char *o = k < 3 ? offs[k] : "1e15";
      const double x0 = atof(o), x1 = x0 + 0.2;
      if (d == 3)
        snprintf(text, sizeof text,
                 "name: far\ndimension: 3\nphysics: {sound_speed: 10}\nnumerics: {dx: 0.01}\n"
                 "time: {end: 0.002, output_interval: 0.002}\ngeometry:\n"
                 "  tank: {x: [%.17g, %.17g], y: [0, 0.1], z: [0, 0.15]}\n"
                 "  fluid:\n    - {x: [%.17g, %.17g], y: [0, 0.1], z: [0, 0.1]}\n",
                 x0, x1, x0, x1);
      else
        snprintf(text, sizeof text,
                 "name: far\nphysics: {sound_speed: 10}\nnumerics: {dx: 0.01}\n"
                 "time: {end: 0.002, output_interval: 0.002}\ngeometry:\n"
                 "  tank: {x: [%.17g, %.17g], y: [0, 0.15]}\n"
                 "  fluid:\n    - {x: [%.17g, %.17g], y: [0, 0.1]}\n",
                 x0, x1, x0, x1);
      write_file("far.yaml", text);
      snprintf(args, sizeof args, "run -q '%s/far.yaml' -o '%s/far%d_%d'", tmp, tmp, d, k);
      if (k == 3) {
        CU_ASSERT_EQUAL(sph(args, out, sizeof out), 1);
        CU_ASSERT(strstr(out, "the geometry reaches 1e+15 m from the origin, where doubles are "
                              "0.222 m apart: too coarse for dx = 0.01 m") != NULL);
        continue;
      }
      CU_ASSERT_EQUAL_FATAL(sph_ok(args, out, sizeof out), 0);
      snprintf(args, sizeof args, "info '%s/far%d_%d/snap_0000.h5'", tmp, d, k);
      CU_ASSERT_EQUAL(sph_ok(args, out, sizeof out), 0);
      const char *want = d == 3 ? "(fluid 2000, " : "(fluid 200, ";
      if (!strstr(out, want)) printf("\n  %d-D, x0 = %s: %s\n", d, o, out);
      CU_ASSERT(strstr(out, want) != NULL);
    }
}

static void test_blowup_stops_cleanly(void) {
  char out[65536], args[8192];
  write_file("good.yaml", GOOD);
  snprintf(args, sizeof args,
           "run '%s/good.yaml' -o '%s/boom' --set time.end=1 --set numerics.density_limit=0.01 "
           "--set 'geometry.fluid=[{x: [0, 0.05], y: [0.02, 0.07], velocity: [0, -3]}]'",
           tmp, tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 3);
  CU_ASSERT(strstr(out, "blow-up at step") != NULL);
  CU_ASSERT(strstr(out, "particle") != NULL);
  snprintf(args, sizeof args, "test -s '%s/boom/snap_0000.h5' && test -s '%s/boom/last_good.h5'",
           tmp, tmp);
  CU_ASSERT_EQUAL(sph_test_system(args), 0);
  snprintf(args, sizeof args, "ls '%s/boom' | grep -c '\\.tmp$' >/dev/null", tmp);
  CU_ASSERT_NOT_EQUAL(sph_test_system(args), 0); /* no temporary file left */
  /* a step that has collapsed stops the run the same way, naming the rule
   * (issue 61, E5: a step of 1e-300 s would run for ever) */
  snprintf(args, sizeof args,
           "run '%s/good.yaml' -o '%s/stall' --set time.end=1 "
           "--set 'numerics.time_step={rule: fixed, dt: 1e-300}'",
           tmp, tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 3);
  const char *want = "t = 9.99e-298 s: the step (numerics.time_step.rule: fixed) has stayed "
                     "below 1e-06 of the case's acoustic step factor h / c0 = 0.0006 s for 1000 "
                     "steps (now 1e-300 s)";
  if (!strstr(out, want)) printf("\n  want '%s' in: %s\n", want, out);
  CU_ASSERT(strstr(out, want) != NULL);
  snprintf(args, sizeof args, "test -s '%s/stall/last_good.h5'", tmp);
  CU_ASSERT_EQUAL(sph_test_system(args), 0);
}

int main(void) {
  tmp = sph_test_tmpdir();
  CU_TestInfo tests[] = {
      {"help, version, unknown command", test_help_and_version},
      {"a 3-D case and a 3-D snapshot go to the 3-D build", test_three_dimensions},
      {"bad input gives a clear error and non-zero exit", test_bad_input},
      {"the particle count is bounded before the set-up", test_resource_bound},
      {"a short run, diagnostics rows, sph info", test_good_run_and_info},
      {"an output time listed twice (interval and list) is one output", test_output_times_merge},
      {"a blow-up stops with a message and keeps snapshots", test_blowup_stops_cleanly},
      {"numerics.scheme runs as its keys written out, bit for bit", test_scheme_is_its_keys},
      {"a case read once: FIFO, /dev/stdin, a pipe, 2-D and 3-D", test_case_read_once},
      {"a fluid block through a box obstacle: its inside stays dry", test_fluid_through_obstacle},
      {"sph face on a 3-D snapshot: heights along z", test_face_3d},
      {"sph profile on a 3-D snapshot: heights along z", test_profile_3d},
      {"a case far from the origin: the same particles; too far: refused", test_far_from_origin},
      {"3-D messages in three components", test_messages_3d},
      {"a signal during the hand-over to sph-3d is not lost", test_signal_in_hand_over},
      {"progress in a log: a line every --progress seconds, 2-D and 3-D", test_progress_in_a_log},
      CU_TEST_INFO_NULL};
  int rc = sph_test_main("cli", tests);
  sph_test_rmtree(tmp);
  return rc;
}
