/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * interact.h - the loops of the main interaction pass, for one particle i
 * over its neighbour row (internal to src/solver/forces.c).
 *
 * The terms in use are a bit set F; a loop compiled for a set has it as a
 * constant at its call sites (LANE_LOOPS, SCALAR_LOOPS, below), so it
 * compiles without the terms it does not use (DESIGN rule 4). One body,
 * interact_row.h, written once, is instantiated here in every arithmetic
 * flavour:
 *   interact_v1     the scalar loop, one pair after the other in row order:
 *                   every term set (the only one for per-particle h and
 *                   mirror particles);
 *   interact_v4e,   the lane loops, four pairs at a time (portable; AVX2 on
 *   interact_v4x    x86-64), or eight at a time into the same four-lane sums
 *   interact_v8z    (AVX-512 on x86-64: the same bits as v4e and v4x).
 * The strain-rate pass of the viscous stress has its lane loop here too
 * (strain_FL, strain_lanes.h), over the same cut rows.
 * Each sum runs over the row in increasing storage index (the lane loop:
 * per lane, then (l0 + l1) + (l2 + l3)), so results do not depend on the
 * thread count, the schedule or the age of the neighbour list.
 */
#ifndef SPH_INTERACT_H
#define SPH_INTERACT_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "core/lanes.h"
#include "core/parallel.h"
#include "core/particles.h"
#include "neighbours/grid.h"
#include "physics/kernel.h"
#include "physics/pair_terms.h"
#include "solver/diffusion.h"
#include "solver/force_pass.h"
#include "solver/row_walk.h"

/* The terms, as bits of F. */
enum {
  F_AV = 1,        /* artificial viscosity */
  F_XSPH = 2,      /* XSPH velocity correction */
  F_STRESS = 4,    /* viscous stress tensor (paper A), SPS stress (paper B), surface tension */
  F_MORRIS = 8,    /* Morris laminar viscosity, paper B */
  F_PERIODIC = 16, /* minimum image along the periodic axis (row_walk.h's SEP) */
  F_VARH = 32,     /* per-particle smoothing length */
  F_LEDGER = 64,   /* energy ledger: du/dt and the power of moving walls */
  F_DDIFF = 128,   /* density diffusion (physics/density_diffusion.h) */
  F_RIEMANN = 256, /* Riemann-solver pressure (Zhang et al. 2017) in place of p/rho^2 */
  F_CGRAD = 512    /* the pressure and continuity with the corrected gradient (forces.h) */
};
_Static_assert(F_PERIODIC == SPH_ROW_PERIODIC, "row_walk.h's SEP reads F_PERIODIC");

/* The lane loops serve the term sets without these (the scalar loop runs them). */
#define F_SCALAR_ONLY F_VARH

/* The loops each flavour is compiled for (forces.c), three kinds, each
 * named by a literal Fc that its parallel region passes down:
 *   a set        Fc = the term set, every bit a literal: the sets the
 *                shipped cases run, listed by a profile of each
 *                (bench/results/loops.md), so that a case pays only for
 *                what it switches on (DESIGN rule 4);
 *   an axes loop Fc = F_RUNTIME | F_AXES_FIXED | (bits of F_AXES): the
 *                lane loops for every combination of the terms that weigh
 *                most on the loop (the axes: AV, XSPH, the stress,
 *                diffusion), the lighter ones (Morris, the Riemann pressure, the ledger,
 *                periodicity) read from the pass's term set (w->terms)
 *                and tested per pair;
 *   run-time     Fc = F_RUNTIME, with or without F_VARH: every bit but
 *                per-particle h read at run time.
 * A term set runs its own loop if it has one, else its axes loop, else
 * the run-time loop (forces.c, find_variant). A bit read at run time
 * gives the same operations in the same order (-ffp-contract=off), so the
 * same results; it costs the registers its constants hold and a branch
 * (bench/results/loops.md: 4-7 % in the axes loops, 9-11 % in the
 * scalar run-time loop, instructions on the shipped cases). Which loops:
 *   lane loops   the sets AV (hydrostatic tank, linear wave), AV + XSPH
 *                (Lobovsky), AV + stress + periodicity (inclined plane),
 *                AV + XSPH + diffusion (Martin & Moyce), AV + stress +
 *                Morris (SPS dam break), AV + XSPH + stress + ledger
 *                (wet-bed dam break), the Riemann pressure alone
 *                (physics.riemann, bench/results/lobovsky.md); the 16 axes
 *                loops
 *   scalar loop  per-particle h and mirror walls only (the lanes run the
 *                rest): the sets AV + XSPH + h (plunging breaker), AV +
 *                XSPH + stress + Morris + h (plunging breaker with SPS);
 *                the run-time loop for per-particle h and for uniform h
 *   portable     on x86-64 the fallback of processors without AVX2: the
 *                run-time loop only; elsewhere as the lane loops
 * -DSPH_FEW_VARIANTS (in CPPFLAGS) compiles the run-time loops only: the
 * same body and the same results, in less build time. The
 * sanitized build (./configure --enable-sanitizers) compiles every loop, so
 * that the specialised loops run under the sanitizers too.
 * Each list entry is V(name, Fc). */
#define F_RUNTIME 1024u    /* not a term: a loop that reads bits at run time */
#define F_AXES_FIXED 2048u /* not a term: with F_RUNTIME, the axes are literals */
/* Two phases (physics.air; interact_row.h, pair_phases): no compiled set has it (a literal
 * loop takes it as 0, and its code is gone from it), so a two-phase pass runs its axes loop or
 * the run-time loop, which read it at run time: one phase costs nothing for it. */
#define F_PHASES 4096u
#define F_AXES (F_AV | F_XSPH | F_STRESS | F_DDIFF)

#define AXES_BITS(k)                                                                               \
  (((k)&1 ? F_AV : 0u) | ((k)&2 ? F_XSPH : 0u) | ((k)&4 ? F_STRESS : 0u) | ((k)&8 ? F_DDIFF : 0u))
#define AXES_LOOP(V, k) V(a##k, F_RUNTIME | F_AXES_FIXED | AXES_BITS(k))
#ifdef SPH_FEW_VARIANTS
#define LANE_LOOPS(V) V(r, F_RUNTIME)
#define SCALAR_LOOPS(V) V(r, F_RUNTIME) V(h, F_RUNTIME | F_VARH)
#else
/* clang-format off */
#define LANE_LOOPS(V)                                                                              \
  AXES_LOOP(V, 0)  AXES_LOOP(V, 1)  AXES_LOOP(V, 2)  AXES_LOOP(V, 3)                               \
  AXES_LOOP(V, 4)  AXES_LOOP(V, 5)  AXES_LOOP(V, 6)  AXES_LOOP(V, 7)                               \
  AXES_LOOP(V, 8)  AXES_LOOP(V, 9)  AXES_LOOP(V, 10) AXES_LOOP(V, 11)                              \
  AXES_LOOP(V, 12) AXES_LOOP(V, 13) AXES_LOOP(V, 14) AXES_LOOP(V, 15)                              \
  V(s1, F_AV)                                                                                      \
  V(s2, F_AV | F_XSPH)                                                                             \
  V(s3, F_AV | F_STRESS | F_PERIODIC)                                                              \
  V(s4, F_AV | F_XSPH | F_DDIFF)                                                                   \
  V(s5, F_AV | F_STRESS | F_MORRIS)                                                                \
  V(s6, F_AV | F_XSPH | F_STRESS | F_LEDGER)                                                       \
  V(s7, F_RIEMANN)
/* clang-format on */
#define SCALAR_LOOPS(V)                                                                            \
  V(r, F_RUNTIME)                                                                                  \
  V(h, F_RUNTIME | F_VARH)                                                                         \
  V(s1, F_VARH | F_AV | F_XSPH)                                                                    \
  V(s2, F_VARH | F_AV | F_XSPH | F_STRESS | F_MORRIS)
#endif
#ifdef SPH_LANES_AVX
#define PORTABLE_LOOPS(V) V(r, F_RUNTIME)
#else
#define PORTABLE_LOOPS(V) LANE_LOOPS(V)
#endif

/* Every term bit (the last one doubled, less 1). */
#define F_TERMS (2u * F_CGRAD - 1u)

/* The bits a loop Fc takes as literals (above). */
#define F_LITERAL(Fc)                                                                              \
  (!((Fc)&F_RUNTIME)     ? (F_TERMS | F_PHASES)                                                    \
   : ((Fc)&F_AXES_FIXED) ? (unsigned)(F_VARH | F_AXES)                                             \
                         : (unsigned)F_VARH)

/* The term set a loop evaluates: the bits of mask from the literal Fc
 * (folded by the compiler), the others from the pass's set Fr. */
#define SPH_TERMS(Fc, mask, Fr) (((Fc) & (mask)) | ((Fr) & ~(unsigned)(mask)))

/* The term set a pass with these parameters needs. */
static inline unsigned sph_interact_terms(const sph_force_params *fp) {
  unsigned F = 0;
  if (fp->alpha != 0.0 || fp->beta != 0.0) F |= F_AV;
  if (fp->xsph != 0.0) F |= F_XSPH;
  if (fp->viscosity == SPH_VISCOSITY_STRESS_TENSOR || fp->sps || fp->sigma > 0.0) F |= F_STRESS;
  if (fp->viscosity == SPH_VISCOSITY_MORRIS) F |= F_MORRIS;
  if (fp->periodic) F |= F_PERIODIC;
  if (fp->var_h) F |= F_VARH;
  if (fp->ledger) F |= F_LEDGER;
  if (fp->diffusion != SPH_DIFFUSION_NONE) F |= F_DDIFF;
  if (fp->riemann) F |= F_RIEMANN;
  if (fp->corrected_gradient) F |= F_CGRAD;
  if (fp->riemann && fp->phases > 1) F |= F_PHASES;
  return F;
}

/* Runtime options of the strain-rate pass (forces.c, strain_lanes.h; not
 * bits of F: the pass is light enough to test them once per particle). */
typedef struct strain_opts {
  const double *const *gv; /* velocity of wall particles in the viscous terms (gv[axis]), or NULL */
  double *const *l;        /* kernel-gradient correction L = M^-1 out (l[SPH_XX], ...), or NULL */
  double *div;             /* div v out (the 3-D SPS closure), or NULL */
  int moment_only;         /* with l: the moment M alone (no velocity sums), L stored and no
                              strain rate (the corrected gradient, forces.c moment_pass) */
} strain_opts;

/* The sums of the strain-rate pass: without the correction s = the
 * symmetric 2 sym(u (x) g) (SPH_SYM components, core/tensor.h) and u . g
 * (s[SPH_SYM]); with it G = sum u (x) g (row-major, SPH_DIM^2) and the moment
 * M (SPH_SYM, after G). */
#define STRAIN_SUMS (SPH_SYM + 1)
#define STRAIN_GM (SPH_DIM * SPH_DIM + SPH_SYM)

/* The end of the strain-rate pass for particle i (strain_one in forces.c,
 * strain_FL in strain_lanes.h), from its sums: without the correction as
 * summed; with it grad v = G M^-1 where M is invertible (Bonet and Lok
 * 1999), L = M^-1 stored. Then eps_i, the deviatoric part as paper A
 * writes it (its 2/3 is the 3-D factor). */
static inline void strain_finish(const strain_opts *o, size_t i, const double s[STRAIN_SUMS],
                                 const double gm[STRAIN_GM], double *const eps[SPH_SYM]) {
#if SPH_DIM == 2
  double sxx = s[0], sxy = s[1], syy = s[2], div = s[3];
  if (o->l) {
    double a[SPH_SYM];
    sph_gradient_correction(gm + 4, a);
    const double axx = a[SPH_XX], axy = a[SPH_XY], ayy = a[SPH_YY];
    o->l[SPH_XX][i] = axx;
    o->l[SPH_XY][i] = axy;
    o->l[SPH_YY][i] = ayy;
    if (o->moment_only) return;
    const double gxx = gm[0], gxy = gm[1], gyx = gm[2], gyy = gm[3];
    const double cxx = gxx * axx + gxy * axy, cxy = gxx * axy + gxy * ayy;
    const double cyx = gyx * axx + gyy * axy, cyy = gyx * axy + gyy * ayy;
    sxx = 2.0 * cxx;
    syy = 2.0 * cyy;
    sxy = cyx + cxy;
    div = cxx + cyy;
  }
  eps[SPH_XX][i] = sxx - (2.0 / 3.0) * div;
  eps[SPH_YY][i] = syy - (2.0 / 3.0) * div;
  eps[SPH_XY][i] = sxy;
#else
  double t[SPH_SYM], div = s[SPH_SYM];
  for (int k = 0; k < SPH_SYM; k++)
    t[k] = s[k];
  if (o->l) {
    double a[SPH_SYM], c[3][3]; /* c = G L */
    sph_gradient_correction(gm + 9, a);
    for (int k = 0; k < SPH_SYM; k++)
      o->l[k][i] = a[k];
    if (o->moment_only) return;
    for (int r = 0; r < 3; r++)
      for (int q = 0; q < 3; q++)
        c[r][q] = (gm[3 * r] * a[sph_sym_index(0, q)] + gm[3 * r + 1] * a[sph_sym_index(1, q)]) +
                  gm[3 * r + 2] * a[sph_sym_index(2, q)];
    for (int r = 0; r < 3; r++)
      for (int q = r; q < 3; q++)
        t[sph_sym_index(r, q)] = r == q ? 2.0 * c[r][r] : c[q][r] + c[r][q];
    div = (c[0][0] + c[1][1]) + c[2][2];
  }
  for (int r = 0; r < 3; r++)
    for (int q = r; q < 3; q++) {
      const int k = sph_sym_index(r, q);
      eps[k][i] = r == q ? t[k] - (2.0 / 3.0) * div : t[k];
    }
  if (o->div) o->div[i] = div;
#endif
}

/* The lane form of sep_x in the flavour of the including loop (LOP): d as its minimum image
 * over the period per, with hper = per/2 and nper = -per/2. */
#define LANE_MIN_IMAGE(d, per, hper, nper) SPH_LANE_MIN_IMAGE(FL, d, per, hper, nper)
/* LANE_MIN_IMAGE's constants along x (per, hper, nper) and, in 3-D, along y and z (pery, ...,
 * nperz), in the flavour of the including loop. */
#define LANE_PERIOD(name, fp, a)                                                                   \
  const LT name = LOP(all)(period_along(fp, a)), h##name = LOP(all)(0.5 * period_along(fp, a));    \
  const LT n##name = LOP(all)(-0.5 * period_along(fp, a))
#if SPH_DIM == 2
#define LANE_PERIODS(fp) LANE_PERIOD(per, fp, 0)
#else
#define LANE_PERIODS(fp)                                                                           \
  LANE_PERIOD(per, fp, 0);                                                                         \
  LANE_PERIOD(pery, fp, 1);                                                                        \
  LANE_PERIOD(perz, fp, 2)
#endif

/* The largest of a lane loop's four maxima, (l0 max l1) max (l2 max l3). */
static inline double lanes_max4(const double lv[4]) {
  const double s01 = lv[0] > lv[1] ? lv[0] : lv[1], s23 = lv[2] > lv[3] ? lv[2] : lv[3];
  return s01 > s23 ? s01 : s23;
}

/* The factor of the density diffusion's pair sum (interact_FL):
 * -2 delta c0 h, with h the smoothing length (1 with per-particle h: the
 * loop multiplies each pair by its h_ij). */
static inline double diffusion_scale(const sph_force_params *fp, const unsigned F) {
  return -2.0 * fp->diffusion_delta * fp->eos.c0 * ((F & F_VARH) ? 1.0 : fp->h);
}

/* The row of i cut to the pairs inside the support (not coincident), in
 * row order, into nb; returns their number. Which entry goes to which lane
 * of the lane loop then depends only on the pairs, never on the skin.
 * cut_row_at goes on from entry k of the row v (sph_nlist_view: its one run
 * in place when one_run, a literal, else written out) with cnt pairs already
 * in nb (the wide cuts below leave it their last entries). */
#define VIEW_AT(v, k, one_run) ((one_run) ? (v).base + (v).o[k] : (v).e[k])
static inline __attribute__((always_inline)) size_t
cut_row_at(const sph_force_hot *restrict hot, const sph_nlist_view v, const int one_run,
           const sph_force_params *restrict fp, size_t i, uint32_t *restrict nb, size_t k,
           size_t cnt, const unsigned F) {
  const sph_force_hot qi = hot[i];
  const double h0 = fp->h;
  const v2 xi = v2_all(qi.x), yi = v2_all(qi.y), zero = v2_all(0.0);
  SPH_IF3(const v2 zi = v2_all(qi.z);)
  const v2 per = v2_all(period_along(fp, 0)), hper = v2_all(0.5 * period_along(fp, 0));
  const v2 nper = v2_all(-0.5 * period_along(fp, 0));
  SPH_IF3(const double py = period_along(fp, 1), pz = period_along(fp, 2);
          const v2 pery = v2_all(py), hpery = v2_all(0.5 * py), npery = v2_all(-0.5 * py);
          const v2 perz = v2_all(pz), hperz = v2_all(0.5 * pz), nperz = v2_all(-0.5 * pz);)
  const size_t len = v.len;
  const double xs0 = qi.x, ys0 = qi.y, s0 = 4.0 * h0 * h0;
  SPH_IF3(const double zs0 = qi.z;)
  const double period = period_along(fp, 0), hp = 0.5 * period_along(fp, 0);
  const v2 sv = v2_all(s0);
  for (; k + 1 < len; k += 2) { /* two entries at a time */
    const uint32_t j0 = VIEW_AT(v, k, one_run), j1 = VIEW_AT(v, k + 1, one_run);
    v2 dx = v2_sub(xi, v2_set(hot[j0].x, hot[j1].x));
    if (F & F_PERIODIC) dx = SPH_LANE_MIN_IMAGE(v2, dx, per, hper, nper);
#if SPH_DIM == 2
    const v2 dy = v2_sub(yi, v2_set(hot[j0].y, hot[j1].y));
    const v2 r2 = v2_add(v2_mul(dx, dx), v2_mul(dy, dy));
#else
    v2 dy = v2_sub(yi, v2_set(hot[j0].y, hot[j1].y)), dz = v2_sub(zi, v2_set(hot[j0].z, hot[j1].z));
    if (F & F_PERIODIC) { /* y or z may be the axis that wraps: sep_x's choice, in both lanes */
      dy = SPH_LANE_MIN_IMAGE(v2, dy, pery, hpery, npery);
      dz = SPH_LANE_MIN_IMAGE(v2, dz, perz, hperz, nperz);
    }
    const v2 r2 = v2_add(v2_add(v2_mul(dx, dx), v2_mul(dy, dy)), v2_mul(dz, dz));
#endif
    const unsigned m = v2_bits2(v2_and(v2_lt(r2, sv), v2_lt(zero, r2)));
    nb[cnt] = j0; /* kept only if counted: no branch */
    cnt += m & 1u;
    nb[cnt] = j1;
    cnt += m >> 1;
  }
  if (k < len) {
    const size_t j = VIEW_AT(v, k, one_run);
    const double dx = sep_x(xs0, hot[j].x, period, hp, F);
#if SPH_DIM == 2
    const double dy = ys0 - hot[j].y;
#else
    const double dy = sep_x(ys0, hot[j].y, py, 0.5 * py, F),
                 dz = sep_x(zs0, hot[j].z, pz, 0.5 * pz, F);
#endif
    const double r2 = SPH_NORM2(dx, dy, dz);
    nb[cnt] = (uint32_t)j;
    cnt += (size_t)((r2 < s0) & (r2 > 0.0));
  }
  return cnt;
}

static inline __attribute__((always_inline)) size_t
cut_row(const sph_force_hot *restrict hot, const sph_nlist *restrict l,
        const sph_force_params *restrict fp, size_t i, uint32_t *restrict nb, const unsigned F) {
  const sph_nlist_view v = sph_nlist_view_of(l, i);
  return v.o ? cut_row_at(hot, v, 1, fp, i, nb, 0, 0, F)
             : cut_row_at(hot, v, 0, fp, i, nb, 0, 0, F);
}

/* The fields of a packed record (sph_force_hot) by their place, for the
 * loops that load whole records and transpose them (v8z_transpose8). */
enum { H_x, H_y, H_vx, H_vy, H_rho, H_prho2, H_cs, H_m, H_z, H_vz };
#define H_FIELDS (SPH_DIM == 2 ? 8 : 10)
typedef char sph_hot_layout_check[(offsetof(sph_force_hot, y) == H_y * sizeof(double) &&
                                   offsetof(sph_force_hot, rho) == H_rho * sizeof(double) &&
                                   offsetof(sph_force_hot, m) == H_m * sizeof(double) &&
                                   sizeof(sph_force_hot) == H_FIELDS * sizeof(double))
                                      ? 1
                                      : -1];
/* cut_row four entries at a time (AVX2; the four- and eight-lane loops
 * both take it): each entry's separation and r^2 are cut_row_at's
 * operations in its own lane (the same bits, so the same pairs are kept),
 * the kept indices packed to the front in row order by a table of byte
 * shuffles and stored at once, the count advanced once per four entries
 * instead of per entry. The last entries, fewer than four, go to
 * cut_row_at. Measured against cut_row_at alone (interleaved pairs, one
 * thread, CPU time): the 2-D dam break a/50 0.946, SPHERIC Test 2 at
 * dx = 0.04 m 0.959; the neighbours' coordinates read by AVX2's gathers
 * instead were slower on this AMD EPYC (1.09 and 1.04), and an eight-wide
 * cut with AVX-512's compress gained less (0.978). */
#ifdef SPH_LANES_AVX
static inline __attribute__((always_inline, target("avx2"))) size_t
cut_row_v4x_of(const sph_force_hot *restrict hot, const sph_nlist_view v, const int one_run,
               const sph_force_params *restrict fp, size_t i, uint32_t *restrict nb,
               const unsigned F) {
  const sph_force_hot qi = hot[i];
  const size_t len = v.len;
  const v4x xi = v4x_all(qi.x), yi = v4x_all(qi.y);
  SPH_IF3(const v4x zi = v4x_all(qi.z);)
  const v4x sv = v4x_all(4.0 * fp->h * fp->h), zero = v4x_all(0.0);
  const v4x per = v4x_all(period_along(fp, 0)), hper = v4x_all(0.5 * period_along(fp, 0));
  const v4x nper = v4x_all(-0.5 * period_along(fp, 0));
  SPH_IF3(const double py = period_along(fp, 1), pz = period_along(fp, 2);
          const v4x pery = v4x_all(py), hpery = v4x_all(0.5 * py), npery = v4x_all(-0.5 * py);
          const v4x perz = v4x_all(pz), hperz = v4x_all(0.5 * pz), nperz = v4x_all(-0.5 * pz);)
  const __m128i base = _mm_set1_epi32((int)v.base);
  /* entry k's record: hb[o[k]] with hb = hot + base (the offset alone in the address), or
   * hot[e[k]] */
  const sph_force_hot *const hb = one_run ? hot + v.base : hot;
#define HOT_AT(k) (one_run ? hb + v.o[k] : hot + v.e[k])
  size_t k = 0, cnt = 0;
  for (; k + 4 <= len; k += 4) {
    /* the four entries: a run's offsets widened and added to its base, or the written-out row */
    const __m128i idx = one_run ? _mm_add_epi32(base, _mm_cvtepu16_epi32(_mm_loadl_epi64((
                                                          const __m128i *)(const void *)(v.o + k))))
                                : _mm_loadu_si128((const __m128i *)(const void *)(v.e + k));
    const sph_force_hot *q0 = HOT_AT(k), *q1 = HOT_AT(k + 1), *q2 = HOT_AT(k + 2),
                        *q3 = HOT_AT(k + 3);
    v4x dx = v4x_sub(xi, v4x_set(q0->x, q1->x, q2->x, q3->x));
    if (F & F_PERIODIC) dx = SPH_LANE_MIN_IMAGE(v4x, dx, per, hper, nper);
#if SPH_DIM == 2
    const v4x dy = v4x_sub(yi, v4x_set(q0->y, q1->y, q2->y, q3->y));
    const v4x r2 = v4x_add(v4x_mul(dx, dx), v4x_mul(dy, dy));
#else
    v4x dy = v4x_sub(yi, v4x_set(q0->y, q1->y, q2->y, q3->y));
    v4x dz = v4x_sub(zi, v4x_set(q0->z, q1->z, q2->z, q3->z));
    if (F & F_PERIODIC) {
      dy = SPH_LANE_MIN_IMAGE(v4x, dy, pery, hpery, npery);
      dz = SPH_LANE_MIN_IMAGE(v4x, dz, perz, hperz, nperz);
    }
    const v4x r2 = v4x_add(v4x_add(v4x_mul(dx, dx), v4x_mul(dy, dy)), v4x_mul(dz, dz));
#endif
    const unsigned m =
        (unsigned)_mm256_movemask_pd(v4x_and(v4x_lt(r2, sv), v4x_lt(zero, r2))); /* lane k: bit k */
    _mm_storeu_si128((__m128i *)(nb + cnt), v4x_pack32(idx, m));
    cnt += (size_t)__builtin_popcount(m);
  }
#undef HOT_AT
  return cut_row_at(hot, v, one_run, fp, i, nb, k, cnt, F);
}
static inline __attribute__((always_inline, target("avx2"))) size_t
cut_row_v4x(const sph_force_hot *restrict hot, const sph_nlist *restrict l,
            const sph_force_params *restrict fp, size_t i, uint32_t *restrict nb,
            const unsigned F) {
  const sph_nlist_view v = sph_nlist_view_of(l, i);
  return v.o ? cut_row_v4x_of(hot, v, 1, fp, i, nb, F) : cut_row_v4x_of(hot, v, 0, fp, i, nb, F);
}
#endif

/* The third axis's fields of a record, gathered one at a time (the
 * transposes take the first eight). */
#if SPH_DIM == 3
#define LHOT_Z(g)                                                                                  \
  g[H_z] = LSET(E_HOT, z);                                                                         \
  g[H_vz] = LSET(E_HOT, vz)
#else
#define LHOT_Z(g) (void)0
#endif

/* The scalar flavour: one pair at a time in row order, every term set (the
 * only one for per-particle h and mirror particles), its sums plain doubles. */
#define LW 1
#define LA v1
#define LAOP(name) v1_##name
#define LMASK v1_mask
#define LACC(s, t) s = LAOP(add)(s, t)
#define LDEC(s, t) s = LAOP(sub)(s, t)
#define LAMAX(s, t) s = LAOP(max)(t, s)
#define LSET(E, a) E(0, a)
#define FL v1
#define LCUT cut_row
#define LOOP_ATTR static inline __attribute__((always_inline))
#define LOOP_SHARED static __attribute__((noipa, unused))
#include "solver/interact_row.h"
#undef LOOP_SHARED
#undef LOOP_ATTR
#undef LCUT
#undef FL
#undef LSET
#undef LAMAX
#undef LDEC
#undef LACC
#undef LMASK
#undef LAOP
#undef LA
#undef LW

/* The four-lane flavours: the sums are the flavour's own vectors. The
 * portable flavour gathers the neighbours' fields one at a time (the
 * compiler drops those a term set does not read), the AVX2 flavour loads
 * the four records whole and transposes them (v4x_transpose8). */
#define LHOT_SET(g)                                                                                \
  LT g[H_FIELDS];                                                                                  \
  g[H_x] = LSET(E_HOT, x);                                                                         \
  g[H_y] = LSET(E_HOT, y);                                                                         \
  g[H_vx] = LSET(E_HOT, vx);                                                                       \
  g[H_vy] = LSET(E_HOT, vy);                                                                       \
  g[H_rho] = LSET(E_HOT, rho);                                                                     \
  g[H_prho2] = LSET(E_HOT, prho2);                                                                 \
  g[H_cs] = LSET(E_HOT, cs);                                                                       \
  g[H_m] = LSET(E_HOT, m);                                                                         \
  LHOT_Z(g)
#define LW 4
#define LA FL
#define LAOP(name) SPH_PT_XGLUE(FL, name)
#define LMASK SPH_PT_XGLUE(FL, mask)
#define LACC(s, t) s = LAOP(add)(s, t)
#define LDEC(s, t) s = LAOP(sub)(s, t)
#define LAMAX(s, t) s = LAOP(max)(t, s)
#define LSET(E, a) LAOP(set)(E(0, a), E(1, a), E(2, a), E(3, a))

#define FL v4e
#define LHOT(g) LHOT_SET(g)
#define LCUT cut_row
#define LOOP_ATTR static inline __attribute__((always_inline))
#define LOOP_SHARED static __attribute__((noipa, unused))
#include "solver/interact_row.h"
#include "solver/strain_lanes.h"
#undef LOOP_SHARED
#undef LOOP_ATTR
#undef LCUT
#undef LHOT
#undef FL

#ifdef SPH_LANES_AVX
#define FL v4x
#define LHOT(g)                                                                                    \
  v4x g[H_FIELDS];                                                                                 \
  {                                                                                                \
    const double *const r_[4] = {&hot[jk[0]].x, &hot[jk[1]].x, &hot[jk[2]].x, &hot[jk[3]].x};      \
    v4x_transpose8(r_, g);                                                                         \
  }                                                                                                \
  LHOT_Z(g)
#define LCUT cut_row_v4x
#define LOOP_ATTR static inline __attribute__((always_inline, target("avx2")))
#define LOOP_SHARED static __attribute__((noipa, unused, target("avx2")))
#include "solver/interact_row.h"
#undef LOOP_SHARED
#include "solver/strain_lanes.h"
#undef LOOP_ATTR
#undef LCUT
#undef LHOT
#undef FL
#endif

#undef LHOT_SET
#undef LSET
#undef LAMAX
#undef LDEC
#undef LACC
#undef LMASK
#undef LAOP
#undef LA
#undef LW

/* The eight-lane flavour: eight pairs evaluated at once, their terms added
 * into four-lane sums, lanes 0-3 first (the four-lane loop's order). */
#ifdef SPH_LANES_AVX512
#define LW 8
#define LA v4x
#define LAOP(name) v4x_##name
#define LMASK v8z_mask
#define LACC(s, t)                                                                                 \
  do {                                                                                             \
    const v8z t_ = (t);                                                                            \
    s = v4x_add(v4x_add(s, v8z_lo(t_)), v8z_hi(t_));                                               \
  } while (0)
#define LDEC(s, t)                                                                                 \
  do {                                                                                             \
    const v8z t_ = (t);                                                                            \
    s = v4x_sub(v4x_sub(s, v8z_lo(t_)), v8z_hi(t_));                                               \
  } while (0)
#define LAMAX(s, t)                                                                                \
  do {                                                                                             \
    const v8z t_ = (t);                                                                            \
    s = v4x_max(v8z_hi(t_), v4x_max(v8z_lo(t_), s));                                               \
  } while (0)
#define LSET(E, a) v8z_set(E(0, a), E(1, a), E(2, a), E(3, a), E(4, a), E(5, a), E(6, a), E(7, a))
#define LHOT(g)                                                                                    \
  v8z g[H_FIELDS];                                                                                 \
  {                                                                                                \
    const double *const r_[8] = {&hot[jk[0]].x, &hot[jk[1]].x, &hot[jk[2]].x, &hot[jk[3]].x,       \
                                 &hot[jk[4]].x, &hot[jk[5]].x, &hot[jk[6]].x, &hot[jk[7]].x};      \
    v8z_transpose8(r_, g);                                                                         \
  }                                                                                                \
  LHOT_Z(g)

#define FL v8z
#define LCUT cut_row_v4x /* (AVX-512 implies AVX2) */
#define LOOP_ATTR static inline __attribute__((always_inline, target("avx512f")))
#define LOOP_SHARED static __attribute__((noipa, unused, target("avx512f")))
#include "solver/interact_row.h"
#undef LOOP_SHARED
#include "solver/strain_lanes.h"
#undef LOOP_ATTR
#undef LCUT
#undef FL

#undef LHOT
#undef LSET
#undef LAMAX
#undef LDEC
#undef LACC
#undef LMASK
#undef LAOP
#undef LA
#undef LW
#endif

#endif
