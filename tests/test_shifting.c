/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_shifting.c - particle shifting (src/physics/shifting.h) on small
 * lattices, against what its formulas give by hand:
 *   - inside a square lattice the concentration gradient vanishes (to
 *     1e-9 of a neighbour's share) and div r is 2 within 3 %: no move;
 *   - a particle moved 0.3 dx toward its right neighbour is moved back
 *     (left, along the line of the pair), its neighbour away (right); the
 *     move is -A h |v| dt grad C exactly: twice the step, twice the move,
 *     and none at rest;
 *   - on the free surface (the top row of a block: div r < 1.5) only the
 *     part along the surface is kept: a surface particle moved sideways is
 *     moved back sideways, with no part along its normal, where without
 *     the correction it would be pushed out of the fluid;
 *   - wall particles count: the first row above three layers of wall
 *     particles on the fluid's lattice is not a surface (div r >= 1.5) and
 *     is not moved, where without the walls it would be a surface;
 *   - sph_shifting_compute moves fluid particles only, as the per-particle
 *     functions do.
 * Whole runs: tests/test_walls.c (the run-up), test_energy.c (the ledger
 * books the moves), test_determinism.c and test_restart.c (bitwise).
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

#define DX 0.01
#define RHO 1000.0
#define H (1.3 * DX)

typedef struct lattice {
  sph_particles p;
  sph_grid g;
  sph_nlist l;
  sph_shifting_params sp;
} lattice;

/* A block of nx x ny fluid particles at ((i + 1/2) dx, (j + 1/2) dx),
 * moving at (vx, vy), with `walls` layers of wall particles below y = 0 on
 * the same lattice (reaching 3 columns beyond the block each side). */
static void make(lattice *L, int nx, int ny, int walls, double vx, double vy) {
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&L->p, 1024, &err) == 0);
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++)
      CU_ASSERT_FATAL(sph_particles_add(&L->p, (i + 0.5) * DX, (j + 0.5) * DX, vx, vy, RHO,
                                        RHO * DX * DX, H, SPH_KIND_FLUID, &err) >= 0);
  for (int j = 0; j < walls; j++)
    for (int i = -3; i < nx + 3; i++)
      CU_ASSERT_FATAL(sph_particles_add(&L->p, (i + 0.5) * DX, -(j + 0.5) * DX, 0, 0, RHO,
                                        RHO * DX * DX, H, SPH_KIND_WALL, &err) >= 0);
  L->sp = (sph_shifting_params){SPH_SHIFTING_COEFFICIENT_DEFAULT, H, DX, SPH_KERNEL_CUBIC_SPLINE};
}

/* The grid and neighbour list of the particles' current positions. */
static void build(lattice *L) {
  sph_error err;
  const double cell = SPH_CUBIC_SUPPORT * H * (1.0 + 1e-9);
  sph_grid_init(&L->g);
  sph_nlist_init(&L->l);
  CU_ASSERT_FATAL(sph_grid_build(&L->g, &L->p, cell, 1u << 24, &err) == 0);
  CU_ASSERT_FATAL(sph_nlist_build(&L->l, &L->g, &L->p, cell, 0.0, 0.0, &err) == 0);
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

/* sph_shifting_displacement into two named components */
static void shift(const sph_shifting_sums *s, double diffusivity, double *dx, double *dy) {
  double d[SPH_DIM];
  sph_shifting_displacement(s, diffusivity, d);
  *dx = d[0];
  *dy = d[1];
}

/* A neighbour's share of grad C: V |grad W| at r = dx. */
static double share(void) {
  double w, dw;
  sph_kernel_w_dw(SPH_KERNEL_CUBIC_SPLINE, DX, H, &w, &dw);
  return DX * DX * fabs(dw);
}

static void test_interior_still(void) {
  lattice L;
  make(&L, 11, 11, 0, 1.0, 0.0);
  build(&L);
  const size_t c = at(&L, 5 * 11 + 5);
  sph_shifting_sums s;
  sph_shifting_sums_of(&L.p, &L.l, &L.sp, c, &s);
  printf("\n  interior: |grad C| %.2e of a neighbour's share, div r %.4f",
         hypot(s.tgx, s.tgy) / share(), s.div);
  CU_ASSERT(hypot(s.gx, s.gy) <= 1e-9 * share());
  CU_ASSERT(hypot(s.tgx, s.tgy) <= 1e-9 * share());
  CU_ASSERT(fabs(s.div - 2.0) <= 0.06);
  double dx, dy;
  shift(&s, SPH_SHIFTING_COEFFICIENT_DEFAULT * H * 1.0 * 1e-4, &dx, &dy);
  CU_ASSERT(hypot(dx, dy) <= 1e-12 * DX);
  drop(&L);
}

static void test_clump_pushed_apart(void) {
  lattice L;
  make(&L, 11, 11, 0, 0.6, 0.8); /* |v| = 1 m/s */
  const size_t c0 = 5 * 11 + 5;
  L.p.x[c0] += 0.3 * DX; /* toward its right neighbour */
  build(&L);
  const size_t c = at(&L, (int64_t)c0), r = at(&L, (int64_t)c0 + 1);
  const double dt = 1e-4;
  double d[2][2], twice[2], still[2];
  sph_shifting_compute(&L.p, &L.l, &L.sp, dt, L.p.acc);
  d[0][0] = L.p.ax[c], d[0][1] = L.p.ay[c], d[1][0] = L.p.ax[r], d[1][1] = L.p.ay[r];
  printf("\n  clumped pair: moves %.3e, %.3e dx (x), %.1e, %.1e dx (y)", d[0][0] / DX, d[1][0] / DX,
         d[0][1] / DX, d[1][1] / DX);
  CU_ASSERT(d[0][0] < -1e-4 * DX);
  CU_ASSERT(d[1][0] > 1e-4 * DX);
  CU_ASSERT(fabs(d[0][1]) <= 1e-9 * fabs(d[0][0])); /* along the line of the pair */
  /* -A h |v| dt grad C, by hand from the row's sums */
  sph_shifting_sums s;
  sph_shifting_sums_of(&L.p, &L.l, &L.sp, c, &s);
  CU_ASSERT(s.div >= SPH_SHIFTING_SURFACE_DIV);
  const double D = SPH_SHIFTING_COEFFICIENT_DEFAULT * H * dt * 1.0;
  CU_ASSERT(fabs(d[0][0] - (-D * s.tgx)) <= 1e-12 * fabs(d[0][0]));
  /* Lind's term pushes a pair closer than dx harder than the plain gradient */
  CU_ASSERT(fabs(s.tgx) > fabs(s.gx));
  sph_shifting_compute(&L.p, &L.l, &L.sp, 2.0 * dt, L.p.acc);
  twice[0] = L.p.ax[c], twice[1] = L.p.ay[c];
  CU_ASSERT(twice[0] == 2.0 * d[0][0]);
  L.p.vx[c] = L.p.vy[c] = 0.0;
  sph_shifting_compute(&L.p, &L.l, &L.sp, dt, L.p.acc);
  still[0] = L.p.ax[c], still[1] = L.p.ay[c];
  CU_ASSERT(still[0] == 0.0 && still[1] == 0.0);
  drop(&L);
}

static void test_surface_tangential(void) {
  lattice L;
  make(&L, 15, 6, 3, 1.0, 0.0);
  const size_t top = 5 * 15 + 3, side = 5 * 15 + 10;
  L.p.x[side] -= 0.3 * DX; /* toward its left neighbour, in the top row */
  build(&L);
  const double D = SPH_SHIFTING_COEFFICIENT_DEFAULT * H * 1e-4;
  /* the undisturbed top-row particle: a surface one, not moved */
  sph_shifting_sums s;
  double dx, dy;
  sph_shifting_sums_of(&L.p, &L.l, &L.sp, at(&L, (int64_t)top), &s);
  printf("\n  top row: div r %.3f", s.div);
  CU_ASSERT(s.div < SPH_SHIFTING_SURFACE_DIV);
  shift(&s, D, &dx, &dy);
  CU_ASSERT(hypot(dx, dy) <= 1e-12 * DX);
  /* without the correction it would be pushed out, up */
  sph_shifting_sums bulk = s;
  bulk.div = 2.0;
  shift(&bulk, D, &dx, &dy);
  printf(", uncorrected move up %.3e dx", dy / DX);
  CU_ASSERT(dy > 1e-5 * DX);
  /* the moved one goes back along the surface, nothing along its normal */
  sph_shifting_sums_of(&L.p, &L.l, &L.sp, at(&L, (int64_t)side), &s);
  CU_ASSERT(s.div < SPH_SHIFTING_SURFACE_DIV);
  shift(&s, D, &dx, &dy);
  const double g = hypot(s.gx, s.gy), nx = -s.gx / g, ny = -s.gy / g;
  printf(", moved surface particle: %.3e dx along, %.1e dx normal", dx / DX,
         (dx * nx + dy * ny) / DX);
  CU_ASSERT(dx > 1e-5 * DX);
  CU_ASSERT(fabs(dx * nx + dy * ny) <= 1e-12 * hypot(dx, dy));
  drop(&L);
}

static void test_walls_count(void) {
  for (int walls = 0; walls <= 3; walls += 3) {
    lattice L;
    make(&L, 11, 8, walls, 1.0, 0.0);
    build(&L);
    sph_shifting_sums s;
    sph_shifting_sums_of(&L.p, &L.l, &L.sp, at(&L, 5), &s); /* the first row's middle */
    double dx, dy;
    shift(&s, SPH_SHIFTING_COEFFICIENT_DEFAULT * H * 1e-4, &dx, &dy);
    printf("\n  first row, %d wall layers: div r %.3f, |grad C| %.2e of a share", walls, s.div,
           hypot(s.tgx, s.tgy) / share());
    if (walls) {
      CU_ASSERT(s.div >= SPH_SHIFTING_SURFACE_DIV);
      CU_ASSERT(hypot(s.tgx, s.tgy) <= 1e-9 * share());
      CU_ASSERT(hypot(dx, dy) <= 1e-12 * DX);
    } else {
      CU_ASSERT(s.div < SPH_SHIFTING_SURFACE_DIV);
    }
    drop(&L);
  }
}

static void test_fluid_only(void) {
  lattice L;
  make(&L, 8, 8, 3, 1.0, 0.5);
  for (size_t i = 0; i < L.p.n; i++) { /* a disordered block */
    L.p.x[i] += 0.2 * DX * sin(12.9898 * (double)i);
    L.p.y[i] += 0.2 * DX * sin(78.233 * (double)i);
  }
  build(&L);
  sph_shifting_compute(&L.p, &L.l, &L.sp, 1e-4, L.p.acc);
  size_t moved = 0, wrong = 0;
  const double D = SPH_SHIFTING_COEFFICIENT_DEFAULT * H * 1e-4 * sqrt(1.25);
  for (size_t i = 0; i < L.p.n; i++) {
    if (L.p.kind[i] != SPH_KIND_FLUID) {
      wrong += L.p.ax[i] != 0.0 || L.p.ay[i] != 0.0;
      continue;
    }
    sph_shifting_sums s;
    double dx, dy;
    sph_shifting_sums_of(&L.p, &L.l, &L.sp, i, &s);
    shift(&s, D, &dx, &dy);
    wrong += dx != L.p.ax[i] || dy != L.p.ay[i];
    moved += L.p.ax[i] != 0.0;
  }
  printf("\n  %zu of 64 fluid particles moved, %zu differ from the per-particle functions", moved,
         wrong);
  CU_ASSERT_EQUAL(wrong, 0);
  CU_ASSERT(moved > 48);
  drop(&L);
}

int main(void) {
  CU_TestInfo tests[] = {
      {"inside a lattice nothing moves", test_interior_still},
      {"a clumped pair is pushed apart, -A h |v| dt grad C", test_clump_pushed_apart},
      {"on the free surface only along it", test_surface_tangential},
      {"wall particles count: the first row is no surface", test_walls_count},
      {"fluid particles only, as the per-particle functions", test_fluid_only},
      CU_TEST_INFO_NULL};
  return sph_test_main("shifting", tests);
}
