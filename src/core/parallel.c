/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * parallel.c - the serial-below threshold of the parallel loops, and the
 * split of a loop into slices of equal cost (see parallel.h).
 */
#include "config.h"

#include "core/parallel.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>

long sph_omp_min(void) {
  static long value = -1;
  long v = value;
  if (v < 0) {
    const char *e = getenv("SPH_TEST_OMP_MIN");
    char *end;
    v = 2048;
    if (e && *e) {
      long x = strtol(e, &end, 10);
      if (*end == '\0' && x >= 0) v = x;
    }
    value = v; /* the same value whichever thread stores it */
  }
  return v;
}

/* The first i in 0..n with prefix[i] >= target. */
static size_t first_at(const size_t *prefix, size_t n, size_t target) {
  size_t a = 0, b = n;
  while (a < b) {
    const size_t m = a + (b - a) / 2;
    if (prefix[m] < target)
      a = m + 1;
    else
      b = m;
  }
  return a;
}

/* floor(total t / parts), without overflowing total * t: where part t of
 * `parts` equal parts of 0..total starts. */
static size_t part_start(size_t total, int t, int parts) {
  const size_t q = total / (size_t)parts, r = total % (size_t)parts;
  return q * (size_t)t + r * (size_t)t / (size_t)parts;
}

/* ---- the learned split ---- */

#define BALANCE_MAX 16              /* teams up to this size learn */
static double balance[BALANCE_MAX]; /* the shares, summing to 1 */
static int balance_parts;           /* the team size they are for; 0: none */

static int balance_off(void) {
  static int value = -1;
  int v = value;
  if (v < 0) {
    const char *e = getenv("SPH_TEST_BALANCE");
    v = e && strcmp(e, "equal") == 0;
    value = v; /* the same value whichever thread stores it */
  }
  return v;
}

void sph_balance_reset(void) { balance_parts = 0; }

double sph_balance_share(int t, int parts) {
  return parts == balance_parts && t >= 0 && t < parts ? balance[t] : 1.0 / parts;
}

/* Where part t of `parts` starts in 0..total: at the sum of the learned
 * shares of the parts before it (`learned` and shares learned for this
 * team size), else at an equal part's. */
static size_t start_of(size_t total, int t, int parts, int learned) {
  if (!learned || parts != balance_parts || t <= 0 || t >= parts)
    return part_start(total, t, parts);
  double f = 0.0;
  for (int k = 0; k < t; k++)
    f += balance[k];
  const double x = f * (double)total;
  return x <= 0.0 ? 0 : x >= (double)total ? total : (size_t)x;
}

/* Part t of `parts`: by cost when prefix is given, else by counts. */
static void part(const size_t *prefix, size_t n, int t, int parts, int learned, size_t *lo,
                 size_t *hi) {
  if (parts <= 1) {
    *lo = 0;
    *hi = n;
    return;
  }
  if (!prefix) {
    *lo = start_of(n, t, parts, learned);
    *hi = start_of(n, t + 1, parts, learned);
    return;
  }
  const size_t total = prefix[n] - prefix[0];
  *lo = t == 0 ? 0 : first_at(prefix, n, prefix[0] + start_of(total, t, parts, learned));
  *hi =
      t == parts - 1 ? n : first_at(prefix, n, prefix[0] + start_of(total, t + 1, parts, learned));
}

void sph_share(const size_t *prefix, size_t n, int t, int parts, size_t *lo, size_t *hi) {
  part(prefix, n, t, parts, 0, lo, hi);
}

static void part_of(const size_t *prefix, size_t n, int t, int parts, size_t *lo, size_t *hi) {
  part(prefix, n, t, parts, 1, lo, hi);
}

void sph_slice(const size_t *prefix, size_t n, size_t *lo, size_t *hi) {
  part_of(prefix, n, sph_thread(), sph_threads(), lo, hi);
}

/* ---- slices with stealing ---- */

static uint64_t steal_pack(size_t front, size_t back) {
  return (uint64_t)back << 32 | (uint64_t)front;
}

int sph_steal_reset(sph_steal *s, const size_t *prefix, size_t n, int parts) {
  if (parts < 1) parts = 1;
  if (n > UINT32_MAX) return -1;
  if (parts > s->cap) {
    void *m = malloc(((size_t)parts + 1) * sizeof(sph_steal_slot));
    if (!m) return -1;
    free(s->mem);
    s->mem = m;
    const uintptr_t a = ((uintptr_t)m + 63) & ~(uintptr_t)63;
    s->slot = (sph_steal_slot *)a;
    s->cap = parts;
  }
  s->parts = parts;
  s->prefix = prefix;
  s->team = 0;
  for (int t = 0; t < parts; t++) {
    size_t lo, hi;
    part_of(prefix, n, t, parts, &lo, &hi);
    s->slot[t].range = steal_pack(lo, hi);
    s->slot[t].done = 0;
  }
  return 0;
}

/* Takes a chunk off the front (the owner: a sixteenth of what is left) or
 * the back (a thief: half) of slot, at least `grain` rows; 0 when the slot
 * is empty. Relaxed order suffices: the claim only has to
 * be atomic (the rows' data are ordered by the region's fork and join). */
static int steal_take(sph_steal_slot *slot, int back, size_t grain, size_t *lo, size_t *hi) {
  uint64_t r = __atomic_load_n(&slot->range, __ATOMIC_RELAXED);
  for (;;) {
    const size_t f = (size_t)(uint32_t)r, b = (size_t)(r >> 32);
    if (f >= b) return 0;
    const size_t rest = b - f;
    size_t g = back ? rest / 2 : rest / 16; /* the owner's chunks shrink as it goes */
    if (g < grain) g = grain;
    if (g > rest) g = rest;
    const uint64_t want = back ? steal_pack(f, b - g) : steal_pack(f + g, b);
    if (__atomic_compare_exchange_n(&slot->range, &r, want, 1, __ATOMIC_RELAXED,
                                    __ATOMIC_RELAXED)) {
      *lo = back ? b - g : f;
      *hi = back ? b : f + g;
      return 1;
    }
  }
}

/* Credits the chunk [lo, hi) to thread t's slot. */
static int steal_took(sph_steal *s, int t, size_t lo, size_t hi) {
  if (t < s->parts) s->slot[t].done += s->prefix ? s->prefix[hi] - s->prefix[lo] : hi - lo;
  return 1;
}

int sph_steal_next(sph_steal *s, size_t grain, size_t *lo, size_t *hi) {
  const int t = sph_thread(), parts = s->parts;
  if (grain < 1) grain = 1;
  /* stored once per loop: a store on every call would pull the line that
   * every thread reads (slot, parts, prefix) away from the other core */
  const int nt = sph_threads();
  if (__atomic_load_n(&s->team, __ATOMIC_RELAXED) != nt)
    __atomic_store_n(&s->team, nt, __ATOMIC_RELAXED);
  if (t < parts && steal_take(&s->slot[t], 0, grain, lo, hi)) return steal_took(s, t, *lo, *hi);
  for (;;) { /* the slice with the most rows left; slices only shrink */
    int v = -1;
    size_t most = 0;
    for (int k = 0; k < parts; k++) {
      const uint64_t r = __atomic_load_n(&s->slot[k].range, __ATOMIC_RELAXED);
      const size_t f = (size_t)(uint32_t)r, b = (size_t)(r >> 32);
      if (b > f && b - f > most) {
        most = b - f;
        v = k;
      }
    }
    if (v < 0) return 0;
    if (steal_take(&s->slot[v], 1, grain, lo, hi)) return steal_took(s, t, *lo, *hi);
  }
}

/* A sixteenth of the way per loop: a core's speed share settles within a
 * few dozen passes, while one pass's hold-up (5-25 %) moves the split by
 * about a percent. */
#define BALANCE_RATE (1.0 / 16.0)

void sph_steal_learn(sph_steal *s) {
  const int parts = s->parts;
  if (parts < 2 || parts > BALANCE_MAX || s->team != parts || balance_off()) return;
  double total = 0.0;
  for (int t = 0; t < parts; t++)
    total += (double)s->slot[t].done;
  if (!(total > 0.0)) return;
  if (balance_parts != parts) {
    for (int t = 0; t < parts; t++)
      balance[t] = 1.0 / parts;
    balance_parts = parts;
  }
  /* the measured shares, raised to at least half an even share each: a
   * convex step toward them keeps every share at least that */
  double f[BALANCE_MAX];
  for (int t = 0; t < parts; t++)
    f[t] = (double)s->slot[t].done / total;
  sph_shares_at_least_half(f, parts);
  for (int t = 0; t < parts; t++)
    balance[t] += BALANCE_RATE * (f[t] - balance[t]);
}

void sph_shares_at_least_half(double *f, int parts) {
  const double least = 0.5 / parts;
  double above = 0.0;
  for (int t = 0; t < parts; t++)
    if (f[t] > least) above += f[t] - least;
  const double scale = above > 0.0 ? (1.0 - parts * least) / above : 0.0;
  for (int t = 0; t < parts; t++)
    f[t] = f[t] > least ? least + scale * (f[t] - least) : least;
}

double sph_seconds(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void sph_steal_free(sph_steal *s) {
  free(s->mem);
  *s = (sph_steal){0};
}
