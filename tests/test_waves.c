/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_waves.c - wave generation by a flap paddle (paper B §4.2) on the
 * coarse flume cases/linear_wave_coarse.yaml (dx = 0.4 m, 10 particles in
 * the depth d = 4 m; T = 4.7 s, S = 2.11 m; gauge at x = 27.3 m).
 *
 * 1. The height of the second generated wave at the gauge against linear
 *    theory, H = S (H/S)(kd) with k from the dispersion relation (flap
 *    transfer function, src/walls/wavemaker.h): H = 1.081 m. The waves are the
 *    stretches between zero up-crossings of the record after it first
 *    exceeds 5 % of H; the second generated wave is the first whole one
 *    (the first generated wave starts as a trough). Measured on this
 *    coarse flume: 0.853 m, 21 % low (10 particles per depth, 2.7 per wave
 *    height: under-resolved; dx = 0.3 m gives 0.859 m, the full case at
 *    dx = 0.2 m 1.005 m, 7 % low); asserted within 25 %, a check that the
 *    paddle makes a wave of the right size, not the accuracy claim, which
 *    is the full case's (doc/method.md, "Linear wave"). Paper B reports about 8 %.
 * 2. The gauge record matches golden/linear_wave_coarse_gauge.csv within
 *    0.02 m at every output time (`make golden`).
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "testutil.h"
#include "walls/wavemaker.h"

typedef struct record {
  size_t n;
  double t[4096], eta[4096];
} record;

static int read_record(const char *path, record *r) {
  r->n = sph_test_csv2(path, "#0,#1", r->t, r->eta, 4096);
  return r->n ? 0 : -1;
}

static char *dir;
static int ran;
static record rec;

static void run_flume(void) {
  char cmd[8192], path[4096];
  snprintf(cmd, sizeof cmd, "'%s' run --quiet '%s' -o '%s'", sph_test_build("src/sph"),
           sph_test_src("cases/linear_wave_coarse.yaml"), dir);
  ran = sph_test_system(cmd) == 0;
  snprintf(path, sizeof path, "%s/gauges.csv", dir);
  if (ran) ran = read_record(path, &rec) == 0;
}

static void test_second_wave(void) {
  run_flume();
  CU_ASSERT_FATAL(ran);
  const double T = 4.7, d = 4.0, S = 2.11, g = 9.81;
  double k;
  sph_error err;
  CU_ASSERT_FATAL(sph_wave_number(2.0 * 3.14159265358979323846 / T, d, g, &k, &err) == 0);
  const double H = S * sph_paddle_transfer(SPH_PADDLE_FLAP, k * d);
  size_t i = 0;
  while (i < rec.n && fabs(rec.eta[i]) < 0.05 * H)
    i++;
  size_t up[3];
  int nu = 0;
  for (i = i + 1; i < rec.n && nu < 3; i++)
    if (rec.eta[i - 1] < 0.0 && rec.eta[i] >= 0.0) up[nu++] = i;
  CU_ASSERT_FATAL(nu >= 2);
  double hi = -INFINITY, lo = INFINITY;
  for (i = up[0]; i < up[1]; i++) {
    if (rec.eta[i] > hi) hi = rec.eta[i];
    if (rec.eta[i] < lo) lo = rec.eta[i];
  }
  const double h2 = hi - lo;
  printf(
      "\n  second wave at the gauge: %.3f m (t = %.1f .. %.1f s); linear theory %.3f m: %+.1f %%",
      h2, rec.t[up[0]], rec.t[up[1]], H, 100 * (h2 - H) / H);
  CU_ASSERT(fabs(h2 - H) < 0.25 * H);
}

static void test_golden_record(void) {
  CU_ASSERT_FATAL(ran);
  static record gold;
  CU_ASSERT_FATAL(read_record(sph_test_src("golden/linear_wave_coarse_gauge.csv"), &gold) == 0);
  CU_ASSERT_EQUAL(gold.n, rec.n);
  double worst = 0.0;
  for (size_t i = 0; i < gold.n && i < rec.n; i++) {
    CU_ASSERT_DOUBLE_EQUAL(gold.t[i], rec.t[i], 1e-9);
    if (fabs(gold.eta[i] - rec.eta[i]) > worst) worst = fabs(gold.eta[i] - rec.eta[i]);
  }
  printf("\n  largest gauge difference from golden: %.3e m", worst);
  CU_ASSERT(worst <= 0.02);
}

int main(void) {
  dir = sph_test_tmpdir();
  CU_TestInfo tests[] = {{"second generated wave against linear theory", test_second_wave},
                         {"gauge record against the golden file", test_golden_record},
                         CU_TEST_INFO_NULL};
  int rc = sph_test_main("waves", tests);
  sph_test_rmtree(dir);
  free(dir);
  return rc;
}
