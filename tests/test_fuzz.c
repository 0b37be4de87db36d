/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_fuzz.c - the fuzzers' findings as regression tests, without AFL++.
 *
 * Every input under tests/data/fuzz/case/ and tests/data/fuzz/snapshot/
 * (crashes and hangs AFL++ found, each fixed; see fuzz/results.md), and the
 * fuzzers' seed corpora (fuzz/seeds/), is fed to the same harness code the
 * fuzzers run (fuzz/harness.c): the parser and the snapshot reader must
 * return normally with the invariants the harness checks (an error that
 * names its origin, a parse that does not depend on uninitialised memory,
 * a restart record whose order is a permutation, ...). A crash aborts this
 * program, so the test fails; under --enable-sanitizers any memory error
 * does too. Each input is also timed: a hang found once must not come back
 * (each input must finish within 5 s). The snapshot findings that crash
 * inside libhdf5 1.10.8 itself (tests/data/fuzz/snapshot-hdf5/) are
 * replayed only with SPH_FUZZ_HDF5 set.
 */
#include "config.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "harness.h"
#include "testutil.h"

static char *tmp;

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Feeds every regular file of dir (relative to the source tree) to the
 * target; returns how many. */
/* which harness replay_dir feeds */
enum { CASE = 0, SNAPSHOT = 1, CSV = 2 };

static int replay_dir(const char *rel, int snapshot) {
  char dir[4096];
  snprintf(dir, sizeof dir, "%s", sph_test_src(rel));
  DIR *d = opendir(dir);
  if (!d) return 0;
  int count = 0;
  struct dirent *e;
  char scratch[4200];
  snprintf(scratch, sizeof scratch, "%s/input.h5", tmp);
  while ((e = readdir(d))) {
    if (e->d_name[0] == '.' || !strcmp(e->d_name, "README.md")) continue;
    char path[8300];
    snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
    size_t len = 0;
    unsigned char *data = (unsigned char *)sph_test_read_file(path, &len);
    CU_ASSERT_FATAL(data != NULL);
    printf("\n    %s (%zu bytes)", e->d_name, len);
    fflush(stdout);
    const double t0 = now();
    const int rc = snapshot == SNAPSHOT ? sph_fuzz_snapshot(data, len, scratch)
                   : snapshot == CSV    ? sph_fuzz_csv(data, len, scratch)
                                        : sph_fuzz_case(data, len);
    const double dt = now() - t0;
    CU_ASSERT_EQUAL(rc, 0);
    if (dt > 5.0) printf(": took %.1f s", dt);
    CU_ASSERT(dt < 5.0);
    free(data);
    count++;
  }
  closedir(d);
  return count;
}

static void test_case_inputs(void) {
  const int n = replay_dir("tests/data/fuzz/case", 0) + replay_dir("fuzz/seeds/case", 0) +
                replay_dir("cases", 0) + replay_dir("tests/data/cases_bad", 0);
  CU_ASSERT(n >= 10);
}

static void test_snapshot_inputs(void) {
  const int n = replay_dir("tests/data/fuzz/snapshot", 1) + replay_dir("fuzz/seeds/snapshot", 1);
  CU_ASSERT(n >= 2);
  /* the findings inside libhdf5 1.10.8 crash it: only on request */
  if (getenv("SPH_FUZZ_HDF5")) replay_dir("tests/data/fuzz/snapshot-hdf5", 1);
}

static void test_csv_inputs(void) {
  const int n = replay_dir("tests/data/fuzz/csv", CSV) + replay_dir("fuzz/seeds/csv", CSV) +
                replay_dir("tests/data/render", CSV);
  CU_ASSERT(n >= 5);
}

int main(void) {
  tmp = sph_test_tmpdir();
  CU_TestInfo tests[] = {{"case parser: fuzz findings and seeds", test_case_inputs},
                         {"snapshot reader: fuzz findings and seeds", test_snapshot_inputs},
                         {"CSV reader: fuzz findings and seeds", test_csv_inputs},
                         CU_TEST_INFO_NULL};
  int rc = sph_test_main("fuzz regressions", tests);
  sph_test_rmtree(tmp);
  return rc;
}
