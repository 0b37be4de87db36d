/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * decomp.c - the domain decomposition (see decomp.h).
 */
#include "config.h"

#include "neighbours/decomp.h"

#include <math.h>
#include <stdint.h>
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

/* The cell of particle i of p (sph_decomp_cell): 0, or -1 outside the curve. */
static int particle_cell(const sph_decomp_grid *g, const sph_particles *p, size_t i,
                         uint32_t c[SPH_DIM]) {
  double x[SPH_DIM];
  for (int a = 0; a < SPH_DIM; a++)
    x[a] = p->pos[a][i];
  return sph_decomp_cell(g, x, c);
}

/* Cells whose keys sph_decomp_keys keeps at hand: 2^SPH_DECOMP_KEY_BITS. */
#define SPH_DECOMP_KEY_BITS 12
#define SPH_DECOMP_KEY_CACHE ((size_t)1 << SPH_DECOMP_KEY_BITS)

int sph_decomp_keys(const sph_decomp_grid *g, const sph_particles *p, uint64_t *keys,
                    sph_error *err) {
  /* the store is sorted by cells, of another grid: a particle's cell is
   * often one met a little before, whose key is kept in a table by the
   * cell (the cell's coordinates packed: below 2^63, so UINT64_MAX marks a
   * free place); without room for it, each key is made */
  uint64_t(*seen)[2] = malloc(SPH_DECOMP_KEY_CACHE * sizeof *seen);
  if (seen)
    for (size_t k = 0; k < SPH_DECOMP_KEY_CACHE; k++)
      seen[k][0] = UINT64_MAX;
  for (size_t i = 0; i < p->n; i++) {
    uint32_t c[SPH_DIM];
    if (particle_cell(g, p, i, c)) {
      free(seen);
      return sph_error_set(err, "decomposition: particle %lld is outside the curve's reach",
                           (long long)p->id[i]);
    }
    uint64_t v = 0;
    for (int a = 0; a < SPH_DIM; a++)
      v = v << SPH_DECOMP_BITS | c[a];
    if (!seen) {
      keys[i] = sph_decomp_hilbert(c, SPH_DECOMP_BITS);
      continue;
    }
    uint64_t *at = seen[(v * 0x9E3779B97F4A7C15ull) >> (64 - SPH_DECOMP_KEY_BITS)];
    if (at[0] != v) at[0] = v, at[1] = sph_decomp_hilbert(c, SPH_DECOMP_BITS);
    keys[i] = at[1];
  }
  free(seen);
  return 0;
}

static int cmp_u64(const void *a, const void *b) {
  const uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return (x > y) - (x < y);
}

/* A key's particles: their weights' sum and the largest of them. */
typedef struct weighted_key {
  uint64_t key, w;
  uint32_t w_max;
} weighted_key;

static int cmp_weighted(const void *a, const void *b) {
  const uint64_t x = ((const weighted_key *)a)->key, y = ((const weighted_key *)b)->key;
  return (x > y) - (x < y);
}

/* s[0..m) with each entry that follows one of its key merged into it (its
 * weights added, the heavier particle kept); returns the entries left. */
static size_t merge_equal_keys(weighted_key *s, size_t m) {
  size_t g = 0;
  for (size_t k = 0; k < m; k++)
    if (g && s[g - 1].key == s[k].key) {
      s[g - 1].w += s[k].w;
      if (s[k].w_max > s[g - 1].w_max) s[g - 1].w_max = s[k].w_max;
    } else
      s[g++] = s[k];
  return g;
}

int sph_decomp_cut_weighted(const uint64_t *keys, const uint32_t *w, size_t n, int ranks,
                            uint64_t *first, sph_error *err) {
  return sph_decomp_cut_shares(keys, w, n, ranks, NULL, first, err);
}

int sph_decomp_cut_shares(const uint64_t *keys, const uint32_t *w, size_t n, int ranks,
                          const double *share, uint64_t *first, sph_error *err) {
  first[0] = 0;
  if (ranks < 2) return 0;
  weighted_key *s = malloc((n ? n : 1) * sizeof *s);
  if (!s) return sph_error_set(err, "decomposition: out of memory");
  /* the runs of equal keys in the particles' order (a cell's particles are
   * mostly together: the store is sorted by cells), sorted by key, then
   * each key's runs merged */
  uint64_t total = 0;
  for (size_t i = 0; i < n; i++)
    s[i] = (weighted_key){keys[i], w[i], w[i]}, total += w[i];
  const size_t m = merge_equal_keys(s, n);
  qsort(s, m, sizeof *s, cmp_weighted);
  const size_t g = merge_equal_keys(s, m);
  /* rank r from the first particle, in the order of keys and, within a
   * key, of weights, before which the weights reach r / ranks of the
   * whole: the first key whose particles but its heaviest reach it with
   * those of the keys before (the running sums at the ends of a key's
   * particles do not depend on their order, so neither does the cut) */
  uint64_t sum = 0;
  size_t at = 0;
  double below = 0.0; /* with shares: the shares of the ranks before r */
  for (int r = 1; r < ranks; r++) {
    if (share) below += share[r - 1];
    while (at < g &&
           (share ? (double)(sum + s[at].w - s[at].w_max) < below * (double)total
                  : (sum + s[at].w - s[at].w_max) * (uint64_t)ranks < (uint64_t)r * total))
      sum += s[at++].w;
    first[r] = g ? (at < g ? s[at].key : s[g - 1].key + 1) : UINT64_MAX;
    if (first[r] < first[r - 1]) first[r] = first[r - 1];
  }
  free(s);
  return 0;
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

/* ---- the halo: the rank's own cells, dilated by `depth` on a box of cells ---- */

/* The box of cells the particles fill, widened by depth on each axis that
 * does not wrap; the periodic axis spans its period's cells. */
typedef struct cellbox {
  int64_t lo[SPH_DIM];
  size_t n[SPH_DIM], total;
} cellbox;

static size_t box_index(const cellbox *b, const uint32_t c[SPH_DIM]) {
  size_t k = 0;
  for (int a = SPH_DIM - 1; a >= 0; a--)
    k = k * b->n[a] + (size_t)((int64_t)c[a] - b->lo[a]);
  return k;
}

/* One axis's dilation: out[c] = 1 where in[c + k a] for some |k| <= depth
 * (wrapping on the periodic axis, clipped on the others). */
static void dilate(const cellbox *b, int a, int wrap, int depth, const unsigned char *in,
                   unsigned char *out) {
  size_t stride = 1;
  for (int q = 0; q < a; q++)
    stride *= b->n[q];
  const long n = (long)b->n[a];
  memset(out, 0, b->total);
  for (size_t k = 0; k < b->total; k++) {
    if (!in[k]) continue;
    const long at = (long)((k / stride) % b->n[a]);
    const size_t base = k - (size_t)at * stride;
    for (long d = -depth; d <= depth; d++) {
      long t = at + d;
      if (wrap)
        t = ((t % n) + n) % n;
      else if (t < 0 || t >= n)
        continue;
      out[base + (size_t)t * stride] = 1;
    }
  }
}

/* Each particle's cell (*at, n of them, the caller's to free) and the box
 * of cells they fill (the periodic axis spanning its period's cells): 0,
 * or -1 with err. */
static int cells_of(const sph_decomp_grid *g, const sph_particles *p, cellbox *b,
                    uint32_t (**at)[SPH_DIM], sph_error *err) {
  const int64_t half = (int64_t)1 << (SPH_DECOMP_BITS - 1);
  int64_t hi[SPH_DIM];
  for (int a = 0; a < SPH_DIM; a++)
    b->lo[a] = INT64_MAX, hi[a] = INT64_MIN;
  uint32_t(*c)[SPH_DIM] = malloc((p->n ? p->n : 1) * sizeof *c);
  if (!c) return sph_error_set(err, "decomposition: out of memory for the particles' cells");
  for (size_t i = 0; i < p->n; i++) {
    if (particle_cell(g, p, i, c[i])) {
      free(c);
      return sph_error_set(err, "decomposition: particle %lld is outside the curve's reach",
                           (long long)p->id[i]);
    }
    for (int a = 0; a < SPH_DIM; a++) {
      if (c[i][a] < b->lo[a]) b->lo[a] = c[i][a];
      if (c[i][a] > hi[a]) hi[a] = c[i][a];
    }
  }
  b->total = p->n ? 1 : 0;
  for (int a = 0; a < SPH_DIM && p->n; a++) {
    if (g->periodic == 1 + a) b->lo[a] = half, hi[a] = half + g->ncell_periodic - 1;
    b->n[a] = (size_t)(hi[a] - b->lo[a] + 1);
    b->total *= b->n[a];
  }
  *at = c;
  return 0;
}

/* The marks of sph_decomp_halo around the particles with mark[i] = 1 on
 * entry (the others 0). */
static long halo_marks(const sph_decomp_grid *g, const sph_particles *p, int depth, int row_depth,
                       unsigned row_kinds, unsigned char *mark, sph_error *err) {
  cellbox b;
  uint32_t(*at)[SPH_DIM];
  if (cells_of(g, p, &b, &at, err)) return -1;
  if (row_depth > depth) row_depth = depth;
  unsigned char *block = calloc(3 * (b.total ? b.total : 1), 1);
  if (!block) {
    free(at);
    return sph_error_set(err, "decomposition: out of memory for the halo"), -1;
  }
  unsigned char *cells = block, *other = block + b.total, *rows = block + 2 * b.total;
  for (size_t i = 0; i < p->n; i++)
    if (mark[i]) cells[box_index(&b, at[i])] = 1;
  /* the 3^D block and beyond, within row_depth cells, then within depth:
   * one axis at a time (the box's edges hold no particle beyond its last
   * cells, so clipping there loses none; a dilation by r then by s is one
   * by r + s) */
  for (int step = 0; step < 2; step++) {
    const int by = step == 0 ? row_depth : depth - row_depth;
    for (int a = 0; a < SPH_DIM && by > 0; a++) {
      dilate(&b, a, g->periodic == 1 + a, by, cells, other);
      unsigned char *t = cells;
      cells = other, other = t;
    }
    if (step == 0) memcpy(rows, cells, b.total);
  }
  long ghosts = 0;
  for (size_t i = 0; i < p->n; i++) {
    if (mark[i]) continue;
    const size_t k = box_index(&b, at[i]);
    if (cells[k]) mark[i] = rows[k] && (row_kinds >> (unsigned)p->kind[i] & 1u) ? 2 : 3, ghosts++;
  }
  free(block);
  free(at);
  return ghosts;
}

long sph_decomp_halo(const sph_decomp_grid *g, const sph_particles *p, const uint64_t *keys,
                     const uint64_t *first, int ranks, int rank, int depth, int row_depth,
                     unsigned row_kinds, unsigned char *mark, sph_error *err) {
  for (size_t i = 0; i < p->n; i++)
    mark[i] = sph_decomp_owner(first, ranks, keys[i]) == rank;
  return halo_marks(g, p, depth, row_depth, row_kinds, mark, err);
}

/* One axis's sum over the 3 cells along it: out[c] = in[c - a] + in[c] +
 * in[c + a] (wrapping on the periodic axis, each cell of its period once;
 * clipped on the others). */
static void sum3(const cellbox *b, int a, int wrap, const uint32_t *in, uint32_t *out) {
  size_t stride = 1;
  for (int q = 0; q < a; q++)
    stride *= b->n[q];
  const long n = (long)b->n[a];
  for (size_t k = 0; k < b->total; k++) {
    const long at = (long)((k / stride) % b->n[a]);
    const size_t base = k - (size_t)at * stride;
    uint32_t s = 0;
    for (long d = -1; d <= 1; d++) {
      long t = at + d;
      if (wrap) {
        if ((d != 0 && n == 1) || (d == 1 && n == 2)) continue;
        t = ((t % n) + n) % n;
      } else if (t < 0 || t >= n)
        continue;
      s += in[base + (size_t)t * stride];
    }
    out[k] = s;
  }
}

int sph_decomp_block_counts(const sph_decomp_grid *g, const sph_particles *p, int32_t kind,
                            uint32_t *all, uint32_t *of_kind, sph_error *err) {
  cellbox b;
  uint32_t(*at)[SPH_DIM];
  if (cells_of(g, p, &b, &at, err)) return -1;
  uint32_t *block = calloc(3 * (b.total ? b.total : 1), sizeof *block);
  if (!block) {
    free(at);
    return sph_error_set(err, "decomposition: out of memory for the cells' counts");
  }
  uint32_t *cells[2] = {block, block + b.total}, *other = block + 2 * b.total;
  for (size_t i = 0; i < p->n; i++) {
    const size_t k = box_index(&b, at[i]);
    cells[0][k]++;
    cells[1][k] += p->kind[i] == kind;
  }
  for (int c = 0; c < 2; c++) /* the 3^D block of cells around each, one axis at a time */
    for (int a = 0; a < SPH_DIM; a++) {
      sum3(&b, a, g->periodic == 1 + a, cells[c], other);
      memcpy(cells[c], other, b.total * sizeof *other);
    }
  for (size_t i = 0; i < p->n; i++) {
    const size_t k = box_index(&b, at[i]);
    all[i] = cells[0][k], of_kind[i] = cells[1][k];
  }
  free(block);
  free(at);
  return 0;
}
