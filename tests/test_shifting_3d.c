/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_shifting_3d.c - particle shifting in 3-D (src/physics/shifting.h,
 * built with -DSPH_DIM=3 and linked with src/libsph3.la) on small cubic
 * lattices, against what its formulas give by hand, as test_shifting.c does
 * in 2-D:
 *   - inside a cubic lattice the concentration gradient vanishes (to 1e-9
 *     of a neighbour's share) and div r is 3 within 3 %: no move;
 *   - a particle moved 0.3 dx toward its neighbour along x is moved back
 *     along x, its neighbour away, nothing along y or z; the move is
 *     -A h |v| dt grad C exactly, and none at rest;
 *   - on the free surface (the top layer of a block on a floor of wall
 *     particles: div r < 2.75) only the part along the surface is kept: the
 *     undisturbed top layer does not move, where without the correction it
 *     would be pushed up, out of the fluid; a top particle moved along y
 *     goes back along y with no part along its normal;
 *   - wall particles count: the first layer above three layers of wall
 *     particles on the fluid's lattice is not a surface (div r >= 2.75) and
 *     does not move; without the walls it is a surface;
 *   - periodic along y, a block's sums are those of the middle of a block
 *     three times as long (the minimum image along y);
 *   - sph_shifting_compute moves fluid particles only, as the per-particle
 *     functions do, and gives the same bits on one thread and two.
 * The energy ledger books the moves of a 3-D run (test_energy_3d).
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/particles.h"
#include "neighbours/grid.h"
#include "physics/kernel.h"
#include "physics/shifting.h"
#include "testutil.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#if SPH_DIM != 3
#error "test_shifting_3d is built with -DSPH_DIM=3"
#endif

#define DX 0.01
#define RHO 1000.0
#define H (1.3 * DX)

typedef struct lattice {
  sph_particles p;
  sph_grid g;
  sph_nlist l;
  sph_shifting_params sp;
  int nx, ny;
} lattice;

static void add(lattice *L, double x, double y, double z, const double v[3], int32_t k) {
  sph_error err;
  const double pos[3] = {x, y, z};
  CU_ASSERT_FATAL(sph_particles_add_at(&L->p, pos, v, RHO, RHO * DX * DX * DX, H, k, &err) >= 0);
}

/* A block of nx x ny x nz fluid particles at ((i + 1/2) dx, (j + 1/2) dx,
 * (k + 1/2) dx) moving at v (ids i + nx (j + ny k)), with `walls` layers of
 * wall particles below z = 0 on the same lattice (reaching 3 columns beyond
 * the block along x and, unless the block is periodic along y, along y). */
static void make(lattice *L, int nx, int ny, int nz, int walls, int periodic_y, const double v[3]) {
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&L->p, 4096, &err) == 0);
  for (int k = 0; k < nz; k++)
    for (int j = 0; j < ny; j++)
      for (int i = 0; i < nx; i++)
        add(L, (i + 0.5) * DX, (j + 0.5) * DX, (k + 0.5) * DX, v, SPH_KIND_FLUID);
  const double rest[3] = {0.0, 0.0, 0.0};
  const int wy = periodic_y ? 0 : 3;
  for (int k = 0; k < walls; k++)
    for (int j = -wy; j < ny + wy; j++)
      for (int i = -3; i < nx + 3; i++)
        add(L, (i + 0.5) * DX, (j + 0.5) * DX, -(k + 0.5) * DX, rest, SPH_KIND_WALL);
  L->sp = (sph_shifting_params){SPH_SHIFTING_COEFFICIENT_DEFAULT, H, DX, SPH_KERNEL_CUBIC_SPLINE};
  L->nx = nx;
  L->ny = ny;
}

/* The grid and neighbour list of the particles' current positions,
 * periodic along y over [0, ny dx) if asked. */
static void build(lattice *L, int periodic_y) {
  sph_error err;
  const double cell = SPH_CUBIC_SUPPORT * H * (1.0 + 1e-9), py = L->ny * DX;
  sph_grid_init(&L->g);
  sph_nlist_init(&L->l);
  const int rc =
      periodic_y ? sph_grid_build_periodic(&L->g, &L->p, cell, SPH_AXIS_Y, 0.0, py, 1u << 24, &err)
                 : sph_grid_build(&L->g, &L->p, cell, 1u << 24, &err);
  CU_ASSERT_FATAL(rc == 0);
  CU_ASSERT_FATAL(sph_nlist_build(&L->l, &L->g, &L->p, cell, 0.0, periodic_y ? py : 0.0, &err) ==
                  0);
}

static void drop(lattice *L) {
  sph_nlist_free(&L->l);
  sph_grid_free(&L->g);
  sph_particles_free(&L->p);
}

/* The storage index of the particle with id k (the grid sorts the store). */
static size_t at(const lattice *L, int64_t k) {
  for (size_t i = 0; i < L->p.n; i++)
    if (L->p.id[i] == k) return i;
  CU_FAIL_FATAL("no such particle");
  return 0;
}

static int64_t id_of(const lattice *L, int i, int j, int k) {
  return (int64_t)i + (int64_t)L->nx * ((int64_t)j + (int64_t)L->ny * k);
}

/* A neighbour's share of grad C: V |grad W| at r = dx. */
static double share(void) {
  double w, dw;
  sph_kernel_w_dw(SPH_KERNEL_CUBIC_SPLINE, DX, H, &w, &dw);
  return DX * DX * DX * fabs(dw);
}

static double norm(const double v[3]) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

static void test_interior_still(void) {
  lattice L;
  make(&L, 9, 9, 9, 0, 0, (double[3]){1.0, 0.0, 0.0});
  build(&L, 0);
  sph_shifting_sums s;
  sph_shifting_sums_of(&L.p, &L.l, &L.sp, at(&L, id_of(&L, 4, 4, 4)), &s);
  printf("\n  interior: |grad C| %.2e of a neighbour's share, div r %.4f", norm(s.tg) / share(),
         s.div);
  CU_ASSERT(norm(s.g) <= 1e-9 * share());
  CU_ASSERT(norm(s.tg) <= 1e-9 * share());
  CU_ASSERT(fabs(s.div - 3.0) <= 0.09);
  double d[3];
  sph_shifting_displacement(&s, SPH_SHIFTING_COEFFICIENT_DEFAULT * H * 1e-4, d);
  CU_ASSERT(norm(d) <= 1e-12 * DX);
  drop(&L);
}

static void test_clump_pushed_apart(void) {
  lattice L;
  make(&L, 9, 9, 9, 0, 0, (double[3]){0.6, 0.0, 0.8}); /* |v| = 1 m/s */
  const int64_t c0 = id_of(&L, 4, 4, 4);
  L.p.x[c0] += 0.3 * DX; /* toward its neighbour along x */
  build(&L, 0);
  const size_t c = at(&L, c0), r = at(&L, c0 + 1);
  const double dt = 1e-4, D = SPH_SHIFTING_COEFFICIENT_DEFAULT * H * dt;
  sph_shifting_compute(&L.p, &L.l, &L.sp, dt, L.p.acc);
  const double mc[3] = {L.p.ax[c], L.p.ay[c], L.p.az[c]};
  const double mr[3] = {L.p.ax[r], L.p.ay[r], L.p.az[r]};
  printf("\n  clumped pair: moves %.3e, %.3e dx along x; %.1e, %.1e dx across", mc[0] / DX,
         mr[0] / DX, hypot(mc[1], mc[2]) / DX, hypot(mr[1], mr[2]) / DX);
  CU_ASSERT(mc[0] < -1e-4 * DX);
  CU_ASSERT(mr[0] > 1e-4 * DX);
  CU_ASSERT(hypot(mc[1], mc[2]) <= 1e-9 * fabs(mc[0])); /* along the line of the pair */
  sph_shifting_sums s;
  sph_shifting_sums_of(&L.p, &L.l, &L.sp, c, &s);
  CU_ASSERT(s.div >= SPH_SHIFTING_SURFACE_DIV);
  for (int a = 0; a < 3; a++)
    CU_ASSERT(mc[a] == -D * s.tg[a]);  /* -A h |v| dt grad C, bit for bit */
  CU_ASSERT(fabs(s.tgx) > fabs(s.gx)); /* Lind's term pushes harder */
  L.p.vx[c] = L.p.vz[c] = 0.0;
  sph_shifting_compute(&L.p, &L.l, &L.sp, dt, L.p.acc);
  CU_ASSERT(L.p.ax[c] == 0.0 && L.p.ay[c] == 0.0 && L.p.az[c] == 0.0);
  drop(&L);
}

static void test_surface_tangential(void) {
  lattice L;
  make(&L, 11, 11, 5, 3, 0, (double[3]){1.0, 0.0, 0.0});
  const int64_t top = id_of(&L, 5, 3, 4), side = id_of(&L, 5, 7, 4);
  L.p.y[side] -= 0.3 * DX; /* toward its neighbour along y, in the top layer */
  build(&L, 0);
  const double D = SPH_SHIFTING_COEFFICIENT_DEFAULT * H * 1e-4;
  sph_shifting_sums s;
  double d[3];
  sph_shifting_sums_of(&L.p, &L.l, &L.sp, at(&L, top), &s);
  printf("\n  top layer: div r %.3f", s.div);
  CU_ASSERT(s.div < SPH_SHIFTING_SURFACE_DIV);
  sph_shifting_displacement(&s, D, d);
  CU_ASSERT(norm(d) <= 1e-12 * DX);
  sph_shifting_sums bulk = s; /* without the correction: pushed up, out */
  bulk.div = 3.0;
  sph_shifting_displacement(&bulk, D, d);
  printf(", uncorrected move up %.3e dx", d[2] / DX);
  CU_ASSERT(d[2] > 1e-5 * DX);
  sph_shifting_sums_of(&L.p, &L.l, &L.sp, at(&L, side), &s);
  CU_ASSERT(s.div < SPH_SHIFTING_SURFACE_DIV);
  sph_shifting_displacement(&s, D, d);
  const double g = norm(s.g);
  const double along_n = -(d[0] * s.gx + d[1] * s.gy + d[2] * s.gz) / g;
  printf(", moved top particle: %.3e dx back along y, %.1e dx normal", d[1] / DX, along_n / DX);
  CU_ASSERT(d[1] > 1e-5 * DX);
  CU_ASSERT(fabs(along_n) <= 1e-12 * norm(d));
  drop(&L);
}

static void test_walls_count(void) {
  for (int walls = 0; walls <= 3; walls += 3) {
    lattice L;
    make(&L, 9, 9, 6, walls, 0, (double[3]){1.0, 0.0, 0.0});
    build(&L, 0);
    sph_shifting_sums s;
    sph_shifting_sums_of(&L.p, &L.l, &L.sp, at(&L, id_of(&L, 4, 4, 0)), &s);
    double d[3];
    sph_shifting_displacement(&s, SPH_SHIFTING_COEFFICIENT_DEFAULT * H * 1e-4, d);
    printf("\n  first layer, %d wall layers: div r %.3f, |grad C| %.2e of a share", walls, s.div,
           norm(s.tg) / share());
    if (walls) {
      CU_ASSERT(s.div >= SPH_SHIFTING_SURFACE_DIV);
      CU_ASSERT(norm(s.tg) <= 1e-9 * share());
      CU_ASSERT(norm(d) <= 1e-12 * DX);
    } else {
      CU_ASSERT(s.div < SPH_SHIFTING_SURFACE_DIV);
    }
    drop(&L);
  }
}

/* Periodic along y over `ny` dx: every particle's sums are those of the
 * middle third of a block 3 ny dx long, to round-off. */
static void periodic_y(int ny) {
  lattice P, B;
  const double v[3] = {1.0, 0.0, 0.0};
  make(&P, 7, ny, 5, 2, 1, v);
  make(&B, 7, 3 * ny, 5, 2, 0, v);
  for (size_t i = 0; i < P.p.n; i++) /* the same disorder in each period */
    P.p.x[i] += 0.1 * DX * sin(3.1 * P.p.z[i] / DX + 2.0 * M_PI * P.p.y[i] / (ny * DX));
  for (size_t i = 0; i < B.p.n; i++)
    B.p.x[i] += 0.1 * DX * sin(3.1 * B.p.z[i] / DX + 2.0 * M_PI * B.p.y[i] / (ny * DX));
  build(&P, 1);
  build(&B, 0);
  double worst = 0.0;
  size_t compared = 0;
  for (int k = 0; k < 5; k++)
    for (int j = 0; j < ny; j++)
      for (int i = 0; i < 7; i++) {
        sph_shifting_sums sp, sb;
        sph_shifting_sums_of(&P.p, &P.l, &P.sp, at(&P, id_of(&P, i, j, k)), &sp);
        sph_shifting_sums_of(&B.p, &B.l, &B.sp, at(&B, id_of(&B, i, j + ny, k)), &sb);
        for (int a = 0; a < 3; a++) {
          const double e = fabs(sp.tg[a] - sb.tg[a]) / share();
          if (e > worst) worst = e;
        }
        const double e = fabs(sp.div - sb.div);
        if (e > worst) worst = e;
        compared++;
      }
  printf("\n  periodic along y over %d dx (%ld cells): %zu particles, largest difference %.1e (of "
         "a share; div r)",
         ny, P.g.ncell[0], compared, worst);
  CU_ASSERT(compared == (size_t)(35 * ny));
  CU_ASSERT(P.g.ncell[0] == (ny >= 8 ? 3 : 2));
  CU_ASSERT(worst <= 1e-12);
  drop(&P);
  drop(&B);
}

/* Over 8 dx (three cells of the grid) and over 6 dx (two: the shortest
 * period the grid takes, every row walked whole). */
static void test_periodic_y(void) {
  periodic_y(8);
  periodic_y(6);
}

static void test_fluid_only_threads(void) {
  lattice L;
  make(&L, 8, 8, 8, 3, 0, (double[3]){1.0, 0.5, -0.5});
  for (size_t i = 0; i < L.p.n; i++) { /* a disordered block */
    L.p.x[i] += 0.2 * DX * sin(12.9898 * (double)i);
    L.p.y[i] += 0.2 * DX * sin(78.233 * (double)i);
    L.p.z[i] += 0.2 * DX * sin(37.719 * (double)i);
  }
  build(&L, 0);
  const size_t n = L.p.n;
  double *one[3];
  for (int a = 0; a < 3; a++)
    one[a] = malloc(n * sizeof *one[a]);
#ifdef _OPENMP
  omp_set_num_threads(1);
#endif
  sph_shifting_compute(&L.p, &L.l, &L.sp, 1e-4, one);
#ifdef _OPENMP
  omp_set_num_threads(2);
#endif
  sph_shifting_compute(&L.p, &L.l, &L.sp, 1e-4, L.p.acc);
  size_t moved = 0, wrong = 0, threads = 0;
  const double D = SPH_SHIFTING_COEFFICIENT_DEFAULT * H * 1e-4 * sqrt(1.5);
  for (size_t i = 0; i < n; i++) {
    for (int a = 0; a < 3; a++)
      threads += one[a][i] != L.p.acc[a][i];
    if (L.p.kind[i] != SPH_KIND_FLUID) {
      wrong += L.p.ax[i] != 0.0 || L.p.ay[i] != 0.0 || L.p.az[i] != 0.0;
      continue;
    }
    sph_shifting_sums s;
    double d[3];
    sph_shifting_sums_of(&L.p, &L.l, &L.sp, i, &s);
    sph_shifting_displacement(&s, D, d);
    wrong += d[0] != L.p.ax[i] || d[1] != L.p.ay[i] || d[2] != L.p.az[i];
    moved += L.p.ax[i] != 0.0;
  }
  printf("\n  %zu of 512 fluid particles moved, %zu differ from the per-particle functions, %zu "
         "components between one thread and two",
         moved, wrong, threads);
  CU_ASSERT_EQUAL(wrong, 0);
  CU_ASSERT_EQUAL(threads, 0);
  CU_ASSERT(moved > 400);
  for (int a = 0; a < 3; a++)
    free(one[a]);
  drop(&L);
}

int main(void) {
  CU_TestInfo tests[] = {
      {"3-D: inside a lattice nothing moves, div r = 3", test_interior_still},
      {"3-D: a clumped pair is pushed apart, -A h |v| dt grad C", test_clump_pushed_apart},
      {"3-D: on the free surface only along it", test_surface_tangential},
      {"3-D: wall particles count: the first layer is no surface", test_walls_count},
      {"3-D: periodic along y = the middle of a long block", test_periodic_y},
      {"3-D: fluid particles only, as the per-particle functions, any thread count",
       test_fluid_only_threads},
      CU_TEST_INFO_NULL};
  return sph_test_main("shifting_3d", tests);
}
