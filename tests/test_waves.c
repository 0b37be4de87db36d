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
 *    coarse flume: 0.865 m, 20 % low (10 particles per depth, 2.7 per wave
 *    height: under-resolved; dx = 0.3 m gives 0.859 m, the full case at
 *    dx = 0.2 m 1.005 m, 7 % low); asserted within 25 %, a check that the
 *    paddle makes a wave of the right size, not the accuracy claim, which
 *    is the full case's (doc/method.md, "Linear wave"). Paper B reports about 8 %.
 * 2. The gauge record matches golden/linear_wave_coarse_gauge.csv within
 *    0.02 m at every output time (`make golden`).
 * 3. The 3-D flume (below).
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

/* Linear theory's height of the flume's waves: H = S (H/S)(kd). */
static double theory_height(void) {
  const double T = 4.7, d = 4.0, S = 2.11, g = 9.81;
  double k;
  sph_error err;
  CU_ASSERT_FATAL(sph_wave_number(2.0 * 3.14159265358979323846 / T, d, g, &k, &err) == 0);
  return S * sph_paddle_transfer(SPH_PADDLE_FLAP, k * d);
}

/* The second generated wave of a record: the stretch between its first two
 * zero up-crossings after it first exceeds 5 % of H; its height, and the
 * crossings' times. 0 if the record has no such wave. */
static int second_wave(const record *r, double H, double *height, double *t0, double *t1) {
  size_t i = 0;
  while (i < r->n && fabs(r->eta[i]) < 0.05 * H)
    i++;
  size_t up[2];
  int nu = 0;
  for (i = i + 1; i < r->n && nu < 2; i++)
    if (r->eta[i - 1] < 0.0 && r->eta[i] >= 0.0) up[nu++] = i;
  if (nu < 2) return 0;
  double hi = -INFINITY, lo = INFINITY;
  for (i = up[0]; i < up[1]; i++) {
    if (r->eta[i] > hi) hi = r->eta[i];
    if (r->eta[i] < lo) lo = r->eta[i];
  }
  *height = hi - lo;
  *t0 = r->t[up[0]];
  *t1 = r->t[up[1]];
  return 1;
}

static void test_second_wave(void) {
  run_flume();
  CU_ASSERT_FATAL(ran);
  const double H = theory_height();
  double h2, t0, t1;
  CU_ASSERT_FATAL(second_wave(&rec, H, &h2, &t0, &t1));
  printf(
      "\n  second wave at the gauge: %.3f m (t = %.1f .. %.1f s); linear theory %.3f m: %+.1f %%",
      h2, t0, t1, H, 100 * (h2 - H) / H);
  CU_ASSERT(fabs(h2 - H) < 0.25 * H);
}

/* 3. The same flume in 3-D (cases/linear_wave_flume_3d.yaml: the flap a
 *    plate across the flume, periodic across 3.6 m), here periodic across
 *    2.4 m (6 dx: two cells of the neighbour grid, the narrowest period it
 *    takes; the flow does not vary across), the gauge the vertical line at
 *    (27.3, 1.2), run by `sph run` (which hands it to sph-3d) to the end of
 *    the second wave: its second wave is the 2-D flume's
 *    (golden/linear_wave_coarse_gauge.csv) within 3 % in height (measured:
 *    0.873 m against 0.865 m, +0.9 %, as at 3.6 m) and 0.3 s in its
 *    up-crossings (measured: 0.2 and 0.1 s earlier; at 3.6 m 0.2 and 0.1 s
 *    too). 87 s here against 118 s at 3.6 m. */
static void test_flume_3d(void) {
  char *dir3 = sph_test_tmpdir();
  char cmd[8192], path[4096];
  snprintf(cmd, sizeof cmd, "'%s' run --quiet '%s' -o '%s' --set time.end=13.4 " SPH_TEST_FLUME_6DX,
           sph_test_build("src/sph"), sph_test_src("cases/linear_wave_flume_3d.yaml"), dir3);
  const int ok = sph_test_system(cmd) == 0;
  CU_ASSERT_FATAL(ok);
  snprintf(path, sizeof path, "%s/gauges.csv", dir3);
  static record r3, gold;
  double *col = NULL;
  CU_ASSERT(sph_test_csv(path, "eta_27.3_1.2 (m)", &col) > 0); /* the column of an (x, y) gauge */
  free(col);
  CU_ASSERT_FATAL(read_record(path, &r3) == 0);
  CU_ASSERT_FATAL(read_record(sph_test_src("golden/linear_wave_coarse_gauge.csv"), &gold) == 0);
  const double H = theory_height();
  double h3, a0, a1, h2, b0, b1;
  CU_ASSERT_FATAL(second_wave(&r3, H, &h3, &a0, &a1));
  CU_ASSERT_FATAL(second_wave(&gold, H, &h2, &b0, &b1));
  printf("\n  3-D flume: second wave %.3f m (t = %.1f .. %.1f s); the 2-D flume's %.3f m (t = %.1f "
         ".. %.1f s): %+.1f %%",
         h3, a0, a1, h2, b0, b1, 100 * (h3 - h2) / h2);
  CU_ASSERT(fabs(h3 - h2) <= 0.03 * h2);
  CU_ASSERT(fabs(a0 - b0) <= 0.3 && fabs(a1 - b1) <= 0.3);
  sph_test_rmtree(dir3);
  free(dir3);
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
                         {"3-D flume: the 2-D flume's second wave", test_flume_3d},
                         CU_TEST_INFO_NULL};
  int rc = sph_test_main("waves", tests);
  sph_test_rmtree(dir);
  free(dir);
  return rc;
}
