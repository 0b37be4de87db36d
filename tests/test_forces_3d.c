/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_forces_3d.c - the interaction passes as the 3-D build compiles them
 * (built with -DSPH_DIM=3, linked with src/libsph3.la; doc/dimensions.md).
 * The 2-D passes are checked term by term against an oracle by
 * test_pair_terms (every term set, walls included); here every check has a
 * 3-D answer of its own:
 *
 * - the symmetric tensors: the 3x3 inverse (m a = I, a singular or
 *   indefinite moment gives the identity) and sym(t a) against the product
 *   written out; the SPS closure of a pure shear in the xz plane against
 *   its closed form;
 * - a cubic lattice at rest, uniform pressure: no force inside but gravity
 *   (0, 0, -g), and no density change;
 * - a linear velocity field along each axis in turn: the continuity
 *   equation gives -rho0 du_a/dx_a inside the lattice (within the lattice's
 *   kernel moment, 3 %), nothing from the other axes;
 * - the hydrostatic lattice, p = rho0 g (H - z) through the equation of
 *   state: the pressure force balances gravity inside within 3 % of g, with
 *   no horizontal force;
 * - the strain rate with the kernel-gradient correction (Bonet and Lok) on
 *   a lattice jittered by 0.1 dx: a shear u = (gamma z, 0, 0) and a
 *   stretch w = a z exactly (1e-9) (at 0.2 dx some interior moments fall
 *   under SPH_GRADIENT_CORRECTION_MIN_DET, a determinant, so a product of
 *   three eigenvalues in 3-D, and keep L = I);
 * - a jittered block with random velocities, artificial viscosity, Morris
 *   viscosity, XSPH and density diffusion: linear momentum sums to zero;
 *   with the energy ledger, the heat balances the internal forces' work
 *   (sum m (v . a + du) = 0) to round-off;
 * - the same pass in the scalar loop, the portable lanes, AVX2 and AVX-512
 *   lanes (where the processor has them): the lane loops bitwise equal,
 *   the scalar loop within round-off; the run-time loop bitwise equal to
 *   the set's own; one and two threads bitwise equal;
 * - the density filters with their 4x4 moments: on a lattice jittered by
 *   0.2 dx the MLS filter gives back a linear density field at every
 *   particle (1e-9 relative; the field's slopes along x, y and z differ), the
 *   Shepard filter a uniform one, with no MLS fallback inside;
 * - the integrators (predictor-corrector and leap-frog, with XSPH) move
 *   along z exactly as along x: a particle's state with its x and z
 *   components exchanged comes out exchanged, bit for bit; the CFL step
 *   reads |v| with v_z;
 * - an all-pairs oracle written here from the papers' equations (no list,
 *   no lanes): drho/dt, dv/dt, XSPH and du/dt of the pass within 1e-12 of
 *   each rate's largest (measured 1.2e-15) for artificial viscosity with
 *   XSPH, with beta and Fourtakas' diffusion, Morris viscosity with
 *   Molteni & Colagrossi's, the Riemann pressure, the first and last of
 *   these periodic in y, the second to fourth again on two layers of
 *   dynamic wall particles (a wall's continuity, diffusion and heat with
 *   fluid neighbours only; no XSPH with walls), and Antuono's diffusion
 *   with its 3x3 renormalisation (the oracle inverts by Gauss-Jordan), the
 *   viscous stress tensor (its 3x3 strain rate with paper A's 2/3), on
 *   walls the stress with SPS and XSPH, and the stress with the
 *   kernel-gradient correction (grad v = G M^-1, the divergence of
 *   sym(tau L)), and per-particle h (h_ij the pair's mean; the scalar loop)
 *   with AV, XSPH, Fourtakas and Morris on walls, each with both kernels (a
 *   wrong Pi_ij denominator shows as 4e-3, a wrong factor in Antuono's c_i
 *   as 5e-3, a 1/3 for the 2/3 as 2e-4, the correction left out of the
 *   divergence as 3e-5, the larger h in place of the mean as 7e-2);
 * - periodic along y and along z: the rates of the block periodic along x
 *   with its axes exchanged;
 * - the wall particles' rows with their fluid neighbours only (grid.h,
 *   wall_fluid_only; three layers of dynamic walls at rest under the
 *   jittered block): the fluid particles' rates the same bits as with
 *   full rows, the walls' within 1e-12 of the largest wall drho/dt, with
 *   artificial viscosity, XSPH and Fourtakas' diffusion (and again with
 *   the ledger: the walls' heat rates within 1e-12 too) and with Morris
 *   viscosity and Molteni's, in the default, scalar and portable loops;
 * - each pair term in 3-D (pair_terms.h with three components) from i's
 *   side and from j's, on 2000 random pairs: the forces (pressure,
 *   artificial viscosity, stress with its six components, Morris, XSPH)
 *   antisymmetric and the scalar terms symmetric, bit for bit, as
 *   test_pair_terms holds them in 2-D; the four-lane flavour gives v1's bits.
 */
#include "config.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/particles.h"
#include "core/tensor.h"
#include "neighbours/grid.h"
#include "physics/eos.h"
#include "physics/filter.h"
#include "physics/kernel.h"
#include "physics/pair_terms.h"
#include "physics/turbulence.h"
#include "solver/diffusion.h"
#include "solver/forces.h"
#include "solver/integrate.h"
#include "testutil.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#if SPH_DIM != 3
#error "test_forces_3d is built with -DSPH_DIM=3"
#endif

static const double RHO0 = 1000.0, DX = 0.01, C0 = 20.0, G = 9.81;
enum { NL = 11 }; /* lattice points per side */

static unsigned long long rng = 88172645463325252ULL;
static double uniform(void) { return sph_test_uniform(&rng); }

/* A cube of NL^3 fluid particles on the lattice of spacing DX (jittered by
 * up to jitter DX), velocity vel(x) (NULL: at rest). */
static void lattice(sph_particles *p, double jitter, void (*vel)(const double x[3], double v[3])) {
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(p, 16, &err) == 0);
  for (int k = 0; k < NL; k++)
    for (int j = 0; j < NL; j++)
      for (int i = 0; i < NL; i++) {
        double x[3] = {i * DX, j * DX, k * DX}, v[3] = {0.0, 0.0, 0.0};
        for (int d = 0; d < 3; d++)
          x[d] += jitter * DX * (2.0 * uniform() - 1.0);
        if (vel) vel(x, v);
        CU_ASSERT_FATAL(sph_particles_add_at(p, x, v, RHO0, RHO0 * DX * DX * DX, 1.3 * DX,
                                             SPH_KIND_FLUID, &err) >= 0);
      }
}

/* Inside the lattice: at least two smoothing lengths from every face. */
static int inside(const sph_particles *p, size_t i) {
  for (int d = 0; d < 3; d++) {
    const double x = p->pos[d][i];
    if (x < 2.6 * DX || x > (NL - 1) * DX - 2.6 * DX) return 0;
  }
  return 1;
}

static sph_force_params params(void) {
  sph_force_params fp;
  memset(&fp, 0, sizeof fp);
  fp.eos = sph_eos_tait(RHO0, C0);
  fp.h = 1.3 * DX;
  fp.eta = 0.1;
  fp.loop = SPH_LOOP_AUTO;
  return fp;
}

/* One pass on p (its store sorted by the grid first); non-zero on failure. */
static int evaluate(sph_particles *p, const sph_force_params *fp) {
  sph_grid g;
  sph_grid_init(&g);
  sph_nlist l;
  sph_nlist_init(&l);
  sph_error err;
  sph_force_work w;
  memset(&w, 0, sizeof w);
  int rc = sph_grid_build(&g, p, 2.0 * fp->h * (1.0 + 1e-9), 1u << 24, &err);
  if (rc == 0) rc = sph_nlist_build(&l, &g, p, 2.0 * fp->h, 0.0, 0.0, &err);
  if (rc == 0) {
    sph_forces_pressure(p, &fp->eos);
    rc = sph_forces_evaluate(p, &l, fp, &w, &err);
  }
  if (rc) fprintf(stderr, "evaluate: %s\n", err.msg);
  sph_force_work_free(&w);
  sph_nlist_free(&l);
  sph_grid_free(&g);
  return rc;
}

static void test_tensors(void) {
  const double m[SPH_SYM] = {2.0, 0.3, -0.2, 1.5, 0.4, 1.1};
  double a[SPH_SYM];
  CU_ASSERT_FATAL(sph_sym_inverse_or_identity(m, 0.1, a) == 1);
  for (int r = 0; r < 3; r++)
    for (int q = 0; q < 3; q++) {
      double s = 0.0;
      for (int k = 0; k < 3; k++)
        s += m[sph_sym_index(r, k)] * a[sph_sym_index(k, q)];
      CU_ASSERT_DOUBLE_EQUAL(s, r == q ? 1.0 : 0.0, 1e-12);
    }
  const double singular[SPH_SYM] = {1.0, 1.0, 0.0, 1.0, 0.0, 1.0};     /* det 0 */
  const double indefinite[SPH_SYM] = {-1.0, 0.0, 0.0, -1.0, 0.0, 1.0}; /* det 1 */
  for (int c = 0; c < 2; c++) {
    CU_ASSERT(sph_sym_inverse_or_identity(c ? indefinite : singular, 0.1, a) == 0);
    for (int k = 0; k < SPH_SYM; k++)
      CU_ASSERT_EQUAL(a[k], (k == SPH_XX || k == SPH_YY || k == SPH_ZZ) ? 1.0 : 0.0);
  }
  /* sym(t a) against t a written out */
  const double t[SPH_SYM] = {0.7, -0.1, 0.25, 0.3, 0.05, -0.4};
  double b[SPH_SYM];
  sph_sym_product(t, m, b);
  for (int r = 0; r < 3; r++)
    for (int q = r; q < 3; q++) {
      double rq = 0.0, qr = 0.0;
      for (int k = 0; k < 3; k++) {
        rq += t[sph_sym_index(r, k)] * m[sph_sym_index(k, q)];
        qr += t[sph_sym_index(q, k)] * m[sph_sym_index(k, r)];
      }
      CU_ASSERT_DOUBLE_EQUAL(b[sph_sym_index(r, q)], 0.5 * (rq + qr), 1e-15);
    }
  /* SPS of a pure shear dv_x/dz = gamma: S_xz = gamma / 2, |S| = gamma */
  const double gamma = 3.0, cs = 0.12, ci = 0.00066, delta = 0.01;
  const double S[SPH_SYM] = {0.0, 0.0, 0.5 * gamma, 0.0, 0.0, 0.0};
  double tau[SPH_SYM];
  CU_ASSERT_DOUBLE_EQUAL(sph_strain_norm_sym(S), gamma, 1e-15);
  sph_sps_stress_sym(S, cs, ci, delta, tau);
  const double nut = cs * delta * cs * delta * gamma, iso = (2.0 / 3.0) * ci * delta * delta * 9.0;
  CU_ASSERT_DOUBLE_EQUAL(tau[SPH_XZ], nut * gamma, 1e-18);
  CU_ASSERT_DOUBLE_EQUAL(tau[SPH_XX], -iso, 1e-18);
  CU_ASSERT_DOUBLE_EQUAL(tau[SPH_ZZ], -iso, 1e-18);
  CU_ASSERT_EQUAL(tau[SPH_XY], 0.0);
  CU_ASSERT_EQUAL(tau[SPH_YZ], 0.0);
}

static void test_rest(void) {
  sph_particles p;
  lattice(&p, 0.0, NULL);
  for (size_t i = 0; i < p.n; i++)
    p.rho[i] = 1.01 * RHO0; /* a uniform pressure */
  sph_force_params fp = params();
  fp.alpha = 0.1;
  fp.gz = -G;
  CU_ASSERT_FATAL(evaluate(&p, &fp) == 0);
  size_t bad = 0, n = 0;
  for (size_t i = 0; i < p.n; i++) {
    if (!inside(&p, i)) continue;
    n++;
    bad += fabs(p.ax[i]) > 1e-9 || fabs(p.ay[i]) > 1e-9 || fabs(p.az[i] + G) > 1e-9 ||
           fabs(p.drho[i]) > 1e-9;
  }
  CU_ASSERT(n >= 27);
  CU_ASSERT_EQUAL(bad, 0);
  sph_particles_free(&p);
}

static int axis_of_field;
static void linear_field(const double x[3], double v[3]) {
  v[axis_of_field] = 2.0 * x[axis_of_field];
}

static void test_continuity(void) {
  for (int a = 0; a < 3; a++) {
    axis_of_field = a;
    sph_particles p;
    lattice(&p, 0.0, linear_field);
    sph_force_params fp = params();
    CU_ASSERT_FATAL(evaluate(&p, &fp) == 0);
    double worst = 0.0;
    for (size_t i = 0; i < p.n; i++)
      if (inside(&p, i)) worst = fmax(worst, fabs(p.drho[i] / (-RHO0 * 2.0) - 1.0));
    CU_ASSERT(worst < 0.03);
    printf("\n    continuity along axis %d: largest error %.2e", a, worst);
    sph_particles_free(&p);
  }
}

static void test_hydrostatic(void) {
  sph_particles p;
  lattice(&p, 0.0, NULL);
  const double H = (NL - 1) * DX + 0.5 * DX;
  sph_force_params fp = params();
  fp.gz = -G;
  for (size_t i = 0; i < p.n; i++)
    p.rho[i] = sph_eos_density(&fp.eos, RHO0 * G * (H - p.z[i]));
  CU_ASSERT_FATAL(evaluate(&p, &fp) == 0);
  double worst = 0.0, side = 0.0;
  for (size_t i = 0; i < p.n; i++) {
    if (!inside(&p, i)) continue;
    worst = fmax(worst, fabs(p.az[i]));
    side = fmax(side, fmax(fabs(p.ax[i]), fabs(p.ay[i])));
  }
  printf("\n    hydrostatic: |a_z| up to %.3g g, |a_x|, |a_y| up to %.2g", worst / G, side);
  CU_ASSERT(worst < 0.03 * G);
  CU_ASSERT(side < 1e-9);
  sph_particles_free(&p);
}

/* eps of the field vel with the gradient correction, at every particle. */
static void strain_of(void (*vel)(const double x[3], double v[3]), double *eps[SPH_SYM],
                      sph_particles *p) {
  lattice(p, 0.1, vel);
  sph_force_params fp = params();
  fp.gradient_correction = 1;
  sph_grid g;
  sph_grid_init(&g);
  sph_error err;
  CU_ASSERT_FATAL(sph_grid_build(&g, p, 2.0 * fp.h * (1.0 + 1e-9), 1u << 24, &err) == 0);
  for (int k = 0; k < SPH_SYM; k++)
    eps[k] = malloc(p->n * sizeof *eps[k]);
  CU_ASSERT_FATAL(sph_forces_strain_rate(p, &g, &fp, eps, &err) == 0);
  sph_grid_free(&g);
}
static void shear(const double x[3], double v[3]) { v[0] = 1.5 * x[2]; }
static void stretch(const double x[3], double v[3]) { v[2] = 0.8 * x[2]; }

static void test_strain_rate(void) {
  for (int c = 0; c < 2; c++) {
    sph_particles p;
    double *eps[SPH_SYM];
    strain_of(c ? stretch : shear, eps, &p);
    /* shear: eps_xz = 1.5, the others 0; stretch: div = 0.8, eps_zz = 2 (0.8) - (2/3) 0.8,
     * eps_xx = eps_yy = -(2/3) 0.8 */
    double want[SPH_SYM] = {0.0};
    if (c)
      want[SPH_ZZ] = 1.6 - 0.8 * 2.0 / 3.0, want[SPH_XX] = want[SPH_YY] = -0.8 * 2.0 / 3.0;
    else
      want[SPH_XZ] = 1.5;
    double worst = 0.0;
    for (size_t i = 0; i < p.n; i++)
      if (inside(&p, i))
        for (int k = 0; k < SPH_SYM; k++)
          worst = fmax(worst, fabs(eps[k][i] - want[k]));
    printf("\n    %s: largest error %.2e", c ? "stretch" : "shear", worst);
    CU_ASSERT(worst < 1e-9);
    for (int k = 0; k < SPH_SYM; k++)
      free(eps[k]);
    sph_particles_free(&p);
  }
}

static void random_velocity(const double x[3], double v[3]) {
  (void)x;
  for (int d = 0; d < 3; d++)
    v[d] = 0.5 * (2.0 * uniform() - 1.0);
}

/* A jittered block with random velocities and densities under the terms
 * of fp; the momentum sum and the ledger's balance. */
static void check_balances(sph_force_params fp) {
  sph_particles p;
  lattice(&p, 0.2, random_velocity);
  for (size_t i = 0; i < p.n; i++)
    p.rho[i] = RHO0 * (1.0 + 0.01 * (2.0 * uniform() - 1.0));
  CU_ASSERT_FATAL(evaluate(&p, &fp) == 0);
  double mom[3] = {0.0, 0.0, 0.0}, scale = 0.0, work = 0.0, heat = 0.0, wscale = 0.0;
  for (size_t i = 0; i < p.n; i++)
    for (int d = 0; d < 3; d++) {
      mom[d] += p.mass[i] * p.acc[d][i];
      scale += fabs(p.mass[i] * p.acc[d][i]);
      work += p.mass[i] * p.vel[d][i] * p.acc[d][i];
      wscale += fabs(p.mass[i] * p.vel[d][i] * p.acc[d][i]);
    }
  for (size_t i = 0; i < p.n && fp.ledger; i++)
    heat += p.mass[i] * p.du[i];
  CU_ASSERT(scale > 0.0);
  for (int d = 0; d < 3; d++)
    CU_ASSERT(fabs(mom[d]) < 1e-12 * scale);
  if (fp.ledger) {
    printf("\n    work %.6g, heat %.6g, sum %.3g", work, heat, work + heat);
    CU_ASSERT(fabs(work + heat) < 1e-12 * wscale); /* the heat balances the work */
  }
  sph_particles_free(&p);
}

static void test_balances(void) {
  sph_force_params fp = params();
  fp.alpha = 0.3;
  fp.beta = 0.1;
  fp.viscosity = SPH_VISCOSITY_MORRIS;
  fp.mu = 1e-2;
  fp.xsph = 0.5;
  fp.diffusion = SPH_DIFFUSION_MOLTENI;
  fp.diffusion_delta = 0.1;
  check_balances(fp);
  fp.ledger = 1;
  fp.xsph = 0.0;
  fp.diffusion = SPH_DIFFUSION_NONE;
  check_balances(fp);
  fp.viscosity = SPH_VISCOSITY_STRESS_TENSOR; /* the 3x3 stress tensor */
  check_balances(fp);
  fp.riemann = 1; /* the Riemann pressure */
  fp.riemann_limiter = 3.0;
  fp.alpha = fp.beta = 0.0;
  check_balances(fp);
}

/* The pass of fp on a jittered block: the rates, for comparison. */
static void rates(sph_force_params fp, double *out) {
  sph_particles p;
  rng = 12345;
  lattice(&p, 0.2, random_velocity);
  for (size_t i = 0; i < p.n; i++)
    p.rho[i] = RHO0 * (1.0 + 0.01 * (2.0 * uniform() - 1.0));
  CU_ASSERT_FATAL(evaluate(&p, &fp) == 0);
  for (size_t i = 0; i < p.n; i++) {
    const size_t k = (size_t)p.id[i] * 7;
    out[k] = p.drho[i];
    for (int d = 0; d < 3; d++)
      out[k + 1 + d] = p.acc[d][i], out[k + 4 + d] = p.xsph[d][i];
  }
  sph_particles_free(&p);
}

static void test_loops_agree(void) {
  const size_t n = (size_t)NL * NL * NL * 7;
  double *ref = calloc(n, sizeof *ref), *got = calloc(n, sizeof *got);
  const sph_force_loop loops[4] = {SPH_LOOP_SCALAR, SPH_LOOP_LANES, SPH_LOOP_LANES_AVX,
                                   SPH_LOOP_LANES_AVX512};
#ifdef _OPENMP
  const int saved = omp_get_max_threads(); /* (make check runs tests on one thread) */
  omp_set_num_threads(2);                  /* the reference on two, compared with one below */
#endif
  for (int set = 0; set < 3; set++) {
    sph_force_params fp = params();
    fp.alpha = 0.2;
    fp.gz = -G;
    if (set >= 1) fp.xsph = 0.5, fp.diffusion = SPH_DIFFUSION_ANTUONO, fp.diffusion_delta = 0.1;
    if (set >= 2)
      fp.viscosity = SPH_VISCOSITY_STRESS_TENSOR, fp.mu = 1e-3, fp.sps = 1, fp.sps_cs = 0.12,
      fp.sps_ci = 0.00066, fp.sps_delta = DX, fp.gradient_correction = 1;
    fp.loop = SPH_LOOP_LANES;
    rates(fp, ref);
    for (int k = 0; k < 4; k++) {
      if (!sph_force_loop_available(loops[k])) {
        printf("\n    (lane loop %d cannot run on this processor)", (int)loops[k]);
        continue;
      }
      fp.loop = loops[k];
      rates(fp, got);
      if (loops[k] == SPH_LOOP_SCALAR) {
        double worst = 0.0, mag = 0.0;
        for (size_t q = 0; q < n; q++)
          worst = fmax(worst, fabs(got[q] - ref[q])), mag = fmax(mag, fabs(ref[q]));
        CU_ASSERT(worst <= 1e-11 * mag);
      } else {
        CU_ASSERT(memcmp(got, ref, n * sizeof *ref) == 0);
      }
    }
    fp.loop = SPH_LOOP_LANES; /* the run-time loop: the same bits as the set's own */
    fp.runtime_terms = 1;
    rates(fp, got);
    CU_ASSERT(memcmp(got, ref, n * sizeof *ref) == 0);
#ifdef _OPENMP
    fp.runtime_terms = 0;
    omp_set_num_threads(1);
    rates(fp, got);
    omp_set_num_threads(2);
    CU_ASSERT(memcmp(got, ref, n * sizeof *ref) == 0);
#endif
  }
#ifdef _OPENMP
  omp_set_num_threads(saved);
#endif
  free(ref);
  free(got);
}

/* The rates of fp on the jittered block of rates() made periodic along axis a (period NL DX)
 * with its coordinates and velocities permuted by perm (axis d of the block becomes axis
 * perm[d]), read back in the block's own axes; loop: the loop to run. */
static void periodic_rates(sph_force_params fp, int a, const int perm[3], double *out) {
  sph_particles p, q;
  sph_error err;
  rng = 777;
  lattice(&p, 0.2, random_velocity);
  CU_ASSERT_FATAL(sph_particles_init(&q, p.n, &err) == 0);
  for (size_t i = 0; i < p.n; i++) {
    double x[3], v[3];
    for (int d = 0; d < 3; d++)
      x[perm[d]] = p.pos[d][i], v[perm[d]] = p.vel[d][i];
    CU_ASSERT_FATAL(sph_particles_add_at(&q, x, v, RHO0 * (1.0 + 0.01 * (2.0 * uniform() - 1.0)),
                                         p.mass[i], p.h[i], SPH_KIND_FLUID, &err) >= 0);
  }
  fp.periodic = 1, fp.paxis = a, fp.period = NL * DX, fp.px0 = 0.0;
  double g[3] = {0.0, 0.0, 0.0};
  g[perm[2]] = -G;
  fp.gx = g[0], fp.gy = g[1], fp.gz = g[2];
  sph_grid gr;
  sph_grid_init(&gr);
  sph_nlist l;
  sph_nlist_init(&l);
  sph_force_work w;
  memset(&w, 0, sizeof w);
  int rc = sph_grid_build_periodic(&gr, &q, 2.0 * fp.h * (1.0 + 1e-9), a, 0.0, fp.period, 1u << 24,
                                   &err);
  if (rc == 0) rc = sph_nlist_build(&l, &gr, &q, 2.0 * fp.h, 0.0, fp.period, &err);
  if (rc == 0) {
    sph_forces_pressure(&q, &fp.eos);
    rc = sph_forces_evaluate(&q, &l, &fp, &w, &err);
  }
  if (rc) fprintf(stderr, "periodic_rates: %s\n", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  for (size_t i = 0; i < q.n; i++) {
    const size_t k = (size_t)q.id[i] * 7;
    out[k] = q.drho[i];
    for (int d = 0; d < 3; d++)
      out[k + 1 + d] = q.acc[perm[d]][i], out[k + 4 + d] = q.xsph[perm[d]][i];
  }
  sph_force_work_free(&w);
  sph_nlist_free(&l);
  sph_grid_free(&gr);
  sph_particles_free(&q);
  sph_particles_free(&p);
}

/* Periodic along y and along z: the block periodic along x with its axes exchanged (x and y,
 * x and z) gives the same rates as periodic along x, to round-off (the squared distances sum
 * in another order), with every term that takes a separation (AV, XSPH, Antuono's diffusion,
 * the stress tensor with its correction and SPS); lane flavours and the run-time loop bitwise
 * as the scalar loop's 1e-11. Every particle has neighbours across the seam within 2 h. */
static void test_periodic_axes(void) {
  const size_t n = (size_t)NL * NL * NL * 7;
  double *ref = calloc(n, sizeof *ref), *got = calloc(n, sizeof *got);
  sph_force_params fp = params();
  fp.alpha = 0.2;
  fp.xsph = 0.5, fp.diffusion = SPH_DIFFUSION_ANTUONO, fp.diffusion_delta = 0.1;
  fp.viscosity = SPH_VISCOSITY_STRESS_TENSOR, fp.mu = 1e-3, fp.sps = 1, fp.sps_cs = 0.12,
  fp.sps_ci = 0.00066, fp.sps_delta = DX, fp.gradient_correction = 1;
  const int same[3] = {0, 1, 2}, xy[3] = {1, 0, 2}, xz[3] = {2, 1, 0};
  fp.loop = SPH_LOOP_LANES;
  periodic_rates(fp, SPH_AXIS_X, same, ref);
  double mag = 0.0;
  for (size_t q = 0; q < n; q++)
    mag = fmax(mag, fabs(ref[q]));
  const sph_force_loop loops[3] = {SPH_LOOP_SCALAR, SPH_LOOP_LANES, SPH_LOOP_LANES_AVX};
  for (int a = SPH_AXIS_Y; a <= SPH_AXIS_Z; a++) {
    double *lanes = calloc(n, sizeof *lanes);
    fp.loop = SPH_LOOP_LANES;
    fp.runtime_terms = 0;
    periodic_rates(fp, a, a == SPH_AXIS_Y ? xy : xz, lanes);
    double worst = 0.0;
    for (size_t q = 0; q < n; q++)
      worst = fmax(worst, fabs(lanes[q] - ref[q]));
    printf("\n    periodic along %c as along x: largest difference %.2g of %.2g", "xyz"[a], worst,
           mag);
    CU_ASSERT(worst <= 1e-11 * mag);
    for (int k = 0; k < 4; k++) {
      if (k < 3 && !sph_force_loop_available(loops[k])) continue;
      fp.loop = k < 3 ? loops[k] : SPH_LOOP_LANES;
      fp.runtime_terms = k == 3; /* the run-time loop */
      periodic_rates(fp, a, a == SPH_AXIS_Y ? xy : xz, got);
      if (k == 0) {
        double w = 0.0;
        for (size_t q = 0; q < n; q++)
          w = fmax(w, fabs(got[q] - lanes[q]));
        CU_ASSERT(w <= 1e-11 * mag);
      } else {
        CU_ASSERT(memcmp(got, lanes, n * sizeof *got) == 0);
      }
    }
    free(lanes);
  }
  free(ref);
  free(got);
}

/* ---- an all-pairs oracle from the papers' equations, 3-D, fluid particles ---------- */

/* x_i - x_j along axis a, the minimum image along fp's periodic axis. */
static double oracle_sep(const sph_force_params *fp, int a, double xi, double xj) {
  double d = xi - xj;
  if (fp->periodic && fp->paxis == a) d -= fp->period * nearbyint(d / fp->period);
  return d;
}

/* Every particle against every other (no list, no grid, no lanes): drho/dt (B eq. 2 with
 * Fourtakas' or Molteni & Colagrossi's diffusion, B eq. 5, and the Riemann scheme's
 * continuity term), dv/dt (A eq. 11 with Monaghan's Pi_ij, A eq. 15-16, or the Riemann
 * interface pressure of Zhang et al. 2017; Morris' viscosity, B eq. 4; gravity), the XSPH
 * correction (B eq. 6) and du/dt (A eq. 28). out: 8 per particle id. */
/* The pair's smoothing length: h, or with per-particle h the pair's mean (paper B). */
static double oracle_h(const sph_particles *p, const sph_force_params *fp, size_t i, size_t j) {
  return fp->var_h ? 0.5 * (p->h[i] + p->h[j]) : fp->h;
}

/* The pair (i, j) if j != i lies within 2 h_ij: d = x_i - x_j (the minimum image), r, W,
 * dW/dr. */
static int oracle_pair(const sph_particles *p, const sph_force_params *fp, size_t i, size_t j,
                       double d[3], double *r, double *w, double *dw) {
  if (j == i) return 0;
  for (int q = 0; q < 3; q++)
    d[q] = oracle_sep(fp, q, p->pos[q][i], p->pos[q][j]);
  *r = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const double h = oracle_h(p, fp, i, j);
  if (*r >= 2.0 * h || *r == 0.0) return 0;
  sph_kernel_w_dw(fp->kernel, *r, h, w, dw);
  return 1;
}

/* L = M^-1 by Gauss-Jordan elimination with partial pivoting where M is invertible enough
 * (positive definite, det M > SPH_GRADIENT_CORRECTION_MIN_DET), else the identity; 1 where it
 * inverted. */
static int oracle_inverse3(const double M[3][3], double out[3][3]) {
  const double det = M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                     M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                     M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
  const int ok = det > SPH_GRADIENT_CORRECTION_MIN_DET && M[0][0] > 0.0 &&
                 M[0][0] * M[1][1] - M[0][1] * M[1][0] > 0.0;
  double L[3][6];
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 6; b++)
      L[a][b] = b < 3 ? M[a][b] : (b - 3 == a);
  for (int col = 0; ok && col < 3; col++) {
    int piv = col;
    for (int r2 = col + 1; r2 < 3; r2++)
      if (fabs(L[r2][col]) > fabs(L[piv][col])) piv = r2;
    for (int b = 0; b < 6; b++) {
      const double t = L[col][b];
      L[col][b] = L[piv][b], L[piv][b] = t;
    }
    const double inv = 1.0 / L[col][col];
    for (int b = 0; b < 6; b++)
      L[col][b] *= inv;
    for (int r2 = 0; r2 < 3; r2++)
      if (r2 != col) {
        const double f = L[r2][col];
        for (int b = 0; b < 6; b++)
          L[r2][b] -= f * L[col][b];
      }
  }
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++)
      out[a][b] = ok ? L[a][3 + b] : (a == b);
  return ok;
}

/* Antuono et al. (2010) eq. (6): c_i = L_i sum_j (rho_j - rho_i) V_j grad_i W_ij / 2 at each
 * fluid particle, L_i = M_i^-1 with M_ab = sum_j V_j (x_j - x_i)_a (grad_i W_ij)_b (the identity
 * where M is not positive definite with det M > SPH_GRADIENT_CORRECTION_MIN_DET); 0 at walls. */
static void oracle_antuono_c(const sph_particles *p, const sph_force_params *fp, double *c) {
  for (size_t i = 0; i < p->n; i++) {
    double g[3] = {0.0, 0.0, 0.0}, M[3][3] = {{0.0}};
    c[3 * i] = c[3 * i + 1] = c[3 * i + 2] = 0.0;
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    for (size_t j = 0; j < p->n; j++) {
      double d[3], r, w, dw;
      if (!oracle_pair(p, fp, i, j, d, &r, &w, &dw)) continue;
      const double V = p->mass[j] / p->rho[j];
      for (int a = 0; a < 3; a++) {
        g[a] += (p->rho[j] - p->rho[i]) * V * dw * d[a] / r;
        for (int b = 0; b < 3; b++)
          M[a][b] -= V * d[a] * dw * d[b] / r;
      }
    }
    double L[3][3];
    oracle_inverse3(M, L);
    for (int a = 0; a < 3; a++)
      c[3 * i + a] = 0.5 * (L[a][0] * g[0] + L[a][1] * g[1] + L[a][2] * g[2]);
  }
}

/* tau_i / rho_i^2 at every particle (6 per particle, core/tensor.h's order): mu eps_i / rho_i^2
 * with paper A eq. (13)-(14), eps = grad v + grad v^T - (2/3) div v I from
 * (grad v)_ab = sum_j V_j (v_j - v_i)_a (grad_i W_ij)_b over every neighbour, plus the SPS
 * stress of paper B eq. (4) over rho_i (its closure, physics/turbulence.h, of S = (eps +
 * (2/3) div v I) / 2). */
static void oracle_stress3(const sph_particles *p, const sph_force_params *fp, double *tau) {
  for (size_t i = 0; i < p->n; i++) {
    double gv[3][3] = {{0.0}}, M[3][3] = {{0.0}}; /* grad v, and the moments M */
    for (size_t j = 0; j < p->n; j++) {
      double d[3], r, w, dw;
      if (!oracle_pair(p, fp, i, j, d, &r, &w, &dw)) continue;
      const double V = p->mass[j] / p->rho[j];
      for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
          gv[a][b] += V * (p->vel[a][j] - p->vel[a][i]) * dw * d[b] / r;
          M[a][b] -= V * d[a] * dw * d[b] / r;
        }
    }
    double L[3][3] = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
    if (fp->gradient_correction) { /* Bonet and Lok: grad v = G M^-1 */
      oracle_inverse3(M, L);
      double c[3][3];
      for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
          c[a][b] = gv[a][0] * L[0][b] + gv[a][1] * L[1][b] + gv[a][2] * L[2][b];
      memcpy(gv, c, sizeof c);
    }
    const double div = gv[0][0] + gv[1][1] + gv[2][2], rho = p->rho[i];
    const double lam = fp->viscosity == SPH_VISCOSITY_STRESS_TENSOR ? fp->mu / (rho * rho) : 0.0;
    double eps[SPH_SYM], S[SPH_SYM];
    for (int a = 0; a < 3; a++)
      for (int b = a; b < 3; b++) {
        const int k = sph_sym_index(a, b);
        eps[k] = gv[a][b] + gv[b][a] - (a == b ? 2.0 / 3.0 * div : 0.0);
        S[k] = 0.5 * (eps[k] + (a == b ? 2.0 / 3.0 * div : 0.0));
        tau[6 * i + k] = lam * eps[k];
      }
    if (fp->sps) {
      double t[SPH_SYM];
      sph_sps_stress_sym(S, fp->sps_cs, fp->sps_ci, fp->sps_delta, t);
      for (int k = 0; k < SPH_SYM; k++)
        tau[6 * i + k] += t[k] / rho;
    }
    if (fp->gradient_correction) { /* the divergence with the corrected gradient: sym(tau L) */
      double c[3][3];
      for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
          c[a][b] = 0.0;
          for (int q = 0; q < 3; q++)
            c[a][b] += tau[6 * i + sph_sym_index(a, q)] * L[q][b];
        }
      for (int a = 0; a < 3; a++)
        for (int b = a; b < 3; b++)
          tau[6 * i + sph_sym_index(a, b)] = a == b ? c[a][a] : 0.5 * (c[a][b] + c[b][a]);
    }
  }
}

/* L_i = M_i^-1 at every particle (9 per particle, row-major), M over every neighbour as in
 * oracle_antuono_c (the identity where M is not invertible enough): the corrected gradient's
 * (Bonet and Lok 1999; numerics.gradient_correction). */
static void oracle_l3(const sph_particles *p, const sph_force_params *fp, double *l) {
  for (size_t i = 0; i < p->n; i++) {
    double M[3][3] = {{0.0}}, L[3][3];
    for (size_t j = 0; j < p->n; j++) {
      double d[3], r, w, dw;
      if (!oracle_pair(p, fp, i, j, d, &r, &w, &dw)) continue;
      const double V = p->mass[j] / p->rho[j];
      for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
          M[a][b] -= V * d[a] * dw * d[b] / r;
    }
    oracle_inverse3(M, L);
    memcpy(l + 9 * i, L, sizeof L);
  }
}

static void oracle3(const sph_particles *p, const sph_force_params *fp, double *out) {
  const double k = 0.5 * fp->eos.rho0 / (fp->eos.c0 * fp->eos.c0); /* Fourtakas' c = k g */
  double *ca = calloc(3 * p->n, sizeof *ca), *tau = calloc(6 * p->n, sizeof *tau);
  double *lc = calloc(9 * p->n, sizeof *lc);
  if (fp->diffusion == SPH_DIFFUSION_ANTUONO) oracle_antuono_c(p, fp, ca);
  if (fp->corrected_gradient) oracle_l3(p, fp, lc);
  const int stress = fp->viscosity == SPH_VISCOSITY_STRESS_TENSOR || fp->sps;
  if (stress) oracle_stress3(p, fp, tau);
  for (size_t i = 0; i < p->n; i++) {
    const double rhoi = p->rho[i], ci = sph_eos_sound_speed(&fp->eos, rhoi);
    const int fluid = p->kind[i] == SPH_KIND_FLUID; /* else a dynamic wall particle at rest */
    double drho = 0.0, a[3] = {fp->gx, fp->gy, fp->gz}, xs[3] = {0.0, 0.0, 0.0}, du = 0.0;
    if (!fluid) a[0] = a[1] = a[2] = 0.0;
    for (size_t j = 0; j < p->n; j++) {
      const int fj = p->kind[j] == SPH_KIND_FLUID;
      /* a wall particle: its continuity, diffusion and heat with fluid neighbours only */
      if (!fluid && !fj) continue;
      double d[3], v[3], g[3], r, w, dw;
      if (!oracle_pair(p, fp, i, j, d, &r, &w, &dw)) continue;
      const double h = oracle_h(p, fp, i, j);
      for (int q = 0; q < 3; q++)
        v[q] = p->vel[q][i] - p->vel[q][j], g[q] = dw * d[q] / r;
      const double mj = p->mass[j], rhoj = p->rho[j];
      /* the pressure's, its Pi_ij's and the continuity's gradient: with the correction
       * (L_i + L_j) / 2 grad_i W_ij */
      double cg[3] = {g[0], g[1], g[2]};
      if (fp->corrected_gradient)
        for (int q = 0; q < 3; q++) {
          cg[q] = 0.0;
          for (int b = 0; b < 3; b++)
            cg[q] += 0.5 * (lc[9 * i + 3 * q + b] + lc[9 * j + 3 * q + b]) * g[b];
        }
      const double vg = v[0] * cg[0] + v[1] * cg[1] + v[2] * cg[2];
      const double vr = v[0] * d[0] + v[1] * d[1] + v[2] * d[2];
      drho += mj * vg;
      /* walls diffuse with fluid when fp->wall_diffusion (solver/diffusion.h) */
      if (fp->diffusion != SPH_DIFFUSION_NONE && ((fluid && fj) || fp->wall_diffusion)) {
        double psi = 2.0 * (rhoj - rhoi);
        if (fp->diffusion == SPH_DIFFUSION_FOURTAKAS)
          psi += 2.0 * 2.0 * k * (fp->gx * d[0] + fp->gy * d[1] + fp->gz * d[2]);
        if (fp->diffusion == SPH_DIFFUSION_ANTUONO)
          for (int q = 0; q < 3; q++)
            psi += 2.0 * (ca[3 * i + q] + ca[3 * j + q]) * d[q];
        const double rji_gw = -(d[0] * g[0] + d[1] * g[1] + d[2] * g[2]);
        drho += fp->diffusion_delta * h * fp->eos.c0 * psi * rji_gw / (r * r) * mj / rhoj;
      }
      double P = p->p[i] / (rhoi * rhoi) + p->p[j] / (rhoj * rhoj);
      if (fp->riemann && fluid && fj) {
        const double jump =
            (p->p[i] - p->p[j]) - fp->eos.rho0 * (fp->gx * d[0] + fp->gy * d[1] + fp->gz * d[2]);
        drho += rhoi * mj / rhoj * jump * dw / (fp->eos.rho0 * fp->eos.c0); /* dW/dr */
      }
      if (fp->riemann) {
        const double closing = -vr / r, c0 = fp->eos.c0;
        const double beta = fmin(fp->riemann_limiter * fmax(closing, 0.0) / c0, 1.0);
        P = (p->p[i] + p->p[j] + beta * fp->eos.rho0 * c0 * closing) / (rhoi * rhoj);
      }
      if ((fp->alpha != 0.0 || fp->beta != 0.0) && vr < 0.0) {
        const double eta = fp->eta * h, mu = h * vr / (r * r + eta * eta);
        const double cbar = 0.5 * (ci + sph_eos_sound_speed(&fp->eos, rhoj));
        P += (-fp->alpha * cbar * mu + fp->beta * mu * mu) / (0.5 * (rhoi + rhoj));
      }
      for (int q = 0; q < 3; q++)
        a[q] -= mj * P * cg[q];
      du += 0.5 * mj * P * vg;
      if (stress) { /* A eq. 11's stress: m_j (tau_i / rho_i^2 + tau_j / rho_j^2) . grad_i W_ij */
        double t[3][3];
        for (int q = 0; q < 3; q++)
          for (int b = 0; b < 3; b++)
            t[q][b] = tau[6 * i + sph_sym_index(q, b)] + tau[6 * j + sph_sym_index(q, b)];
        for (int q = 0; q < 3; q++) {
          a[q] += mj * (t[q][0] * g[0] + t[q][1] * g[1] + t[q][2] * g[2]);
          for (int b = 0; b < 3; b++)
            du -= 0.5 * mj * t[q][b] * v[q] * g[b];
        }
      }
      if (fp->viscosity == SPH_VISCOSITY_MORRIS) {
        const double eta = fp->eta * h;
        const double c = mj * 4.0 * fp->mu / fp->eos.rho0 *
                         (d[0] * g[0] + d[1] * g[1] + d[2] * g[2]) /
                         ((rhoi + rhoj) * (r * r + eta * eta));
        for (int q = 0; q < 3; q++)
          a[q] += c * v[q];
        du -= 0.5 * c * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      }
      for (int q = 0; q < 3; q++)
        xs[q] -= fj ? mj / (0.5 * (rhoi + rhoj)) * v[q] * w : 0.0;
    }
    if (!fluid) a[0] = a[1] = a[2] = xs[0] = xs[1] = xs[2] = 0.0;
    double *o = out + 8 * (size_t)p->id[i];
    o[0] = drho;
    for (int q = 0; q < 3; q++)
      o[1 + q] = a[q], o[4 + q] = fp->xsph * xs[q];
    o[7] = du;
  }
  free(ca);
  free(tau);
  free(lc);
}

/* The oracle against the pass (the lane loop; the scalar loop agrees with it to 1e-11,
 * test_loops_agree) for seventeen term sets (the corrected gradient among them), both kernels, with
 * and without periodicity along y and dynamic wall particles, on a jittered block with random
 * velocities and densities: every rate within 1e-12 of the largest of its kind over the block. */
static void test_oracle(void) {
  const size_t n = (size_t)NL * NL * (NL + 2);
  double *ref = calloc(8 * n, sizeof *ref);
  for (int set = 0; set < 34; set++) {
    sph_force_params fp = params();
    fp.kernel = set % 2 ? SPH_KERNEL_WENDLAND_C2 : SPH_KERNEL_CUBIC_SPLINE;
    fp.gz = -G;
    fp.ledger = 1;
    /* sets 1-3 again on two layers of dynamic walls, and the last six term sets */
    const int walls = (set >= 12 && set < 18) || set >= 22;
    switch (set >= 12 && set < 18 ? set / 2 - 5 : set / 2) {
    case 9: fp.alpha = 0.1, fp.diffusion = SPH_DIFFUSION_ANTUONO; break;
    case 10: fp.alpha = 0.1, fp.viscosity = SPH_VISCOSITY_STRESS_TENSOR, fp.mu = 0.05; break;
    case 11:
      fp.viscosity = SPH_VISCOSITY_STRESS_TENSOR, fp.mu = 0.01, fp.sps = 1, fp.sps_cs = 0.12,
      fp.sps_ci = 0.00066, fp.sps_delta = DX, fp.xsph = 0.5;
      break;
    case 12:
      fp.alpha = 0.1, fp.viscosity = SPH_VISCOSITY_STRESS_TENSOR, fp.mu = 0.05;
      fp.gradient_correction = 1;
      break;
    case 13: /* per-particle h (the scalar loop), on walls */
      fp.alpha = 0.2, fp.beta = 0.4, fp.xsph = 0.5, fp.var_h = 1;
      fp.diffusion = SPH_DIFFUSION_FOURTAKAS, fp.viscosity = SPH_VISCOSITY_MORRIS, fp.mu = 0.02;
      break;
    case 14: /* the corrected gradient (its own moment pass), on walls */
      fp.alpha = 0.2, fp.xsph = 0.5, fp.corrected_gradient = 1;
      fp.diffusion = SPH_DIFFUSION_FOURTAKAS;
      break;
    case 15: /* the corrected gradient with the stress's (one L for both), on walls */
      fp.alpha = 0.1, fp.viscosity = SPH_VISCOSITY_STRESS_TENSOR, fp.mu = 0.05;
      fp.gradient_correction = 1, fp.corrected_gradient = 1;
      break;
    case 16: /* the corrected gradient with the stress uncorrected and per-particle h */
      fp.alpha = 0.1, fp.viscosity = SPH_VISCOSITY_STRESS_TENSOR, fp.mu = 0.05;
      fp.corrected_gradient = 1, fp.var_h = 1;
      break;
    case 0: fp.alpha = 0.3, fp.xsph = 0.5; break;
    case 1: fp.alpha = 0.2, fp.beta = 0.4, fp.diffusion = SPH_DIFFUSION_FOURTAKAS; break;
    case 2:
      fp.viscosity = SPH_VISCOSITY_MORRIS, fp.mu = 0.05, fp.diffusion = SPH_DIFFUSION_MOLTENI;
      break;
    case 3: fp.riemann = 1, fp.riemann_limiter = 3.0; break;
    case 4: fp.alpha = 0.3, fp.xsph = 0.5, fp.periodic = 1, fp.paxis = SPH_AXIS_Y; break;
    default:
      fp.riemann = 1, fp.riemann_limiter = 3.0, fp.diffusion = SPH_DIFFUSION_FOURTAKAS,
      fp.periodic = 1, fp.paxis = SPH_AXIS_Y;
      break;
    }
    if (fp.diffusion != SPH_DIFFUSION_NONE) fp.diffusion_delta = 0.1;
    if (fp.periodic) fp.period = NL * DX, fp.px0 = 0.0;
    sph_particles p;
    sph_error err;
    rng = 4242 + (unsigned long long)set;
    lattice(&p, 0.2, random_velocity);
    sph_particles_use(&p, SPH_ARRAYS_HEAT);
    for (int layer = 1; walls && layer <= 2; layer++) /* below the block, at rest */
      for (int j = 0; j < NL; j++)
        for (int i = 0; i < NL; i++) {
          const double x[3] = {i * DX, j * DX, -layer * DX}, v[3] = {0.0, 0.0, 0.0};
          CU_ASSERT_FATAL(sph_particles_add_at(&p, x, v, RHO0, RHO0 * DX * DX * DX, 1.3 * DX,
                                               SPH_KIND_WALL, &err) >= 0);
        }
    double hmax = fp.h;
    for (size_t i = 0; i < p.n; i++) {
      p.rho[i] = RHO0 * (1.0 + 0.01 * (2.0 * uniform() - 1.0));
      if (fp.var_h) p.h[i] = fp.h * (1.0 + 0.05 * (2.0 * uniform() - 1.0));
      hmax = fmax(hmax, p.h[i]);
    }
    fp.wall_diffusion = sph_diffusion_walls(&p, &fp);
    sph_grid g;
    sph_grid_init(&g);
    sph_nlist l;
    sph_nlist_init(&l);
    sph_force_work w;
    memset(&w, 0, sizeof w);
    const double cell = 2.0 * hmax * (1.0 + 1e-9);
    int rc = fp.periodic
                 ? sph_grid_build_periodic(&g, &p, cell, fp.paxis, 0.0, fp.period, 1u << 24, &err)
                 : sph_grid_build(&g, &p, cell, 1u << 24, &err);
    if (rc == 0) rc = sph_nlist_build(&l, &g, &p, 2.0 * hmax, 0.0, fp.period, &err);
    if (rc == 0) {
      sph_forces_pressure(&p, &fp.eos);
      rc = sph_forces_evaluate(&p, &l, &fp, &w, &err);
    }
    if (rc) printf("\n    %s", err.msg);
    CU_ASSERT_FATAL(rc == 0);
    oracle3(&p, &fp, ref);
    double mag[8] = {0.0}, worst[8] = {0.0};
    for (size_t i = 0; i < p.n; i++) {
      const double *o = ref + 8 * (size_t)p.id[i];
      const double got[8] = {p.drho[i],    p.ax[i],      p.ay[i],      p.az[i],
                             p.xsph[0][i], p.xsph[1][i], p.xsph[2][i], p.du[i]};
      for (int q = 0; q < 8; q++)
        mag[q] = fmax(mag[q], fabs(o[q])), worst[q] = fmax(worst[q], fabs(got[q] - o[q]));
    }
    double rel = 0.0;
    for (int q = 0; q < 8; q++)
      if (mag[q] > 0.0) rel = fmax(rel, worst[q] / mag[q]);
    printf("\n    set %d: largest difference from the oracle %.2g of the rate's largest", set, rel);
    CU_ASSERT(rel < 1e-12);
    CU_ASSERT(mag[0] > 0.0 && mag[1] > 0.0 && mag[7] > 0.0);
    sph_force_work_free(&w);
    sph_nlist_free(&l);
    sph_grid_free(&g);
    sph_particles_free(&p);
  }
  free(ref);
}

/* ---- each pair term in 3-D, from i's side and from j's -------------------------------- */

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }
static double between(double a, double b) { return a + (b - a) * uniform(); }

/* Random pairs within 2h in 3-D, every term evaluated with its inputs formed as a loop forms
 * them from i's side (x_i - x_j, v_i - v_j) and from j's: the forces exactly antisymmetric
 * (equal masses), the scalar terms (continuity, signal, Pi_ij, heats, Morris' factor, the
 * Riemann pressure) exactly symmetric, the diffusion's psi and the Riemann continuity term
 * antisymmetric; a free-slip wall's normal part antisymmetric and along the normal; and the
 * portable four-lane flavour gives v1's bits in each lane. */
static void test_pair_symmetry_3d(void) {
  rng = 777777;
  unsigned checked = 0;
  for (int t = 0; t < 2000; t++) {
    const double h = DX * between(1.0, 1.5), m = between(0.3, 0.5);
    double xi[3], xj[3], vi[3], vj[3], s[6];
    for (int a = 0; a < 3; a++) {
      xi[a] = between(0, 1), xj[a] = xi[a] + between(-1.2, 1.2) * h;
      vi[a] = between(-2, 2), vj[a] = between(-2, 2);
    }
    for (int a = 0; a < 6; a++)
      s[a] = between(-1, 1);
    const double rhoi = between(990, 1010), rhoj = between(990, 1010);
    const double ci = between(19, 21), cj = between(19, 21);
    vec_v1 rv, qv, dv, ev;
    for (int a = 0; a < 3; a++)
      rv.c[a] = xi[a] - xj[a], qv.c[a] = xj[a] - xi[a], dv.c[a] = vi[a] - vj[a],
      ev.c[a] = vj[a] - vi[a];
    const double r2 = SPH_NORM2(rv.c[0], rv.c[1], rv.c[2]),
                 q2 = SPH_NORM2(qv.c[0], qv.c[1], qv.c[2]);
    if (!(r2 < 4 * h * h) || r2 == 0) continue;
    CU_ASSERT(same_bits(r2, q2));
    const double inv_r2 = 1 / r2, r = sqrt(r2), inv_r = r * inv_r2, inv_h = 1 / h;
    const double sigma = sph_kernel_sigma(SPH_KERNEL_CUBIC_SPLINE, inv_h);
    double w, f;
    cubic_w_f_v1(r, inv_r, inv_h, sigma, sigma * inv_h, &w, &f);
    vec_v1 gv, hv;
    for (int a = 0; a < 3; a++)
      gv.c[a] = f * rv.c[a], hv.c[a] = f * qv.c[a];
    const double vr = dot_v1(dv, rv), ur = dot_v1(ev, qv);
    CU_ASSERT(same_bits(vr, ur));
    CU_ASSERT(same_bits(continuity_v1(m, dv, gv), continuity_v1(m, ev, hv)));
    CU_ASSERT(same_bits(signal_v1(h, vr, inv_r2), signal_v1(h, ur, inv_r2)));
    const double eta2 = 0.01 * h * h, irb = inv_rho_mean_v1(rhoi, rhoj);
    CU_ASSERT(same_bits(irb, inv_rho_mean_v1(rhoj, rhoi)));
    const double pi_ij = artificial_viscosity_v1(vr, h, r2, eta2, ci, cj, -0.08, 0.5, irb);
    const double pi_ji = artificial_viscosity_v1(ur, h, q2, eta2, cj, ci, -0.08, 0.5, irb);
    CU_ASSERT(same_bits(pi_ij, pi_ji));
    const double mp = m * ((s[0] + s[1]) + pi_ij), mq = m * ((s[1] + s[0]) + pi_ji);
    vec_v1 a = pressure_force_v1(mp, gv), b = pressure_force_v1(mq, hv);
    for (int q = 0; q < 3; q++)
      CU_ASSERT(same_bits(a.c[q], -b.c[q]));
    CU_ASSERT(same_bits(pressure_heat_v1(mp, dv, gv), pressure_heat_v1(mq, ev, hv)));
    sym_v1 tv, uv; /* tau_i + tau_j from either side */
    const double si[6] = {s[0], s[1], s[2], s[3], s[4], s[5]};
    const double sj[6] = {s[5], s[3], s[1], s[4], s[0], s[2]};
    for (int k = 0; k < 6; k++)
      tv.c[k] = si[k] + sj[k], uv.c[k] = sj[k] + si[k];
    a = stress_force_v1(m, tv, gv);
    b = stress_force_v1(m, uv, hv);
    for (int q = 0; q < 3; q++)
      CU_ASSERT(same_bits(a.c[q], -b.c[q]));
    CU_ASSERT(same_bits(stress_heat_v1(m, tv, dv, gv), stress_heat_v1(m, uv, ev, hv)));
    const double c = morris_factor_v1(m, 2e-4, f, r2, rhoi, rhoj, eta2);
    CU_ASSERT(same_bits(c, morris_factor_v1(m, 2e-4, f, q2, rhoj, rhoi, eta2)));
    CU_ASSERT(same_bits(morris_heat_v1(c, dv), morris_heat_v1(c, ev)));
    const double xf = xsph_factor_v1(m, irb, w);
    for (int q = 0; q < 3; q++)
      CU_ASSERT(same_bits(xf * dv.c[q], -(xf * ev.c[q])) && same_bits(c * dv.c[q], -(c * ev.c[q])));
    const double lj = lennard_jones_v1(5.0, 1.2 * h, r2);
    CU_ASSERT(same_bits(lj, lennard_jones_v1(5.0, 1.2 * h, q2)));
    { /* a free-slip wall's normal part: antisymmetric, along the normal */
      const vec_v1 mv = {{s[2] * DX, s[3] * DX, s[4] * DX}};
      const vec_v1 n = normal_part_v1(gv, mv), o = normal_part_v1(hv, mv);
      double cross = 0.0;
      for (int q = 0; q < 3; q++) {
        CU_ASSERT(same_bits(n.c[q], -o.c[q]));
        const double cq =
            n.c[(q + 1) % 3] * mv.c[(q + 2) % 3] - n.c[(q + 2) % 3] * mv.c[(q + 1) % 3];
        cross = fmax(cross, fabs(cq));
      }
      CU_ASSERT(cross <= 1e-12 * sqrt(dot_v1(gv, gv) * dot_v1(mv, mv)));
    }
    { /* the Riemann pressure symmetric, its continuity term antisymmetric */
      const double z0 = 1000.0 * 20.0, kc = 3.0 / 20.0, pi_ = s[4] * 1e4, pj_ = s[5] * 1e4;
      const double P = riemann_pressure_v1(pi_, pj_, rhoi, rhoj, -vr * inv_r, z0, kc);
      CU_ASSERT(same_bits(P, riemann_pressure_v1(pj_, pi_, rhoj, rhoi, -ur * inv_r, z0, kc)));
      const double d = riemann_density_v1(rhoi, m, rhoi, pi_ - pj_, f, r, 1 / z0);
      CU_ASSERT(same_bits(d, -riemann_density_v1(rhoi, m, rhoi, pj_ - pi_, f, r, 1 / z0)));
    }
    const vec_v1 cc = {{s[0] * 1e3, s[1] * 1e3, s[2] * 1e3}}; /* c_i + c_j of the diffusion */
    CU_ASSERT(
        same_bits(diffusion_psi_v1(rhoi, rhoj, rv, cc), -diffusion_psi_v1(rhoj, rhoi, qv, cc)));
    /* the four-lane flavour: scaled copies of the pair in its lanes, v1's bits in each */
    const double k4[4] = {1.0, 0.9, 0.8, 0.7};
    vec_v4e g4, d4;
    for (int q = 0; q < 3; q++) {
      g4.c[q] = v4e_set(gv.c[q] * k4[0], gv.c[q] * k4[1], gv.c[q] * k4[2], gv.c[q] * k4[3]);
      d4.c[q] = v4e_set(dv.c[q] * k4[0], dv.c[q] * k4[1], dv.c[q] * k4[2], dv.c[q] * k4[3]);
    }
    const v4e m4 = v4e_set(m * k4[0], m * k4[1], m * k4[2], m * k4[3]);
    double cont[4], heat[4];
    v4e_store(cont, continuity_v4e(m4, d4, g4));
    v4e_store(heat, pressure_heat_v4e(m4, d4, g4));
    for (int q = 0; q < 4; q++) {
      vec_v1 gq, dq;
      for (int a2 = 0; a2 < 3; a2++)
        gq.c[a2] = gv.c[a2] * k4[q], dq.c[a2] = dv.c[a2] * k4[q];
      CU_ASSERT(same_bits(cont[q], continuity_v1(m * k4[q], dq, gq)));
      CU_ASSERT(same_bits(heat[q], pressure_heat_v1(m * k4[q], dq, gq)));
    }
    checked++;
  }
  printf("\n    %u pairs within 2h: every term symmetric or antisymmetric bit for bit", checked);
  CU_ASSERT(checked > 1000);
}

static double linear_rho(const double x[3]) {
  return RHO0 * (1.0 + 0.3 * x[0] - 0.2 * x[1] + 0.5 * x[2]);
}

static void test_filters(void) {
  for (int mls = 0; mls < 2; mls++) {
    sph_particles p;
    lattice(&p, 0.2, NULL);
    for (size_t i = 0; i < p.n; i++) {
      const double x[3] = {p.x[i], p.y[i], p.z[i]};
      p.rho[i] = mls ? linear_rho(x) : 1.02 * RHO0;
      p.mass[i] = p.rho[i] * DX * DX * DX; /* any volumes: V = m / rho */
    }
    sph_grid g;
    sph_grid_init(&g);
    sph_error err;
    CU_ASSERT_FATAL(sph_grid_build(&g, &p, 2.6 * DX * (1.0 + 1e-9), 1u << 24, &err) == 0);
    sph_filter_params fp;
    sph_filter_params_default(&fp, 1.3 * DX);
    double *scratch = malloc(p.n * sizeof *scratch);
    size_t fallbacks = 0;
    const int rc = mls ? sph_filter_mls(&p, &g, &fp, scratch, &fallbacks, &err)
                       : sph_filter_shepard(&p, &g, &fp, scratch, &fallbacks, &err);
    CU_ASSERT_FATAL(rc == 0);
    double worst = 0.0;
    for (size_t i = 0; i < p.n; i++) {
      const double x[3] = {p.x[i], p.y[i], p.z[i]};
      const double want = mls ? linear_rho(x) : 1.02 * RHO0;
      if (mls || inside(&p, i)) worst = fmax(worst, fabs(p.rho[i] / want - 1.0));
    }
    printf("\n    %s: largest error %.2g, %zu fallbacks", mls ? "MLS" : "Shepard", worst,
           fallbacks);
    CU_ASSERT(worst < 1e-9);
    CU_ASSERT_EQUAL(fallbacks, 0);
    free(scratch);
    sph_grid_free(&g);
    sph_particles_free(&p);
  }
}

/* One particle per integrator stage, twice: state (a, b, c) and (c, b, a). */
static void test_integrators(void) {
  const sph_eos eos = sph_eos_tait(RHO0, C0);
  for (int scheme = 0; scheme < 3; scheme++) {
    sph_particles p;
    sph_error err;
    CU_ASSERT_FATAL(sph_particles_init(&p, 4, &err) == 0);
    const double x[2][3] = {{0.1, 0.2, 0.7}, {0.7, 0.2, 0.1}};
    const double v[2][3] = {{1.5, -0.25, 3.0}, {3.0, -0.25, 1.5}};
    const double a[2][3] = {{0.3, 0.0, -9.81}, {-9.81, 0.0, 0.3}};
    const double xs[2][3] = {{0.01, 0.02, -0.03}, {-0.03, 0.02, 0.01}};
    for (int k = 0; k < 2; k++) {
      sph_particles_add_at(&p, x[k], v[k], 1001.0, 1.0, 0.013, SPH_KIND_FLUID, &err);
      for (int d = 0; d < 3; d++)
        p.acc[d][k] = a[k][d], p.xsph[d][k] = xs[k][d];
      p.drho[k] = 0.5;
    }
    const size_t cost[3] = {0, 1, 2};
    for (int step = 0; step < 3; step++)
      if (scheme == 0) {
        sph_pc_half(&p, 1e-3, 1, &eos, cost);
        sph_pc_finish(&p, 1e-3, 1, &eos, cost);
      } else {
        sph_leapfrog_step(&p, 1e-3, 1e-3, step == 0, scheme == 2, &eos, cost);
      }
    for (int d = 0; d < 3; d++) {
      CU_ASSERT_EQUAL(p.pos[d][0], p.pos[2 - d][1]);
      CU_ASSERT_EQUAL(p.vel[d][0], p.vel[2 - d][1]);
    }
    CU_ASSERT(p.z[0] != x[0][2] && p.vz[0] != v[0][2]); /* z moved */
    CU_ASSERT_EQUAL(p.rho[0], p.rho[1]);
    sph_particles_free(&p);
  }
  /* the CFL step: c + |v| with |v| = 5 from (0, 0, 5) */
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 4, &err) == 0);
  const double x[3] = {0.0, 0.0, 0.0}, v[3] = {0.0, 0.0, 5.0};
  sph_particles_add_at(&p, x, v, RHO0, 1.0, 0.01, SPH_KIND_FLUID, &err);
  CU_ASSERT_DOUBLE_EQUAL(sph_dt_cfl(&p, &eos, 0.01, 0.3), 0.3 * 0.01 / (C0 + 5.0), 1e-15);
  sph_particles_free(&p);
}

/* The rates of fp on the jittered block of rates() whose three lowest
 * layers are dynamic wall particles at rest, with the list's wall rows
 * holding every neighbour or (fluid_only) their fluid ones only
 * (grid.h, wall_fluid_only); *entries: the list's entries; *wall_walls:
 * wall neighbours listed in wall rows. */
static void wall_rates(sph_force_params fp, int fluid_only, double *out, size_t *entries,
                       size_t *wall_walls) {
  sph_particles p;
  rng = 4242;
  lattice(&p, 0.2, random_velocity);
  for (size_t i = 0; i < p.n; i++) {
    p.rho[i] = RHO0 * (1.0 + 0.01 * (2.0 * uniform() - 1.0));
    if (p.z[i] < 2.5 * DX) {
      p.kind[i] = SPH_KIND_WALL;
      for (int d = 0; d < 3; d++)
        p.vel[d][i] = 0.0;
    }
  }
  sph_grid g;
  sph_grid_init(&g);
  sph_nlist l;
  sph_nlist_init(&l);
  l.wall_fluid_only = fluid_only;
  sph_error err;
  sph_force_work w;
  memset(&w, 0, sizeof w);
  CU_ASSERT_FATAL(sph_grid_build(&g, &p, 2.0 * fp.h * (1.0 + 1e-9), 1u << 24, &err) == 0);
  CU_ASSERT_FATAL(sph_nlist_build(&l, &g, &p, 2.0 * fp.h, 0.0, 0.0, &err) == 0);
  const char *bad = sph_nlist_check(&l, &p, 2.0 * fp.h);
  CU_ASSERT_PTR_NULL(bad);
  if (bad) printf("\n    %s", bad);
  *entries = *wall_walls = 0;
  uint32_t *row = malloc((l.maxcount + SPH_NLIST_SLACK) * sizeof *row);
  CU_ASSERT_FATAL(row != NULL);
  for (size_t i = 0; i < p.n; i++) {
    const uint32_t c = sph_nlist_decode(&l, i, row);
    *entries += c;
    for (uint32_t k = 0; k < c && p.kind[i] == SPH_KIND_WALL; k++)
      *wall_walls += p.kind[row[k]] == SPH_KIND_WALL;
  }
  free(row);
  sph_forces_pressure(&p, &fp.eos);
  CU_ASSERT_FATAL(sph_forces_evaluate(&p, &l, &fp, &w, &err) == 0);
  for (size_t i = 0; i < p.n; i++) {
    const size_t k = (size_t)p.id[i] * 9;
    out[k] = p.drho[i];
    for (int d = 0; d < 3; d++)
      out[k + 1 + d] = p.acc[d][i], out[k + 4 + d] = p.xsph[d][i];
    out[k + 7] = fp.ledger ? p.du[i] : 0.0;
    out[k + 8] = p.kind[i];
  }
  sph_force_work_free(&w);
  sph_nlist_free(&l);
  sph_grid_free(&g);
  sph_particles_free(&p);
}

/* Wall rows with their fluid neighbours only (what sim.c picks for
 * dynamic walls at rest in 3-D): every fluid particle's rates the same
 * bits (its row is the same), every wall particle's within round-off (its
 * sums lose only +-0 terms, added in other lanes), for two term sets and
 * each loop; the wall rows hold no walls and the list is shorter. */
static void test_wall_rows_fluid(void) {
  const size_t n = (size_t)NL * NL * NL * 9;
  double *ref = calloc(n, sizeof *ref), *got = calloc(n, sizeof *got);
  CU_ASSERT_FATAL(ref && got);
  const sph_force_loop loops[3] = {SPH_LOOP_AUTO, SPH_LOOP_SCALAR, SPH_LOOP_LANES};
  for (int set = 0; set < 3; set++)
    for (int q = 0; q < 3; q++) {
      sph_force_params fp = params();
      fp.gz = -G;
      fp.loop = loops[q];
      fp.wall_diffusion = 1;
      if (set == 0 || set == 2)
        fp.alpha = 0.2, fp.xsph = 0.5, fp.diffusion = SPH_DIFFUSION_FOURTAKAS,
        fp.diffusion_delta = 0.1;
      if (set == 2)
        fp.ledger = 1; /* a wall's heat: its pairs with fluid only */
      else
        fp.viscosity = SPH_VISCOSITY_MORRIS, fp.mu = 1e-3, fp.diffusion = SPH_DIFFUSION_MOLTENI,
        fp.diffusion_delta = 0.1;
      size_t e_all, e_fluid, ww_all, ww_fluid;
      wall_rates(fp, 0, ref, &e_all, &ww_all);
      wall_rates(fp, 1, got, &e_fluid, &ww_fluid);
      CU_ASSERT(ww_all > 0 && ww_fluid == 0 && e_fluid + ww_all == e_all);
      double worst = 0.0, mag = 0.0;
      size_t walls = 0, fluid_differs = 0;
      double heat = 0.0, hworst = 0.0; /* the largest wall heat rate, and its change */
      for (size_t i = 0; i < n; i += 9) {
        if (ref[i + 8] == SPH_KIND_FLUID) {
          fluid_differs += memcmp(ref + i, got + i, 9 * sizeof *ref) != 0;
          continue;
        }
        walls++;
        for (int k = 0; k < 7; k++)
          worst = fmax(worst, fabs(got[i + k] - ref[i + k]));
        mag = fmax(mag, fabs(ref[i])); /* a wall's drho: its fluid neighbours' */
        heat = fmax(heat, fabs(ref[i + 7]));
        hworst = fmax(hworst, fabs(got[i + 7] - ref[i + 7]));
      }
      CU_ASSERT(walls > 0 && mag > 0.0);
      CU_ASSERT(set != 2 || heat > 0.0);
      CU_ASSERT(hworst <= 1e-12 * heat);
      CU_ASSERT_EQUAL(fluid_differs, 0);
      CU_ASSERT(worst <= 1e-12 * mag);
      if (worst > 1e-12 * mag || hworst > 1e-12 * heat || fluid_differs)
        printf("\n    set %d loop %d: walls off by %.3g of %.3g (heat %.3g of %.3g), %zu fluid "
               "rates differ",
               set, (int)loops[q], worst, mag, hworst, heat, fluid_differs);
    }
  free(ref);
  free(got);
}

int main(void) {
  CU_TestInfo tests[] = {
      {"3x3 symmetric inverse and product; SPS of a shear in 3-D", test_tensors},
      {"3-D lattice at rest: gravity alone, no density change", test_rest},
      {"3-D continuity of a linear field along each axis", test_continuity},
      {"3-D hydrostatic lattice: pressure balances gravity along z", test_hydrostatic},
      {"3-D strain rate with the gradient correction: exact for linear fields", test_strain_rate},
      {"3-D momentum sums to zero; the ledger's heat balances the work", test_balances},
      {"3-D scalar, lane flavours, run-time loop and thread counts agree", test_loops_agree},
      {"3-D integrators move along z as along x, bit for bit", test_integrators},
      {"3-D pass against an all-pairs oracle from the equations (seventeen term sets)",
       test_oracle},
      {"3-D pair terms from i's side and from j's: symmetric, antisymmetric, lanes = v1",
       test_pair_symmetry_3d},
      {"3-D periodic along y and z: the rates of periodic along x, axes exchanged",
       test_periodic_axes},
      {"3-D MLS filter: exact for a linear density; Shepard for a uniform one", test_filters},
      {"3-D wall rows with fluid neighbours only: fluid the same bits, walls within round-off",
       test_wall_rows_fluid},
      CU_TEST_INFO_NULL};
  return sph_test_main("forces_3d", tests);
}
