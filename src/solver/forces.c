/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * forces.c - the interaction passes (see forces.h for the equations): the
 * per-pass set-up, the strain-rate pass, the main pass's variants and
 * its dispatch (the Lennard-Jones wall force is src/walls/repulsion.c).
 *
 * The physics of a pair is written once, in src/physics/pair_terms.h; the
 * loops that sum it over a neighbour row are in src/solver/interact.h (the
 * scalar loop and the four-lane loop). Here each loop is instantiated for
 * every combination of terms F (DESIGN rule 4: a case pays only for what
 * it switches on), F a literal inside its parallel region. Particles are
 * processed in parallel, each writing only its own rates, so results are
 * bitwise independent of the thread count, the schedule and the age of
 * the list.
 *
 * What makes a pass fast (bench/results/martin_moyce.md, features.md):
 *   - the neighbour list: a row holds the particles within the support
 *     plus a skin, so the loop no longer tests the ~3x more candidates of
 *     the 3x3 cells, and the list outlives many passes (sim.c);
 *   - the fields a neighbour reads are packed in one 64-byte record per
 *     particle (sph_force_hot), refreshed at every pass;
 *   - every variant but per-particle h and mirror particles runs the
 *     lane loop (interact_lanes.h), AVX-512 or AVX2
 *     where the processor has it, the energy ledger included; so does the
 *     strain-rate pass of the viscous stress (strain_lanes.h);
 *   - the step rule's max of c + sigma is reduced inside the pass.
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
#include "core/check.h"
#include "physics/kernel.h"
#include "physics/pair_terms.h"
#include "physics/turbulence.h"
#include "solver/diffusion.h"
#include "solver/interact.h"
#include "walls/repulsion.h"

/* Rows per stolen chunk of the interaction loop: a few microseconds of
 * work, so a thread waits at most that long at the end of a pass. */
#define SPH_STEAL_GRAIN 32

void sph_force_work_free(sph_force_work *w) {
  free(w->block);
  free(w->rows);
  free(w->keep);
  sph_steal_free(&w->steal);
  sph_wall_velocity_work_free(&w->wv);
  *w = (sph_force_work){0};
}

/* Room for n particles: every per-particle array in one block (arrays.h),
 * the contents of the old one carried over. */
static int work_reserve(sph_force_work *w, size_t n, sph_error *err) {
  if (n <= w->cap) return 0;
  const size_t cap = n + n / 4 + 16;
  void **arrays[] = {(void **)&w->hot,  (void **)&w->prho2, (void **)&w->cs,  (void **)&w->sigma,
                     (void **)&w->sxx,  (void **)&w->sxy,   (void **)&w->syy, (void **)&w->wpow,
                     (void **)&w->wfx,  (void **)&w->wfy,   (void **)&w->lxx, (void **)&w->lxy,
                     (void **)&w->lyy,  (void **)&w->gvx,   (void **)&w->gvy, (void **)&w->ddcx,
                     (void **)&w->ddcy, (void **)&w->dd,    (void **)&w->lj,  (void **)&w->ddm,
                     (void **)&w->fm,   (void **)&w->keepn};
  enum { N_ARRAYS = sizeof arrays / sizeof arrays[0] };
  size_t size[N_ARRAYS];
  size[0] = sizeof *w->hot;
  for (size_t k = 1; k < N_ARRAYS - 1; k++)
    size[k] = sizeof(double);
  size[N_ARRAYS - 1] = sizeof *w->keepn;
  if (sph_arrays_regrow(&w->block, cap, w->cap, N_ARRAYS, size, arrays, NULL))
    return sph_error_set(err, "forces: out of memory for %zu particles", n);
  w->cap = cap;
  return 0;
}

void sph_forces_pressure(sph_particles *p, const sph_eos *eos) {
  const long n = (long)p->n;
#pragma omp parallel for schedule(static) if (n > SPH_OMP_MIN)
  for (long i = 0; i < n; i++)
    p->p[i] = sph_eos_pressure(eos, p->rho[i]);
}

/* The neighbour row of i in the list l: j = nb[0], ..., nb[cnt - 1]. */
/* ---- the strain-rate pass (paper A eq. 13-14) ------------------------------------ */

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
    sph_kernel_w_dw(fp->kernel, r, hij, &wij, &dw);
    const double f = dw / r * (m[j] / rho[j]);
    const double gx = f * dx, gy = f * dy;           /* V_j grad_i W_ij */
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
  const double sums[4] = {sxx, sxy, syy, div}, gm[7] = {gxx, gxy, gyx, gyy, mxx, mxy, myy};
  strain_finish(o, i, sums, gm, exx, exy, eyy);
}

/* One function per variant, with F a literal inside the parallel region
 * (OpenMP outlines the region before inlining, so a constant must be
 * spelled out there to reach the loop). */
#define STRAIN_VARIANT(k)                                                                          \
  static void strain_all_##k(const sph_particles *p, const sph_nlist *l,                           \
                             const sph_force_params *fp, double *exx, double *exy, double *eyy,    \
                             const strain_opts *o) {                                               \
    const long n = (long)p->n;                                                                     \
    _Pragma("omp parallel for schedule(dynamic, 256) if (n > SPH_OMP_MIN)") for (long i = 0;       \
                                                                                 i < n; i++)       \
        strain_one(p, l, fp, (size_t)i, exx, exy, eyy, o, k);                                      \
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

/* The strain-rate pass in a lane flavour, F a literal (0 or F_PERIODIC):
 * each row cut into the kept rows (w->keep, keep_rows), which the main pass
 * of the same evaluation then reads instead of cutting its rows again. */
typedef void (*strain_fn)(const sph_particles *, const sph_nlist *, const sph_force_params *,
                          sph_force_work *, double *, double *, double *, const strain_opts *);
#define STRAIN_LANES(k, FL, ATTR)                                                                  \
  ATTR void strain_##FL##_##k(const sph_particles *p, const sph_nlist *l,                          \
                              const sph_force_params *fp, sph_force_work *w, double *exx,          \
                              double *exy, double *eyy, const strain_opts *o) {                    \
    const long n = (long)p->n;                                                                     \
    _Pragma("omp parallel for schedule(dynamic, 256) if (n > SPH_OMP_MIN)") for (long i = 0;       \
                                                                                 i < n; i++)       \
        strain_##FL(w->hot, l, fp, w->keep + l->start[i] + SPH_KEEP_PAD * (size_t)i, w->keepn + i, \
                    (size_t)i, o, exx, exy, eyy, k);                                               \
    w->keep_valid = 1;                                                                             \
  }
STRAIN_LANES(0, v4e, static)
STRAIN_LANES(16, v4e, static)
#ifdef SPH_LANES_AVX
STRAIN_LANES(0, v4x, static __attribute__((target("avx2"))))
STRAIN_LANES(16, v4x, static __attribute__((target("avx2"))))
#endif
#ifdef SPH_LANES_AVX512
STRAIN_LANES(0, v8z, static __attribute__((target("avx512f"))))
STRAIN_LANES(16, v8z, static __attribute__((target("avx512f"))))
#endif

/* The kernel's reach: 2 h, or 2 max h with per-particle h. */
static double kernel_reach(const sph_particles *p, const sph_force_params *fp) {
  double hmax = fp->h;
  if (fp->var_h)
    for (size_t i = 0; i < p->n; i++)
      if (p->h[i] > hmax) hmax = p->h[i];
  return SPH_CUBIC_SUPPORT * hmax;
}

/* The velocities the strain-rate pass reads, no-slip walls extrapolated. */
static int wall_ghosts(const sph_particles *p, const sph_force_params *fp, double *gvx, double *gvy,
                       sph_wall_velocity_work *wv, sph_error *err) {
  return sph_wall_velocity(p, kernel_reach(p, fp), fp->px0, fp->periodic ? fp->period : 0.0, gvx,
                           gvy, wv, err);
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
  if (fp->mirror) { /* mirror particles: their no-slip velocity (boundary.h) */
    if (!fp->no_slip)
      for (size_t i = 0; i < p->n; i++) {
        w->gvx[i] = p->vx[i];
        w->gvy[i] = p->vy[i];
      }
    for (size_t i = 0; i < p->n; i++)
      if (p->kind[i] == SPH_KIND_MIRROR) {
        w->gvx[i] = p->vxh[i];
        w->gvy[i] = p->vyh[i];
      }
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
  int rc =
      sph_nlist_build(&l, g, p, kernel_reach(p, fp), 0.0, fp->periodic ? fp->period : 0.0, err);
  if (rc == 0) rc = work_reserve(&w, p->n, err);
  if (rc == 0) rc = strain_setup(p, fp, &w, &o, err);
  if (rc == 0) strain_list(p, &l, fp, exx, exy, eyy, &o);
  sph_force_work_free(&w);
  sph_nlist_free(&l);
  return rc;
}

/* One particle of the main pass in a flavour. */
#define PARTICLE_v1(p, l, fp, w, i, k) interact_one(p, l, fp, w, i, k)
#define PARTICLE_v4e(p, l, fp, w, i, k) interact_v4e(p, l, fp, w, i, k)
#define PARTICLE_v4x(p, l, fp, w, i, k) interact_v4x(p, l, fp, w, i, k)
#define PARTICLE_v8z(p, l, fp, w, i, k) interact_v8z(p, l, fp, w, i, k)

/* One function per combination of terms and flavour, F a literal in its
 * parallel region (see STRAIN_VARIANT). */
#define VARIANT_FL(k, FL, NAME, ATTR)                                                              \
  ATTR void NAME##_##k(sph_particles *p, const sph_nlist *l, const sph_force_params *fp,           \
                       sph_force_work *w) {                                                        \
    const long n = (long)p->n;                                                                     \
    double mx = 0.0; /* max of cs + sigma: exact in any order */                                   \
    _Pragma("omp parallel if (n > SPH_OMP_MIN) reduction(max : mx)") {                             \
      size_t lo, hi; /* slices of equal cost, with stealing (parallel.h) */                        \
      while (sph_steal_next(&w->steal, SPH_STEAL_GRAIN, &lo, &hi))                                 \
        for (size_t i = lo; i < hi; i++) {                                                         \
          PARTICLE_##FL(p, l, fp, w, i, k);                                                        \
          const double c = w->cs[i] + w->sigma[i];                                                 \
          if (c > mx) mx = c;                                                                      \
        }                                                                                          \
    }                                                                                              \
    sph_steal_learn(&w->steal);                                                                    \
    w->cs_sigma_max = mx;                                                                          \
  }

/* The scalar loop for all 256 term sets; the lane loops only for the 128
 * sets without F_SCALAR_ONLY (per-particle h: F = 0..31, 64..95, 128..159,
 * 192..223), the others fall back to the scalar loop (pick_variant). */
#define VARIANT_S(k) VARIANT_FL(k, v1, interact_scalar, static)
#if defined(SPH_LANES_AVX512)
#define VARIANT_L(k)                                                                               \
  VARIANT_FL(k, v4e, interact_all, static)                                                         \
  VARIANT_FL(k, v4x, interact_avx, static __attribute__((target("avx2"))))                         \
  VARIANT_FL(k, v8z, interact_avx512, static __attribute__((target("avx512f"))))
#elif defined(SPH_LANES_AVX)
#define VARIANT_L(k)                                                                               \
  VARIANT_FL(k, v4e, interact_all, static)                                                         \
  VARIANT_FL(k, v4x, interact_avx, static __attribute__((target("avx2"))))
#else
#define VARIANT_L(k) VARIANT_FL(k, v4e, interact_all, static)
#endif
#define VARIANTS8(V, a, b, c, d, e, f, g, h) V(a) V(b) V(c) V(d) V(e) V(f) V(g) V(h)
VARIANTS8(VARIANT_S, 0, 1, 2, 3, 4, 5, 6, 7)
VARIANTS8(VARIANT_S, 8, 9, 10, 11, 12, 13, 14, 15)
VARIANTS8(VARIANT_S, 16, 17, 18, 19, 20, 21, 22, 23)
VARIANTS8(VARIANT_S, 24, 25, 26, 27, 28, 29, 30, 31)
VARIANTS8(VARIANT_S, 32, 33, 34, 35, 36, 37, 38, 39)
VARIANTS8(VARIANT_S, 40, 41, 42, 43, 44, 45, 46, 47)
VARIANTS8(VARIANT_S, 48, 49, 50, 51, 52, 53, 54, 55)
VARIANTS8(VARIANT_S, 56, 57, 58, 59, 60, 61, 62, 63)
VARIANTS8(VARIANT_S, 64, 65, 66, 67, 68, 69, 70, 71)
VARIANTS8(VARIANT_S, 72, 73, 74, 75, 76, 77, 78, 79)
VARIANTS8(VARIANT_S, 80, 81, 82, 83, 84, 85, 86, 87)
VARIANTS8(VARIANT_S, 88, 89, 90, 91, 92, 93, 94, 95)
VARIANTS8(VARIANT_S, 96, 97, 98, 99, 100, 101, 102, 103)
VARIANTS8(VARIANT_S, 104, 105, 106, 107, 108, 109, 110, 111)
VARIANTS8(VARIANT_S, 112, 113, 114, 115, 116, 117, 118, 119)
VARIANTS8(VARIANT_S, 120, 121, 122, 123, 124, 125, 126, 127)
VARIANTS8(VARIANT_S, 128, 129, 130, 131, 132, 133, 134, 135)
VARIANTS8(VARIANT_S, 136, 137, 138, 139, 140, 141, 142, 143)
VARIANTS8(VARIANT_S, 144, 145, 146, 147, 148, 149, 150, 151)
VARIANTS8(VARIANT_S, 152, 153, 154, 155, 156, 157, 158, 159)
VARIANTS8(VARIANT_S, 160, 161, 162, 163, 164, 165, 166, 167)
VARIANTS8(VARIANT_S, 168, 169, 170, 171, 172, 173, 174, 175)
VARIANTS8(VARIANT_S, 176, 177, 178, 179, 180, 181, 182, 183)
VARIANTS8(VARIANT_S, 184, 185, 186, 187, 188, 189, 190, 191)
VARIANTS8(VARIANT_S, 192, 193, 194, 195, 196, 197, 198, 199)
VARIANTS8(VARIANT_S, 200, 201, 202, 203, 204, 205, 206, 207)
VARIANTS8(VARIANT_S, 208, 209, 210, 211, 212, 213, 214, 215)
VARIANTS8(VARIANT_S, 216, 217, 218, 219, 220, 221, 222, 223)
VARIANTS8(VARIANT_S, 224, 225, 226, 227, 228, 229, 230, 231)
VARIANTS8(VARIANT_S, 232, 233, 234, 235, 236, 237, 238, 239)
VARIANTS8(VARIANT_S, 240, 241, 242, 243, 244, 245, 246, 247)
VARIANTS8(VARIANT_S, 248, 249, 250, 251, 252, 253, 254, 255)
VARIANTS8(VARIANT_L, 0, 1, 2, 3, 4, 5, 6, 7)
VARIANTS8(VARIANT_L, 8, 9, 10, 11, 12, 13, 14, 15)
VARIANTS8(VARIANT_L, 16, 17, 18, 19, 20, 21, 22, 23)
VARIANTS8(VARIANT_L, 24, 25, 26, 27, 28, 29, 30, 31)
VARIANTS8(VARIANT_L, 64, 65, 66, 67, 68, 69, 70, 71)
VARIANTS8(VARIANT_L, 72, 73, 74, 75, 76, 77, 78, 79)
VARIANTS8(VARIANT_L, 80, 81, 82, 83, 84, 85, 86, 87)
VARIANTS8(VARIANT_L, 88, 89, 90, 91, 92, 93, 94, 95)
VARIANTS8(VARIANT_L, 128, 129, 130, 131, 132, 133, 134, 135)
VARIANTS8(VARIANT_L, 136, 137, 138, 139, 140, 141, 142, 143)
VARIANTS8(VARIANT_L, 144, 145, 146, 147, 148, 149, 150, 151)
VARIANTS8(VARIANT_L, 152, 153, 154, 155, 156, 157, 158, 159)
VARIANTS8(VARIANT_L, 192, 193, 194, 195, 196, 197, 198, 199)
VARIANTS8(VARIANT_L, 200, 201, 202, 203, 204, 205, 206, 207)
VARIANTS8(VARIANT_L, 208, 209, 210, 211, 212, 213, 214, 215)
VARIANTS8(VARIANT_L, 216, 217, 218, 219, 220, 221, 222, 223)

typedef void (*interact_fn)(sph_particles *, const sph_nlist *, const sph_force_params *,
                            sph_force_work *);
/* The variants of one flavour (prefix P) for the term sets a, ..., h. */
#define FN8(P, a, b, c, d, e, f, g, h) P##a, P##b, P##c, P##d, P##e, P##f, P##g, P##h
/* The scalar loop's 256 variants in the order of F. */
static const interact_fn VARIANT_TABLE_SCALAR[256] = {
    FN8(interact_scalar_, 0, 1, 2, 3, 4, 5, 6, 7),
    FN8(interact_scalar_, 8, 9, 10, 11, 12, 13, 14, 15),
    FN8(interact_scalar_, 16, 17, 18, 19, 20, 21, 22, 23),
    FN8(interact_scalar_, 24, 25, 26, 27, 28, 29, 30, 31),
    FN8(interact_scalar_, 32, 33, 34, 35, 36, 37, 38, 39),
    FN8(interact_scalar_, 40, 41, 42, 43, 44, 45, 46, 47),
    FN8(interact_scalar_, 48, 49, 50, 51, 52, 53, 54, 55),
    FN8(interact_scalar_, 56, 57, 58, 59, 60, 61, 62, 63),
    FN8(interact_scalar_, 64, 65, 66, 67, 68, 69, 70, 71),
    FN8(interact_scalar_, 72, 73, 74, 75, 76, 77, 78, 79),
    FN8(interact_scalar_, 80, 81, 82, 83, 84, 85, 86, 87),
    FN8(interact_scalar_, 88, 89, 90, 91, 92, 93, 94, 95),
    FN8(interact_scalar_, 96, 97, 98, 99, 100, 101, 102, 103),
    FN8(interact_scalar_, 104, 105, 106, 107, 108, 109, 110, 111),
    FN8(interact_scalar_, 112, 113, 114, 115, 116, 117, 118, 119),
    FN8(interact_scalar_, 120, 121, 122, 123, 124, 125, 126, 127),
    FN8(interact_scalar_, 128, 129, 130, 131, 132, 133, 134, 135),
    FN8(interact_scalar_, 136, 137, 138, 139, 140, 141, 142, 143),
    FN8(interact_scalar_, 144, 145, 146, 147, 148, 149, 150, 151),
    FN8(interact_scalar_, 152, 153, 154, 155, 156, 157, 158, 159),
    FN8(interact_scalar_, 160, 161, 162, 163, 164, 165, 166, 167),
    FN8(interact_scalar_, 168, 169, 170, 171, 172, 173, 174, 175),
    FN8(interact_scalar_, 176, 177, 178, 179, 180, 181, 182, 183),
    FN8(interact_scalar_, 184, 185, 186, 187, 188, 189, 190, 191),
    FN8(interact_scalar_, 192, 193, 194, 195, 196, 197, 198, 199),
    FN8(interact_scalar_, 200, 201, 202, 203, 204, 205, 206, 207),
    FN8(interact_scalar_, 208, 209, 210, 211, 212, 213, 214, 215),
    FN8(interact_scalar_, 216, 217, 218, 219, 220, 221, 222, 223),
    FN8(interact_scalar_, 224, 225, 226, 227, 228, 229, 230, 231),
    FN8(interact_scalar_, 232, 233, 234, 235, 236, 237, 238, 239),
    FN8(interact_scalar_, 240, 241, 242, 243, 244, 245, 246, 247),
    FN8(interact_scalar_, 248, 249, 250, 251, 252, 253, 254, 255),
};
/* A lane loop's 128 variants, in the order of lane_index(F). */
#define LANE_TABLE(P)                                                                              \
  {                                                                                                \
    FN8(P, 0, 1, 2, 3, 4, 5, 6, 7), FN8(P, 8, 9, 10, 11, 12, 13, 14, 15),                          \
        FN8(P, 16, 17, 18, 19, 20, 21, 22, 23), FN8(P, 24, 25, 26, 27, 28, 29, 30, 31),            \
        FN8(P, 64, 65, 66, 67, 68, 69, 70, 71), FN8(P, 72, 73, 74, 75, 76, 77, 78, 79),            \
        FN8(P, 80, 81, 82, 83, 84, 85, 86, 87), FN8(P, 88, 89, 90, 91, 92, 93, 94, 95),            \
        FN8(P, 128, 129, 130, 131, 132, 133, 134, 135),                                            \
        FN8(P, 136, 137, 138, 139, 140, 141, 142, 143),                                            \
        FN8(P, 144, 145, 146, 147, 148, 149, 150, 151),                                            \
        FN8(P, 152, 153, 154, 155, 156, 157, 158, 159),                                            \
        FN8(P, 192, 193, 194, 195, 196, 197, 198, 199),                                            \
        FN8(P, 200, 201, 202, 203, 204, 205, 206, 207),                                            \
        FN8(P, 208, 209, 210, 211, 212, 213, 214, 215),                                            \
        FN8(P, 216, 217, 218, 219, 220, 221, 222, 223),                                            \
  }
static const interact_fn VARIANT_TABLE[128] = LANE_TABLE(interact_all_);
#ifdef SPH_LANES_AVX
static const interact_fn VARIANT_TABLE_AVX[128] = LANE_TABLE(interact_avx_);
#endif
#ifdef SPH_LANES_AVX512
static const interact_fn VARIANT_TABLE_AVX512[128] = LANE_TABLE(interact_avx512_);
#endif

/* The place of a term set without F_SCALAR_ONLY in a lane table. */
static unsigned lane_index(unsigned F) {
  return (F & 31u) | ((F & F_LEDGER) ? 32u : 0u) | ((F & F_DDIFF) ? 64u : 0u);
}

int sph_force_loop_available(sph_force_loop loop) {
  switch (loop) {
  case SPH_LOOP_AUTO:
  case SPH_LOOP_SCALAR:
  case SPH_LOOP_LANES: return 1;
  case SPH_LOOP_LANES_AVX:
#ifdef SPH_LANES_AVX
    return sph_cpu_has_avx2();
#else
    return 0;
#endif
  case SPH_LOOP_LANES_AVX512:
#ifdef SPH_LANES_AVX512
    return sph_cpu_has_avx512();
#else
    return 0;
#endif
  }
  return 0;
}

/* The lane flavour of a lane loop that can run here (pick_variant checks);
 * AUTO is the widest the processor has. */
typedef enum { FLAVOUR_NONE, FLAVOUR_V4E, FLAVOUR_V4X, FLAVOUR_V8Z } lane_flavour;
static lane_flavour flavour_of(sph_force_loop loop) {
  switch (loop) {
  case SPH_LOOP_LANES: return FLAVOUR_V4E;
  case SPH_LOOP_LANES_AVX: return FLAVOUR_V4X;
  case SPH_LOOP_LANES_AVX512: return FLAVOUR_V8Z;
  case SPH_LOOP_AUTO:
#ifdef SPH_LANES_AVX512
    if (sph_cpu_has_avx512()) return FLAVOUR_V8Z;
#endif
#ifdef SPH_LANES_AVX
    if (sph_cpu_has_avx2()) return FLAVOUR_V4X;
#endif
    return FLAVOUR_V4E;
  default: return FLAVOUR_NONE;
  }
}

/* The lane table of a lane loop that can run here. */
static const interact_fn *lane_table(sph_force_loop loop) {
  switch (flavour_of(loop)) {
  case FLAVOUR_V4E: return VARIANT_TABLE;
#ifdef SPH_LANES_AVX
  case FLAVOUR_V4X: return VARIANT_TABLE_AVX;
#endif
#ifdef SPH_LANES_AVX512
  case FLAVOUR_V8Z: return VARIANT_TABLE_AVX512;
#endif
  default: return NULL;
  }
}

/* The variant of the main pass for the term set F in the loop asked for:
 * SPH_LOOP_AUTO is the widest lanes the processor has (AVX-512, AVX2, else
 * the portable lanes; all give the same bits); each lane loop falls back to
 * the scalar loop for per-particle h, and every loop for mirror particles
 * (`scalar`). NULL if that loop cannot run here. */
static interact_fn pick_variant(unsigned F, sph_force_loop loop, int scalar) {
  if (!sph_force_loop_available(loop)) return NULL;
  if (scalar || loop == SPH_LOOP_SCALAR || (F & F_SCALAR_ONLY)) return VARIANT_TABLE_SCALAR[F];
  const interact_fn *table = lane_table(loop);
  return table ? table[lane_index(F)] : NULL;
}

/* The strain-rate pass's lane loop for fp: the flavour of the main pass's
 * lane loop as fp->loop asks for it (also where the main pass runs the
 * scalar loop for mirror walls), NULL for the scalar loop
 * (asked for, or per-particle h). */
static strain_fn strain_lanes(const sph_force_params *fp) {
  if (fp->var_h || fp->loop == SPH_LOOP_SCALAR) return NULL;
  const int per = fp->periodic;
  switch (flavour_of(fp->loop)) {
  case FLAVOUR_V4E: return per ? strain_v4e_16 : strain_v4e_0;
#ifdef SPH_LANES_AVX
  case FLAVOUR_V4X: return per ? strain_v4x_16 : strain_v4x_0;
#endif
#ifdef SPH_LANES_AVX512
  case FLAVOUR_V8Z: return per ? strain_v8z_16 : strain_v8z_0;
#endif
  default: return NULL;
  }
}

/* Per pass: the packed state of every particle (w->hot, w->cs), a cut-row
 * buffer per thread, and the interaction loop's slices (the list's, with
 * stealing). */
static int prepare_pass(const sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                        sph_force_work *w, const unsigned F, sph_error *err) {
  const long n = (long)p->n;
  if (work_reserve(w, p->n, err)) return -1;
  const int fm = (F & (F_XSPH | F_LEDGER)) != 0; /* the lane loop reads the fluid masses */
#pragma omp parallel if (n > SPH_OMP_MIN)
  {
    size_t lo, hi; /* the slices of the interaction loop */
    sph_slice(l->cost, p->n, &lo, &hi);
    for (size_t i = lo; i < hi; i++) {
      const double rho = p->rho[i], cs = sph_eos_sound_speed(&fp->eos, rho);
      w->cs[i] = cs;
      w->hot[i] = (sph_force_hot){
          p->x[i], p->y[i], p->vx[i], p->vy[i], rho, p->p[i] / (rho * rho), cs, p->mass[i]};
      if (fm) w->fm[i] = p->kind[i] == SPH_KIND_FLUID ? p->mass[i] : 0.0;
    }
  }
  const size_t stride = (size_t)l->maxcount + 8, /* + padding lanes */
      need = stride * (size_t)sph_max_threads();
  if (need > w->rows_cap) {
    uint32_t *a = realloc(w->rows, need * sizeof *a);
    if (!a) return sph_error_set(err, "forces: out of memory for neighbour rows");
    w->rows = a;
    w->rows_cap = need;
  }
  w->rows_stride = stride;
  w->keep_valid = 0;
  if (sph_steal_reset(&w->steal, l->cost, p->n, sph_team_size(p->n)))
    return sph_error_set(err, "forces: out of memory for the thread slices");
  return 0;
}

/* Room for every particle's cut row, padded (w->keep; their lengths go to
 * w->keepn, a per-particle array of work_reserve): as much as the list
 * holds plus SPH_KEEP_PAD entries per particle. */
static int keep_rows(const sph_particles *p, const sph_nlist *l, sph_force_work *w,
                     sph_error *err) {
  const size_t need = l->start[p->n] + SPH_KEEP_PAD * p->n;
  if (need <= w->keep_cap) return 0;
  const size_t cap = need + need / 4;
  uint32_t *a = realloc(w->keep, cap * sizeof *a);
  if (!a) return sph_error_set(err, "forces: out of memory for the kept neighbour rows");
  w->keep = a;
  w->keep_cap = cap;
  return 0;
}

/* The strain-rate pass and tau / rho^2 at every particle (w->sxx, sxy,
 * syy): the laminar mu eps of paper A eq. (13)-(14) plus the SPS stress of
 * paper B eq. (4), with the kernel-gradient correction when asked for. */
static int stress_pass(const sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                       sph_force_work *w, sph_error *err) {
  const long n = (long)p->n;
  strain_opts o;
  if (strain_setup(p, fp, w, &o, err)) return -1;
  const strain_fn lanes = strain_lanes(fp);
  if (lanes && keep_rows(p, l, w, err)) return -1;
  if (lanes)
    lanes(p, l, fp, w, w->sxx, w->sxy, w->syy, &o);
  else
    strain_list(p, l, fp, w->sxx, w->sxy, w->syy, &o);
#pragma omp parallel for schedule(static) if (n > SPH_OMP_MIN)
  for (long i = 0; i < n; i++) {
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
  return 0;
}

/* Debug invariant: every rate of the pass is finite (a NaN here is a bug in
 * a term or a loop, not a blow-up: the state it read was checked). */
static void check_rates(const sph_particles *p, const sph_force_work *w, unsigned F) {
  for (size_t i = 0; i < p->n; i++) {
    int ok =
        isfinite(p->drho[i]) && isfinite(p->ax[i]) && isfinite(p->ay[i]) && isfinite(w->sigma[i]);
    if ((F & F_XSPH) && p->kind[i] == SPH_KIND_FLUID)
      ok &= isfinite(p->xsx[i]) && isfinite(p->xsy[i]);
    if (F & F_LEDGER) ok &= isfinite(p->du[i]) && isfinite(w->wpow[i]);
    SPH_INVARIANT(ok, "particle %zu (id %lld) has a rate that is not finite after a pass", i,
                  (long long)p->id[i]);
  }
}

int sph_forces_evaluate(sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                        sph_force_work *w, sph_error *err) {
  const unsigned F = sph_interact_terms(fp);
  const interact_fn run = pick_variant(F, fp->loop, fp->mirror);
  if (!run) return sph_error_set(err, "forces: the interaction loop asked for cannot run here");
  if (prepare_pass(p, l, fp, w, F, err)) return -1;
  if ((F & F_STRESS) && stress_pass(p, l, fp, w, err)) return -1;
  if (F & F_DDIFF) sph_diffusion_prepare(p, l, fp, w);
  run(p, l, fp, w);
  if (SPH_DEBUG) check_rates(p, w, F);
  if (fp->repulsive) {
    const sph_repulsion_ledger lg = {w->wfx, w->wfy, w->wpow, w->lj};
    sph_repulsion_add(p, l, fp->lj_d, fp->lj_r0, fp->periodic ? fp->period : 0.0,
                      (F & F_LEDGER) ? &lg : NULL);
  }
  return 0;
}
