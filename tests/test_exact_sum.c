/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_exact_sum.c - the order-free sum (src/core/exact_sum.h).
 *
 * Against an independent oracle, Shewchuk's exact partials with the
 * correctly rounded final step (the algorithm of Python's math.fsum;
 * J. R. Shewchuk, Discrete Comput. Geom. 18 (1997) 305-363): random sets
 * with exponents over the whole range, heavy cancellation, subnormals and
 * signed zeros give the oracle's bits. The same terms in any order, or
 * split into parts summed apart and merged (as threads or MPI ranks do),
 * give the same bits. Rounding ties go to even, a term below the tie
 * breaks it; infinities and NaN as plain addition; more terms than a
 * normalisation period (2^30 additions) still exact.
 */
#include "config.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/exact_sum.h"
#include "testutil.h"

static unsigned long long rng = 0x9e3779b97f4a7c15ULL;
static double uniform(void) { return sph_test_uniform(&rng); }

/* Shewchuk's sum with the correctly rounded final step (math.fsum), for
 * finite terms whose partial sums do not overflow. */
static double oracle(const double *x, size_t n) {
  double *part = malloc((n + 1) * sizeof *part);
  size_t np = 0;
  for (size_t k = 0; k < n; k++) {
    double v = x[k];
    size_t i = 0;
    for (size_t j = 0; j < np; j++) {
      double y = part[j];
      if (fabs(v) < fabs(y)) {
        const double t = v;
        v = y, y = t;
      }
      const double hi = v + y, lo = y - (hi - v);
      if (lo != 0.0) part[i++] = lo;
      v = hi;
    }
    part[i] = v;
    np = i + 1;
  }
  double hi = 0.0, lo = 0.0;
  size_t j = np;
  if (j > 0) {
    hi = part[--j];
    while (j > 0) {
      const double v = hi, y = part[--j];
      hi = v + y;
      lo = y - (hi - v);
      if (lo != 0.0) break;
    }
    if (j > 0 && ((lo < 0.0 && part[j - 1] < 0.0) || (lo > 0.0 && part[j - 1] > 0.0))) {
      const double y = lo * 2.0, v = hi + y;
      if (y == v - hi) hi = v;
    }
  }
  free(part);
  return hi;
}

static double xsum(const double *x, size_t n) {
  sph_xsum s;
  sph_xsum_init(&s);
  for (size_t k = 0; k < n; k++)
    sph_xsum_add(&s, x[k]);
  return sph_xsum_round(&s);
}

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* A term of a random set of kind `kind`. */
static double term(int kind) {
  const double sgn = uniform() < 0.5 ? -1.0 : 1.0;
  switch (kind) {
  case 0: return sgn * uniform();                                              /* one scale */
  case 1: return sgn * ldexp(1.0 + uniform(), (int)(uniform() * 2000) - 1000); /* every scale */
  case 2: return sgn * ldexp(uniform(), -1074 + (int)(uniform() * 60));        /* subnormals */
  default: return sgn * ldexp(1.0 + uniform(), (int)(uniform() * 120) - 60);   /* mixed */
  }
}

static void test_against_oracle(void) {
  enum { N = 4000 };
  double *x = malloc(2 * N * sizeof *x);
  int agree = 0, sets = 0;
  for (int kind = 0; kind < 4; kind++)
    for (int trial = 0; trial < 25; trial++) {
      const size_t n = 1 + (size_t)(uniform() * N);
      for (size_t k = 0; k < n; k++)
        x[k] = term(kind);
      /* heavy cancellation: every term again, negated, but the last few */
      size_t m = n;
      if (trial % 2)
        for (size_t k = 0; k + 3 < n; k++)
          x[m++] = -x[k];
      const double a = xsum(x, m), b = oracle(x, m);
      sets++;
      agree += same_bits(a, b);
      if (!same_bits(a, b)) printf("\n  kind %d trial %d: %.17g, oracle %.17g", kind, trial, a, b);
    }
  printf("\n  %d of %d random sets: the oracle's bits", agree, sets);
  CU_ASSERT_EQUAL(agree, sets);
  free(x);
}

/* The same terms shuffled, and split into parts merged in another order:
 * the same bits; a plain sum in those orders differs. */
static void test_any_order_any_split(void) {
  enum { N = 20000 };
  double *x = malloc(N * sizeof *x);
  for (size_t k = 0; k < N; k++)
    x[k] = term(3);
  const double ref = xsum(x, N);
  int plain_moved = 0;
  double plain_ref = 0.0;
  for (size_t k = 0; k < N; k++)
    plain_ref += x[k];
  for (int trial = 0; trial < 10; trial++) {
    for (size_t k = N - 1; k > 0; k--) {
      const size_t j = (size_t)(uniform() * (double)(k + 1));
      const double t = x[k];
      x[k] = x[j], x[j] = t;
    }
    enum { PARTS = 7 };
    sph_xsum part[PARTS], all;
    for (int q = 0; q < PARTS; q++)
      sph_xsum_init(&part[q]);
    for (size_t k = 0; k < N; k++) /* uneven parts, as ranks of unequal size */
      sph_xsum_add(&part[(k * k) % PARTS], x[k]);
    sph_xsum_init(&all);
    for (int q = PARTS - 1; q >= 0; q--)
      sph_xsum_merge(&all, &part[q]);
    CU_ASSERT(same_bits(sph_xsum_round(&all), ref));
    CU_ASSERT(same_bits(xsum(x, N), ref));
    double plain = 0.0;
    for (size_t k = 0; k < N; k++)
      plain += x[k];
    plain_moved |= !same_bits(plain, plain_ref);
  }
  printf("\n  10 shuffles, each also in 7 merged parts: the same bits (a plain sum: %s)",
         plain_moved ? "moved" : "did not move");
  CU_ASSERT(plain_moved); /* the test can tell orders apart */
  free(x);
}

static void test_rounding(void) {
  const double two53 = 9007199254740992.0;
  { /* exact cancellation around a small term */
    const double x[] = {1e16, 1.0, -1e16};
    CU_ASSERT_EQUAL(xsum(x, 3), 1.0);
  }
  { /* a tie: 2^53 + 1 rounds to even (2^53), 2^53 + 3 to 2^53 + 4 */
    const double a[] = {two53, 1.0}, b[] = {two53, 3.0};
    CU_ASSERT_EQUAL(xsum(a, 2), two53);
    CU_ASSERT_EQUAL(xsum(b, 2), two53 + 4.0);
  }
  { /* a term far below breaks the tie upwards, and downwards */
    const double a[] = {two53, 1.0, 0x1p-900}, b[] = {two53, 1.0, -0x1p-900};
    CU_ASSERT_EQUAL(xsum(a, 3), two53 + 2.0);
    CU_ASSERT_EQUAL(xsum(b, 3), two53);
  }
  { /* negative sums, and zeros */
    const double a[] = {-two53, -1.0, -0x1p-900}, z[] = {-0.0, 0.0, 5.0, -5.0};
    CU_ASSERT_EQUAL(xsum(a, 3), -(two53 + 2.0));
    CU_ASSERT(same_bits(xsum(z, 4), 0.0));
    CU_ASSERT(same_bits(xsum(z, 0), 0.0));
  }
  { /* the extremes: subnormals add exactly, DBL_MAX stays, twice it is inf */
    const double s[] = {0x1p-1074, 0x1p-1074, 0x1p-1073}, m[] = {DBL_MAX, -DBL_MAX, DBL_MAX},
                 o[] = {DBL_MAX, DBL_MAX, -DBL_MAX};
    CU_ASSERT_EQUAL(xsum(s, 3), 0x1p-1072);
    CU_ASSERT_EQUAL(xsum(m, 3), DBL_MAX);
    CU_ASSERT_EQUAL(xsum(o, 3), DBL_MAX); /* exact: the intermediate overflow is no matter */
    const double big[] = {DBL_MAX, DBL_MAX};
    CU_ASSERT(isinf(xsum(big, 2)) && xsum(big, 2) > 0);
  }
  { /* infinities and NaN as plain addition */
    const double a[] = {1.0, INFINITY}, b[] = {INFINITY, -INFINITY}, c[] = {1.0, NAN, 2.0};
    CU_ASSERT(isinf(xsum(a, 2)) && xsum(a, 2) > 0);
    CU_ASSERT(isnan(xsum(b, 2)));
    CU_ASSERT(isnan(xsum(c, 3)));
  }
}

/* Past the normalisation period: 2^30 + 1000 additions of terms whose
 * digits all carry (1 - 2^-53 at the top of a digit), then their exact sum. */
static void test_many_terms(void) {
  sph_xsum s, half;
  sph_xsum_init(&s);
  const double t = 1.0 - 0x1p-53, n = 1073741824.0 + 1000.0;
  for (long k = 0; k < (1L << 30) + 1000; k++)
    sph_xsum_add(&s, t);
  /* n t = n - n 2^-53, exact in 84 bits; rounded: n - 2^-23 n ~ n (1 - 2^-53) */
  const double want = oracle((const double[]){n, -n * 0x1p-53}, 2);
  CU_ASSERT(same_bits(sph_xsum_round(&s), want));
  sph_xsum_init(&half);
  sph_xsum_add(&half, -t);
  sph_xsum_merge(&s, &half);
  const double want2 = oracle((const double[]){n - 1.0, -(n - 1.0) * 0x1p-53}, 2);
  CU_ASSERT(same_bits(sph_xsum_round(&s), want2));
  printf("\n  2^30 + 1000 terms of 1 - 2^-53: %.17g (exact, rounded once)", sph_xsum_round(&s));
}

int main(void) {
  CU_TestInfo tests[] = {
      {"random sets: the correctly rounded sum (Shewchuk's partials)", test_against_oracle},
      {"any order, any split into merged parts: the same bits", test_any_order_any_split},
      {"ties to even, sticky terms, signs, extremes, inf and NaN", test_rounding},
      {"more terms than a normalisation period", test_many_terms},
      CU_TEST_INFO_NULL};
  return sph_test_main("exact_sum", tests);
}
