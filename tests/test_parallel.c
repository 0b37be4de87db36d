/* SPDX-License-Identifier: BSD-3-Clause */
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
 * test_determinism's job: it compares runs on 1, 2 and 3 threads.)
 *
 * sph_steal: for 1..5 slices and teams of 1..4 threads (more slices than
 * threads, and fewer) every row is handed out exactly once, in chunks of at
 * least the grain unless fewer rows were left; one thread alone takes its
 * own slice front to back before any other's; a thread that finds nothing
 * left ends at once; and a thread whose partner has not started takes the
 * partner's slice as well (stealing happens). More than 2^32 rows is
 * refused.
 *
 * Learned split: after a pass in which thread 0 of 2 took all the cost the
 * shares move a sixteenth of the way toward 0.75 and 0.25 (its 1 and 0
 * kept to at least half an equal share each), to 0.515625, sph_slice
 * and sph_steal_reset (by cost and by counts) split there, every row is
 * still handed out once; a team smaller than its slices, and other team
 * sizes, split equally; 200 such passes leave thread 1 at least half an
 * equal share; sph_balance_reset returns to equal shares.
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

#include "core/arrays.h"
#include "core/parallel.h"
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
  for (size_t i = 0; i <= N; i++)
    prefix[i] = 3 * i;
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
  for (size_t i = 0; i < N; i++)
    prefix[i + 1] = prefix[i] + (i < 400 ? 90 : 10);
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
  for (size_t i = 0; i < N; i++)
    prefix[i + 1] = prefix[i] + 1 + (i * 7919) % 50;
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
  for (size_t k = 0; k < K; k++)
    size[k] = k % 3 == 0 ? 8 : k % 3 == 1 ? 4 : 1;
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
  CU_ASSERT_FATAL(sph_arrays_regrow(&block, 10, 0, 2, size, field, NULL) == 0);
  CU_ASSERT_PTR_NOT_NULL_FATAL(block);
  for (int i = 0; i < 10; i++) {
    a[i] = 0.5 * i;
    b[i] = -i;
  }
  void *old = block;
  CU_ASSERT_FATAL(sph_arrays_regrow(&block, 1000, 10, 2, size, field, NULL) == 0);
  CU_ASSERT(block != old);
  int kept = 1, zero = 1;
  for (int i = 0; i < 10; i++)
    kept &= a[i] == 0.5 * i && b[i] == -i;
  for (int i = 10; i < 1000; i++)
    zero &= a[i] == 0.0 && b[i] == 0;
  CU_ASSERT(kept); /* the first `keep` elements carried over */
  CU_ASSERT(zero); /* the rest zero */
  CU_ASSERT_EQUAL((uintptr_t)a % 4096, 0);
  CU_ASSERT_EQUAL((uintptr_t)b % 4096, 64);
  /* out of memory: -1 and nothing changed */
  double *a0 = a;
  old = block;
  CU_ASSERT(sph_arrays_regrow(&block, SIZE_MAX / 4, 10, 2, size, field, NULL) == -1);
  CU_ASSERT(block == old && a == a0 && a[9] == 4.5);
  /* a skipped array is not copied: it comes zero, the other keeps its values */
  const unsigned char skip[] = {0, 1};
  CU_ASSERT_FATAL(sph_arrays_regrow(&block, 2000, 10, 2, size, field, skip) == 0);
  kept = zero = 1;
  for (int i = 0; i < 10; i++)
    kept &= a[i] == 0.5 * i, zero &= b[i] == 0;
  CU_ASSERT(kept);
  CU_ASSERT(zero);
  free(block);
}

/* Hands out prefix's N rows (parts slices) to a team of nth threads with
 * the given grain; counts how often each row came out in count. */
static void steal_run(sph_steal *s, const size_t *prefix, size_t n, int parts, int nth,
                      size_t grain, int *count, int *small_chunks) {
  CU_ASSERT_FATAL(sph_steal_reset(s, prefix, n, parts) == 0);
  int small = 0;
#ifdef _OPENMP
#pragma omp parallel num_threads(nth) reduction(+ : small)
#else
  (void)nth;
#endif
  {
    size_t lo, hi;
    while (sph_steal_next(s, grain, &lo, &hi)) {
      if (hi - lo < grain) small++; /* allowed only for the last rows of a slice */
      for (size_t i = lo; i < hi; i++)
        __atomic_fetch_add(&count[i], 1, __ATOMIC_RELAXED);
    }
    if (sph_steal_next(s, grain, &lo, &hi)) small += 1000; /* nothing after the end */
  }
  *small_chunks = small;
}

static void test_steal_once(void) {
  enum { N = 20000 };
  size_t *prefix = malloc((N + 1) * sizeof *prefix);
  int *count = malloc(N * sizeof *count);
  CU_ASSERT_PTR_NOT_NULL_FATAL(prefix);
  CU_ASSERT_PTR_NOT_NULL_FATAL(count);
  prefix[0] = 0;
  for (size_t i = 0; i < N; i++)
    prefix[i + 1] = prefix[i] + (i < 3000 ? 60 : 8);
  sph_steal s = {0};
  for (int parts = 1; parts <= 5; parts++)
    for (int nth = 1; nth <= 4; nth++)
      for (size_t grain = 1; grain <= 64; grain *= 8) {
        memset(count, 0, N * sizeof *count);
        int small = 0;
        steal_run(&s, parts % 2 ? prefix : NULL, N, parts, nth, grain, count, &small);
        int once = 1;
        for (size_t i = 0; i < N; i++)
          once &= count[i] == 1;
        CU_ASSERT(once);
        /* a chunk below the grain empties its slice: one per slice at most */
        CU_ASSERT(small <= parts);
      }
  sph_steal_free(&s);
  free(count);
  free(prefix);
}

static void test_steal_alone(void) {
  enum { N = 1000 };
  sph_steal s = {0};
  /* one slice, one thread: front to back, in order */
  CU_ASSERT_FATAL(sph_steal_reset(&s, NULL, N, 1) == 0);
  size_t lo, hi, next = 0;
  int chunks = 0;
  while (sph_steal_next(&s, 10, &lo, &hi)) {
    CU_ASSERT_EQUAL(lo, next);
    CU_ASSERT(hi > lo);
    next = hi;
    chunks++;
  }
  CU_ASSERT_EQUAL(next, N);
  CU_ASSERT(chunks > 1 && chunks <= N / 10); /* chunks of at least the grain */
  /* an empty store */
  CU_ASSERT_FATAL(sph_steal_reset(&s, NULL, 0, 3) == 0);
  CU_ASSERT_FALSE(sph_steal_next(&s, 10, &lo, &hi));
  /* rows must fit in 32 bits */
  CU_ASSERT(sph_steal_reset(&s, NULL, (size_t)UINT32_MAX + 1, 2) == -1);
  sph_steal_free(&s);
}

/* Thread 1 starts only once thread 0 has run out of rows: thread 0 must
 * have taken thread 1's slice too. */
static void test_steal_takes_over(void) {
  enum { N = 3000 };
  sph_steal s = {0};
  CU_ASSERT_FATAL(sph_steal_reset(&s, NULL, N, 2) == 0);
  size_t taken[2] = {0, 0};
  int done = 0;
#ifdef _OPENMP
#pragma omp parallel num_threads(2)
#endif
  {
    const int t = sph_thread();
    if (t == 1)
      while (!__atomic_load_n(&done, __ATOMIC_ACQUIRE)) {
      }
    size_t lo, hi;
    while (sph_steal_next(&s, 16, &lo, &hi))
      taken[t] += hi - lo;
    if (t == 0) __atomic_store_n(&done, 1, __ATOMIC_RELEASE);
  }
  CU_ASSERT_EQUAL(taken[0], N);
  CU_ASSERT_EQUAL(taken[1], 0);
  sph_steal_free(&s);
}

/* One stealing pass over prefix's N rows by a team of nth threads in which
 * thread 0 takes every row (the others start once it has run out), then
 * sph_steal_learn. */
static void pass_by_thread0(sph_steal *s, const size_t *prefix, size_t n, int nth) {
  CU_ASSERT_FATAL(sph_steal_reset(s, prefix, n, 2) == 0);
  int done = 0;
#ifdef _OPENMP
#pragma omp parallel num_threads(nth)
#else
  (void)nth;
#endif
  {
    const int t = sph_thread();
    if (t != 0)
      while (!__atomic_load_n(&done, __ATOMIC_ACQUIRE)) {
      }
    size_t lo, hi;
    while (sph_steal_next(s, 16, &lo, &hi)) {
    }
    if (t == 0) __atomic_store_n(&done, 1, __ATOMIC_RELEASE);
  }
  sph_steal_learn(s);
}

/* The first i with prefix[i] >= target, by a plain scan. */
static size_t scan_at(const size_t *prefix, size_t n, size_t target) {
  size_t i = 0;
  while (i < n && prefix[i] < target)
    i++;
  return i;
}

/* sph_steal_learn moves a team's shares a sixteenth of the way to the cost
 * each thread took, never below half an equal share; sph_slice and
 * sph_steal_reset then split by them; other team sizes, a team smaller
 * than its slices and sph_balance_reset give equal shares. */
static void test_balance_learn(void) {
  enum { N = 3000 };
  size_t *prefix = malloc((N + 1) * sizeof *prefix);
  int *count = malloc(N * sizeof *count);
  CU_ASSERT_PTR_NOT_NULL_FATAL(prefix);
  CU_ASSERT_PTR_NOT_NULL_FATAL(count);
  prefix[0] = 0;
  for (size_t i = 0; i < N; i++)
    prefix[i + 1] = prefix[i] + (i < 1000 ? 5 : 1);
  const size_t total = prefix[N];
  sph_steal s = {0};
  sph_balance_reset();
  CU_ASSERT_DOUBLE_EQUAL(sph_balance_share(0, 2), 0.5, 0.0);
  /* a team of one thread for two slices teaches nothing */
  pass_by_thread0(&s, prefix, N, 1);
  CU_ASSERT_DOUBLE_EQUAL(sph_balance_share(0, 2), 0.5, 0.0);
  pass_by_thread0(&s, prefix, N, 2);
#ifdef _OPENMP
  /* thread 0 took all the cost: 1 and 0, raised to 0.75 and 0.25 */
  const double b0 = 0.5 + (0.75 - 0.5) / 16.0;
#else
  const double b0 = 0.5; /* no teams: nothing to learn */
#endif
  CU_ASSERT_DOUBLE_EQUAL(sph_balance_share(0, 2), b0, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(sph_balance_share(1, 2), 1.0 - b0, 1e-15);
  /* the split follows: thread 0's slice holds b0 of the cost */
  const size_t cut = scan_at(prefix, N, (size_t)(b0 * (double)total));
  size_t got[2][2] = {{0, 0}, {0, 0}};
#ifdef _OPENMP
#pragma omp parallel num_threads(2)
#endif
  {
    const int t = sph_thread();
    sph_slice(prefix, N, &got[t][0], &got[t][1]);
  }
#ifdef _OPENMP
  CU_ASSERT(got[0][0] == 0 && got[0][1] == cut && got[1][0] == cut && got[1][1] == N);
  CU_ASSERT(cut > 0 && cut < N);
#endif
  CU_ASSERT_FATAL(sph_steal_reset(&s, prefix, N, 2) == 0);
  CU_ASSERT_EQUAL(s.slot[0].range, (uint64_t)cut << 32);
  CU_ASSERT_EQUAL(s.slot[1].range, (uint64_t)N << 32 | cut);
  /* by counts when there is no prefix */
  CU_ASSERT_FATAL(sph_steal_reset(&s, NULL, N, 2) == 0);
  CU_ASSERT_EQUAL(s.slot[0].range, (uint64_t)(size_t)(b0 * N) << 32);
  /* every row still handed out once */
  for (int nth = 1; nth <= 3; nth++) {
    memset(count, 0, N * sizeof *count);
    int small = 0, once = 1;
    steal_run(&s, prefix, N, 2, nth, 8, count, &small);
    for (size_t i = 0; i < N; i++)
      once &= count[i] == 1;
    CU_ASSERT(once);
  }
  /* other team sizes split equally */
  CU_ASSERT_DOUBLE_EQUAL(sph_balance_share(0, 3), 1.0 / 3.0, 0.0);
  CU_ASSERT_FATAL(sph_steal_reset(&s, prefix, N, 3) == 0);
  for (int t = 0; t < 3; t++) {
    size_t lo, hi;
    sph_share(prefix, N, t, 3, &lo, &hi);
    CU_ASSERT_EQUAL(s.slot[t].range, (uint64_t)hi << 32 | lo);
  }
  /* never below half an equal share, and the shares sum to 1 */
  for (int k = 0; k < 200; k++)
    pass_by_thread0(&s, prefix, N, 2);
#ifdef _OPENMP
  CU_ASSERT(sph_balance_share(1, 2) >= 0.25 - 1e-15 && sph_balance_share(1, 2) < 0.26);
#endif
  CU_ASSERT_DOUBLE_EQUAL(sph_balance_share(0, 2) + sph_balance_share(1, 2), 1.0, 1e-15);
  sph_balance_reset();
  CU_ASSERT_DOUBLE_EQUAL(sph_balance_share(0, 2), 0.5, 0.0);
  sph_steal_free(&s);
  free(count);
  free(prefix);
}

int main(void) {
  CU_TestInfo tests[] = {
      {"share: uniform cost, the equal-count split", test_share_uniform},
      {"share: a dense block is split by cost", test_share_skewed},
      {"share: zero cost and no items", test_share_degenerate},
      {"slice: each thread of a team takes its share", test_slice_in_team},
      {"steal: every row once, for any slices and team", test_steal_once},
      {"steal: one thread takes its slice in order", test_steal_alone},
      {"steal: an idle thread's slice is taken over", test_steal_takes_over},
      {"balance: the split learns each thread's share", test_balance_learn},
      {"arrays block: staggered, disjoint, zeroed", test_arrays_block},
      {"arrays regrow: keeps the first elements, zeroes the rest", test_arrays_regrow},
      CU_TEST_INFO_NULL};
  return sph_test_main("parallel", tests);
}
