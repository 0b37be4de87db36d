/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * exact_sum.h - a sum of doubles that does not depend on the order of its
 * terms: every term is added exactly into a long fixed-point accumulator
 * (Kulisch's long accumulator: U. Kulisch, "Computer Arithmetic and
 * Validity", de Gruyter 2008, ch. 7), and the sum is rounded to the nearest
 * double once, at the end, ties to even. Two accumulators merge exactly, so
 * partial sums over any split of the terms (threads, MPI ranks) give the
 * same bits as one sum in any order: the reductions of the diagnostics and
 * the energy ledger use it (doc/method.md, "Determinism").
 *
 * The accumulator covers every double: 32-bit digits at 2^(32k - 1074),
 * k = 0 .. SPH_XSUM_DIGITS - 1, each held in an int64 with room for 2^29
 * unnormalised additions (a term touches three digits), normalised when
 * that many have been made. A term that is infinite or NaN makes the sum
 * that infinity or NaN (+inf and -inf: NaN), as plain addition would.
 */
#ifndef SPH_EXACT_SUM_H
#define SPH_EXACT_SUM_H

#include <stdint.h>
#include <string.h>

#define SPH_XSUM_DIGITS 68

typedef struct sph_xsum {
  int64_t d[SPH_XSUM_DIGITS]; /* the value: sum of d[k] 2^(32k - 1074) */
  int64_t adds;               /* additions since the last normalisation */
  double special;             /* the sum of the infinite and NaN terms (0 if none) */
} sph_xsum;

/* An empty sum (zero). */
void sph_xsum_init(sph_xsum *s);
/* Additions between normalisations: each adds below 2^33 to a digit, and
 * a digit holds 2^63. */
#define SPH_XSUM_MAX_ADDS ((int64_t)1 << 29)

/* Carries every digit but the top one into [0, 2^32) (the value unchanged). */
void sph_xsum_normalise_(int64_t d[SPH_XSUM_DIGITS]);

/* Adds x exactly (inline: a handful of integer operations, in the loops
 * that sum over the particles). */
static inline void sph_xsum_add(sph_xsum *s, double x) {
  uint64_t bits;
  memcpy(&bits, &x, sizeof bits);
  const unsigned ex = (unsigned)(bits >> 52) & 0x7ffu;
  if (ex == 0x7ffu) { /* infinite or NaN */
    s->special += x;
    return;
  }
  /* x = +-m 2^(pos - 1074): m with its hidden bit (none when subnormal);
   * a zero adds zeros */
  const uint64_t m = (bits & (((uint64_t)1 << 52) - 1)) | ((uint64_t)(ex != 0) << 52);
  const unsigned pos = ex ? ex - 1 : 0, sh = pos % 32;
  const int k = (int)(pos / 32);
  /* m shifted by sh, in 32-bit pieces: its low 32 bits and its high 21
   * apart, so that no piece leaves 64 bits */
  const uint64_t lo = (m & 0xffffffffu) << sh, hi = (m >> 32) << sh;
  const int64_t neg = -(int64_t)(bits >> 63); /* 0, or -1: subtract */
  const int64_t c0 = (int64_t)(lo & 0xffffffffu), c1 = (int64_t)((lo >> 32) + (hi & 0xffffffffu)),
                c2 = (int64_t)(hi >> 32);
  s->d[k] += (c0 ^ neg) - neg;
  s->d[k + 1] += (c1 ^ neg) - neg;
  s->d[k + 2] += (c2 ^ neg) - neg;
  if (++s->adds >= SPH_XSUM_MAX_ADDS) {
    sph_xsum_normalise_(s->d);
    s->adds = 0;
  }
}
/* Adds the sum b into a, exactly. */
void sph_xsum_merge(sph_xsum *a, const sph_xsum *b);
/* The sum rounded to the nearest double (ties to even); +0 for an empty
 * sum or one whose terms cancel. */
double sph_xsum_round(const sph_xsum *s);

#endif
