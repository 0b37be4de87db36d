/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * forces.h - the interaction passes: rates of change of every particle from
 * its neighbours (gather form: each particle sums over its own neighbours
 * into its own accumulators, so no two threads write the same memory and
 * the summation order is fixed by the sorted store).
 *
 * Terms (paper A = dam-break paper, paper B = breaking-wave paper):
 *   continuity       drho_i/dt = sum_j m_j (v_i - v_j) . grad_i W_ij      (B eq. 2, A eq. 12),
 *                    over fluid neighbours only for a wall particle i
 *   momentum         dv_i/dt = -sum_j m_j (p_i/rho_i^2 + p_j/rho_j^2 + Pi_ij) grad_i W_ij + g
 *                                                                         (A eq. 11, B eq. 3)
 *   art. viscosity   Pi_ij = (-alpha c_ij mu_ij + beta mu_ij^2)/rho_ij if v_ij.r_ij < 0, else 0
 *                    mu_ij = h_ij v_ij.r_ij / (r_ij^2 + eta^2), eta = eta_f h_ij (A eq. 15-16)
 *   viscous stress   + sum_j m_j sum_d (tau_i^ad/rho_i^2 + tau_j^ad/rho_j^2) dW_ij/dx_i^d,
 *                    tau = mu eps, eps from the strain-rate pass          (A eq. 11, 13, 14)
 *   Morris viscosity + sum_j m_j 4 nu0 r_ij.grad_i W_ij / ((rho_i + rho_j)(r_ij^2 + eta^2)) v_ij
 *                    nu0 = mu / rho0                                       (B eq. 4, laminar)
 *   XSPH             dr_i/dt = v_i + eps sum_j (m_j/rho_ij) (v_j - v_i) W_ij  (B eq. 6),
 *                    over fluid neighbours only (a wall at rest would drag
 *                    the fluid otherwise)
 *   SPS turbulence   + sum_j m_j (tau*_i/rho_i^2 + tau*_j/rho_j^2) . grad_i W_ij, tau* the
 *                    Smagorinsky SPS stress of src/physics/turbulence.h       (B eq. 4)
 *   Lennard-Jones    + D [(r0/r)^12 - (r0/r)^4] r_ij / r^2 from repulsive wall particles
 *                    closer than r0                                        (A eq. 21-22)
 *   density diff.    + delta h c0 sum_j psi_ij (r_ji . grad_i W_ij) / r_ij^2 V_j on drho_i/dt,
 *                    fluid pairs only (physics/density_diffusion.h: Molteni &
 *                    Colagrossi 2009, Antuono et al. 2010, Fourtakas et al. 2019)
 *   time-step data   sigma_i = max_j |h v_ij.r_ij / r_ij^2|                 (B §2.6)
 *   energy ledger    du_i/dt = 1/2 sum_j m_j (p_i/rho_i^2 + p_j/rho_j^2 + Pi_ij) v_ij.grad_i W_ij
 *                    (A eq. 28-29, with the artificial-viscosity share) plus the
 *                    viscous dissipation in the pairwise form that balances
 *                    the viscous force's work exactly, for fluid and dynamic
 *                    wall particles (each takes half of a pair's heat); and
 *                    the power sum_j a_ij . v_j of wall particles j on fluid i
 * Dynamic wall particles (GOST R 57700.6 3.4.7) get drho/dt (and du/dt with
 * the ledger); repulsive wall particles and mirror particles get no rates. Walls and mirrors act on
 * fluid through their pressure and the viscous terms.
 *
 * Kernel-gradient correction of the pressure (numerics.gradient_correction;
 * Bonet and Lok 1999, CMAME 180:97, their symmetric form): the pressure
 * force, its artificial viscosity, their heat and the continuity term take
 * L_ij grad_i W_ij in place of grad_i W_ij, L_ij = (L_i + L_j) / 2, with
 * L = M^-1 of every particle from the strain-rate pass's moment M (below;
 * forces.c, moment_pass). L_ij is the same for both particles of a pair,
 * so the force stays antisymmetric (momentum conserved) and the
 * continuity term matches the pressure's work (the ledger closes). A
 * linear pressure field then balances exactly inside the water, which the
 * cubic spline's lattice sum at h = 1.3 dx misses by 0.65 % in 3-D
 * (M_zz = 0.9935; 1.0105 in 2-D), enough to leave a still tank's floor
 * 1.8 % over rho0 g H (doc/dimensions.md). The viscous terms keep
 * grad_i W_ij.
 *
 * Kernel-gradient correction of the stress tensor (physics.viscosity.
 * gradient_correction; Bonet and Lok 1999): the strain-rate pass sums
 * G_ab = sum_j V_j (v_j - v_i)_a dW_ij/dx_i^b and the moment
 * M_ab = sum_j V_j (x_j - x_i)_a dW_ij/dx_i^b, and takes grad v = G M^-1
 * (exact for a linear field whatever the neighbours); the stress divergence
 * then uses sym(tau L_i), L = M^-1, in place of tau_i, so that a linear
 * stress has its exact divergence while the pair terms stay antisymmetric
 * (momentum conserved). On a square lattice at h = 1.3 dx M = 1.0105 I,
 * so without it the nested gradients make the Laplacian 2.1 % too large.
 * Where det M <= SPH_GRADIENT_CORRECTION_MIN_DET (the free surface, the
 * outer layers of a wall) L = I: inverting a truncated moment there
 * amplifies noise (at 4900 particles the film blew up at 0.05 s with 0.25).
 * With extrapolated wall velocities (wall_velocity.h) the strain-rate pass
 * reads the wall particles' ghost velocities.
 *
 * The term sets the shipped cases run have loops of their own, the terms
 * they do not use compiled out (DESIGN rule 4); every other set runs a
 * loop compiled for its heaviest terms that tests the others per pair
 * (interact.h, LANE_LOOPS and SCALAR_LOOPS).
 */
#ifndef SPH_FORCES_H
#define SPH_FORCES_H

#include "core/parallel.h"
#include "core/particles.h"
#include "core/tensor.h"
#include "neighbours/grid.h"
#include "physics/density_diffusion.h"
#include "physics/eos.h"
#include "physics/models.h"
#include "walls/wall_velocity.h"

#define SPH_GRADIENT_CORRECTION_MIN_DET 0.8

/* L = M^-1 of the symmetric moment M where M is invertible enough
 * (det M > SPH_GRADIENT_CORRECTION_MIN_DET, M positive definite), else
 * L = I (see above): the kernel-gradient correction of the strain-rate pass
 * and the renormalised density gradient (diffusion.c). */
static inline void sph_gradient_correction(const double m[SPH_SYM], double a[SPH_SYM]) {
  sph_sym_inverse_or_identity(m, SPH_GRADIENT_CORRECTION_MIN_DET, a);
}

/* Which loop evaluates the main pass (src/solver/interact.h). Every loop
 * gives the same physics; they differ in summation order (the scalar loop
 * sums a row in order, the lane loops in four lanes), so each is bitwise
 * reproducible but two of them agree only to round-off, except the lane
 * flavours, which agree bitwise with one another (four or eight lanes).
 * The default is what runs use; the others are for tests
 * (tests/test_pair_terms.c) and benchmarks. */
typedef enum {
  SPH_LOOP_AUTO = 0,        /* the widest lanes the processor has: AVX-512, AVX2, portable */
  SPH_LOOP_SCALAR = 1,      /* the scalar loop for every term set */
  SPH_LOOP_LANES = 2,       /* the portable four-lane loop (scalar for var_h, ledger) */
  SPH_LOOP_LANES_AVX = 3,   /* the AVX2 four-lane loop (scalar for var_h, ledger) */
  SPH_LOOP_LANES_AVX512 = 4 /* the AVX-512 eight-lane loop into four-lane sums (the same) */
} sph_force_loop;

/* Whether the loop can run on this build and processor. */
int sph_force_loop_available(sph_force_loop loop);

typedef struct sph_force_params {
  sph_eos eos;
  double h;           /* smoothing length when uniform */
  int var_h;          /* per-particle h (pair mean h_ij); the grid must fit 2 max h */
  double alpha, beta; /* artificial viscosity; both 0 = off */
  double eta;         /* eta = eta_f * h_ij */
  double xsph;        /* XSPH epsilon; 0 = off */
  SPH_COMPONENTS(double, g, gx, gy, gz); /* body force per unit mass */
  sph_viscosity_kind viscosity;
  double mu;               /* dynamic viscosity (Pa s) */
  int periodic;            /* minimum image along axis paxis */
  int paxis;               /* the axis that wraps: 0 (x); in 3-D also 1 (y) or 2 (z) */
  double period;           /* length of the period */
  int repulsive;           /* repulsive wall particles present */
  double lj_d, lj_r0;      /* Lennard-Jones strength D and range r0 */
  int ledger;              /* energy ledger: du/dt and the power of wall particles on fluid */
  int sps;                 /* SPS turbulence stress (src/physics/turbulence.h) */
  int gradient_correction; /* kernel-gradient correction of the stress tensor (below) */
  int no_slip;             /* some wall particles carry SPH_FLAG_NO_SLIP (wall_velocity.h) */
  int free_slip;           /* some wall particles carry SPH_FLAG_FREE_SLIP: the scalar loop */
  int mdbc;                /* some wall particles carry SPH_FLAG_MDBC (diffusion.c) */
  int adami;               /* some wall particles carry SPH_FLAG_ADAMI: their rows are skipped,
                              their no-slip velocity in the work's gv (walls/adami.h) */
  int moving_walls;        /* some wall particles move: a wall row's continuity then skips
                              its wall (and mirror) neighbours, as with mirror walls; for
                              walls at rest each such pair adds +-0 */
  int wall_diffusion;      /* density diffusion on and some dynamic or fixed_layers wall
                              particles, which take part in it (diffusion.h) */
  int mirror;              /* mirror walls: their particles' no-slip velocity in vxh, vyh, the
                              scalar loop (boundary.h) */
  double px0;              /* periodic: the period starts at px0 along paxis */
  double sps_cs, sps_ci, sps_delta;
  sph_force_loop loop;          /* default SPH_LOOP_AUTO */
  int runtime_terms;            /* the loop a term set falls back to (its axes loop or the
                                   run-time loop) even where it has its own (tests and
                                   benchmarks; interact.h, LANE_LOOPS) */
  sph_kernel_kind kernel;       /* the smoothing kernel; default (0) the cubic spline */
  sph_diffusion_kind diffusion; /* density diffusion (physics/density_diffusion.h); NONE = off */
  double diffusion_delta;       /* its delta */
  int riemann;                  /* Riemann-solver pressure (pair_terms.h, riemann_pressure) in
                                   place of p_i/rho_i^2 + p_j/rho_j^2 */
  double riemann_limiter;       /* its limiter eta: beta = min(eta max(dU, 0) / c0, 1) */
  int corrected_gradient;       /* the pressure, its artificial viscosity and continuity with
                                   the pair's corrected kernel gradient L_ij grad_i W_ij
                                   (above) */
} sph_force_params;

/* Whether some wall particles carry their normal (SPH_WALL_NORMAL: mdbc,
 * adami, no-slip and free-slip walls), which the Riemann pressure's closing
 * speed reads (interact_row.h, forces.c). */
static inline int sph_force_wall_normals(const sph_force_params *fp) {
  return fp->mdbc || fp->no_slip || fp->free_slip || fp->adami;
}

/* The fields a neighbour reads, packed in one cache line per particle
 * (storage order), so that walking a neighbour row touches one line per
 * neighbour instead of one per field. */
typedef struct sph_force_hot {
  double x, y, vx, vy, rho;
  double prho2; /* p / rho^2 */
  double cs;    /* sound speed */
  double m;     /* mass */
#if SPH_DIM == 3
  double z, vz; /* the third axis after the first eight (the lane loops transpose those) */
#endif
} sph_force_hot;

/* Padding after each kept row: room for the widest lane loop's padding lanes. */
#define SPH_KEEP_PAD 8

/* Per-particle quantities of a pass (storage order). */
typedef struct sph_force_work {
  size_t cap;
  void *block;          /* the one allocation of the arrays below (arrays.h) */
  sph_force_hot *hot;   /* packed copy of the state read from neighbours */
  double *prho2;        /* scratch of n doubles (p / rho^2 lives in hot) */
  double *sigma;        /* max_j |h v_ij.r_ij / r_ij^2|, filled only with keep_sigma (the loops
                           reduce cs + sigma as they go: cs_sigma_max) */
  SPH_SYM_ARRAYS(s, s); /* tau / rho^2 (stress-tensor viscosity only): sxx, sxy, syy */
  double *wpow;         /* ledger: sum over wall neighbours j of a_ij . v_j (fluid i) */
  SPH_AXES(wf, wfx, wfy, wfz); /* ledger: sum over wall and mirror neighbours j of a_ij (fluid i) */
  SPH_SYM_ARRAYS(l, l);        /* kernel-gradient correction M^-1 of the strain-rate pass */
  SPH_AXES(gv, gvx, gvy, gvz); /* velocity in the viscous terms: every particle's in the
                                  strain-rate pass (extrapolated on no-slip walls); an adami wall
                                  particle's no-slip velocity (walls/adami.h, set before the
                                  pass) also in the main pass */
  SPH_AXES(ddc, ddcx, ddcy, ddcz); /* density diffusion: the model's vector c_i (diffusion.h),
                                      antuono's only: the others' is ddc0 */
  double ddc0[SPH_DIM];            /* the vector c_i of a model that has one for every particle */
#if SPH_DIM == 3
  double *sdiv; /* the strain pass's div v, which the 3-D SPS closure reads (tr eps = 0) */
#endif
  double *ddm;     /* density diffusion: the mass a particle diffuses with (0: none); not
                      filled where it is fm (sph_diffusion_mass_is_fm) */
  double *fm;      /* the mass of a fluid particle, 0 for the others (every pass) */
  uint32_t *keepn; /* the pairs of each kept row (below) */
  uint32_t *nwall; /* Riemann pressure: 1 where the particle's list row holds a wall
                      particle with a normal (SPH_WALL_NORMAL), else 0 (prepare_pass) */
  double *dd;      /* density diffusion D_i of the last pass (fluid; with the ledger) */
  double *lj;      /* repulsive walls' potential energy per unit mass (with the ledger) */
  sph_wall_velocity_work wv;
  double cs_sigma_max; /* max over the particles of cs + sigma (the step rule) */
  int keep_sigma;      /* set by a caller that reads sigma per particle (the tests) */
  unsigned terms;      /* the pass's term set (interact.h: the bits a loop tests at run time) */
  uint32_t *rows;      /* per thread: a neighbour row cut to the support */
  size_t rows_stride, rows_cap;
  /* With the stress tensor in lanes: every particle's row cut by the
   * strain-rate pass, kept for the main pass of the same evaluation (row i
   * at keep + sph_nlist_slot(l, i) + SPH_KEEP_PAD i, padded; keepn[i] pairs) */
  uint32_t *keep;
  size_t keep_cap;
  int keep_valid;  /* set by the strain-rate pass, cleared by each new pass */
  sph_steal steal; /* the interaction loop's slices (parallel.h) */
} sph_force_work;

void sph_force_work_free(sph_force_work *w);

/* Room in w for n particles (the contents carried over): for a caller
 * that fills one of its arrays before the pass (adami walls' gv). */
int sph_force_work_reserve(sph_force_work *w, size_t n, sph_error *err);

/* Sets p->p from the equation of state for every particle. */
void sph_forces_pressure(sph_particles *p, const sph_eos *eos);

/* One interaction pass over the neighbour list l (complete for the
 * support 2 h, 2 max h with var_h, and for the Lennard-Jones range r0 on
 * p's current positions: see sph_nlist_fresh): fills p->drho, p->ax, p->ay
 * (and p->xsx, p->xsy when XSPH is on), w->hot (its cs the sound speed),
 * w->cs_sigma_max and, with w->keep_sigma, w->sigma. Needs p->p current. */
int sph_forces_evaluate(sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                        sph_force_work *w, sph_error *err);

/* The loop the main pass runs with fp, as the run reports it: "scalar"
 * (asked for, per-particle h, mirror walls), "portable lanes", "AVX2
 * lanes" or "AVX-512 lanes" (SPH_LOOP_AUTO: the widest the processor has). */
const char *sph_force_loop_name(const sph_force_params *fp);

/* Rounds of the start-up choice of lane loop, and the margin by which the
 * AVX2 loop must be faster to be chosen over the AVX-512 one. */
#define SPH_FASTEST_ROUNDS 3
#define SPH_FASTEST_MARGIN 0.03

/* The lane loop (*loop) a run with fp->loop = SPH_LOOP_AUTO should use on
 * this processor: where both the AVX2 and the AVX-512 loops can run, each
 * evaluates the pass on p SPH_FASTEST_ROUNDS times, interleaved, and the
 * AVX2 loop is chosen if its fastest time is under (1 - margin) times the
 * AVX-512 loop's (some processors run AVX-512 divisions and square roots
 * at half the rate, or lower their clock for it). *ratio gets AVX2 time /
 * AVX-512 time (1 where nothing was measured). Both loops give the same
 * bits, so the choice moves run time only; the pass's rates are left as
 * one evaluation leaves them. Otherwise *loop = fp->loop (SPH_LOOP_AUTO
 * where a single lane loop can run, or for per-particle h and mirror
 * walls). Non-zero if an evaluation failed. */
int sph_forces_fastest_loop(sph_particles *p, const sph_nlist *l, const sph_force_params *fp,
                            sph_force_work *w, sph_force_loop *loop, double *ratio, sph_error *err);

/* The strain-rate tensor of paper A eq. (13)-(14) at every particle, for
 * tests and output: eps[SPH_XX], eps[SPH_XY], ... (each n values,
 * core/tensor.h); with fp's gradient correction and extrapolated wall
 * velocities when set. */
int sph_forces_strain_rate(const sph_particles *p, const sph_grid *g, const sph_force_params *fp,
                           double *const eps[SPH_SYM], sph_error *err);

#endif
