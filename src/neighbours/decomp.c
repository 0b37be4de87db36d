/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * decomp.c - the domain decomposition (see decomp.h).
 */
#include "config.h"

#include "neighbours/decomp.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Skilling (2004), "Programming the Hilbert curve": the cell's coordinates
 * turned in place into the "transpose" of its Hilbert index (bit j of axis
 * a is bit j * D + (D - 1 - a) of the index), then the bits interleaved. */
uint64_t sph_decomp_hilbert(const uint32_t c[SPH_DIM], int bits) {
  uint32_t x[SPH_DIM];
  for (int a = 0; a < SPH_DIM; a++)
    x[a] = c[a];
  const uint32_t top = (uint32_t)1 << (bits - 1);
  for (uint32_t q = top; q > 1; q >>= 1) { /* undo the excess work of the axes' reflections */
    const uint32_t low = q - 1;
    for (int a = 0; a < SPH_DIM; a++)
      if (x[a] & q)
        x[0] ^= low; /* invert the low bits of the first axis */
      else {         /* or exchange them with this axis's */
        const uint32_t t = (x[0] ^ x[a]) & low;
        x[0] ^= t;
        x[a] ^= t;
      }
  }
  for (int a = 1; a < SPH_DIM; a++) /* Gray encoding */
    x[a] ^= x[a - 1];
  uint32_t t = 0;
  for (uint32_t q = top; q > 1; q >>= 1)
    if (x[SPH_DIM - 1] & q) t ^= q - 1;
  for (int a = 0; a < SPH_DIM; a++)
    x[a] ^= t;
  uint64_t key = 0;
  for (int j = bits - 1; j >= 0; j--)
    for (int a = 0; a < SPH_DIM; a++)
      key = key << 1 | (uint64_t)(x[a] >> j & 1u);
  return key;
}

/* The cell index along axis a of coordinate v (periodic axes wrapped),
 * offset into [0, 2^bits); -1 outside. */
static int64_t cell_along(const sph_decomp_grid *g, int a, double v) {
  const int64_t half = (int64_t)1 << (SPH_DECOMP_BITS - 1);
  if (!isfinite(v)) return -1;
  if (g->periodic == 1 + a) {
    const double k = floor((v - g->period_lo) / g->side);
    if (!(fabs(k) < 1e15)) return -1;
    int64_t m = (int64_t)k % g->ncell_periodic;
    if (m < 0) m += g->ncell_periodic;
    return m + half;
  }
  const double k = floor(v / g->side);
  if (!(k >= -(double)half && k < (double)half)) return -1;
  return (int64_t)k + half;
}

int sph_decomp_cell(const sph_decomp_grid *g, const double x[SPH_DIM], uint32_t c[SPH_DIM]) {
  for (int a = 0; a < SPH_DIM; a++) {
    const int64_t k = cell_along(g, a, x[a]);
    if (k < 0) return -1;
    c[a] = (uint32_t)k;
  }
  return 0;
}

int sph_decomp_keys(const sph_decomp_grid *g, const sph_particles *p, uint64_t *keys,
                    sph_error *err) {
  for (size_t i = 0; i < p->n; i++) {
    double x[SPH_DIM];
    uint32_t c[SPH_DIM];
    for (int a = 0; a < SPH_DIM; a++)
      x[a] = p->pos[a][i];
    if (sph_decomp_cell(g, x, c))
      return sph_error_set(err, "decomposition: particle %lld is outside the curve's reach",
                           (long long)p->id[i]);
    keys[i] = sph_decomp_hilbert(c, SPH_DECOMP_BITS);
  }
  return 0;
}

static int cmp_u64(const void *a, const void *b) {
  const uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return (x > y) - (x < y);
}

int sph_decomp_cut(const uint64_t *keys, size_t n, int ranks, uint64_t *first, sph_error *err) {
  first[0] = 0;
  if (ranks < 2) return 0;
  uint64_t *s = malloc((n ? n : 1) * sizeof *s);
  if (!s) return sph_error_set(err, "decomposition: out of memory");
  memcpy(s, keys, n * sizeof *s);
  qsort(s, n, sizeof *s, cmp_u64);
  for (int r = 1; r < ranks; r++) {
    const size_t at = (size_t)((unsigned long long)r * n / (unsigned long long)ranks);
    first[r] = n ? (at < n ? s[at] : s[n - 1] + 1) : UINT64_MAX;
    if (first[r] < first[r - 1]) first[r] = first[r - 1];
  }
  free(s);
  return 0;
}

int sph_decomp_owner(const uint64_t *first, int ranks, uint64_t k) {
  int lo = 0, hi = ranks - 1; /* the last rank whose first key is <= k */
  while (lo < hi) {
    const int mid = (lo + hi + 1) / 2;
    if (first[mid] <= k)
      lo = mid;
    else
      hi = mid - 1;
  }
  return lo;
}

/* ---- the halo: a set of cells (open addressing on the packed coordinates) ---- */

typedef struct cellset {
  uint64_t *slot; /* packed coordinates + 1; 0 = empty */
  size_t cap, n;
} cellset;

static uint64_t pack(const uint32_t c[SPH_DIM]) {
  uint64_t v = 0;
  for (int a = 0; a < SPH_DIM; a++)
    v = v << SPH_DECOMP_BITS | c[a];
  return v + 1;
}

static size_t slot_of(const cellset *s, uint64_t v) {
  uint64_t h = v * 0x9E3779B97F4A7C15ull;
  size_t i = (size_t)(h >> 17) & (s->cap - 1);
  while (s->slot[i] && s->slot[i] != v)
    i = (i + 1) & (s->cap - 1);
  return i;
}

static int set_add(cellset *s, uint64_t v) {
  if (2 * (s->n + 1) > s->cap) {
    cellset t = {calloc(s->cap ? 2 * s->cap : 1024, sizeof *t.slot), s->cap ? 2 * s->cap : 1024, 0};
    if (!t.slot) return -1;
    for (size_t i = 0; i < s->cap; i++)
      if (s->slot[i]) t.slot[slot_of(&t, s->slot[i])] = s->slot[i], t.n++;
    free(s->slot);
    *s = t;
  }
  const size_t i = slot_of(s, v);
  if (!s->slot[i]) s->slot[i] = v, s->n++;
  return 0;
}

static int set_has(const cellset *s, uint64_t v) { return s->cap && s->slot[slot_of(s, v)] == v; }

/* Adds every cell within depth of c (a periodic axis wrapping). */
static int add_block(const sph_decomp_grid *g, cellset *s, const uint32_t c[SPH_DIM], int depth) {
  const int side = 2 * depth + 1;
  long total = 1;
  for (int a = 0; a < SPH_DIM; a++)
    total *= side;
  const int64_t half = (int64_t)1 << (SPH_DECOMP_BITS - 1);
  for (long k = 0; k < total; k++) {
    uint32_t d[SPH_DIM];
    long rest = k;
    int ok = 1;
    for (int a = 0; a < SPH_DIM; a++) {
      int64_t v = (int64_t)c[a] + rest % side - depth;
      rest /= side;
      if (g->periodic == 1 + a) {
        v -= half;
        v %= g->ncell_periodic;
        if (v < 0) v += g->ncell_periodic;
        v += half;
      }
      if (v < 0 || v >= 2 * half) ok = 0;
      d[a] = (uint32_t)v;
    }
    if (ok && set_add(s, pack(d))) return -1;
  }
  return 0;
}

long sph_decomp_halo(const sph_decomp_grid *g, const sph_particles *p, const uint64_t *keys,
                     const uint64_t *first, int ranks, int rank, int depth, unsigned char *mark,
                     sph_error *err) {
  cellset need = {NULL, 0, 0};
  long ghosts = 0;
  for (size_t i = 0; i < p->n; i++) {
    mark[i] = sph_decomp_owner(first, ranks, keys[i]) == rank;
    if (!mark[i]) continue;
    double x[SPH_DIM];
    uint32_t c[SPH_DIM];
    for (int a = 0; a < SPH_DIM; a++)
      x[a] = p->pos[a][i];
    if (sph_decomp_cell(g, x, c) || add_block(g, &need, c, depth)) {
      free(need.slot);
      return sph_error_set(err, "decomposition: out of memory or outside the curve"), -1;
    }
  }
  for (size_t i = 0; i < p->n; i++) {
    if (mark[i]) continue;
    double x[SPH_DIM];
    uint32_t c[SPH_DIM];
    for (int a = 0; a < SPH_DIM; a++)
      x[a] = p->pos[a][i];
    if (!sph_decomp_cell(g, x, c) && set_has(&need, pack(c))) mark[i] = 2, ghosts++;
  }
  free(need.slot);
  return ghosts;
}
