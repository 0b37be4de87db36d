/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * testutil.h - shared helpers of the CUnit test programs.
 *
 * Each test program registers one suite and ends with
 *   return sph_test_main("suite name", tests);
 * which runs it and returns the number of failed assertions as the exit
 * status (CUnit's basic runner itself returns 0 even on failure).
 */
#ifndef SPH_TESTUTIL_H
#define SPH_TESTUTIL_H

#include <CUnit/CUnit.h>
#include <stddef.h>

/* Runs the suite; returns 0 if every assertion passed, 1 otherwise. */
int sph_test_main(const char *suite, CU_TestInfo *tests);

/* Absolute path of a file in the source tree (SPH_SRCDIR, or the
 * directory the test started in when unset), e.g. sph_test_src("cases/martin_moyce_coarse.yaml").
 * The result is one of 8 static buffers used in turn: copy it if it must outlive 7 more calls of
 * these two functions. */
const char *sph_test_src(const char *rel);
/* Same for the build tree (SPH_BUILDDIR), e.g. "src/sph". */
const char *sph_test_build(const char *rel);
/* Creates a fresh empty temporary directory and returns its path (static
 * buffer per call index is not kept: copy it). Aborts the test on failure. */
char *sph_test_tmpdir(void);
/* Removes a directory tree made by sph_test_tmpdir. */
void sph_test_rmtree(const char *dir);

/* `sph run` settings of cases made narrow across their periodic axis: two
 * cells of the neighbour grid, the least period it takes. The film of
 * cases/inclined_plane.yaml 6 dx wide (its bed across that period); the
 * 3-D flume of cases/linear_wave_flume_3d.yaml 6 dx (2.4 m) wide, its gauge
 * on the middle line (27.3, 1.2). */
#define SPH_TEST_FILM_6DX                                                                          \
  "--set 'geometry.periodic_x=[0.0, 3.0e-4]' "                                                     \
  "--set 'geometry.fluid=[{x: [0.0, 3.0e-4], y: [0.0, 1.0e-3], hydrostatic: false}]' "             \
  "--set 'geometry.walls=[{from: [2.75e-4, -2.5e-5], to: [2.5e-5, -2.5e-5], layers: 4, "           \
  "stagger: false, extrapolated_velocity: true, boundary: fixed_layers}]' "
#define SPH_TEST_FLUME_6DX                                                                         \
  "--set 'geometry.tank={x: [-3.0, 70.0], y: [0.0, 2.4], z: [0.0, 7.0]}' "                         \
  "--set 'geometry.periodic_y=[0.0, 2.4]' "                                                        \
  "--set 'geometry.fluid=[{x: [0.0, 70.0], y: [0.0, 2.4], z: [0.0, 4.0]}]' "                       \
  "--set 'output.gauges=[[27.3, 1.2]]' "
/* Runs a shell command, returns its exit status (or -1). */
int sph_test_system(const char *cmd);
/* Whether two directories hold the same files, byte for byte (diff -r). */
int sph_test_same_dirs(const char *a, const char *b);
/* A restart on another rank or process count: runs `cmd` (the restart,
 * into `again`), asserts that it succeeds, and returns whether again's
 * snap_0002.h5 is whole's byte for byte, printing "what: identical" (or
 * DIFFERENT). */
int sph_test_restart_same(const char *cmd, const char *whole, const char *again, const char *what);
/* Runs the build tree's `sph ARGS` (ARGS shell-quoted by the caller) with
 * stdout and stderr captured in DIR/sph.log and returned in out (len
 * bytes, truncated, NUL-terminated); returns the exit status. */
int sph_test_sph(const char *args, const char *dir, char *out, size_t len);
/* sph_test_sph for a run that should succeed: prints the command and its
 * output when the exit status is not 0, and returns the status (the caller
 * asserts it, so the failure names the caller's line). */
int sph_test_sph_ok(const char *args, const char *dir, char *out, size_t len);

/* A uniform draw in [0, 1) from the xorshift64 state *s (advanced): the
 * tests' one generator, the same sequence on every platform. */
double sph_test_uniform(unsigned long long *s);

/* The median of n values (sorts a copy; n > 0). */
double sph_test_median(const double *v, int n);
/* The series (t[i], x[i]), i < n, t increasing, at time `at`: linear between samples, x[0]
 * before the first and x[n - 1] after the last (a dam-break front that stopped at the wall
 * stays there). */
double sph_test_interp(const double *t, const double *x, size_t n, double at);
/* Simpson's rule for the integral of f over [a, b] with m (even) intervals. */
double sph_test_simpson(double (*f)(double), double a, double b, int m);

/* The whole file at path, malloc'd and NUL-terminated (free it), or NULL;
 * its length in bytes in *len unless len is NULL (binary files too). */
char *sph_test_read_file(const char *path, size_t *len);

/* Reads columns of the CSV table at path with the project's one reader
 * (src/io/csv.h): `names` lists them by header name, comma-separated
 * ("time,front_x"), or by position as "#0,#1" (for tables whose header
 * names carry units); out[k] receives a malloc'd array of the rows'
 * values of the k-th (free each). Returns the row count, or -1 (message
 * printed) if the file, a column or a number is missing. */
long sph_test_csv(const char *path, const char *names, double **out);
/* The same for two columns into the arrays a and b of cap values each;
 * returns the rows kept (at most cap), or 0 if none could be read. */
size_t sph_test_csv2(const char *path, const char *names, double *a, double *b, size_t cap);

#endif
