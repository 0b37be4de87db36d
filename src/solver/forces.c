/*
 * forces.c - the interaction passes (see forces.h for the equations).
 *
 * Loops are written once as always-inline functions taking a bit set F of
 * the terms in use; every call site passes a constant F, so each of the 128
 * combinations compiles to a loop without the terms it does not use
 * (DESIGN rule 4: a case pays only for what it switches on). Particles are
 * processed in parallel, each writing only its own rates; each sum runs
 * over the particle's row of the neighbour list (grid.h) in increasing
 * storage index, so results are bitwise independent of the thread count,
 * the schedule and the age of the list.
 *
 * What makes a pass fast (bench/results/martin_moyce.md, features.md):
 *   - the neighbour list: a row holds the particles within the support
 *     plus a skin, so the loop no longer tests the ~3x more candidates of
 *     the 3x3 cells, and the list outlives many passes (sim.c);
 *   - the fields a neighbour reads are packed in one 64-byte record per
 *     particle (sph_force_hot), refreshed at every pass;
 *   - the common variants (no per-particle h, no energy ledger) first cut
 *     the row to the pairs inside the support, then evaluate them four at
 *     a time in lanes (interact_v4*), without data-dependent branches:
 *     the kernel's two branches are one expression (sph_cubic_w_f), the
 *     artificial viscosity's "approaching" test a min(), 1/r comes from
 *     1/r^2 and sqrt(r^2) side by side, and one 1/rho_ij serves both the
 *     viscosity and XSPH. Each lane keeps its own partial sums (entries
 *     0, 4, 8, ... of the cut row in lane 0, and so on), added as
 *     (l0 + l1) + (l2 + l3) at the end: a fixed order, whatever the
 *     machine's vector width;
 *   - the step rule's max of c + sigma is reduced inside the pass.
 * The ledger and variable-h variants run the scalar loop (interact_one),
 * one pair after the other in row order.
 *
 * The viscous stress needs the strain rate of both particles of a pair, so
 * with that model a first pass computes eps_i at every particle (paper A
 * eq. 13-14) and stores tau_i / rho_i^2; the main pass then reads it.
 */
#include "config.h"

#include "core/parallel.h"

#include "solver/forces.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/arrays.h"
#include "physics/kernel.h"
#include "physics/turbulence.h"

/* Rows per stolen chunk of the interaction loop: a few microseconds of
 * work, so a thread waits at most that long at the end of a pass. */
#define SPH_STEAL_GRAIN 32

/* The terms, as bits of F. */
enum {
  F_AV = 1,        /* artificial viscosity */
  F_XSPH = 2,      /* XSPH velocity correction */
  F_STRESS = 4,    /* viscous stress tensor, paper A */
  F_MORRIS = 8,    /* Morris laminar viscosity, paper B */
  F_PERIODIC = 16, /* minimum image in x */
  F_VARH = 32,     /* per-particle smoothing length */
  F_LEDGER = 64    /* energy ledger: du/dt and the power of moving walls */
};

void sph_force_work_free(sph_force_work *w) {
  free(w->block);
  free(w->rows);
  sph_steal_free(&w->steal);
  sph_wall_velocity_work_free(&w->wv);
  *w = (sph_force_work){0};
}

/* Room for n particles: every per-particle array in one block (arrays.h),
 * the contents of the old one carried over. */
static int work_reserve(sph_force_work *w, size_t n, sph_error *err) {
  if (n <= w->cap) return 0;
  const size_t cap = n + n / 4 + 16;
  void **arrays[] = {(void **)&w->hot, (void **)&w->prho2, (void **)&w->cs,
                     (void **)&w->sigma, (void **)&w->sxx, (void **)&w->sxy,
                     (void **)&w->syy, (void **)&w->wpow, (void **)&w->wfx,
                     (void **)&w->wfy, (void **)&w->lxx, (void **)&w->lxy,
                     (void **)&w->lyy, (void **)&w->gvx, (void **)&w->gvy};
  enum { N_ARRAYS = sizeof arrays / sizeof arrays[0] };
  size_t size[N_ARRAYS];
  size[0] = sizeof *w->hot;
  for (size_t k = 1; k < N_ARRAYS; k++) size[k] = sizeof(double);
  if (sph_arrays_regrow(&w->block, cap, w->cap, N_ARRAYS, size, arrays))
    return sph_error_set(err, "forces: out of memory for %zu particles", n);
  w->cap = cap;
  return 0;
}

void sph_forces_pressure(sph_particles *p, const sph_eos *eos) {
  const long n = (long)p->n;
#pragma omp parallel for schedule(static) if (n > SPH_OMP_MIN)
  for (long i = 0; i < n; i++) p->p[i] = sph_eos_pressure(eos, p->rho[i]);
}

/* The neighbour row of i in the list l: j = nb[0], ..., nb[cnt - 1]. */
#define ROW(l, i, row_, len_)                                                                \
  const uint32_t *restrict row_ = (l)->nb + (l)->start[i];                                  \
  const size_t len_ = (l)->count[i];

/* x_i - x_j with the minimum image when periodic. */
static inline __attribute__((always_inline)) double sep_x(double xi, double xj, double period,
                                                          double half, const unsigned F) {
  double d = xi - xj;
  if (F & F_PERIODIC) {
    if (d > half)
      d -= period;
    else if (d < -half)
      d += period;
  }
  return d;
}

/* ---- two-lane arithmetic ---------------------------------------------------------
 *
 * Two doubles at a time: with SSE2 in one register, without it one lane
 * after the other, with bitwise the same results (each lane does exactly
 * the IEEE operations of the scalar code). Used to cut neighbour rows to
 * the support, and as the halves of the portable four-lane flavour. */
#if defined(__SSE2__)
#include <emmintrin.h>
typedef __m128d v2;
static inline v2 v2_set(double a, double b) { return _mm_set_pd(b, a); }
static inline v2 v2_all(double a) { return _mm_set1_pd(a); }
static inline v2 v2_add(v2 a, v2 b) { return _mm_add_pd(a, b); }
static inline v2 v2_sub(v2 a, v2 b) { return _mm_sub_pd(a, b); }
static inline v2 v2_mul(v2 a, v2 b) { return _mm_mul_pd(a, b); }
static inline v2 v2_div(v2 a, v2 b) { return _mm_div_pd(a, b); }
static inline v2 v2_sqrt(v2 a) { return _mm_sqrt_pd(a); }
static inline v2 v2_max(v2 a, v2 b) { return _mm_max_pd(a, b); } /* a > b ? a : b, per lane */
static inline v2 v2_min(v2 a, v2 b) { return _mm_min_pd(a, b); } /* a < b ? a : b, per lane */
static inline v2 v2_abs(v2 a) { return _mm_andnot_pd(_mm_set1_pd(-0.0), a); }
static inline v2 v2_lt(v2 a, v2 b) { return _mm_cmplt_pd(a, b); } /* all ones where a < b */
static inline v2 v2_ne(v2 a, v2 b) { return _mm_cmpneq_pd(a, b); }
static inline v2 v2_and(v2 a, v2 b) { return _mm_and_pd(a, b); }
static inline v2 v2_andnot(v2 m, v2 a) { return _mm_andnot_pd(m, a); } /* ~m & a */
static inline v2 v2_or(v2 a, v2 b) { return _mm_or_pd(a, b); }
static inline double v2_lane0(v2 a) { return _mm_cvtsd_f64(a); }
static inline double v2_lane1(v2 a) { return _mm_cvtsd_f64(_mm_unpackhi_pd(a, a)); }
static inline unsigned v2_bits2(v2 m) { return (unsigned)_mm_movemask_pd(m); } /* lane k: bit k */
#else
typedef struct {
  double l[2];
} v2;
static inline v2 v2_set(double a, double b) { return (v2){{a, b}}; }
static inline v2 v2_all(double a) { return (v2){{a, a}}; }
#define V2_OP(name, expr)                                                                    \
  static inline v2 name(v2 a, v2 b) {                                                        \
    v2 r;                                                                                    \
    for (int k = 0; k < 2; k++) {                                                            \
      const double x = a.l[k], y = b.l[k];                                                   \
      r.l[k] = (expr);                                                                       \
    }                                                                                        \
    return r;                                                                                \
  }
static inline double v2_bits(uint64_t u) {
  double d;
  memcpy(&d, &u, sizeof d);
  return d;
}
static inline uint64_t v2_u(double d) {
  uint64_t u;
  memcpy(&u, &d, sizeof u);
  return u;
}
V2_OP(v2_add, x + y)
V2_OP(v2_sub, x - y)
V2_OP(v2_mul, x * y)
V2_OP(v2_div, x / y)
V2_OP(v2_max, x > y ? x : y)
V2_OP(v2_min, x < y ? x : y)
V2_OP(v2_lt, v2_bits(x < y ? ~(uint64_t)0 : 0))
V2_OP(v2_ne, v2_bits(x != y ? ~(uint64_t)0 : 0))
V2_OP(v2_and, v2_bits(v2_u(x) & v2_u(y)))
V2_OP(v2_andnot, v2_bits(~v2_u(x) & v2_u(y)))
V2_OP(v2_or, v2_bits(v2_u(x) | v2_u(y)))
static inline v2 v2_sqrt(v2 a) { return (v2){{sqrt(a.l[0]), sqrt(a.l[1])}}; }
static inline v2 v2_abs(v2 a) { return (v2){{fabs(a.l[0]), fabs(a.l[1])}}; }
static inline double v2_lane0(v2 a) { return a.l[0]; }
static inline double v2_lane1(v2 a) { return a.l[1]; }
static inline unsigned v2_bits2(v2 m) {
  return (unsigned)(v2_u(m.l[0]) >> 63) | (unsigned)(v2_u(m.l[1]) >> 63) << 1;
}
#endif
/* m ? a : b per lane (m all ones or all zeros) */
static inline v2 v2_sel(v2 m, v2 a, v2 b) { return v2_or(v2_and(m, a), v2_andnot(m, b)); }

/* ---- four-lane arithmetic --------------------------------------------------------
 *
 * The lane loop of the main pass (interact_v4*) runs four neighbours at a
 * time. Two flavours with bitwise the same results: v4e, two two-lane
 * halves (SSE2 or plain C), and on x86 v4x, one AVX register, chosen at
 * run time when the processor has AVX2. Both do the same IEEE operations
 * per lane (no FMA: the flavour only changes how many lanes an instruction
 * holds), so a result never depends on the machine's vector width. */
typedef struct {
  v2 lo, hi;
} v4e;
#define V4E_OP(name)                                                                         \
  static inline v4e v4e_##name(v4e a, v4e b) {                                               \
    return (v4e){v2_##name(a.lo, b.lo), v2_##name(a.hi, b.hi)};                              \
  }
V4E_OP(add)
V4E_OP(sub)
V4E_OP(mul)
V4E_OP(div)
V4E_OP(max)
V4E_OP(min)
V4E_OP(lt)
V4E_OP(and)
static inline v4e v4e_set(double a, double b, double c, double d) {
  return (v4e){v2_set(a, b), v2_set(c, d)};
}
static inline v4e v4e_all(double a) { return (v4e){v2_all(a), v2_all(a)}; }
static inline v4e v4e_sqrt(v4e a) { return (v4e){v2_sqrt(a.lo), v2_sqrt(a.hi)}; }
static inline v4e v4e_abs(v4e a) { return (v4e){v2_abs(a.lo), v2_abs(a.hi)}; }
static inline v4e v4e_sel(v4e m, v4e a, v4e b) {
  return (v4e){v2_sel(m.lo, a.lo, b.lo), v2_sel(m.hi, a.hi, b.hi)};
}
static inline void v4e_store(double *o, v4e a) {
  o[0] = v2_lane0(a.lo);
  o[1] = v2_lane1(a.lo);
  o[2] = v2_lane0(a.hi);
  o[3] = v2_lane1(a.hi);
}

#if defined(__GNUC__) && defined(__x86_64__)
#define SPH_LANES_AVX 1
#include <immintrin.h>
#define AVX2 static inline __attribute__((always_inline, target("avx2")))
typedef __m256d v4x;
AVX2 v4x v4x_set(double a, double b, double c, double d) { return _mm256_set_pd(d, c, b, a); }
AVX2 v4x v4x_all(double a) { return _mm256_set1_pd(a); }
AVX2 v4x v4x_add(v4x a, v4x b) { return _mm256_add_pd(a, b); }
AVX2 v4x v4x_sub(v4x a, v4x b) { return _mm256_sub_pd(a, b); }
AVX2 v4x v4x_mul(v4x a, v4x b) { return _mm256_mul_pd(a, b); }
AVX2 v4x v4x_div(v4x a, v4x b) { return _mm256_div_pd(a, b); }
AVX2 v4x v4x_sqrt(v4x a) { return _mm256_sqrt_pd(a); }
AVX2 v4x v4x_max(v4x a, v4x b) { return _mm256_max_pd(a, b); } /* as maxpd */
AVX2 v4x v4x_min(v4x a, v4x b) { return _mm256_min_pd(a, b); } /* as minpd */
AVX2 v4x v4x_abs(v4x a) { return _mm256_andnot_pd(_mm256_set1_pd(-0.0), a); }
AVX2 v4x v4x_lt(v4x a, v4x b) { return _mm256_cmp_pd(a, b, _CMP_LT_OS); } /* as cmpltpd */
AVX2 v4x v4x_and(v4x a, v4x b) { return _mm256_and_pd(a, b); }
AVX2 v4x v4x_sel(v4x m, v4x a, v4x b) { return _mm256_blendv_pd(b, a, m); }
AVX2 void v4x_store(double *o, v4x a) { _mm256_storeu_pd(o, a); }
#endif

/* ---- the strain-rate pass (paper A eq. 13-14) ------------------------------------ */

/* Runtime options of the strain-rate pass (not bits of F: the loop is not
 * hot enough to need a variant each). */
typedef struct strain_opts {
  const double *gvx, *gvy; /* velocity of wall particles in the viscous terms, or NULL */
  double *lxx, *lxy, *lyy; /* kernel-gradient correction L = M^-1 out, or NULL (off) */
} strain_opts;

static inline __attribute__((always_inline)) void
strain_one(const sph_particles *restrict p, const sph_nlist *restrict l,
           const sph_force_params *restrict fp, size_t i, double *exx, double *exy, double *eyy,
           const strain_opts *o, const unsigned F) {
  const double *restrict x = p->x, *restrict y = p->y, *restrict h = p->h;
  const double *restrict vx = o->gvx ? o->gvx : p->vx, *restrict vy = o->gvy ? o->gvy : p->vy;
  const double *restrict m = p->mass, *restrict rho = p->rho;
  const double period = fp->period, half = 0.5 * fp->period;
  const double xi = x[i], yi = y[i], vxi = vx[i], vyi = vy[i];
  double sxx = 0.0, sxy = 0.0, syy = 0.0, div = 0.0;
  /* with the correction: G_ab = sum_j V_j (v_j - v_i)_a (grad_i W_ij)_b and
   * M_ab = sum_j V_j (x_j - x_i)_a (grad_i W_ij)_b */
  double gxx = 0.0, gxy = 0.0, gyx = 0.0, gyy = 0.0, mxx = 0.0, mxy = 0.0, myy = 0.0;
  const int correct = o->lxx != NULL;
  ROW(l, i, nb, cnt)
  for (size_t k = 0; k < cnt; k++) {
      const size_t j = nb[k];
      const double dx = sep_x(xi, x[j], period, half, F), dy = yi - y[j];
      const double r2 = dx * dx + dy * dy;
      const double hij = (F & F_VARH) ? 0.5 * (h[i] + h[j]) : fp->h;
      if (r2 >= 4.0 * hij * hij || r2 == 0.0) continue;
      const double r = sqrt(r2);
      double wij, dw;
      sph_cubic_w_dw(r, hij, &wij, &dw);
      const double f = dw / r * (m[j] / rho[j]);
      const double gx = f * dx, gy = f * dy;       /* V_j grad_i W_ij */
      const double ux = vx[j] - vxi, uy = vy[j] - vyi; /* v_ji */
      if (correct) {
        gxx += ux * gx;
        gxy += ux * gy;
        gyx += uy * gx;
        gyy += uy * gy;
        mxx -= dx * gx;
        mxy -= dx * gy;
        myy -= dy * gy;
      } else {
        sxx += 2.0 * ux * gx;
        syy += 2.0 * uy * gy;
        sxy += uy * gx + ux * gy;
        div += ux * gx + uy * gy;
      }
    }
  if (correct) { /* grad v = G M^-1 where M is invertible (Bonet and Lok 1999) */
    const double det = mxx * myy - mxy * mxy;
    double axx = 1.0, axy = 0.0, ayy = 1.0;
    if (det > SPH_GRADIENT_CORRECTION_MIN_DET && mxx > 0.0) {
      axx = myy / det;
      axy = -mxy / det;
      ayy = mxx / det;
    }
    o->lxx[i] = axx;
    o->lxy[i] = axy;
    o->lyy[i] = ayy;
    const double cxx = gxx * axx + gxy * axy, cxy = gxx * axy + gxy * ayy;
    const double cyx = gyx * axx + gyy * axy, cyy = gyx * axy + gyy * ayy;
    sxx = 2.0 * cxx;
    syy = 2.0 * cyy;
    sxy = cyx + cxy;
    div = cxx + cyy;
  }
  /* the deviatoric part as the paper writes it (its 2/3 is the 3-D factor) */
  exx[i] = sxx - (2.0 / 3.0) * div;
  eyy[i] = syy - (2.0 / 3.0) * div;
  exy[i] = sxy;
}

/* One function per variant, with F a literal inside the parallel region
 * (OpenMP outlines the region before inlining, so a constant must be
 * spelled out there to reach the loop). */
#define STRAIN_VARIANT(k)                                                                    \
  static void strain_all_##k(const sph_particles *p, const sph_nlist *l,                      \
                             const sph_force_params *fp, double *exx, double *exy,            \
                             double *eyy, const strain_opts *o) {                             \
    const long n = (long)p->n;                                                               \
    _Pragma("omp parallel for schedule(dynamic, 256) if (n > SPH_OMP_MIN)") for (long i = 0; i < n; i++)          \
        strain_one(p, l, fp, (size_t)i, exx, exy, eyy, o, k);                                 \
  }
STRAIN_VARIANT(0)
STRAIN_VARIANT(16)
STRAIN_VARIANT(32)
STRAIN_VARIANT(48)

static void strain_list(const sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                        double *exx, double *exy, double *eyy, const strain_opts *o) {
  const unsigned F = (fp->periodic ? F_PERIODIC : 0) | (fp->var_h ? F_VARH : 0);
  switch (F) {
  case 0: strain_all_0(p, l, fp, exx, exy, eyy, o); break;
  case F_PERIODIC: strain_all_16(p, l, fp, exx, exy, eyy, o); break;
  case F_VARH: strain_all_32(p, l, fp, exx, exy, eyy, o); break;
  default: strain_all_48(p, l, fp, exx, exy, eyy, o); break;
  }
}

/* The kernel's reach: 2 h, or 2 max h with per-particle h. */
static double kernel_reach(const sph_particles *p, const sph_force_params *fp) {
  double hmax = fp->h;
  if (fp->var_h)
    for (size_t i = 0; i < p->n; i++)
      if (p->h[i] > hmax) hmax = p->h[i];
  return SPH_CUBIC_SUPPORT * hmax;
}

/* The velocities the strain-rate pass reads, no-slip walls extrapolated. */
static int wall_ghosts(const sph_particles *p, const sph_force_params *fp, double *gvx,
                       double *gvy, sph_wall_velocity_work *wv, sph_error *err) {
  return sph_wall_velocity(p, kernel_reach(p, fp), fp->px0, fp->periodic ? fp->period : 0.0,
                           gvx, gvy, wv, err);
}

/* The options of the strain-rate pass as fp asks for them, into w's arrays:
 * the gradient correction's L, and the wall particles' extrapolated
 * velocities (computed here). */
static int strain_setup(const sph_particles *p, const sph_force_params *fp, sph_force_work *w,
                        strain_opts *o, sph_error *err) {
  *o = (strain_opts){0};
  if (fp->gradient_correction) {
    o->lxx = w->lxx;
    o->lxy = w->lxy;
    o->lyy = w->lyy;
  }
  if (fp->no_slip) {
    if (wall_ghosts(p, fp, w->gvx, w->gvy, &w->wv, err)) return -1;
    o->gvx = w->gvx;
    o->gvy = w->gvy;
  }
  return 0;
}

int sph_forces_strain_rate(const sph_particles *p, const sph_grid *g, const sph_force_params *fp,
                           double *exx, double *exy, double *eyy, sph_error *err) {
  sph_nlist l;
  sph_nlist_init(&l);
  sph_force_work w = {0};
  strain_opts o;
  int rc = sph_nlist_build(&l, g, p, kernel_reach(p, fp), 0.0, fp->periodic ? fp->period : 0.0,
                           err);
  if (rc == 0) rc = work_reserve(&w, p->n, err);
  if (rc == 0) rc = strain_setup(p, fp, &w, &o, err);
  if (rc == 0) strain_list(p, &l, fp, exx, exy, eyy, &o);
  sph_force_work_free(&w);
  sph_nlist_free(&l);
  return rc;
}

/* ---- the main pass ----------------------------------------------------------------- */

static inline __attribute__((always_inline)) void
interact_one(sph_particles *restrict p, const sph_nlist *restrict l,
             const sph_force_params *restrict fp, sph_force_work *restrict w, size_t i,
             const unsigned F) {
  const sph_force_hot *restrict hot = w->hot;
  const double *restrict h = p->h;
  const double *restrict sxx = w->sxx, *restrict sxy = w->sxy, *restrict syy = w->syy;
  const int32_t *restrict kind = p->kind;
  const double period = fp->period, half = 0.5 * fp->period;
  const double nu4 = 4.0 * fp->mu / fp->eos.rho0;
  const double alpha = fp->alpha, beta = fp->beta, eta_f = fp->eta;
  if (kind[i] == SPH_KIND_MIRROR || (p->flags[i] & SPH_FLAG_REPULSIVE)) {
    p->drho[i] = p->ax[i] = p->ay[i] = 0.0;
    w->sigma[i] = 0.0;
    if (F & F_LEDGER) p->du[i] = w->wpow[i] = w->wfx[i] = w->wfy[i] = 0.0;
    return;
  }
  const sph_force_hot qi = hot[i];
  const double xi = qi.x, yi = qi.y, vxi = qi.vx, vyi = qi.vy;
  const double rhoi = qi.rho, pri = qi.prho2, ci = qi.cs;
  const int fluid = kind[i] == SPH_KIND_FLUID;
  /* fixed h: 1/h and 4h^2 once per particle (F_VARH: per pair) */
  const double h0 = fp->h, inv_h0 = 1.0 / h0, supp0 = 4.0 * h0 * h0;
  double drho = 0.0, ax = 0.0, ay = 0.0, xs = 0.0, ys = 0.0, sig = 0.0;
  double du = 0.0, wpow = 0.0, wfx = 0.0, wfy = 0.0; /* energy and momentum ledger */
  ROW(l, i, nb, cnt)
  for (size_t k = 0; k < cnt; k++) {
    const size_t j = nb[k];
    const sph_force_hot *restrict qj = &hot[j];
    const double dx = sep_x(xi, qj->x, period, half, F), dy = yi - qj->y;
    const double r2 = dx * dx + dy * dy;
    const double hij = (F & F_VARH) ? 0.5 * (h[i] + h[j]) : h0;
    const double supp = (F & F_VARH) ? 4.0 * hij * hij : supp0;
    if (r2 >= supp || r2 == 0.0) continue; /* outside the support, or coincident */
    const double inv_r2 = 1.0 / r2, r = sqrt(r2), inv_r = r * inv_r2;
    double wij, f; /* W_ij and (1/r) dW/dr: grad_i W_ij = f (dx, dy) */
    sph_cubic_w_f(r, inv_r, (F & F_VARH) ? 1.0 / hij : inv_h0, &wij, &f);
    const double gx = f * dx, gy = f * dy;
    const double dvx = vxi - qj->vx, dvy = vyi - qj->vy;
    const double mj = qj->m;
    drho += mj * (dvx * gx + dvy * gy); /* continuity, B eq. 2 */
    const double vdotr = dvx * dx + dvy * dy;
    const double s = fabs(hij * vdotr) * inv_r2; /* B §2.6 */
    sig = s > sig ? s : sig;
    /* a wall particle needs the pair terms only for its share of the heat */
    if (!fluid && !((F & F_LEDGER) && kind[j] == SPH_KIND_FLUID)) continue;
    double pij = pri + qj->prho2;
    double inv_rb = 0.0; /* 1 / rho_ij, rho_ij = (rho_i + rho_j) / 2 */
    if (F & (F_AV | F_XSPH)) inv_rb = 2.0 / (rhoi + qj->rho);
    if (F & F_AV) { /* A eq. 15-16; mu = 0 unless approaching (no branch) */
      const double eta = eta_f * hij;
      const double mu = hij * (vdotr < 0.0 ? vdotr : 0.0) / (r2 + eta * eta);
      const double cbar = 0.5 * (ci + qj->cs);
      pij += (-alpha * cbar * mu + beta * mu * mu) * inv_rb;
    }
    /* the pair's acceleration of i (momentum, paper A eq. 11) */
    const double mp = mj * pij;
    double pax = -mp * gx, pay = -mp * gy;
    if (F & F_LEDGER) du += 0.5 * mp * (dvx * gx + dvy * gy); /* A eq. 28 */
    if (F & F_STRESS) {
      const double txx = sxx[i] + sxx[j], txy = sxy[i] + sxy[j], tyy = syy[i] + syy[j];
      pax += mj * (txx * gx + txy * gy);
      pay += mj * (txy * gx + tyy * gy);
      /* viscous dissipation, the discrete form of A eq. 29 that balances
       * the pair's work exactly */
      if (F & F_LEDGER)
        du -= 0.5 * mj * (txx * dvx * gx + txy * (dvx * gy + dvy * gx) + tyy * dvy * gy);
    }
    if (F & F_MORRIS) { /* B eq. 4 */
      const double eta = eta_f * hij;
      const double c = mj * nu4 * (f * r2) / ((rhoi + qj->rho) * (r2 + eta * eta));
      pax += c * dvx;
      pay += c * dvy;
      if (F & F_LEDGER) du -= 0.5 * c * (dvx * dvx + dvy * dvy);
    }
    if (!fluid) continue;
    ax += pax;
    ay += pay;
    /* power of a (moving) wall particle's force on i, per unit mass of i */
    if ((F & F_LEDGER) && kind[j] == SPH_KIND_WALL) wpow += pax * qj->vx + pay * qj->vy;
    /* force of walls and mirror particles on i: external to the fluid */
    if ((F & F_LEDGER) && kind[j] != SPH_KIND_FLUID) {
      wfx += pax;
      wfy += pay;
    }
    if (F & F_XSPH) { /* B eq. 6, over fluid neighbours */
      const double c = kind[j] == SPH_KIND_FLUID ? mj * inv_rb * wij : 0.0;
      xs -= c * dvx;
      ys -= c * dvy;
    }
  }
  p->drho[i] = drho;
  w->sigma[i] = sig;
  if (F & F_LEDGER) {
    p->du[i] = du;
    w->wpow[i] = wpow;
    w->wfx[i] = wfx;
    w->wfy[i] = wfy;
  }
  if (fluid) {
    p->ax[i] = ax + fp->gx;
    p->ay[i] = ay + fp->gy;
    if (F & F_XSPH) {
      p->xsx[i] = fp->xsph * xs;
      p->xsy[i] = fp->xsph * ys;
    }
  } else {
    p->ax[i] = p->ay[i] = 0.0;
  }
}

/* The row of i cut to the pairs inside the support (not coincident), in
 * row order, into nb; returns their number. Which entry goes to which lane
 * of the lane loop then depends only on the pairs, never on the skin. */
static inline __attribute__((always_inline)) size_t
cut_row(const sph_force_hot *restrict hot, const sph_nlist *restrict l,
        const sph_force_params *restrict fp, size_t i, uint32_t *restrict nb, const unsigned F) {
  const sph_force_hot qi = hot[i];
  const double h0 = fp->h;
  const v2 xi = v2_all(qi.x), yi = v2_all(qi.y), zero = v2_all(0.0);
  const v2 per = v2_all(fp->period), hper = v2_all(0.5 * fp->period), nper = v2_all(-0.5 * fp->period);
  size_t cnt = 0;
  ROW(l, i, row, len)
  const double xs0 = qi.x, ys0 = qi.y, s0 = 4.0 * h0 * h0;
  const double period = fp->period, hp = 0.5 * fp->period;
  const v2 sv = v2_all(s0);
  size_t k = 0;
  for (; k + 1 < len; k += 2) { /* two entries at a time */
    const uint32_t j0 = row[k], j1 = row[k + 1];
    v2 dx = v2_sub(xi, v2_set(hot[j0].x, hot[j1].x));
    if (F & F_PERIODIC)
      dx = v2_sel(v2_lt(hper, dx), v2_sub(dx, per), v2_sel(v2_lt(dx, nper), v2_add(dx, per), dx));
    const v2 dy = v2_sub(yi, v2_set(hot[j0].y, hot[j1].y));
    const v2 r2 = v2_add(v2_mul(dx, dx), v2_mul(dy, dy));
    const unsigned m = v2_bits2(v2_and(v2_lt(r2, sv), v2_lt(zero, r2)));
    nb[cnt] = j0; /* kept only if counted: no branch */
    cnt += m & 1u;
    nb[cnt] = j1;
    cnt += m >> 1;
  }
  if (k < len) {
    const size_t j = row[k];
    const double dx = sep_x(xs0, hot[j].x, period, hp, F), dy = ys0 - hot[j].y;
    const double r2 = dx * dx + dy * dy;
    nb[cnt] = (uint32_t)j;
    cnt += (size_t)((r2 < s0) & (r2 > 0.0));
  }
  return cnt;
}

/* The main pass four neighbours at a time (see "four-lane arithmetic"),
 * for the variants without per-particle h and the energy ledger: the same
 * terms and the same IEEE operations per pair as interact_one, summed in
 * four lanes, (l0 + l1) + (l2 + l3) at the end. Written once, instantiated
 * for each lane flavour (templates by macro). */
#define DEFINE_INTERACT_LANES(FL, ATTR)                                                                                              \
ATTR void                                                                                                                            \
interact_##FL(sph_particles *restrict p, const sph_nlist *restrict l,                                                                \
              const sph_force_params *restrict fp, sph_force_work *restrict w, size_t i,                                             \
              const unsigned F) {                                                                                                    \
  const sph_force_hot *restrict hot = w->hot;                                                                                        \
  const double *restrict sxx = w->sxx, *restrict sxy = w->sxy, *restrict syy = w->syy;                                               \
  const int32_t *restrict kind = p->kind;                                                                                            \
  if (kind[i] == SPH_KIND_MIRROR || (p->flags[i] & SPH_FLAG_REPULSIVE)) {                                                            \
    p->drho[i] = p->ax[i] = p->ay[i] = 0.0;                                                                                          \
    w->sigma[i] = 0.0;                                                                                                               \
    return;                                                                                                                          \
  }                                                                                                                                  \
  uint32_t *restrict nb = w->rows + (size_t)sph_thread() * w->rows_stride;                                                           \
  const size_t cnt = cut_row(hot, l, fp, i, nb, F);                                                                                  \
  for (size_t k = cnt; k < cnt + 3 && cnt > 0; k++) nb[k] = nb[cnt - 1]; /* padding lanes */                                         \
  const sph_force_hot qi = hot[i];                                                                                                   \
  const int fluid = kind[i] == SPH_KIND_FLUID;                                                                                       \
  const double h0 = fp->h;                                                                                                           \
  const FL xi = FL##_all(qi.x), yi = FL##_all(qi.y), vxi = FL##_all(qi.vx), vyi = FL##_all(qi.vy);                                   \
  const FL rhoi = FL##_all(qi.rho), pri = FL##_all(qi.prho2), ci = FL##_all(qi.cs);                                                  \
  const FL hh = FL##_all(h0), inv_h = FL##_all(1.0 / h0);                                                                            \
  const FL one = FL##_all(1.0), two = FL##_all(2.0), zero = FL##_all(0.0), half = FL##_all(0.5);                                     \
  const FL sigma = FL##_all((10.0 / (7.0 * SPH_PI)) * (1.0 / h0) * (1.0 / h0));                                                      \
  const FL sigma_h = FL##_all((10.0 / (7.0 * SPH_PI)) * (1.0 / h0) * (1.0 / h0) * (1.0 / h0));                                       \
  const FL per = FL##_all(fp->period), hper = FL##_all(0.5 * fp->period), nper = FL##_all(-0.5 * fp->period);                        \
  const double eta = fp->eta * h0;                                                                                                   \
  const FL eta2 = FL##_all(eta * eta), nalpha = FL##_all(-fp->alpha), beta = FL##_all(fp->beta);                                     \
  const FL nu4 = FL##_all(4.0 * fp->mu / fp->eos.rho0);                                                                              \
  const FL lane = FL##_set(0.0, 1.0, 2.0, 3.0), n = FL##_all((double)cnt);                                                           \
  FL drho = zero, ax = zero, ay = zero, xs = zero, ys = zero, sig = zero;                                                            \
  for (size_t k = 0; k < cnt; k += 4) {                                                                                              \
    const size_t j0 = nb[k], j1 = nb[k + 1], j2 = nb[k + 2], j3 = nb[k + 3];                                                         \
    const sph_force_hot *restrict a = &hot[j0], *restrict b = &hot[j1];                                                              \
    const sph_force_hot *restrict c_ = &hot[j2], *restrict d = &hot[j3];                                                             \
    FL dx = FL##_sub(xi, FL##_set(a->x, b->x, c_->x, d->x));                                                                         \
    if (F & F_PERIODIC) { /* minimum image, as sep_x */                                                                              \
      dx = FL##_sel(FL##_lt(hper, dx), FL##_sub(dx, per), FL##_sel(FL##_lt(dx, nper), FL##_add(dx, per), dx));                       \
    }                                                                                                                                \
    const FL dy = FL##_sub(yi, FL##_set(a->y, b->y, c_->y, d->y));                                                                   \
    const FL r2s = FL##_add(FL##_mul(dx, dx), FL##_mul(dy, dy));                                                                     \
    /* the padding lanes past the row's end repeat its last pair, masked out */                                                      \
    const FL in = FL##_lt(FL##_add(FL##_all((double)k), lane), n);                                                                   \
    /* 1/r2 and sqrt(r2) run side by side: a shorter chain than 1/sqrt(r2) */                                                        \
    const FL inv_r2 = FL##_div(one, r2s), r = FL##_sqrt(r2s), inv_r = FL##_mul(r, inv_r2);                                           \
    /* the cubic spline, as sph_cubic_w_f */                                                                                         \
    const FL q = FL##_mul(r, inv_h), t = FL##_sub(two, q);                                                                           \
    const FL am = FL##_sel(FL##_lt(q, one), FL##_sub(one, q), zero);                                                                 \
    const FL wij = FL##_and(in, FL##_mul(sigma, FL##_sub(FL##_mul(FL##_all(0.25), FL##_mul(FL##_mul(t, t), t)),                      \
                                               FL##_mul(FL##_mul(am, am), am))));                                                    \
    const FL f = FL##_and(in, FL##_mul(FL##_mul(sigma_h, FL##_sub(FL##_mul(FL##_all(3.0), FL##_mul(am, am)),                         \
                                                     FL##_mul(FL##_all(0.75), FL##_mul(t, t)))),                                     \
                                inv_r));                                                                                             \
    const FL gx = FL##_mul(f, dx), gy = FL##_mul(f, dy);                                                                             \
    const FL dvx = FL##_sub(vxi, FL##_set(a->vx, b->vx, c_->vx, d->vx)), dvy = FL##_sub(vyi, FL##_set(a->vy, b->vy, c_->vy, d->vy)); \
    const FL mj = FL##_set(a->m, b->m, c_->m, d->m);                                                                                 \
    drho = FL##_add(drho, FL##_mul(mj, FL##_add(FL##_mul(dvx, gx), FL##_mul(dvy, gy))));                                             \
    const FL vdotr = FL##_add(FL##_mul(dvx, dx), FL##_mul(dvy, dy));                                                                 \
    const FL s = FL##_and(in, FL##_mul(FL##_abs(FL##_mul(hh, vdotr)), inv_r2));                                                      \
    sig = FL##_max(s, sig);                                                                                                          \
    if (!fluid) continue; /* a wall particle needs no pair terms */                                                                  \
    FL pij = FL##_add(pri, FL##_set(a->prho2, b->prho2, c_->prho2, d->prho2));                                                       \
    FL inv_rb = zero;                                                                                                                \
    if (F & (F_AV | F_XSPH)) inv_rb = FL##_div(two, FL##_add(rhoi, FL##_set(a->rho, b->rho, c_->rho, d->rho)));                      \
    if (F & F_AV) {                                                                                                                  \
      const FL mu = FL##_div(FL##_mul(hh, FL##_min(vdotr, zero)), FL##_add(r2s, eta2));                                              \
      const FL cbar = FL##_mul(half, FL##_add(ci, FL##_set(a->cs, b->cs, c_->cs, d->cs)));                                           \
      pij = FL##_add(pij, FL##_mul(FL##_add(FL##_mul(FL##_mul(nalpha, cbar), mu), FL##_mul(FL##_mul(beta, mu), mu)),                 \
                             inv_rb));                                                                                               \
    }                                                                                                                                \
    const FL mp = FL##_mul(mj, pij);                                                                                                 \
    const FL nmp = FL##_sub(zero, mp);                                                                                               \
    FL pax = FL##_mul(nmp, gx), pay = FL##_mul(nmp, gy);                                                                             \
    if (F & F_STRESS) {                                                                                                              \
      const FL txx = FL##_add(FL##_all(sxx[i]), FL##_set(sxx[j0], sxx[j1], sxx[j2], sxx[j3]));                                       \
      const FL txy = FL##_add(FL##_all(sxy[i]), FL##_set(sxy[j0], sxy[j1], sxy[j2], sxy[j3]));                                       \
      const FL tyy = FL##_add(FL##_all(syy[i]), FL##_set(syy[j0], syy[j1], syy[j2], syy[j3]));                                       \
      pax = FL##_add(pax, FL##_mul(mj, FL##_add(FL##_mul(txx, gx), FL##_mul(txy, gy))));                                             \
      pay = FL##_add(pay, FL##_mul(mj, FL##_add(FL##_mul(txy, gx), FL##_mul(tyy, gy))));                                             \
    }                                                                                                                                \
    if (F & F_MORRIS) {                                                                                                              \
      const FL c = FL##_div(FL##_mul(FL##_mul(mj, nu4), FL##_mul(f, r2s)),                                                           \
                        FL##_mul(FL##_add(rhoi, FL##_set(a->rho, b->rho, c_->rho, d->rho)), FL##_add(r2s, eta2)));                   \
      pax = FL##_add(pax, FL##_mul(c, dvx));                                                                                         \
      pay = FL##_add(pay, FL##_mul(c, dvy));                                                                                         \
    }                                                                                                                                \
    ax = FL##_add(ax, pax);                                                                                                          \
    ay = FL##_add(ay, pay);                                                                                                          \
    if (F & F_XSPH) { /* over fluid neighbours */                                                                                    \
      const FL mx = FL##_set(kind[j0] == SPH_KIND_FLUID ? a->m : 0.0,                                                                \
                         kind[j1] == SPH_KIND_FLUID ? b->m : 0.0,                                                                    \
                         kind[j2] == SPH_KIND_FLUID ? c_->m : 0.0,                                                                   \
                         kind[j3] == SPH_KIND_FLUID ? d->m : 0.0);                                                                   \
      const FL c = FL##_mul(FL##_mul(mx, inv_rb), wij);                                                                              \
      xs = FL##_sub(xs, FL##_mul(c, dvx));                                                                                           \
      ys = FL##_sub(ys, FL##_mul(c, dvy));                                                                                           \
    }                                                                                                                                \
  }                                                                                                                                  \
  double lv[4];                                                                                                                      \
  FL##_store(lv, drho);                                                                                                              \
  p->drho[i] = (lv[0] + lv[1]) + (lv[2] + lv[3]);                                                                                    \
  FL##_store(lv, sig);                                                                                                               \
  const double s01 = lv[0] > lv[1] ? lv[0] : lv[1], s23 = lv[2] > lv[3] ? lv[2] : lv[3];                                             \
  w->sigma[i] = s01 > s23 ? s01 : s23;                                                                                               \
  if (fluid) {                                                                                                                       \
    FL##_store(lv, ax);                                                                                                              \
    p->ax[i] = ((lv[0] + lv[1]) + (lv[2] + lv[3])) + fp->gx;                                                                         \
    FL##_store(lv, ay);                                                                                                              \
    p->ay[i] = ((lv[0] + lv[1]) + (lv[2] + lv[3])) + fp->gy;                                                                         \
    if (F & F_XSPH) {                                                                                                                \
      FL##_store(lv, xs);                                                                                                            \
      p->xsx[i] = fp->xsph * ((lv[0] + lv[1]) + (lv[2] + lv[3]));                                                                    \
      FL##_store(lv, ys);                                                                                                            \
      p->xsy[i] = fp->xsph * ((lv[0] + lv[1]) + (lv[2] + lv[3]));                                                                    \
    }                                                                                                                                \
  } else {                                                                                                                           \
    p->ax[i] = p->ay[i] = 0.0;                                                                                                       \
  }                                                                                                                                  \
}

DEFINE_INTERACT_LANES(v4e, static inline __attribute__((always_inline)))
#ifdef SPH_LANES_AVX
DEFINE_INTERACT_LANES(v4x, AVX2)
#endif

/* One function per combination of terms, F a literal in its parallel
 * region (see STRAIN_VARIANT). */
#define VARIANT_FL(k, FL, NAME, ATTR)                                                         \
  ATTR void NAME##_##k(sph_particles *p, const sph_nlist *l, const sph_force_params *fp,       \
                       sph_force_work *w) {                                                   \
    const long n = (long)p->n;                                                               \
    double mx = 0.0; /* max of cs + sigma: exact in any order */                             \
    _Pragma("omp parallel if (n > SPH_OMP_MIN) reduction(max : mx)") {                       \
      size_t lo, hi; /* slices of equal cost, with stealing (parallel.h) */                  \
      while (sph_steal_next(&w->steal, SPH_STEAL_GRAIN, &lo, &hi))                           \
        for (size_t i = lo; i < hi; i++) {                                                   \
          if ((k) & (F_VARH | F_LEDGER))                                                     \
            interact_one(p, l, fp, w, i, k);                                                 \
          else                                                                               \
            interact_##FL(p, l, fp, w, i, k);                                                \
          const double c = w->cs[i] + w->sigma[i];                                           \
          if (c > mx) mx = c;                                                                \
        }                                                                                    \
    }                                                                                        \
    sph_steal_learn(&w->steal);                                                              \
    w->cs_sigma_max = mx;                                                                    \
  }
#ifdef SPH_LANES_AVX
#define VARIANT(k)                                                                           \
  VARIANT_FL(k, v4e, interact_all, static)                                                   \
  VARIANT_FL(k, v4x, interact_avx, static __attribute__((target("avx2"))))
#else
#define VARIANT(k) VARIANT_FL(k, v4e, interact_all, static)
#endif
#define VARIANTS8(a, b, c, d, e, f, g, h)                                                    \
  VARIANT(a) VARIANT(b) VARIANT(c) VARIANT(d) VARIANT(e) VARIANT(f) VARIANT(g) VARIANT(h)
VARIANTS8(0, 1, 2, 3, 4, 5, 6, 7)
VARIANTS8(8, 9, 10, 11, 12, 13, 14, 15)
VARIANTS8(16, 17, 18, 19, 20, 21, 22, 23)
VARIANTS8(24, 25, 26, 27, 28, 29, 30, 31)
VARIANTS8(32, 33, 34, 35, 36, 37, 38, 39)
VARIANTS8(40, 41, 42, 43, 44, 45, 46, 47)
VARIANTS8(48, 49, 50, 51, 52, 53, 54, 55)
VARIANTS8(56, 57, 58, 59, 60, 61, 62, 63)
VARIANTS8(64, 65, 66, 67, 68, 69, 70, 71)
VARIANTS8(72, 73, 74, 75, 76, 77, 78, 79)
VARIANTS8(80, 81, 82, 83, 84, 85, 86, 87)
VARIANTS8(88, 89, 90, 91, 92, 93, 94, 95)
VARIANTS8(96, 97, 98, 99, 100, 101, 102, 103)
VARIANTS8(104, 105, 106, 107, 108, 109, 110, 111)
VARIANTS8(112, 113, 114, 115, 116, 117, 118, 119)
VARIANTS8(120, 121, 122, 123, 124, 125, 126, 127)

typedef void (*interact_fn)(sph_particles *, const sph_nlist *, const sph_force_params *,
                            sph_force_work *);
/* The 128 variants of one flavour (prefix P) in the order of F. */
#define FN8(P, a, b, c, d, e, f, g, h) P##a, P##b, P##c, P##d, P##e, P##f, P##g, P##h
#define VARIANTS128(P)                                                                       \
  {                                                                                          \
    FN8(P, 0, 1, 2, 3, 4, 5, 6, 7), FN8(P, 8, 9, 10, 11, 12, 13, 14, 15),                    \
        FN8(P, 16, 17, 18, 19, 20, 21, 22, 23), FN8(P, 24, 25, 26, 27, 28, 29, 30, 31),      \
        FN8(P, 32, 33, 34, 35, 36, 37, 38, 39), FN8(P, 40, 41, 42, 43, 44, 45, 46, 47),      \
        FN8(P, 48, 49, 50, 51, 52, 53, 54, 55), FN8(P, 56, 57, 58, 59, 60, 61, 62, 63),      \
        FN8(P, 64, 65, 66, 67, 68, 69, 70, 71), FN8(P, 72, 73, 74, 75, 76, 77, 78, 79),      \
        FN8(P, 80, 81, 82, 83, 84, 85, 86, 87), FN8(P, 88, 89, 90, 91, 92, 93, 94, 95),      \
        FN8(P, 96, 97, 98, 99, 100, 101, 102, 103),                                          \
        FN8(P, 104, 105, 106, 107, 108, 109, 110, 111),                                      \
        FN8(P, 112, 113, 114, 115, 116, 117, 118, 119),                                      \
        FN8(P, 120, 121, 122, 123, 124, 125, 126, 127)                                       \
  }
static const interact_fn VARIANT_TABLE[128] = VARIANTS128(interact_all_);
#ifdef SPH_LANES_AVX
static const interact_fn VARIANT_TABLE_AVX[128] = VARIANTS128(interact_avx_);
#endif

/* ---- repulsive walls (paper A eq. 21-22) ------------------------------------------- */

static void lennard_jones(sph_particles *p, const sph_nlist *l, const sph_force_params *fp) {
  const long n = (long)p->n;
  const double r0 = fp->lj_r0, d = fp->lj_d;
  const double period = fp->periodic ? fp->period : 0.0;
#pragma omp parallel for schedule(dynamic, 256) if (n > SPH_OMP_MIN)
  for (long li = 0; li < n; li++) {
    const size_t i = (size_t)li;
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    ROW(l, i, nb, cnt)
    double ax = 0.0, ay = 0.0;
    for (size_t k = 0; k < cnt; k++) {
      const size_t j = nb[k];
      if (!(p->flags[j] & SPH_FLAG_REPULSIVE)) continue;
      const double dx = sph_grid_min_image(p->x[i] - p->x[j], period);
      const double dy = p->y[i] - p->y[j];
      const double r2 = dx * dx + dy * dy;
      if (r2 >= r0 * r0 || r2 == 0.0) continue;
      const double q2 = r0 * r0 / r2, q4 = q2 * q2, q12 = q4 * q4 * q4;
      const double f = d * (q12 - q4) / r2;
      ax += f * dx;
      ay += f * dy;
    }
    p->ax[i] += ax;
    p->ay[i] += ay;
  }
}

#ifdef SPH_LANES_AVX
/* The AVX flavour of the lane loop when the processor has AVX2, unless
 * SPH_LANES=portable asks for the other (the results are the same: tests
 * compare them). */
static int use_avx(void) {
  static int value = -1;
  int v = value;
  if (v < 0) {
    const char *e = getenv("SPH_LANES");
    __builtin_cpu_init();
    v = !(e && strcmp(e, "portable") == 0) && __builtin_cpu_supports("avx2");
    value = v; /* the same value whichever thread stores it */
  }
  return v;
}
#endif

int sph_forces_evaluate(sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                        sph_force_work *w, sph_error *err) {
  const long n = (long)p->n;
  if (work_reserve(w, p->n, err)) return -1;
#pragma omp parallel if (n > SPH_OMP_MIN)
  {
    size_t lo, hi; /* the slices of the interaction loop below */
    sph_slice(l->cost, p->n, &lo, &hi);
    for (size_t i = lo; i < hi; i++) {
      const double rho = p->rho[i], cs = sph_eos_sound_speed(&fp->eos, rho);
      w->cs[i] = cs;
      w->hot[i] = (sph_force_hot){p->x[i], p->y[i], p->vx[i], p->vy[i], rho,
                                  p->p[i] / (rho * rho), cs, p->mass[i]};
    }
  }
  {
    const size_t stride = (size_t)l->maxcount + 4, need = stride * (size_t)sph_max_threads();
    if (need > w->rows_cap) {
      uint32_t *a = realloc(w->rows, need * sizeof *a);
      if (!a) return sph_error_set(err, "forces: out of memory for neighbour rows");
      w->rows = a;
      w->rows_cap = need;
    }
    w->rows_stride = stride;
  }
  /* the interaction loop's slices: the list's, with stealing */
  if (sph_steal_reset(&w->steal, l->cost, p->n, sph_team_size(p->n)))
    return sph_error_set(err, "forces: out of memory for the thread slices");
  unsigned F = 0;
  if (fp->alpha != 0.0 || fp->beta != 0.0) F |= F_AV;
  if (fp->xsph != 0.0) F |= F_XSPH;
  if (fp->viscosity == SPH_VISCOSITY_STRESS_TENSOR || fp->sps) F |= F_STRESS;
  if (fp->viscosity == SPH_VISCOSITY_MORRIS) F |= F_MORRIS;
  if (fp->periodic) F |= F_PERIODIC;
  if (fp->var_h) F |= F_VARH;
  if (fp->ledger) F |= F_LEDGER;
  if (F & F_STRESS) {
    strain_opts o;
    if (strain_setup(p, fp, w, &o, err)) return -1;
    strain_list(p, l, fp, w->sxx, w->sxy, w->syy, &o);
#pragma omp parallel for schedule(static) if (n > SPH_OMP_MIN)
    for (long i = 0; i < n; i++) { /* tau / rho^2: laminar mu eps, plus the SPS stress */
      const double rho = p->rho[i];
      const double exx = w->sxx[i], exy = w->sxy[i], eyy = w->syy[i];
      const double lam = fp->viscosity == SPH_VISCOSITY_STRESS_TENSOR ? fp->mu / (rho * rho) : 0.0;
      double txx = lam * exx, txy = lam * exy, tyy = lam * eyy;
      if (fp->sps) {
        /* S from eps (eps_xx = 2 S_xx - (2/3) div, div = S_xx + S_yy) */
        double a, b, c;
        sph_sps_stress(0.5 * (2.0 * exx + eyy), 0.5 * exy, 0.5 * (2.0 * eyy + exx), fp->sps_cs,
                       fp->sps_ci, fp->sps_delta, &a, &b, &c);
        txx += a / rho;
        txy += b / rho;
        tyy += c / rho;
      }
      if (o.lxx) { /* sym(tau L): the divergence with the corrected gradient */
        const double axx = w->lxx[i], axy = w->lxy[i], ayy = w->lyy[i];
        const double bxx = txx * axx + txy * axy, byy = txy * axy + tyy * ayy;
        const double bxy = 0.5 * ((txx * axy + txy * ayy) + (txy * axx + tyy * axy));
        txx = bxx;
        txy = bxy;
        tyy = byy;
      }
      w->sxx[i] = txx;
      w->sxy[i] = txy;
      w->syy[i] = tyy;
    }
  }
#ifdef SPH_LANES_AVX
  if (use_avx())
    VARIANT_TABLE_AVX[F](p, l, fp, w);
  else
#endif
    VARIANT_TABLE[F](p, l, fp, w);
  if (fp->repulsive) lennard_jones(p, l, fp);
  return 0;
}
