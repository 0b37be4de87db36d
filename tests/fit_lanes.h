/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * fit_lanes.h - a check shared by test_wall_velocity (2-D) and
 * test_walls_3d (3-D): the walls' fits (src/walls/wall_velocity.h) give
 * the same bits whether they take their candidates two at a time
 * (work.narrow) or eight (AVX-512, the default where the processor has
 * it). Included once by each test; SPH_DIM is the includer's.
 *
 * A random cloud of fluid, dense enough that a cell holds more than the
 * FIT_CHUNK (64) candidates a fit takes at a time and that the last
 * vector of a chunk is partly full, with h spread over +-20 % (the reach
 * 2 h_j per candidate), carrying a random density and velocity; wall
 * particles below it, mdbc and no-slip, their mirror points in the cloud
 * and a few beyond the fluid's reach; periodic along x or not. The ghost
 * velocities and the mdbc densities of both ways compared bit for bit.
 */
#ifndef SPH_TEST_FIT_LANES_H
#define SPH_TEST_FIT_LANES_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/lanes.h"
#include "core/particles.h"
#include "testutil.h"
#include "walls/wall_velocity.h"

/* A uniform draw in [0, 1) from the state s (xorshift64*). */
static double fit_lanes_draw(uint64_t *s) {
  *s ^= *s >> 12, *s ^= *s << 25, *s ^= *s >> 27;
  return (double)((*s * 0x2545F4914F6CDD1DULL) >> 11) / 9007199254740992.0;
}

/* The fits of a random cloud both ways; the number of wall particles whose
 * values differ in any bit (0 expected), and into *fitted how many of them
 * a fit reached (the ghost velocity moved off the wall's own). */
static size_t fit_lanes_differ(int periodic, uint64_t seed, size_t *fitted) {
  const double dx = 0.01, h0 = 1.3 * dx, side = 0.2, rho0 = 1000.0;
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 8192, &err) == 0);
  uint64_t s = seed;
  /* fluid over [0, side)^D above the wall, 8 particles per dx^2 in 2-D and 4 per
   * dx^3 in 3-D: about 80 and 120 in a cell of the fits */
  size_t nf = 1;
  for (int a = 0; a < SPH_DIM; a++)
    nf *= (size_t)(side / dx);
  nf *= SPH_DIM == 2 ? 8 : 4;
  for (size_t k = 0; k < nf; k++) {
    double x[SPH_DIM], v[SPH_DIM];
    for (int a = 0; a < SPH_DIM; a++) {
      x[a] = side * fit_lanes_draw(&s);
      v[a] = fit_lanes_draw(&s) - 0.5;
    }
    const double h = h0 * (0.8 + 0.4 * fit_lanes_draw(&s));
    CU_ASSERT_FATAL(sph_particles_add_at(&p, x, v, rho0 * (1.0 + 0.01 * fit_lanes_draw(&s)), 1e-3,
                                         h, SPH_KIND_FLUID, &err) >= 0);
  }
  /* walls: three layers under the fluid (the last axis down), their mirror
   * points up into it, a tenth of them pointing past the fluid's top */
  sph_particles_use(&p, SPH_ARRAYS_OFFSET);
  const size_t first_wall = p.n;
  for (size_t k = 0; k < 600; k++) {
    double x[SPH_DIM], v[SPH_DIM] = {0.0};
    for (int a = 0; a < SPH_DIM - 1; a++)
      x[a] = side * fit_lanes_draw(&s);
    const int layer = (int)(3.0 * fit_lanes_draw(&s));
    x[SPH_DIM - 1] = -(0.5 + layer) * dx;
    const long q = sph_particles_add_at(&p, x, v, rho0, 1e-3, h0, SPH_KIND_WALL, &err);
    CU_ASSERT_FATAL(q >= 0);
    p.flags[q] |= SPH_FLAG_MDBC | SPH_FLAG_NO_SLIP;
    for (int a = 0; a < SPH_DIM - 1; a++)
      p.mirror_offset[a][q] = dx * (fit_lanes_draw(&s) - 0.5);
    p.mirror_offset[SPH_DIM - 1][q] =
        k % 10 == 9 ? side + 10.0 * h0 : -2.0 * x[SPH_DIM - 1] + dx * fit_lanes_draw(&s);
  }
  const double period = periodic ? side : 0.0;
  const double head[SPH_DIM] = {0.0};
  double *g[2], *rho[2];
  for (int way = 0; way < 2; way++) { /* narrow, then the default */
    sph_wall_velocity_work w = {0};
    w.narrow = way == 0;
    g[way] = malloc(SPH_DIM * p.n * sizeof *g[way]);
    rho[way] = malloc(p.n * sizeof *rho[way]);
    CU_ASSERT_FATAL(g[way] && rho[way]);
    double *gv[SPH_DIM];
    for (int a = 0; a < SPH_DIM; a++)
      gv[a] = g[way] + (size_t)a * p.n;
    CU_ASSERT_FATAL(sph_wall_velocity(&p, 2.0 * 1.2 * h0, 0.0, period, 0, gv, &w, &err) == 0);
    w.narrow = way == 0;
    CU_ASSERT_FATAL(
        sph_wall_mdbc_density(&p, 2.0 * 1.2 * h0, 0.0, period, 0, rho0, head, &w, &err) == 0);
    memcpy(rho[way], p.rho, p.n * sizeof *p.rho);
    for (size_t i = first_wall; i < p.n; i++) /* the next way starts from the same state */
      p.rho[i] = rho0;
    sph_wall_velocity_work_free(&w);
  }
  size_t differ = 0;
  *fitted = 0;
  for (size_t i = first_wall; i < p.n; i++) {
    int same = memcmp(&rho[0][i], &rho[1][i], sizeof(double)) == 0, moved = 0;
    for (int a = 0; a < SPH_DIM; a++) {
      same &= memcmp(&g[0][(size_t)a * p.n + i], &g[1][(size_t)a * p.n + i], sizeof(double)) == 0;
      moved |= g[0][(size_t)a * p.n + i] != 0.0;
    }
    differ += !same;
    *fitted += moved;
  }
  for (int way = 0; way < 2; way++)
    free(g[way]), free(rho[way]);
  sph_particles_free(&p);
  return differ;
}

/* The check: both domains, two seeds; most wall particles fitted, a tenth
 * (those pointing past the fluid) not. */
static void test_fit_lanes(void) {
#ifdef SPH_LANES_AVX512
  const int wide = sph_cpu_has_avx512();
#else
  const int wide = 0;
#endif
  if (!wide)
    printf("\n    (no AVX-512 on this processor: both ways take two candidates at a time; "
           "the eight-lane fit is not compared)");
  for (int periodic = 0; periodic < 2; periodic++)
    for (uint64_t seed = 1; seed <= 2; seed++) {
      size_t fitted;
      const size_t differ = fit_lanes_differ(periodic, 0x9e3779b97f4a7c15ULL * seed, &fitted);
      CU_ASSERT(differ == 0);
      CU_ASSERT(fitted >= 520 && fitted <= 540); /* 60 point past the fluid */
      printf("\n    %s, seed %d: %zu of 600 wall particles fitted, %zu differ",
             periodic ? "periodic along x" : "closed", (int)seed, fitted, differ);
    }
}

#endif
