/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_dam_break.c - the coarse Martin & Moyce dam break
 * (cases/martin_moyce_coarse.yaml, dx = a/20) run through the `sph` program:
 *
 * 1. determinism: the run with 1 thread and with 2 threads gives
 *    byte-identical output directories (every snapshot, the XDMF index and
 *    diagnostics.csv);
 * 2. validation: the surge front Z = front_x / a against the Martin & Moyce
 *    (1952) table (tests/data/martin_moyce_1952_front_n2_2.csv) at the
 *    experimental times T = t sqrt(2g/a), over the points with Z < 3.9
 *    (past the end of the run, when its front stands at the right wall, the
 *    front of the last output is used):
 *    RMS relative error below 5 % and maximum below 10 %;
 * 3. golden: front_x at every output time matches
 *    golden/martin_moyce_coarse_front.csv within 0.05 dx (a change that
 *    moves the front by a twentieth of a particle spacing is caught;
 *    regenerate with `make golden`).
 * 4. gauges over a dry bed (x = 0.1 and 0.2 m, ahead of the column): every
 *    value of gauges.csv is finite, 0 until the surge front has passed the
 *    gauge, then the depth of water, positive and below the column's 2a;
 *    it was -inf and nan on every row.
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "testutil.h"

#define A 0.05715
#define DX (A / 20)
#define G 9.81

static char *dir1, *dir2;
static int runs_ok;

typedef struct series {
  size_t n;
  double t[4096], x[4096];
} series;

/* Reads columns `time` and `front_x` of a CSV with a header (lines
 * starting with '#' skipped). */
static int read_front(const char *path, series *s) {
  s->n = sph_test_csv2(path, "time,front_x", s->t, s->x, 4096);
  return s->n ? 0 : -1;
}

static double interp(const series *s, double t) { return sph_test_interp(s->t, s->x, s->n, t); }

static int run(const char *dir, int threads) {
  char cmd[8192];
  /* SPH_TEST_OMP_MIN=0: run every loop in parallel however small the case */
  snprintf(cmd, sizeof cmd, "SPH_TEST_OMP_MIN=0 '%s' run --quiet --threads %d '%s' -o '%s'",
           sph_test_build("src/sph"), threads, sph_test_src("cases/martin_moyce_coarse.yaml"), dir);
  return sph_test_system(cmd);
}

static void test_determinism(void) {
  CU_ASSERT_FATAL(run(dir1, 1) == 0);
  CU_ASSERT_FATAL(run(dir2, 2) == 0);
  runs_ok = 1;
  char cmd[8192];
  snprintf(cmd, sizeof cmd, "diff -r '%s' '%s' >/dev/null", dir1, dir2);
  CU_ASSERT(sph_test_system(cmd) == 0);
  snprintf(cmd, sizeof cmd, "test -s '%s/snap_0010.h5' && test -s '%s/snapshots.xmf'", dir1, dir1);
  CU_ASSERT(sph_test_system(cmd) == 0);
}

static void test_front_against_experiment(void) {
  CU_ASSERT_FATAL(runs_ok);
  static series sim;
  char path[4096];
  snprintf(path, sizeof path, "%s/diagnostics.csv", dir1);
  CU_ASSERT_FATAL(read_front(path, &sim) == 0);
  double *exp_[2] = {NULL, NULL}; /* T = t sqrt(2g/a), Z = x/a */
  const long nexp =
      sph_test_csv(sph_test_src("tests/data/martin_moyce_1952_front_n2_2.csv"), "#0,#1", exp_);
  CU_ASSERT_FATAL(nexp > 0);
  double sum2 = 0.0, emax = 0.0;
  int n = 0;
  printf("\n     T     Z_exp   Z_sph   rel.err\n");
  for (long k = 0; k < nexp; k++) {
    const double T = exp_[0][k], Z = exp_[1][k];
    if (Z >= 3.9) continue;
    const double t = T / sqrt(2 * G / A);
    const double zs = interp(&sim, t) / A;
    const double e = (zs - Z) / Z;
    printf("  %5.2f  %6.3f  %6.3f  %+7.2f %%\n", T, Z, zs, 100 * e);
    CU_ASSERT(isfinite(zs));
    sum2 += e * e;
    if (fabs(e) > emax) emax = fabs(e);
    n++;
  }
  free(exp_[0]);
  free(exp_[1]);
  const double rms = sqrt(sum2 / n);
  printf("  front vs Martin & Moyce (%d points, Z < 3.9): RMS %.2f %%, max %.2f %%\n", n, 100 * rms,
         100 * emax);
  CU_ASSERT(n >= 13);
  CU_ASSERT(rms < 0.05);
  CU_ASSERT(emax < 0.10);
}

static void test_golden_front(void) {
  CU_ASSERT_FATAL(runs_ok);
  static series sim, gold;
  char path[4096];
  snprintf(path, sizeof path, "%s/diagnostics.csv", dir1);
  CU_ASSERT_FATAL(read_front(path, &sim) == 0);
  CU_ASSERT_FATAL(read_front(sph_test_src("golden/martin_moyce_coarse_front.csv"), &gold) == 0);
  CU_ASSERT_EQUAL(sim.n, gold.n);
  const size_t n = sim.n < gold.n ? sim.n : gold.n;
  double worst = 0.0;
  for (size_t i = 0; i < n; i++) {
    CU_ASSERT_DOUBLE_EQUAL(sim.t[i], gold.t[i], 1e-12);
    const double d = fabs(sim.x[i] - gold.x[i]);
    if (d > worst) worst = d;
  }
  printf("\n  largest front difference from golden: %.3e m (tolerance %.3e m)\n", worst, 0.05 * DX);
  CU_ASSERT(worst <= 0.05 * DX);
}

static void test_dry_bed_gauges(void) {
  char *dir = sph_test_tmpdir(), cmd[8192], path[4096];
  snprintf(cmd, sizeof cmd,
           "'%s' run --quiet '%s' -o '%s' --set 'output.gauges=[0.1, 0.2]' "
           "--set output.snapshots=false",
           sph_test_build("src/sph"), sph_test_src("cases/martin_moyce_coarse.yaml"), dir);
  CU_ASSERT_FATAL(sph_test_system(cmd) == 0);
  static double t[4096], g1[4096], g2[4096], ft[4096], fx[4096];
  snprintf(path, sizeof path, "%s/gauges.csv", dir);
  size_t n = sph_test_csv2(path, "time,eta_0.1", t, g1, 4096);
  CU_ASSERT_FATAL(n > 10 && sph_test_csv2(path, "time,eta_0.2", t, g2, 4096) == n);
  snprintf(path, sizeof path, "%s/diagnostics.csv", dir);
  CU_ASSERT_FATAL(sph_test_csv2(path, "time,front_x", ft, fx, 4096) == n);
  int bad = 0, wet1 = 0, wet2 = 0;
  for (size_t k = 0; k < n; k++) {
    const double x[2] = {0.1, 0.2}, v[2] = {g1[k], g2[k]};
    for (int q = 0; q < 2; q++) {
      const int reached = fx[k] > x[q] - DX; /* the front is within dx of the gauge */
      if (!isfinite(v[q]) || v[q] < 0.0 || v[q] > 2 * A || (!reached && v[q] != 0.0)) bad++;
    }
    wet1 += g1[k] > 0.0;
    wet2 += g2[k] > 0.0;
  }
  printf("\n  dry-bed gauges: %zu rows, wet at x = 0.1 m in %d, at 0.2 m in %d; last: %.4f, %.4f m",
         n, wet1, wet2, g1[n - 1], g2[n - 1]);
  CU_ASSERT(bad == 0);
  CU_ASSERT(wet1 > 0 && wet2 > 0 && g1[0] == 0.0 && g2[0] == 0.0);
  sph_test_rmtree(dir);
  free(dir);
}

int main(void) {
  dir1 = sph_test_tmpdir();
  dir2 = sph_test_tmpdir();
  CU_TestInfo tests[] = {{"1 and 2 threads give byte-identical output", test_determinism},
                         {"front against Martin & Moyce (1952)", test_front_against_experiment},
                         {"front against the golden file", test_golden_front},
                         {"gauges over a dry bed read 0, then the depth", test_dry_bed_gauges},
                         CU_TEST_INFO_NULL};
  int rc = sph_test_main("dam_break", tests);
  sph_test_rmtree(dir1);
  sph_test_rmtree(dir2);
  return rc;
}
