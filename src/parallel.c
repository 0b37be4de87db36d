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

void sph_slice(const size_t *prefix, size_t n, size_t *lo, size_t *hi) {
  const int t = sph_thread(), parts = sph_threads();
  if (prefix) {
    sph_share(prefix, n, t, parts, lo, hi);
    return;
  }
  *lo = part_start(n, t, parts);
  *hi = part_start(n, t + 1, parts);
}
