/*
 * test_parallel.c - how loops are split among threads (parallel.h) and the
 * staggered array blocks their data lives in (arrays.h).
 *
 * sph_share: for 1..7 parts the slices are contiguous, in order, cover
 * 0..n-1 exactly once, and each holds its share of the total cost to within
 * one item's cost, for uniform, skewed (a dense block, as at the bottom of a
 * tank), zero-cost and empty inputs; with uniform cost the slices are the
 * equal-count split that sph_slice uses without a prefix. Inside an OpenMP
 * team of 1..4 threads sph_slice gives each thread exactly its sph_share
 * slice. (That a run's output does not depend on the split is
 * test_determinism's job: it compares runs on 1 and 2 threads.)
 *
 * sph_arrays_block: every array starts k cache lines past a page boundary,
 * arrays do not overlap, every byte is zero, and an impossible size gives
 * NULL rather than a short block. sph_arrays_regrow carries the first
 * `keep` elements of every array into the new block, zeroes the rest, and
 * changes nothing when the memory is not there.
 */
#include "config.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "arrays.h"
#include "parallel.h"
#include "testutil.h"

/* Checks the slices of prefix (n items) for 1..7 parts. */
static void check_shares(const size_t *prefix, size_t n, size_t max_item) {
  for (int parts = 1; parts <= 7; parts++) {
    size_t next = 0;
    const double total = (double)(prefix[n] - prefix[0]);
    for (int t = 0; t < parts; t++) {
      size_t lo, hi;
      sph_share(prefix, n, t, parts, &lo, &hi);
      CU_ASSERT_EQUAL(lo, next); /* contiguous and in order */
      CU_ASSERT(hi >= lo);
      CU_ASSERT(hi <= n);
      next = hi;
      const double cost = (double)(prefix[hi] - prefix[lo]);
      CU_ASSERT(cost <= total / parts + 2.0 * (double)max_item + 1.0);
    }
    CU_ASSERT_EQUAL(next, n); /* covers everything */
  }
}

static void test_share_uniform(void) {
  enum { N = 1001 };
  size_t prefix[N + 1];
  for (size_t i = 0; i <= N; i++) prefix[i] = 3 * i;
  check_shares(prefix, N, 3);
  /* uniform cost: the equal-count split */
  for (int parts = 1; parts <= 4; parts++)
    for (int t = 0; t < parts; t++) {
      size_t lo, hi;
      sph_share(prefix, N, t, parts, &lo, &hi);
      CU_ASSERT(lo == (size_t)N * (size_t)t / (size_t)parts ||
                lo == (size_t)N * (size_t)t / (size_t)parts + 1);
    }
}

static void test_share_skewed(void) {
  enum { N = 2000 };
  size_t prefix[N + 1];
  prefix[0] = 7; /* a prefix need not start at 0 */
  for (size_t i = 0; i < N; i++) prefix[i + 1] = prefix[i] + (i < 400 ? 90 : 10);
  check_shares(prefix, N, 90);
  /* two parts: 36000 of the 52000 lie in the dense block, so the first
   * part ends inside it, at 26000 / 90 = 289 */
  size_t lo, hi;
  sph_share(prefix, N, 0, 2, &lo, &hi);
  const size_t half = (prefix[N] - prefix[0]) / 2;
  CU_ASSERT(prefix[hi] - prefix[0] >= half);
  CU_ASSERT(prefix[hi - 1] - prefix[0] < half);
  CU_ASSERT_EQUAL(hi, 289);
}

static void test_share_degenerate(void) {
  size_t zero[6] = {0, 0, 0, 0, 0, 0};
  check_shares(zero, 5, 0);
  size_t one[1] = {0};
  check_shares(one, 0, 0);
  size_t lo = 99, hi = 99;
  sph_share(one, 0, 2, 3, &lo, &hi);
  CU_ASSERT(lo == 0 && hi == 0);
}

static void test_slice_in_team(void) {
  enum { N = 5000 };
  size_t *prefix = malloc((N + 1) * sizeof *prefix);
  CU_ASSERT_PTR_NOT_NULL_FATAL(prefix);
  prefix[0] = 0;
  for (size_t i = 0; i < N; i++) prefix[i + 1] = prefix[i] + 1 + (i * 7919) % 50;
  for (int nth = 1; nth <= 4; nth++) {
    size_t got[4][2], uni[4][2];
    int team = 0;
#ifdef _OPENMP
#pragma omp parallel num_threads(nth)
#endif
    {
      const int t = sph_thread();
      if (t == 0) team = sph_threads();
      sph_slice(prefix, N, &got[t][0], &got[t][1]);
      sph_slice(NULL, N, &uni[t][0], &uni[t][1]);
    }
#ifdef _OPENMP
    CU_ASSERT_EQUAL(team, nth);
#else
    CU_ASSERT_EQUAL(team, 1);
#endif
    size_t next_g = 0, next_u = 0;
    for (int t = 0; t < team; t++) {
      size_t lo, hi;
      sph_share(prefix, N, t, team, &lo, &hi);
      CU_ASSERT(got[t][0] == lo && got[t][1] == hi);
      CU_ASSERT_EQUAL(got[t][0], next_g);
      CU_ASSERT_EQUAL(uni[t][0], next_u);
      /* equal counts: sizes differ by at most one */
      const size_t size = uni[t][1] - uni[t][0];
      CU_ASSERT(size == N / (size_t)team || size == N / (size_t)team + 1);
      next_g = got[t][1];
      next_u = uni[t][1];
    }
    CU_ASSERT_EQUAL(next_g, N);
    CU_ASSERT_EQUAL(next_u, N);
  }
  free(prefix);
}

static void test_arrays_block(void) {
  enum { K = 70 };
  size_t size[K];
  void *start[K];
  const size_t cap = 3001;
  for (size_t k = 0; k < K; k++) size[k] = k % 3 == 0 ? 8 : k % 3 == 1 ? 4 : 1;
  char *block = sph_arrays_block(cap, K, size, start);
  CU_ASSERT_PTR_NOT_NULL_FATAL(block);
  for (size_t k = 0; k < K; k++) {
    const uintptr_t a = (uintptr_t)start[k];
    CU_ASSERT_EQUAL(a % 4096, 64 * (k % 64)); /* staggered by a cache line */
    for (size_t b = 0; b < cap * size[k]; b++)
      if (((const char *)start[k])[b] != 0) {
        CU_FAIL("array not zeroed");
        break;
      }
    if (k > 0) /* after the end of the previous one */
      CU_ASSERT(a >= (uintptr_t)start[k - 1] + cap * size[k - 1]);
    memset(start[k], 0xff, cap * size[k]); /* inside the block (ASan checks) */
  }
  free(block);
  size_t huge[2] = {8, 8};
  CU_ASSERT_PTR_NULL(sph_arrays_block(SIZE_MAX / 4, 2, huge, start));
}

static void test_arrays_regrow(void) {
  double *a = NULL;
  int32_t *b = NULL;
  void *block = NULL;
  void **const field[] = {(void **)&a, (void **)&b};
  const size_t size[] = {sizeof *a, sizeof *b};
  CU_ASSERT_FATAL(sph_arrays_regrow(&block, 10, 0, 2, size, field) == 0);
  CU_ASSERT_PTR_NOT_NULL_FATAL(block);
  for (int i = 0; i < 10; i++) {
    a[i] = 0.5 * i;
    b[i] = -i;
  }
  void *old = block;
  CU_ASSERT_FATAL(sph_arrays_regrow(&block, 1000, 10, 2, size, field) == 0);
  CU_ASSERT(block != old);
  int kept = 1, zero = 1;
  for (int i = 0; i < 10; i++) kept &= a[i] == 0.5 * i && b[i] == -i;
  for (int i = 10; i < 1000; i++) zero &= a[i] == 0.0 && b[i] == 0;
  CU_ASSERT(kept); /* the first `keep` elements carried over */
  CU_ASSERT(zero); /* the rest zero */
  CU_ASSERT_EQUAL((uintptr_t)a % 4096, 0);
  CU_ASSERT_EQUAL((uintptr_t)b % 4096, 64);
  /* out of memory: -1 and nothing changed */
  double *a0 = a;
  old = block;
  CU_ASSERT(sph_arrays_regrow(&block, SIZE_MAX / 4, 10, 2, size, field) == -1);
  CU_ASSERT(block == old && a == a0 && a[9] == 4.5);
  free(block);
}

int main(void) {
  CU_TestInfo tests[] = {{"share: uniform cost, the equal-count split", test_share_uniform},
                         {"share: a dense block is split by cost", test_share_skewed},
                         {"share: zero cost and no items", test_share_degenerate},
                         {"slice: each thread of a team takes its share", test_slice_in_team},
                         {"arrays block: staggered, disjoint, zeroed", test_arrays_block},
                         {"arrays regrow: keeps the first elements, zeroes the rest",
                          test_arrays_regrow},
                         CU_TEST_INFO_NULL};
  return sph_test_main("parallel", tests);
}
