/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * force_pass.h - what an interaction pass reads and writes beside the
 * particles: its parameters (sph_force_params), the neighbours' packed
 * records (sph_force_hot) and its work arrays (sph_force_work), the loop
 * that evaluates it and the moment's inverse of the gradient correction.
 * The types the passes share (forces.c, the loops of interact.h,
 * diffusion.c); the passes themselves are in forces.h. Internal to
 * src/solver/.
 */
#ifndef SPH_FORCE_PASS_H
#define SPH_FORCE_PASS_H

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
 * L = I (forces.h says why): the kernel-gradient correction of the strain-rate pass
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

typedef struct sph_force_params {
  sph_eos eos; /* the liquid's law (phase 0) */
  /* two phases (physics.air; doc/method.md, Two phases): phases 2, phase_mat[k] the material
   * of phase k as the case gives it (physics/models.h: phase 0 the liquid's, phase 1
   * physics.air's), and from it phase_eos[k] its law (phase_eos[0] = eos), phase_z[k] its
   * impedance rho0 c0, phase_mu[k] its dynamic viscosity (Pa s; phase_mu[0] = mu), flat for
   * the loops' gathers; one phase: phases 1 */
  int phases;
  sph_material phase_mat[SPH_PHASES_MAX];
  sph_eos phase_eos[SPH_PHASES_MAX];
  double phase_z[SPH_PHASES_MAX];
  double phase_mu[SPH_PHASES_MAX];
  double sigma;   /* two phases: the interface's surface tension (N/m; surface_tension.h), 0 none */
  double h;       /* smoothing length when uniform */
  int var_h;      /* per-particle h (pair mean h_ij); the grid must fit 2 max h */
  double h_reach; /* with var_h: the largest h of the whole store, whose 2 h the wall
                   * velocity fit's cells fit (sim.c sets it per pass; a rank's store
                   * holds the whole store's, not its own); 0: this store's own */
  double alpha, beta;                    /* artificial viscosity; both 0 = off */
  double eta;                            /* eta = eta_f * h_ij */
  double xsph;                           /* XSPH epsilon; 0 = off */
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
  int gradient_correction; /* kernel-gradient correction of the stress tensor (forces.h) */
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
  int nwall_every;              /* find the rows that meet a wall with a normal at every pass,
                                   not once a list build (the test hook SPH_TEST_NWALL=every:
                                   prepare_pass, forces.c) */
  sph_kernel_kind kernel;       /* the smoothing kernel; default (0) the cubic spline */
  sph_diffusion_kind diffusion; /* density diffusion (physics/density_diffusion.h); NONE = off */
  double diffusion_delta;       /* its delta */
  int riemann;                  /* Riemann-solver pressure (pair_terms.h, riemann_pressure) in
                                   place of p_i/rho_i^2 + p_j/rho_j^2 */
  double riemann_limiter;       /* its limiter eta: beta = min(eta max(dU, 0) / c0, 1) */
  int corrected_gradient;       /* the pressure, its artificial viscosity and continuity with
                                   the pair's corrected kernel gradient L_ij grad_i W_ij
                                   (forces.h) */
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
  /* the list build nwall was found for (sph_nlist.serial: the same rows on the same store;
   * the contents outlive a regrowth) */
  uint64_t nwall_serial;
  sph_wall_velocity_work wv;
  double cs_sigma_max; /* max over the particles of cs + sigma (the step rule) */
  int keep_sigma;      /* set by a caller that reads sigma per particle (the tests) */
  int skip_ghosts;     /* a rank's store: no rates for SPH_FLAG_GHOST (solver/ranks.c) */
  /* Or NULL: the interaction loop's rows in two phases, those with late[i] = 1, then, after
   * late_hook(late_ctx) has given some particles their values (and their packed copies), those
   * with late[i] = 2 (a process's rows that read its ghost walls, whose values another process
   * sends: solver/ranks.c). The rows are independent: the same bits. */
  const unsigned char *late;
  void (*late_hook)(void *ctx);
  void (*late_progress)(void *ctx); /* or NULL: called by the first phase's first thread every
                                       few thousand rows (the values on their way: procs.h) */
  void *late_ctx;
  int phase;      /* the phase a loop makes (0: every row) */
  unsigned terms; /* the pass's term set (interact.h: the bits a loop tests at run time) */
  uint32_t *rows; /* per thread: a neighbour row cut to the support */
  size_t rows_stride, rows_cap;
  /* With the stress tensor in lanes: every particle's row cut by the
   * strain-rate pass, kept for the main pass of the same evaluation (row i
   * at keep + sph_nlist_slot(l, i) + SPH_KEEP_PAD i, padded; keepn[i] pairs) */
  uint32_t *keep;
  size_t keep_cap;
  int keep_valid;  /* set by the strain-rate pass, cleared by each new pass */
  sph_steal steal; /* the interaction loop's slices (parallel.h) */
} sph_force_work;

#endif
