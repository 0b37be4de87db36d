/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * lanes.h - the arithmetic that pair terms are written in: one set of
 * operations, several flavours, bitwise the same results in each lane.
 *
 *   v1   one double (the scalar loop); masks are ints
 *   v2   two doubles: SSE2 where there is SSE2, else plain C (row cuts)
 *   v4e  four doubles as two v2 halves (the portable lane loop)
 *   v4x  four doubles in one AVX register (x86-64 with GCC, chosen at run
 *        time when the processor has AVX2; SPH_LANES_AVX is then defined)
 *   v8z  eight doubles in one AVX-512 register (x86-64 with GCC, chosen at
 *        run time when the processor has AVX-512F); its masks are __mmask8
 *        and v8z_lo / v8z_hi give its halves as v4x, so that a loop can
 *        evaluate eight pairs at once and still add them into four-lane sums
 *        in the four-lane order (src/solver/interact_lanes.h)
 *
 * Every flavour FL has the same names: FL_all(a), FL_add/sub/mul/div(a, b),
 * FL_sqrt, FL_abs, FL_neg (IEEE negation: the sign bit flipped),
 * FL_min(a, b) = a < b ? a : b and FL_max(a, b) = a > b ? a : b per lane
 * (the x86 minpd/maxpd rule, also for the plain-C lanes), FL_lt(a, b) a
 * mask (all ones where a < b), FL_sel(m, a, b) = m ? a : b, FL_and(m, a)
 * = m ? a : +0. Each lane does exactly the IEEE operations of v1 on its own
 * numbers, with no fused multiply-add (the build has -ffp-contract=off), so
 * a term written once in these operations (src/physics/pair_terms.h) gives
 * the same bits in the scalar loop and in any lane of any flavour: a result
 * never depends on the machine's vector width. The four-lane flavours also
 * have FL_set(a, b, c, d) and FL_store(out[4], a), v8z has
 * v8z_set(a0, ..., a7); FL_mask is each flavour's mask type.
 */
#ifndef SPH_LANES_H
#define SPH_LANES_H

#include <math.h>
#include <stdint.h>
#include <string.h>

/* The minimum image of a separation d = x_i - x_j over a period per in the
 * lanes of flavour P (v2, v4x, v8z, ...; P_sel, P_lt, P_sub, P_add), with
 * hper = per/2 and nper = -per/2: d - per where hper < d, d + per where
 * d < nper, else d. Lane for lane the scalar rule of sph_grid_min_image
 * and the loops' sep_x, bit for bit; a period of 0 leaves d as it is. */
#define SPH_LANE_MIN_IMAGE(P, d, per, hper, nper) SPH_LANE_MIN_IMAGE_(P, d, per, hper, nper)
#define SPH_LANE_MIN_IMAGE_(P, d, per, hper, nper)                                                 \
  P##_sel(P##_lt(hper, d), P##_sub(d, per), P##_sel(P##_lt(d, nper), P##_add(d, per), d))

#define SPH_LANE_INLINE static inline __attribute__((always_inline))

/* ---- v1: one double -------------------------------------------------------------- */

typedef double v1;
typedef int v1_mask;
SPH_LANE_INLINE v1 v1_all(double a) { return a; }
SPH_LANE_INLINE v1 v1_add(v1 a, v1 b) { return a + b; }
SPH_LANE_INLINE v1 v1_sub(v1 a, v1 b) { return a - b; }
SPH_LANE_INLINE v1 v1_mul(v1 a, v1 b) { return a * b; }
SPH_LANE_INLINE v1 v1_div(v1 a, v1 b) { return a / b; }
SPH_LANE_INLINE v1 v1_sqrt(v1 a) { return sqrt(a); }
SPH_LANE_INLINE v1 v1_abs(v1 a) { return fabs(a); }
SPH_LANE_INLINE v1 v1_neg(v1 a) { return -a; }
SPH_LANE_INLINE v1 v1_min(v1 a, v1 b) { return a < b ? a : b; }
SPH_LANE_INLINE v1 v1_max(v1 a, v1 b) { return a > b ? a : b; }
SPH_LANE_INLINE v1_mask v1_lt(v1 a, v1 b) { return a < b; }
SPH_LANE_INLINE v1 v1_sel(v1_mask m, v1 a, v1 b) { return m ? a : b; }
SPH_LANE_INLINE v1 v1_and(v1_mask m, v1 a) { return m ? a : 0.0; }

/* ---- v2: two doubles ------------------------------------------------------------- */

#if defined(__SSE2__)
#include <emmintrin.h>
typedef __m128d v2;
SPH_LANE_INLINE v2 v2_set(double a, double b) { return _mm_set_pd(b, a); }
SPH_LANE_INLINE v2 v2_all(double a) { return _mm_set1_pd(a); }
SPH_LANE_INLINE v2 v2_add(v2 a, v2 b) { return _mm_add_pd(a, b); }
SPH_LANE_INLINE v2 v2_sub(v2 a, v2 b) { return _mm_sub_pd(a, b); }
SPH_LANE_INLINE v2 v2_mul(v2 a, v2 b) { return _mm_mul_pd(a, b); }
SPH_LANE_INLINE v2 v2_div(v2 a, v2 b) { return _mm_div_pd(a, b); }
SPH_LANE_INLINE v2 v2_sqrt(v2 a) { return _mm_sqrt_pd(a); }
SPH_LANE_INLINE v2 v2_max(v2 a, v2 b) { return _mm_max_pd(a, b); }
SPH_LANE_INLINE v2 v2_min(v2 a, v2 b) { return _mm_min_pd(a, b); }
SPH_LANE_INLINE v2 v2_abs(v2 a) { return _mm_andnot_pd(_mm_set1_pd(-0.0), a); }
SPH_LANE_INLINE v2 v2_neg(v2 a) { return _mm_xor_pd(_mm_set1_pd(-0.0), a); }
SPH_LANE_INLINE v2 v2_lt(v2 a, v2 b) { return _mm_cmplt_pd(a, b); }
SPH_LANE_INLINE v2 v2_and(v2 a, v2 b) { return _mm_and_pd(a, b); }
SPH_LANE_INLINE v2 v2_andnot(v2 m, v2 a) { return _mm_andnot_pd(m, a); } /* ~m & a */
SPH_LANE_INLINE v2 v2_or(v2 a, v2 b) { return _mm_or_pd(a, b); }
SPH_LANE_INLINE double v2_lane0(v2 a) { return _mm_cvtsd_f64(a); }
SPH_LANE_INLINE double v2_lane1(v2 a) { return _mm_cvtsd_f64(_mm_unpackhi_pd(a, a)); }
SPH_LANE_INLINE unsigned v2_bits2(v2 m) { return (unsigned)_mm_movemask_pd(m); } /* lane k: bit k */
#else
typedef struct {
  double l[2];
} v2;
SPH_LANE_INLINE double v2_bits(uint64_t u) {
  double d;
  memcpy(&d, &u, sizeof d);
  return d;
}
SPH_LANE_INLINE uint64_t v2_u(double d) {
  uint64_t u;
  memcpy(&u, &d, sizeof u);
  return u;
}
#define SPH_V2_OP(name, expr)                                                                      \
  SPH_LANE_INLINE v2 name(v2 a, v2 b) {                                                            \
    v2 r;                                                                                          \
    for (int k = 0; k < 2; k++) {                                                                  \
      const double x = a.l[k], y = b.l[k];                                                         \
      r.l[k] = (expr);                                                                             \
    }                                                                                              \
    return r;                                                                                      \
  }
SPH_LANE_INLINE v2 v2_set(double a, double b) { return (v2){{a, b}}; }
SPH_LANE_INLINE v2 v2_all(double a) { return (v2){{a, a}}; }
SPH_V2_OP(v2_add, x + y)
SPH_V2_OP(v2_sub, x - y)
SPH_V2_OP(v2_mul, x *y)
SPH_V2_OP(v2_div, x / y)
SPH_V2_OP(v2_max, x > y ? x : y)
SPH_V2_OP(v2_min, x < y ? x : y)
SPH_V2_OP(v2_lt, v2_bits(x < y ? ~(uint64_t)0 : 0))
SPH_V2_OP(v2_and, v2_bits(v2_u(x) & v2_u(y)))
SPH_V2_OP(v2_andnot, v2_bits(~v2_u(x) & v2_u(y)))
SPH_V2_OP(v2_or, v2_bits(v2_u(x) | v2_u(y)))
#undef SPH_V2_OP
SPH_LANE_INLINE v2 v2_sqrt(v2 a) { return (v2){{sqrt(a.l[0]), sqrt(a.l[1])}}; }
SPH_LANE_INLINE v2 v2_abs(v2 a) { return (v2){{fabs(a.l[0]), fabs(a.l[1])}}; }
SPH_LANE_INLINE v2 v2_neg(v2 a) { return (v2){{-a.l[0], -a.l[1]}}; }
SPH_LANE_INLINE double v2_lane0(v2 a) { return a.l[0]; }
SPH_LANE_INLINE double v2_lane1(v2 a) { return a.l[1]; }
SPH_LANE_INLINE unsigned v2_bits2(v2 m) {
  return (unsigned)(v2_u(m.l[0]) >> 63) | (unsigned)(v2_u(m.l[1]) >> 63) << 1;
}
#endif
SPH_LANE_INLINE v2 v2_sel(v2 m, v2 a, v2 b) { return v2_or(v2_and(m, a), v2_andnot(m, b)); }

/* ---- v4e: four doubles as two v2 halves ------------------------------------------ */

typedef struct {
  v2 lo, hi;
} v4e;
typedef v4e v4e_mask;
#define SPH_V4E_OP(name)                                                                           \
  SPH_LANE_INLINE v4e v4e_##name(v4e a, v4e b) {                                                   \
    return (v4e){v2_##name(a.lo, b.lo), v2_##name(a.hi, b.hi)};                                    \
  }
SPH_V4E_OP(add)
SPH_V4E_OP(sub)
SPH_V4E_OP(mul)
SPH_V4E_OP(div)
SPH_V4E_OP(max)
SPH_V4E_OP(min)
SPH_V4E_OP(lt)
SPH_V4E_OP(and)
#undef SPH_V4E_OP
SPH_LANE_INLINE v4e v4e_set(double a, double b, double c, double d) {
  return (v4e){v2_set(a, b), v2_set(c, d)};
}
SPH_LANE_INLINE v4e v4e_all(double a) { return (v4e){v2_all(a), v2_all(a)}; }
SPH_LANE_INLINE v4e v4e_sqrt(v4e a) { return (v4e){v2_sqrt(a.lo), v2_sqrt(a.hi)}; }
SPH_LANE_INLINE v4e v4e_abs(v4e a) { return (v4e){v2_abs(a.lo), v2_abs(a.hi)}; }
SPH_LANE_INLINE v4e v4e_neg(v4e a) { return (v4e){v2_neg(a.lo), v2_neg(a.hi)}; }
SPH_LANE_INLINE v4e v4e_sel(v4e m, v4e a, v4e b) {
  return (v4e){v2_sel(m.lo, a.lo, b.lo), v2_sel(m.hi, a.hi, b.hi)};
}
SPH_LANE_INLINE void v4e_store(double *o, v4e a) {
  o[0] = v2_lane0(a.lo);
  o[1] = v2_lane1(a.lo);
  o[2] = v2_lane0(a.hi);
  o[3] = v2_lane1(a.hi);
}

/* ---- v4x: four doubles in one AVX register ---------------------------------------- */

#if defined(__GNUC__) && defined(__x86_64__)
#define SPH_LANES_AVX 1
#include <immintrin.h>
#define SPH_AVX2 static inline __attribute__((always_inline, target("avx2")))

/* Whether the processor has AVX2 (asked once per file that calls it; the
 * same value whichever thread stores it). */
static inline int sph_cpu_has_avx2(void) {
  static int value = -1;
  int v = value;
  if (v < 0) {
    __builtin_cpu_init();
    v = __builtin_cpu_supports("avx2") ? 1 : 0;
    value = v;
  }
  return v;
}
typedef __m256d v4x;
typedef v4x v4x_mask;
/* byte shuffles packing the 32-bit lanes set in a 4-bit mask to the front */
static const uint8_t v4x_pack32_table[16][16] = {
    {0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3},
    {0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3},
    {4, 5, 6, 7, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3},
    {0, 1, 2, 3, 4, 5, 6, 7, 0, 1, 2, 3, 0, 1, 2, 3},
    {8, 9, 10, 11, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3},
    {0, 1, 2, 3, 8, 9, 10, 11, 0, 1, 2, 3, 0, 1, 2, 3},
    {4, 5, 6, 7, 8, 9, 10, 11, 0, 1, 2, 3, 0, 1, 2, 3},
    {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 0, 1, 2, 3},
    {12, 13, 14, 15, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3},
    {0, 1, 2, 3, 12, 13, 14, 15, 0, 1, 2, 3, 0, 1, 2, 3},
    {4, 5, 6, 7, 12, 13, 14, 15, 0, 1, 2, 3, 0, 1, 2, 3},
    {0, 1, 2, 3, 4, 5, 6, 7, 12, 13, 14, 15, 0, 1, 2, 3},
    {8, 9, 10, 11, 12, 13, 14, 15, 0, 1, 2, 3, 0, 1, 2, 3},
    {0, 1, 2, 3, 8, 9, 10, 11, 12, 13, 14, 15, 0, 1, 2, 3},
    {4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 0, 1, 2, 3},
    {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15}};

/* The 32-bit lanes of v whose bits are set in the 4-bit mask m, packed to
 * the front in lane order (the rest: copies of lane 0): the kept entries of a
 * row cut or a neighbour list's row, stored four at a time. */
SPH_AVX2 __m128i v4x_pack32(__m128i v, unsigned m) {
  return _mm_shuffle_epi8(v, _mm_loadu_si128((const __m128i *)v4x_pack32_table[m]));
}
SPH_AVX2 v4x v4x_set(double a, double b, double c, double d) { return _mm256_set_pd(d, c, b, a); }
SPH_AVX2 v4x v4x_all(double a) { return _mm256_set1_pd(a); }
SPH_AVX2 v4x v4x_add(v4x a, v4x b) { return _mm256_add_pd(a, b); }
SPH_AVX2 v4x v4x_sub(v4x a, v4x b) { return _mm256_sub_pd(a, b); }
SPH_AVX2 v4x v4x_mul(v4x a, v4x b) { return _mm256_mul_pd(a, b); }
SPH_AVX2 v4x v4x_div(v4x a, v4x b) { return _mm256_div_pd(a, b); }
SPH_AVX2 v4x v4x_sqrt(v4x a) { return _mm256_sqrt_pd(a); }
SPH_AVX2 v4x v4x_max(v4x a, v4x b) { return _mm256_max_pd(a, b); } /* as maxpd */
SPH_AVX2 v4x v4x_min(v4x a, v4x b) { return _mm256_min_pd(a, b); } /* as minpd */
SPH_AVX2 v4x v4x_abs(v4x a) { return _mm256_andnot_pd(_mm256_set1_pd(-0.0), a); }
SPH_AVX2 v4x v4x_neg(v4x a) { return _mm256_xor_pd(_mm256_set1_pd(-0.0), a); }
SPH_AVX2 v4x v4x_lt(v4x a, v4x b) { return _mm256_cmp_pd(a, b, _CMP_LT_OS); } /* as cmpltpd */
SPH_AVX2 v4x v4x_and(v4x a, v4x b) { return _mm256_and_pd(a, b); }
SPH_AVX2 v4x v4x_sel(v4x m, v4x a, v4x b) { return _mm256_blendv_pd(b, a, m); }
SPH_AVX2 void v4x_store(double *o, v4x a) { _mm256_storeu_pd(o, a); }

/* Four records of eight doubles, r[q][0..7], turned into eight vectors:
 * out[f] lane q = r[q][f]. Eight loads and 16 shuffles (two 4 x 4
 * transposes) in place of 32 single-element moves. */
SPH_AVX2 void v4x_transpose8(const double *const r[4], v4x out[8]) {
  for (int h = 0; h < 8; h += 4) {
    const v4x a = _mm256_loadu_pd(r[0] + h), b = _mm256_loadu_pd(r[1] + h);
    const v4x c = _mm256_loadu_pd(r[2] + h), d = _mm256_loadu_pd(r[3] + h);
    const v4x t0 = _mm256_unpacklo_pd(a, b), t1 = _mm256_unpackhi_pd(a, b); /* a0 b0 a2 b2 */
    const v4x t2 = _mm256_unpacklo_pd(c, d), t3 = _mm256_unpackhi_pd(c, d);
    out[h] = _mm256_permute2f128_pd(t0, t2, 0x20); /* a0 b0 c0 d0 */
    out[h + 2] = _mm256_permute2f128_pd(t0, t2, 0x31);
    out[h + 1] = _mm256_permute2f128_pd(t1, t3, 0x20);
    out[h + 3] = _mm256_permute2f128_pd(t1, t3, 0x31);
  }
}

/* ---- v8z: eight doubles in one AVX-512 register ----------------------------------- */

/* AVX-512F only (abs and neg through the integer logic: the floating-point
 * and/xor forms are AVX-512DQ). The same instructions as v4x at twice the
 * width: vaddpd, ..., vmaxpd/vminpd (the maxpd/minpd rule), vcmppd LT_OS. */
#define SPH_LANES_AVX512 1
#define SPH_AVX512 static inline __attribute__((always_inline, target("avx512f")))

/* Whether the processor has AVX-512F (asked once per file; valgrind's
 * emulated processor says no). */
static inline int sph_cpu_has_avx512(void) {
  static int value = -1;
  int v = value;
  if (v < 0) {
    __builtin_cpu_init();
    v = __builtin_cpu_supports("avx512f") ? 1 : 0;
    value = v;
  }
  return v;
}
typedef __m512d v8z;
typedef __mmask8 v8z_mask;
SPH_AVX512 v8z v8z_set(double a0, double a1, double a2, double a3, double a4, double a5, double a6,
                       double a7) {
  return _mm512_set_pd(a7, a6, a5, a4, a3, a2, a1, a0);
}
SPH_AVX512 v8z v8z_all(double a) { return _mm512_set1_pd(a); }
SPH_AVX512 v8z v8z_add(v8z a, v8z b) { return _mm512_add_pd(a, b); }
SPH_AVX512 v8z v8z_sub(v8z a, v8z b) { return _mm512_sub_pd(a, b); }
SPH_AVX512 v8z v8z_mul(v8z a, v8z b) { return _mm512_mul_pd(a, b); }
SPH_AVX512 v8z v8z_div(v8z a, v8z b) { return _mm512_div_pd(a, b); }
SPH_AVX512 v8z v8z_sqrt(v8z a) { return _mm512_sqrt_pd(a); }
SPH_AVX512 v8z v8z_max(v8z a, v8z b) { return _mm512_max_pd(a, b); } /* as maxpd */
SPH_AVX512 v8z v8z_min(v8z a, v8z b) { return _mm512_min_pd(a, b); } /* as minpd */
SPH_AVX512 v8z v8z_abs(v8z a) {
  return _mm512_castsi512_pd(
      _mm512_and_si512(_mm512_castpd_si512(a), _mm512_set1_epi64(INT64_C(0x7fffffffffffffff))));
}
SPH_AVX512 v8z v8z_neg(v8z a) {
  return _mm512_castsi512_pd(
      _mm512_xor_si512(_mm512_castpd_si512(a), _mm512_set1_epi64(INT64_MIN)));
}
SPH_AVX512 v8z_mask v8z_lt(v8z a, v8z b) { return _mm512_cmp_pd_mask(a, b, _CMP_LT_OS); }
SPH_AVX512 v8z v8z_and(v8z_mask m, v8z a) { return _mm512_maskz_mov_pd(m, a); } /* m ? a : +0 */
SPH_AVX512 v8z v8z_sel(v8z_mask m, v8z a, v8z b) { return _mm512_mask_blend_pd(m, b, a); }
SPH_AVX512 v4x v8z_lo(v8z a) { return _mm512_castpd512_pd256(a); }    /* lanes 0-3 */
SPH_AVX512 v4x v8z_hi(v8z a) { return _mm512_extractf64x4_pd(a, 1); } /* lanes 4-7 */

/* Eight records of eight doubles, r[q][0..7] (each 64 bytes, one cache
 * line where aligned), turned into eight vectors: out[f] lane q = r[q][f].
 * Eight loads and 24 shuffles in place of 64 single-element moves. */
SPH_AVX512 void v8z_transpose8(const double *const r[8], v8z out[8]) {
  const v8z r0 = _mm512_loadu_pd(r[0]), r1 = _mm512_loadu_pd(r[1]);
  const v8z r2 = _mm512_loadu_pd(r[2]), r3 = _mm512_loadu_pd(r[3]);
  const v8z r4 = _mm512_loadu_pd(r[4]), r5 = _mm512_loadu_pd(r[5]);
  const v8z r6 = _mm512_loadu_pd(r[6]), r7 = _mm512_loadu_pd(r[7]);
  /* pairs of records: t0 = (r0 f0, r1 f0, r0 f2, r1 f2, r0 f4, ...), t1 the odd fields */
  const v8z t0 = _mm512_unpacklo_pd(r0, r1), t1 = _mm512_unpackhi_pd(r0, r1);
  const v8z t2 = _mm512_unpacklo_pd(r2, r3), t3 = _mm512_unpackhi_pd(r2, r3);
  const v8z t4 = _mm512_unpacklo_pd(r4, r5), t5 = _mm512_unpackhi_pd(r4, r5);
  const v8z t6 = _mm512_unpacklo_pd(r6, r7), t7 = _mm512_unpackhi_pd(r6, r7);
  /* quads: u0 = (r0..r3 f0, r0..r3 f4), u2 = (f2, f6), u1 = (f1, f5), u3 = (f3, f7) */
  const __m512i ia = _mm512_set_epi64(13, 12, 5, 4, 9, 8, 1, 0);
  const __m512i ib = _mm512_set_epi64(15, 14, 7, 6, 11, 10, 3, 2);
  const v8z u0 = _mm512_permutex2var_pd(t0, ia, t2), u2 = _mm512_permutex2var_pd(t0, ib, t2);
  const v8z u1 = _mm512_permutex2var_pd(t1, ia, t3), u3 = _mm512_permutex2var_pd(t1, ib, t3);
  const v8z u4 = _mm512_permutex2var_pd(t4, ia, t6), u6 = _mm512_permutex2var_pd(t4, ib, t6);
  const v8z u5 = _mm512_permutex2var_pd(t5, ia, t7), u7 = _mm512_permutex2var_pd(t5, ib, t7);
  /* halves: field f of r0..r3 then of r4..r7 */
  out[0] = _mm512_shuffle_f64x2(u0, u4, 0x44);
  out[4] = _mm512_shuffle_f64x2(u0, u4, 0xee);
  out[1] = _mm512_shuffle_f64x2(u1, u5, 0x44);
  out[5] = _mm512_shuffle_f64x2(u1, u5, 0xee);
  out[2] = _mm512_shuffle_f64x2(u2, u6, 0x44);
  out[6] = _mm512_shuffle_f64x2(u2, u6, 0xee);
  out[3] = _mm512_shuffle_f64x2(u3, u7, 0x44);
  out[7] = _mm512_shuffle_f64x2(u3, u7, 0xee);
}
#endif

/* A static function `name` of the parameters `params` (a parenthesised list)
 * with the body `...` (braces included), compiled twice where the
 * processor may have AVX2: plainly and for AVX2, `name` calling the one
 * the processor runs (sph_cpu_has_avx2) with `args`. A body whose loop
 * the compiler vectorises (omp simd) then runs in four lanes there, the
 * same operations in the same order: the same results. Elsewhere `name`
 * is the plain function alone. */
#ifdef SPH_LANES_AVX
#define SPH_AVX2_TWIN(ret, name, params, args, ...)                                                \
  static ret name##_plain params __VA_ARGS__ __attribute__((                                       \
      target("avx2"))) static ret name##_avx2 params __VA_ARGS__ static inline ret name params {   \
    return sph_cpu_has_avx2() ? name##_avx2 args : name##_plain args;                              \
  }
#else
#define SPH_AVX2_TWIN(ret, name, params, args, ...) static ret name params __VA_ARGS__
#endif

#endif
