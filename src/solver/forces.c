/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * forces.c - the interaction passes (see forces.h for the equations): the
 * per-pass set-up, the strain-rate pass and the main pass's dispatch (the
 * Lennard-Jones wall force is src/walls/repulsion.c).
 *
 * The physics of a pair is written once, in src/physics/pair_terms.h; the
 * loops that sum it over a neighbour row are in src/solver/interact.h (the
 * scalar loop and the lane loops). Each loop is instantiated, a translation
 * unit per flavour (loops.h: loops_scalar.c, loops_lanes.c, loops_avx2.c,
 * loops_avx512.c), for the term sets the shipped cases run, for the
 * combinations of the terms that weigh most, and once with every term read
 * at run time (interact.h, LANE_LOOPS: DESIGN rule 4, a shipped case pays
 * only for what it switches on), each its Fc a literal inside its parallel
 * region; here the pass picks one. Particles are
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
 *     lane loop (interact_row.h), AVX-512 or AVX2
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
#include "solver/loops.h"
#include "solver/surface_tension.h"
#include "walls/repulsion.h"

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
int sph_force_work_reserve(sph_force_work *w, size_t n, sph_error *err) {
  if (n <= w->cap) return 0;
  const size_t cap = n + n / 4 + 16;
  void **arrays[] = {
    (void **)&w->hot,
    (void **)&w->prho2,
    (void **)&w->sigma,
    (void **)&w->sxx,
    (void **)&w->sxy,
    (void **)&w->syy,
    (void **)&w->wpow,
    (void **)&w->wfx,
    (void **)&w->wfy,
    (void **)&w->lxx,
    (void **)&w->lxy,
    (void **)&w->lyy,
    (void **)&w->gvx,
    (void **)&w->gvy,
    (void **)&w->ddcx,
    (void **)&w->ddcy,
    (void **)&w->dd,
    (void **)&w->lj,
    (void **)&w->ddm,
#if SPH_DIM == 3 /* the third axis's and the tensors' other components */
    (void **)&w->sxz,
    (void **)&w->syz,
    (void **)&w->szz,
    (void **)&w->wfz,
    (void **)&w->lxz,
    (void **)&w->lyz,
    (void **)&w->lzz,
    (void **)&w->gvz,
    (void **)&w->ddcz,
    (void **)&w->sdiv,
#endif
    (void **)&w->fm,
    (void **)&w->keepn,
    (void **)&w->nwall
  };
  enum { N_ARRAYS = sizeof arrays / sizeof arrays[0] };
  size_t size[N_ARRAYS];
  size[0] = sizeof *w->hot;
  for (size_t k = 1; k < N_ARRAYS - 2; k++)
    size[k] = sizeof(double);
  size[N_ARRAYS - 2] = sizeof *w->keepn;
  size[N_ARRAYS - 1] = sizeof *w->nwall;
  if (sph_arrays_regrow(&w->block, cap, w->cap, N_ARRAYS, size, arrays, NULL))
    return sph_error_set(err, "forces: out of memory for %zu particles", n);
  w->cap = cap;
  return 0;
}

void sph_forces_pressure(sph_particles *p, const sph_eos *eos) {
  const long n = (long)p->n;
  const uint8_t *ph = sph_particles_phases(p);
#pragma omp parallel for schedule(static) if (n > SPH_OMP_MIN)
  for (long i = 0; i < n; i++)
    p->p[i] = sph_eos_pressure(sph_eos_of(eos, ph, (size_t)i), p->rho[i]);
}

/* The neighbour row of i in the list l: j = nb[0], ..., nb[cnt - 1]. */
/* ---- the strain-rate pass (paper A eq. 13-14) ------------------------------------ */

static inline __attribute__((always_inline)) void
strain_one(const sph_particles *restrict p, const sph_nlist *restrict l,
           const sph_force_params *restrict fp, size_t i, double *const *eps, const strain_opts *o,
           const unsigned F) {
  const double *restrict x = p->x, *restrict y = p->y, *restrict h = p->h;
  const double *restrict vx = o->gv ? o->gv[0] : p->vx, *restrict vy = o->gv ? o->gv[1] : p->vy;
  const double *restrict m = p->mass, *restrict rho = p->rho;
  const double period = period_along(fp, 0), half = 0.5 * period_along(fp, 0);
  const double xi = x[i], yi = y[i], vxi = vx[i], vyi = vy[i];
  double sxx = 0.0, sxy = 0.0, syy = 0.0, div = 0.0;
  /* with the correction: G_ab = sum_j V_j (v_j - v_i)_a (grad_i W_ij)_b and
   * M_ab = sum_j V_j (x_j - x_i)_a (grad_i W_ij)_b */
  double gxx = 0.0, gxy = 0.0, gyx = 0.0, gyy = 0.0, mxx = 0.0, mxy = 0.0, myy = 0.0;
  SPH_IF3(const double *restrict z = p->z, *restrict vz = o->gv ? o->gv[2] : p->vz;
          const double zi = z[i], vzi = vz[i]; double sxz = 0.0, syz = 0.0, szz = 0.0;
          double gxz = 0.0, gyz = 0.0, gzx = 0.0, gzy = 0.0, gzz = 0.0, mxz = 0.0, myz = 0.0;
          double mzz = 0.0;)
  const int correct = o->l != NULL;
  ROW(l, i, nb, cnt)
  for (size_t k = 0; k < cnt; k++) {
    const size_t j = nb[k];
    const double dx = sep_x(xi, x[j], period, half, F), dy = SEP(fp, 1, yi, y[j], F);
    SPH_IF3(const double dz = SEP(fp, 2, zi, z[j], F);)
    const double r2 = SPH_NORM2(dx, dy, dz);
    const double hij = (F & F_VARH) ? 0.5 * (h[i] + h[j]) : fp->h;
    if (r2 >= 4.0 * hij * hij || r2 == 0.0) continue;
    const double r = sqrt(r2);
    double wij, dw;
    sph_kernel_w_dw(fp->kernel, r, hij, &wij, &dw);
    const double f = dw / r * (m[j] / rho[j]);
    const double gx = f * dx, gy = f * dy;           /* V_j grad_i W_ij */
    const double ux = vx[j] - vxi, uy = vy[j] - vyi; /* v_ji */
    SPH_IF3(const double gz = f * dz, uz = vz[j] - vzi;)
    if (correct) {
      if (!o->moment_only) {
        gxx += ux * gx;
        gxy += ux * gy;
        gyx += uy * gx;
        gyy += uy * gy;
        SPH_IF3(gxz += ux * gz; gyz += uy * gz; gzx += uz * gx; gzy += uz * gy; gzz += uz * gz;)
      }
      mxx -= dx * gx;
      mxy -= dx * gy;
      myy -= dy * gy;
      SPH_IF3(mxz -= dx * gz; myz -= dy * gz; mzz -= dz * gz;)
    } else {
      sxx += 2.0 * ux * gx;
      syy += 2.0 * uy * gy;
      sxy += uy * gx + ux * gy;
#if SPH_DIM == 2
      div += ux * gx + uy * gy;
#else
      szz += 2.0 * uz * gz;
      sxz += uz * gx + ux * gz;
      syz += uz * gy + uy * gz;
      div += ux * gx + uy * gy + uz * gz;
#endif
    }
  }
#if SPH_DIM == 2
  const double sums[STRAIN_SUMS] = {sxx, sxy, syy, div};
  const double gm[STRAIN_GM] = {gxx, gxy, gyx, gyy, mxx, mxy, myy};
#else
  const double sums[STRAIN_SUMS] = {sxx, sxy, sxz, syy, syz, szz, div};
  const double gm[STRAIN_GM] = {gxx, gxy, gxz, gyx, gyy, gyz, gzx, gzy,
                                gzz, mxx, mxy, mxz, myy, myz, mzz};
#endif
  strain_finish(o, i, sums, gm, eps);
}

/* One function per variant, with F_VARH a literal inside the parallel
 * region (OpenMP outlines the region before inlining, so a constant must be
 * spelled out there to reach the loop); periodicity is a branch per pair. */
#define STRAIN_VARIANT(k)                                                                          \
  static void strain_all_##k(const sph_particles *p, const sph_nlist *l,                           \
                             const sph_force_params *fp, double *const *eps,                       \
                             const strain_opts *o) {                                               \
    const long n = (long)p->n;                                                                     \
    const unsigned F = (k) | (fp->periodic ? F_PERIODIC : 0u);                                     \
    _Pragma("omp parallel for schedule(dynamic, 256) if (n > SPH_OMP_MIN)") for (long i = 0;       \
                                                                                 i < n; i++)       \
        strain_one(p, l, fp, (size_t)i, eps, o, F);                                                \
  }
STRAIN_VARIANT(0)
STRAIN_VARIANT(32)

static void strain_list(const sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                        double *const *eps, const strain_opts *o) {
  if (fp->var_h)
    strain_all_32(p, l, fp, eps, o);
  else
    strain_all_0(p, l, fp, eps, o);
}

/* The strain-rate pass in a lane flavour, F a literal (0 or F_PERIODIC):
 * each row cut into the kept rows (w->keep, keep_rows), which the main pass
 * of the same evaluation then reads instead of cutting its rows again. */
typedef void (*strain_fn)(const sph_particles *, const sph_nlist *, const sph_force_params *,
                          sph_force_work *, double *const *, const strain_opts *);
#define STRAIN_LANES(k, FL, ATTR)                                                                  \
  ATTR void strain_##FL##_##k(const sph_particles *p, const sph_nlist *l,                          \
                              const sph_force_params *fp, sph_force_work *w, double *const *eps,   \
                              const strain_opts *o) {                                              \
    const long n = (long)p->n;                                                                     \
    _Pragma("omp parallel for schedule(dynamic, 256) if (n > SPH_OMP_MIN)") for (long i = 0;       \
                                                                                 i < n; i++)       \
        strain_##FL(w->hot, l, fp, w->keep + sph_nlist_slot(l, i) + SPH_KEEP_PAD * (size_t)i,      \
                    w->keepn + i, (size_t)i, o, eps, k);                                           \
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

/* The velocities the strain-rate pass reads, no-slip walls extrapolated:
 * the fit's cells fit the whole store's 2 max h (fp->h_reach), so that a
 * rank's store, which holds part of it, fits each point in the same order
 * (walls/wall_velocity.c). */
static int wall_ghosts(const sph_particles *p, const sph_force_params *fp, double *const *gv,
                       sph_wall_velocity_work *wv, sph_error *err) {
  const double reach =
      fp->var_h && fp->h_reach > 0.0 ? SPH_CUBIC_SUPPORT * fp->h_reach : kernel_reach(p, fp);
  wv->narrow = sph_force_loop_narrow(fp->loop);
  return sph_wall_velocity(p, reach, fp->px0, fp->periodic ? fp->period : 0.0, fp->paxis, gv, wv,
                           err);
}

/* The options of the strain-rate pass as fp asks for them, into w's arrays:
 * the gradient correction's L, and the wall particles' extrapolated
 * velocities (computed here). */
static int strain_setup(const sph_particles *p, const sph_force_params *fp, sph_force_work *w,
                        strain_opts *o, sph_error *err) {
  *o = (strain_opts){0};
  if (fp->gradient_correction) o->l = w->l;
  SPH_IF3(if (fp->sps) o->div = w->sdiv;)
  if (!(fp->no_slip || fp->mirror || fp->adami)) return 0;
  /* every particle's own velocity but an adami wall particle's, set before the pass
   * (walls/adami.h); sph_wall_velocity leaves those too */
  if (fp->no_slip) {
    if (wall_ghosts(p, fp, w->gv, &w->wv, err)) return -1;
  } else {
    for (size_t i = 0; i < p->n; i++)
      if (!(p->flags[i] & SPH_FLAG_ADAMI))
        for (int d = 0; d < SPH_DIM; d++)
          w->gv[d][i] = p->vel[d][i];
  }
  if (fp->mirror) /* mirror particles: their no-slip velocity (boundary.h) */
    for (size_t i = 0; i < p->n; i++)
      if (p->kind[i] == SPH_KIND_MIRROR)
        for (int d = 0; d < SPH_DIM; d++)
          w->gv[d][i] = p->velh[d][i];
  o->gv = (const double *const *)w->gv;
  return 0;
}

int sph_forces_strain_rate(const sph_particles *p, const sph_grid *g, const sph_force_params *fp,
                           double *const eps[SPH_SYM], sph_error *err) {
  sph_nlist l;
  sph_nlist_init(&l);
  sph_force_work w = {0};
  strain_opts o;
  int rc =
      sph_nlist_build(&l, g, p, kernel_reach(p, fp), 0.0, fp->periodic ? fp->period : 0.0, err);
  if (rc == 0) rc = sph_force_work_reserve(&w, p->n, err);
  if (rc == 0) rc = strain_setup(p, fp, &w, &o, err);
  if (rc == 0) strain_list(p, &l, fp, eps, &o);
  sph_force_work_free(&w);
  sph_nlist_free(&l);
  return rc;
}

/* The loop of a table for the term set F (interact.h): the one compiled
 * for F, else F's axes loop, else the run-time loop for F's per-particle
 * h; with `runtime` set, the first is skipped (the tests compare it with
 * the others). NULL if the table has none of them. */
static sph_loop_fn find_variant(const sph_loop_table *t, unsigned F, int runtime) {
  const unsigned want[3] = {F, F_RUNTIME | F_AXES_FIXED | (F & F_AXES), F_RUNTIME | (F & F_VARH)};
  for (int w = runtime ? 1 : 0; w < 3; w++)
    for (size_t k = 0; k < t->n; k++)
      if (t->entry[k].fc == want[w]) return t->entry[k].fn;
  return NULL;
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

/* The variant of a lane loop that can run here for the term set F (NULL:
 * none), from its flavour's table (find_variant). */
static sph_loop_fn lane_variant(sph_force_loop loop, unsigned F, int runtime) {
  switch (flavour_of(loop)) {
  case FLAVOUR_V4E: return find_variant(&sph_loops_lanes, F, runtime);
#ifdef SPH_LANES_AVX
  case FLAVOUR_V4X: return find_variant(&sph_loops_avx2, F, runtime);
#endif
#ifdef SPH_LANES_AVX512
  case FLAVOUR_V8Z: return find_variant(&sph_loops_avx512, F, runtime);
#endif
  default: return NULL;
  }
}

const char *sph_force_loop_name(const sph_force_params *fp) {
  if (fp->mirror || fp->var_h || fp->loop == SPH_LOOP_SCALAR) return "scalar"; /* pick_variant */
  switch (flavour_of(fp->loop)) {
  case FLAVOUR_V4E: return "portable lanes";
  case FLAVOUR_V4X: return "AVX2 lanes";
  case FLAVOUR_V8Z: return "AVX-512 lanes";
  default: return "none";
  }
}

/* The variant of the main pass for the term set F in the loop asked for:
 * SPH_LOOP_AUTO is the widest lanes the processor has (AVX-512, AVX2, else
 * the portable lanes; all give the same bits); each lane loop falls back to
 * the scalar loop for per-particle h, and every loop for mirror particles
 * (`scalar`); `runtime` asks for the flavour's run-time loop even where F
 * has a loop of its own. NULL if that loop cannot run here. */
static sph_loop_fn pick_variant(unsigned F, sph_force_loop loop, int scalar, int runtime) {
  if (!sph_force_loop_available(loop)) return NULL;
  if (scalar || loop == SPH_LOOP_SCALAR || (F & F_SCALAR_ONLY))
    return find_variant(&sph_loops_scalar, F, runtime);
  return lane_variant(loop, F, runtime);
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

/* Particle i's packed state (w->hot). */
static inline void pack_hot(const sph_particles *p, const sph_force_params *fp, sph_force_work *w,
                            size_t i) {
  const uint8_t *ph = sph_particles_phases(p); /* (two phases: each particle's law) */
  const double rho = p->rho[i],
               cs = sph_eos_sound_speed(ph ? &fp->phase_eos[ph[i]] : &fp->eos, rho);
  w->hot[i] = (sph_force_hot){p->x[i],  p->y[i],
                              p->vx[i], p->vy[i],
                              rho,      p->p[i] / (rho * rho),
                              cs,       p->mass[i] SPH_IF3(, p->z[i], p->vz[i])};
}

void sph_force_work_repack(const sph_particles *p, const sph_force_params *fp, sph_force_work *w,
                           size_t i) {
  pack_hot(p, fp, w, i);
}

/* Per pass: the packed state of every particle (w->hot), a cut-row
 * buffer per thread, and the interaction loop's slices (the list's, with
 * stealing). */
static int prepare_pass(const sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                        sph_force_work *w, const unsigned F, sph_error *err) {
  const long n = (long)p->n;
  if (sph_force_work_reserve(w, p->n, err)) return -1;
  /* the loops read the fluid masses: XSPH, the ledger, the Riemann terms, and a wall row's
   * continuity where walls move (interact_row.h) */
  const int fm = (F & (F_XSPH | F_LEDGER | F_RIEMANN)) || fp->moving_walls || fp->mirror;
  /* the Riemann pressure's rows that meet a wall with a normal (interact_row.h, rnorm) */
  const int nwall = (F & F_RIEMANN) && sph_force_wall_normals(fp);
#pragma omp parallel if (n > SPH_OMP_MIN)
  {
    size_t lo, hi; /* the slices of the interaction loop */
    sph_slice(l->cost, p->n, &lo, &hi);
    for (size_t i = lo; i < hi; i++) {
      pack_hot(p, fp, w, i);
      if (fm) w->fm[i] = p->kind[i] == SPH_KIND_FLUID ? p->mass[i] : 0.0;
    }
  }
  /* nwall from the walls' rows (the list is symmetric): few, and no two writers; found again
   * only when the list was built again (a list holds for one store in one order, whose walls'
   * flags do not change; a rank's store taken again with the same particles keeps it:
   * solver/ranks.c) */
  if (nwall && (fp->nwall_every || w->nwall_serial != l->serial || l->serial == 0)) {
    memset(w->nwall, 0, p->n * sizeof *w->nwall);
    for (size_t i = 0; i < p->n; i++) {
      if (p->kind[i] != SPH_KIND_WALL || !(p->flags[i] & SPH_WALL_NORMAL)) continue;
      size_t cnt;
      const uint32_t *row = sph_nlist_row(l, i, &cnt);
      for (size_t k = 0; k < cnt; k++)
        w->nwall[row[k]] = 1;
    }
    w->nwall_serial = l->serial;
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
 * w->keepn, a per-particle array of work_reserve): row i at the list's
 * slot of row i (sph_nlist_slot) plus SPH_KEEP_PAD entries per particle. */
static int keep_rows(const sph_particles *p, const sph_nlist *l, sph_force_work *w,
                     sph_error *err) {
  const size_t need = sph_nlist_slot(l, p->n) + SPH_KEEP_PAD * p->n;
  if (need <= w->keep_cap) return 0;
  const size_t cap = need + need / 4;
  uint32_t *a = realloc(w->keep, cap * sizeof *a);
  if (!a) return sph_error_set(err, "forces: out of memory for the kept neighbour rows");
  w->keep = a;
  w->keep_cap = cap;
  return 0;
}

/* The strain-rate pass with the options o, its strain rate into w->s: in
 * the lane flavour of fp's loop, its cut rows kept for the main pass
 * (keep_rows), else the scalar pass. */
static int strain_run(const sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                      sph_force_work *w, const strain_opts *o, sph_error *err) {
  const strain_fn lanes = strain_lanes(fp);
  if (lanes && keep_rows(p, l, w, err)) return -1;
  if (lanes)
    lanes(p, l, fp, w, w->s, o);
  else
    strain_list(p, l, fp, w->s, o);
  return 0;
}

/* The strain-rate pass and tau / rho^2 at every particle (w->sxx, sxy,
 * syy): the laminar mu eps of paper A eq. (13)-(14) plus the SPS stress of
 * paper B eq. (4), with the kernel-gradient correction when asked for. */
static int stress_pass(const sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                       sph_force_work *w, sph_error *err) {
  const long n = (long)p->n;
  strain_opts o;
  if (strain_setup(p, fp, w, &o, err) || strain_run(p, l, fp, w, &o, err)) return -1;
  double *restrict const sxx = w->sxx, *restrict const sxy = w->sxy, *restrict const syy = w->syy;
  SPH_IF3(double *restrict const sxz = w->sxz, *restrict const syz = w->syz;
          double *restrict const szz = w->szz; const double *restrict const sdiv = w->sdiv;)
#pragma omp parallel for schedule(static) if (n > SPH_OMP_MIN)
  for (long i = 0; i < n; i++) {
    const double rho = p->rho[i];
    const double lam = fp->viscosity == SPH_VISCOSITY_STRESS_TENSOR ? fp->mu / (rho * rho) : 0.0;
    const double exx = sxx[i], exy = sxy[i], eyy = syy[i];
#if SPH_DIM == 2
    double t[SPH_SYM] = {lam * exx, lam * exy, lam * eyy};
#else
    const double exz = sxz[i], eyz = syz[i], ezz = szz[i];
    double t[SPH_SYM] = {lam * exx, lam * exy, lam * exz, lam * eyy, lam * eyz, lam * ezz};
#endif
    if (fp->sps) {
      /* S from eps = 2 S - (2/3) tr S I: in 2-D from eps alone (div = S_xx + S_yy =
       * (3/2) tr eps), in 3-D with the pass's div v (there tr eps = 0) */
#if SPH_DIM == 2
      const double S[SPH_SYM] = {0.5 * (2.0 * exx + eyy), 0.5 * exy, 0.5 * (2.0 * eyy + exx)};
#else
      const double d = (2.0 / 3.0) * sdiv[i];
      const double S[SPH_SYM] = {0.5 * (exx + d), 0.5 * exy, 0.5 * exz,
                                 0.5 * (eyy + d), 0.5 * eyz, 0.5 * (ezz + d)};
#endif
      double a[SPH_SYM];
      sph_sps_stress_sym(S, fp->sps_cs, fp->sps_ci, fp->sps_delta, a);
#pragma GCC unroll 6
      for (int k = 0; k < SPH_SYM; k++)
        t[k] += a[k] / rho;
    }
    if (o.l) { /* sym(tau L): the divergence with the corrected gradient */
      double a[SPH_SYM], b[SPH_SYM];
#pragma GCC unroll 6
      for (int k = 0; k < SPH_SYM; k++)
        a[k] = o.l[k][i];
      sph_sym_product(t, a, b);
#pragma GCC unroll 6
      for (int k = 0; k < SPH_SYM; k++)
        t[k] = b[k];
    }
    sxx[i] = t[SPH_XX];
    sxy[i] = t[SPH_XY];
    syy[i] = t[SPH_YY];
    SPH_IF3(sxz[i] = t[SPH_XZ]; syz[i] = t[SPH_YZ]; szz[i] = t[SPH_ZZ];)
  }
  return 0;
}

/* L = M^-1 at every particle (w->l) for the corrected gradient (forces.h),
 * where the stress pass does not give it: the strain-rate pass with the
 * correction summing its moment M alone (Bonet and Lok 1999; no strain
 * rate, eps not written). In lanes it keeps the cut rows for the main
 * pass, as the stress pass does. */
static int moment_pass(const sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                       sph_force_work *w, sph_error *err) {
  const strain_opts o = {.l = w->l, .moment_only = 1};
  return strain_run(p, l, fp, w, &o, err);
}

int sph_forces_fastest_loop(sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                            sph_force_work *w, sph_force_loop *loop, double *ratio,
                            sph_error *err) {
  *loop = fp->loop;
  *ratio = 1.0;
  if (fp->loop != SPH_LOOP_AUTO || fp->var_h || fp->mirror) return 0; /* scalar there */
  if (!sph_force_loop_available(SPH_LOOP_LANES_AVX) ||
      !sph_force_loop_available(SPH_LOOP_LANES_AVX512))
    return 0; /* one lane loop: nothing to choose */
  const sph_force_loop loops[2] = {SPH_LOOP_LANES_AVX512, SPH_LOOP_LANES_AVX};
  double best[2] = {INFINITY, INFINITY};
  sph_force_params q = *fp;
  for (int round = 0; round < SPH_FASTEST_ROUNDS; round++) /* interleaved: A B A B ... */
    for (int k = 0; k < 2; k++) {
      q.loop = loops[k];
      const double t0 = sph_seconds();
      if (sph_forces_evaluate(p, l, &q, w, err)) return -1;
      const double t = sph_seconds() - t0;
      if (t < best[k]) best[k] = t;
    }
  *ratio = best[0] > 0.0 ? best[1] / best[0] : 1.0; /* AVX2 time over AVX-512 time */
  *loop = sph_forces_loop_for_ratio(*ratio);
  return 0;
}

sph_force_loop sph_forces_loop_for_ratio(double ratio) {
  /* the eight lanes unless the four are faster by a clear margin */
  return ratio < 1.0 - SPH_FASTEST_MARGIN ? SPH_LOOP_LANES_AVX : SPH_LOOP_LANES_AVX512;
}

/* Debug invariant: every rate of the pass is finite (a NaN here is a bug in
 * a term or a loop, not a blow-up: the state it read was checked). */
static void check_rates(const sph_particles *p, const sph_force_work *w, unsigned F) {
  for (size_t i = 0; i < p->n; i++) {
    int ok = isfinite(p->drho[i]) && (!w->keep_sigma || isfinite(w->sigma[i]));
    for (int d = 0; d < SPH_DIM; d++) {
      ok &= isfinite(p->acc[d][i]);
      if ((F & F_XSPH) && p->kind[i] == SPH_KIND_FLUID) ok &= isfinite(p->xsph[d][i]);
    }
    if (F & F_LEDGER) ok &= isfinite(p->du[i]) && isfinite(w->wpow[i]);
    SPH_INVARIANT(ok, "particle %zu (id %lld) has a rate that is not finite after a pass", i,
                  (long long)p->id[i]);
  }
}

int sph_forces_evaluate(sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                        sph_force_work *w, sph_error *err) {
  const unsigned F = sph_interact_terms(fp);
  const sph_loop_fn run = pick_variant(F, fp->loop, fp->mirror, fp->runtime_terms);
  if (!run) return sph_error_set(err, "forces: the interaction loop asked for cannot run here");
  if (prepare_pass(p, l, fp, w, F, err)) return -1;
  w->terms = F;
  /* the corrected gradient's L (the stress's corrected strain rate gives it too) */
  if ((F & F_CGRAD) && !((F & F_STRESS) && fp->gradient_correction) &&
      moment_pass(p, l, fp, w, err))
    return -1;
  if ((F & F_STRESS) && fp->sigma > 0.0) /* (two phases: no viscous stress) */
    sph_surface_stress(p, l, fp, w);
  else if ((F & F_STRESS) && stress_pass(p, l, fp, w, err))
    return -1;
  if (F & F_DDIFF)
    sph_diffusion_prepare(p, l, fp, w, sph_diffusion_mass_is_fm(fp, (F & F_XSPH) != 0));
  if (w->late) { /* the rows in two phases around late_hook (force_pass.h) */
    w->phase = 1;
    run(p, l, fp, w);
    const double mx = w->cs_sigma_max;
    w->late_hook(w->late_ctx);
    w->phase = 2;
    if (sph_steal_reset(&w->steal, l->cost, p->n, sph_team_size(p->n))) {
      w->phase = 0;
      return sph_error_set(err, "forces: out of memory for the thread slices");
    }
    run(p, l, fp, w);
    w->phase = 0;
    if (mx > w->cs_sigma_max) w->cs_sigma_max = mx;
  } else
    run(p, l, fp, w);
  if (SPH_DEBUG) check_rates(p, w, F);
  if (fp->repulsive) {
    const sph_repulsion_ledger lg = {w->wf, w->wpow, w->lj};
    sph_repulsion_add(p, l, fp->lj_d, fp->lj_r0, (F & F_LEDGER) ? &lg : NULL);
  }
  return 0;
}
