/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * ops.c - how fast this core runs the arithmetic of the interaction loop
 * (bench/limit): four-lane double division, square root, and multiply /
 * add (eight-lane, AVX-512, when built with -DOPS_512: every kind then
 * carries the suffix _512), each as eight independent chains held in registers, so that the
 * time per instruction is the unit's throughput, not its latency (and as
 * one chain, the latency of division and square root); and the
 * clock, from a chain of dependent integer additions (one cycle each).
 * Prints one line per kind:
 *   clock_ghz GHz
 *   kind ns_per_instruction
 * Built by bench/limit with -O2 -mavx2 (and again with -O2 -mavx512f
 * -DOPS_512 where the processor has AVX-512F); no fast-math.
 */
#include <immintrin.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#ifdef OPS_512
typedef __m512d vd;
#define V(name) _mm512_##name
#define W 8
#define KIND(name) name "_512"
#else
typedef __m256d vd;
#define V(name) _mm256_##name
#define W 4
#define KIND(name) name
#endif

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double lanes(vd v) {
  double l[W], s = 0.0;
  V(storeu_pd)(l, v);
  for (int k = 0; k < W; k++)
    s += l[k];
  return s;
}

/* Best of five timings of `iters` iterations of `body` (which updates the
 * chains v0..v7), per instruction; `per_iter` instructions an iteration.
 * The empty asm keeps the chains in registers and the work in the loop. */
#define TIME(name, per_iter, body)                                                                 \
  do {                                                                                             \
    double best = 1e30, s = 0.0;                                                                   \
    for (int r = 0; r < 5; r++) {                                                                  \
      vd v0 = V(set1_pd)(1.0), v1 = V(set1_pd)(1.1), v2 = V(set1_pd)(1.2), v3 = V(set1_pd)(1.3),   \
         v4 = V(set1_pd)(1.4), v5 = V(set1_pd)(1.5), v6 = V(set1_pd)(1.6), v7 = V(set1_pd)(1.7);   \
      const double t0 = now();                                                                     \
      for (long it = 0; it < iters; it++) {                                                        \
        body;                                                                                      \
        __asm__ volatile(""                                                                        \
                         : "+x"(v0), "+x"(v1), "+x"(v2), "+x"(v3), "+x"(v4), "+x"(v5), "+x"(v6),   \
                           "+x"(v7));                                                              \
      }                                                                                            \
      const double t = now() - t0;                                                                 \
      if (t < best) best = t;                                                                      \
      s += lanes(v0) + lanes(v1) + lanes(v2) + lanes(v3) + lanes(v4) + lanes(v5) + lanes(v6) +     \
           lanes(v7);                                                                              \
    }                                                                                              \
    printf("%s %.4f%s\n", name, 1e9 * best / ((double)iters * (per_iter)),                         \
           s == 12345.678 ? " !" : "");                                                            \
  } while (0)

#define ALL8(f)                                                                                    \
  f(v0);                                                                                           \
  f(v1);                                                                                           \
  f(v2);                                                                                           \
  f(v3);                                                                                           \
  f(v4);                                                                                           \
  f(v5);                                                                                           \
  f(v6);                                                                                           \
  f(v7)
#define DIV(v) v = V(div_pd)(d, v)
#define SQRT(v) v = V(sqrt_pd)(v)

/* The clock: a chain of dependent integer additions, one cycle each;
 * prints GHz. */
static void clock_rate(long iters) {
  double best = 1e30;
  unsigned long x = 0;
  for (int r = 0; r < 5; r++) {
    const double t0 = now();
    for (long it = 0; it < iters; it++)
      __asm__ volatile("add $1, %0\n\tadd $1, %0\n\tadd $1, %0\n\tadd $1, %0\n\t"
                       "add $1, %0\n\tadd $1, %0\n\tadd $1, %0\n\tadd $1, %0"
                       : "+r"(x));
    const double t = now() - t0;
    if (t < best) best = t;
  }
  printf("clock_ghz %.4f%s\n", (double)iters * 8.0 / best * 1e-9, x == 1 ? " !" : "");
}

/* Twelve chains, six of multiplies and six of adds: with a latency of
 * three cycles, enough to fill four pipes. */
static void mul_add12(long iters) {
  const vd a = V(set1_pd)(0.9999999), b = V(set1_pd)(1e-9);
  double best = 1e30, s = 0.0;
  for (int r = 0; r < 5; r++) {
    vd m0 = a, m1 = a, m2 = a, m3 = a, m4 = a, m5 = a;
    vd s0 = b, s1 = b, s2 = b, s3 = b, s4 = b, s5 = b;
    const double t0 = now();
    for (long it = 0; it < iters; it++) {
      m0 = V(mul_pd)(m0, a);
      s0 = V(add_pd)(s0, b);
      m1 = V(mul_pd)(m1, a);
      s1 = V(add_pd)(s1, b);
      m2 = V(mul_pd)(m2, a);
      s2 = V(add_pd)(s2, b);
      m3 = V(mul_pd)(m3, a);
      s3 = V(add_pd)(s3, b);
      m4 = V(mul_pd)(m4, a);
      s4 = V(add_pd)(s4, b);
      m5 = V(mul_pd)(m5, a);
      s5 = V(add_pd)(s5, b);
      __asm__ volatile(""
                       : "+x"(m0), "+x"(m1), "+x"(m2), "+x"(m3), "+x"(m4), "+x"(m5), "+x"(s0),
                         "+x"(s1), "+x"(s2), "+x"(s3), "+x"(s4), "+x"(s5));
    }
    const double t = now() - t0;
    if (t < best) best = t;
    s += lanes(m0) + lanes(m1) + lanes(m2) + lanes(m3) + lanes(m4) + lanes(m5) + lanes(s0) +
         lanes(s1) + lanes(s2) + lanes(s3) + lanes(s4) + lanes(s5);
  }
  printf(KIND("mul_add12") " %.4f%s\n", 1e9 * best / ((double)iters * 12.0),
         s == 12345.678 ? " !" : "");
}

int main(int argc, char **argv) {
  const long iters = argc > 1 ? atol(argv[1]) : 2000000;
  clock_rate(4 * iters); /* (both builds print it; the run keeps the best) */
  const vd d = V(set1_pd)(1.0000001), a = V(set1_pd)(0.9999999), b = V(set1_pd)(1e-9);
  /* x <- d / x stays near 1 */
  TIME(KIND("div"), 8, ALL8(DIV));
  /* x <- sqrt(x) tends to 1 */
  TIME(KIND("sqrt"), 8, ALL8(SQRT));
  /* one chain: the latency */
  TIME(KIND("div_latency"), 1, DIV(v0));
  TIME(KIND("sqrt_latency"), 1, SQRT(v0));
  /* the interaction loop's mix: three divisions and a square root per
   * four-lane iteration; two iterations' worth per turn */
  TIME(KIND("div3_sqrt1"), 2, {
    DIV(v0);
    DIV(v1);
    DIV(v2);
    SQRT(v3);
    DIV(v4);
    DIV(v5);
    DIV(v6);
    SQRT(v7);
  });
  /* four chains of multiplies, four of adds (no fused multiply-add); with
   * a latency of three cycles eight chains may not fill the pipes, so this
   * is an upper bound on the time per instruction */
  TIME(KIND("mul_add"), 8, {
    v0 = V(mul_pd)(v0, a);
    v1 = V(add_pd)(v1, b);
    v2 = V(mul_pd)(v2, a);
    v3 = V(add_pd)(v3, b);
    v4 = V(mul_pd)(v4, a);
    v5 = V(add_pd)(v5, b);
    v6 = V(mul_pd)(v6, a);
    v7 = V(add_pd)(v7, b);
  });
  mul_add12(iters);
  return 0;
}
