/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * exact_sum.c - the long accumulator of exact_sum.h.
 */
#include "config.h"

#include "core/exact_sum.h"

#include <math.h>
#include <string.h>

#define DIGIT 4294967296.0 /* 2^32 */
#define LOW32 0xffffffffu

typedef unsigned __int128 u128;

void sph_xsum_init(sph_xsum *s) { memset(s, 0, sizeof *s); }

/* Every digit but the top one into [0, 2^32), the carries upwards; the
 * value unchanged. */
void sph_xsum_normalise_(int64_t d[SPH_XSUM_DIGITS]) {
  for (int k = 0; k < SPH_XSUM_DIGITS - 1; k++) {
    const int64_t low = (int64_t)((uint64_t)d[k] & LOW32);
    d[k + 1] += (d[k] - low) / (int64_t)DIGIT; /* exact: a multiple of 2^32 */
    d[k] = low;
  }
}

void sph_xsum_merge(sph_xsum *a, const sph_xsum *b) {
  if (a->adds + b->adds + 1 >= SPH_XSUM_MAX_ADDS) sph_xsum_normalise_(a->d), a->adds = 0;
  sph_xsum b1 = *b;
  if (b1.adds + 1 >= SPH_XSUM_MAX_ADDS) sph_xsum_normalise_(b1.d), b1.adds = 0;
  for (int k = 0; k < SPH_XSUM_DIGITS; k++)
    a->d[k] += b1.d[k];
  a->adds += b1.adds + 1;
  a->special += b1.special;
}

double sph_xsum_round(const sph_xsum *s) {
  if (s->special != 0.0) return s->special; /* (true for NaN too) */
  int64_t d[SPH_XSUM_DIGITS];
  memcpy(d, s->d, sizeof d);
  sph_xsum_normalise_(d);
  double sign = 1.0;
  if (d[SPH_XSUM_DIGITS - 1] < 0) { /* negative: round its magnitude */
    for (int k = 0; k < SPH_XSUM_DIGITS; k++)
      d[k] = -d[k];
    sph_xsum_normalise_(d);
    sign = -1.0;
  }
  int t = SPH_XSUM_DIGITS - 1;
  while (t >= 0 && d[t] == 0)
    t--;
  if (t < 0) return 0.0;
  /* the top three digits (zeros below digit 0), and whether any below is not 0 */
  const uint64_t d1 = t >= 1 ? (uint64_t)d[t - 1] : 0, d2 = t >= 2 ? (uint64_t)d[t - 2] : 0;
  const u128 acc = ((u128)(uint64_t)d[t] << 64) | ((u128)d1 << 32) | d2;
  int sticky = 0;
  for (int k = 0; k < t - 2; k++)
    sticky |= d[k] != 0;
  const int base = 32 * (t - 2) - 1074; /* the exponent of acc's lowest bit */
  const uint64_t hi = (uint64_t)(acc >> 64);
  const int len = 64 + (64 - __builtin_clzll(hi)); /* acc's bit length: over 64 (hi > 0) */
  int shift = len - 53;
  uint64_t mant = (uint64_t)(acc >> shift);
  const u128 rem = acc & (((u128)1 << shift) - 1), half = (u128)1 << (shift - 1);
  if (rem > half || (rem == half && (sticky || (mant & 1u)))) mant++;
  if (mant == (uint64_t)1 << 53) mant >>= 1, shift++;
  return sign * ldexp((double)mant, base + shift);
}
