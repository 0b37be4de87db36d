/*
 * parallel.c - the serial-below threshold of the parallel loops, and the
 * split of a loop into slices of equal cost (see parallel.h).
 */
#include "config.h"

#include "parallel.h"

#include <stdlib.h>

long sph_omp_min(void) {
  static long value = -1;
  long v = value;
  if (v < 0) {
    const char *e = getenv("SPH_OMP_MIN");
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

void sph_share(const size_t *prefix, size_t n, int t, int parts, size_t *lo, size_t *hi) {
  if (parts <= 1) {
    *lo = 0;
    *hi = n;
    return;
  }
  const size_t total = prefix[n] - prefix[0];
  *lo = t == 0 ? 0 : first_at(prefix, n, prefix[0] + part_start(total, t, parts));
  *hi = t == parts - 1 ? n : first_at(prefix, n, prefix[0] + part_start(total, t + 1, parts));
}

/* Part t of `parts`: by cost when prefix is given, else equal counts. */
static void part_of(const size_t *prefix, size_t n, int t, int parts, size_t *lo, size_t *hi) {
  if (prefix) {
    sph_share(prefix, n, t, parts, lo, hi);
    return;
  }
  *lo = part_start(n, t, parts);
  *hi = part_start(n, t + 1, parts);
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
  for (int t = 0; t < parts; t++) {
    size_t lo, hi;
    part_of(prefix, n, t, parts, &lo, &hi);
    s->slot[t].range = steal_pack(lo, hi);
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

int sph_steal_next(sph_steal *s, size_t grain, size_t *lo, size_t *hi) {
  const int t = sph_thread(), parts = s->parts;
  if (grain < 1) grain = 1;
  if (t < parts && steal_take(&s->slot[t], 0, grain, lo, hi)) return 1;
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
    if (steal_take(&s->slot[v], 1, grain, lo, hi)) return 1;
  }
}

void sph_steal_free(sph_steal *s) {
  free(s->mem);
  *s = (sph_steal){0};
}
