/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_adami.c - Adami, Hu and Adams' (2012) generalized wall boundary
 * condition (walls/adami.h; boundary: adami).
 *
 * 1. The extrapolation alone (sph_wall_adami on a lattice): with the fluid's
 *    pressure a linear field p = p0 + rho0 (g - a) . (x - x0), as a fluid at
 *    rest in a tank accelerated by a presses (constant density), every wall
 *    particle with fluid in reach reads that field continued to it, to
 *    1e-9 of its scale, for walls at rest and for a piston's wall particles
 *    at an instant of its motion (a its acceleration there); their density
 *    is the Tait inverse of it; their no-slip velocity is 2 v_w - v for a
 *    uniform fluid velocity v; a wall particle with no fluid in reach reads
 *    0 and rho0; a field below 0 reads 0 (clipped).
 * 1b. The walls' guard (walls.h, sph_walls_keep_off) is the face itself for
 *    adami walls: a particle just in front of a tank face or a box
 *    obstacle's face stays, one that crossed it is reflected to as far in
 *    front as it was behind (other walls' guard moves both); one that
 *    crossed two faces into the tank's corner is kept off both.
 * 1c. A 2-D tank's side walls lie on the fluid's rows (every particle at
 *    y0 + (j + 1/2) dx, the top one on the tank's last row), for heights a
 *    whole number of dx and not; the still water beside them is not pulled
 *    toward them (lateral acceleration at mid-depth over the first step
 *    below 0.01 m/s^2; measured 4e-4 and 1.2e-3; 0.92 while the side walls
 *    ran to the tank's top, their rows 2.52 mm apart at dx = 2.5 mm).
 * 2. Still water (tests/data/still_tank.yaml, 0.5 s, both integrators):
 *    no fluid particle crosses a wall face; the largest speed stays under
 *    1 % of sqrt(g H) in the first 0.1 s and 0.5 % after (measured 0.41 /
 *    0.24 with either integrator: the lattice's free surface settling;
 *    0.55 / 0.35 with the side walls off the fluid's rows; mdbc walls
 *    0.46 / 0.25); the floor's wall particles with fluid in
 *    reach carry the hydrostatic pressure continued to their depth within
 *    0.75 % of rho0 g H (measured 0.02 %; 0.46 % at the corners with the
 *    side walls off the fluid's rows), the side walls' within 2 %
 *    (measured 0.43 %, at the free surface's corner; 1.36 % with the side
 *    walls off the rows); the first fluid row stands 0.5 +- 0.05 dx above
 *    the floor (measured 0.500 dx).
 * 3. A wall pushed into still water (tests/data/piston.yaml with an adami
 *    tank and piston, 3 layers): its work within 3 % of the linear
 *    shallow-water estimate 0.2040 J (measured 0.2023 J), the closed
 *    balance within 1e-5 of E0 (measured 3e-7), also free-slip.
 * 4. In 3-D (tests/data/still_tank_3d.yaml, to 0.3 s, sph-3d): the floor sensor
 *    reads the hydrostatic pressure within 2.5 % (the plain kernel
 *    gradient's 3-D lattice sum leaves a still tank's water 1.6-1.9 % heavy
 *    on its floor whatever the walls, doc/method.md; measured +1.75 %).
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "case/case.h"
#include "core/particles.h"
#include "neighbours/grid.h"
#include "physics/eos.h"
#include "physics/kernel.h"
#include "solver/diag.h"
#include "solver/sim.h"
#include "testsim.h"
#include "testutil.h"
#include "walls/adami.h"
#include "walls/walls.h"

#define DX 0.01
#define RHO0 1000.0

/* A fluid lattice over [0, 0.3] x [0, 0.2] (x0 + (i + 1/2) dx) above a floor and left of a
 * right wall, each three layers deep on the lattice continued (boundary: adami), the right wall's
 * particles a moving body 0 (rest positions set). */
static void lattice(sph_particles *p) {
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(p, 4096, &err) == 0);
  const double m = RHO0 * DX * DX, h = 1.3 * DX;
  for (int j = -3; j < 20; j++)
    for (int i = 0; i < 33; i++) {
      const double x = (i + 0.5) * DX, y = (j + 0.5) * DX;
      const int wall = j < 0 || i >= 30;
      const long k = sph_particles_add(p, x, y, 0.0, 0.0, RHO0, m, h,
                                       wall ? SPH_KIND_WALL : SPH_KIND_FLUID, &err);
      CU_ASSERT_FATAL(k >= 0);
      if (wall) p->flags[k] = SPH_FLAG_ADAMI;
      p->body[k] = i >= 30 && j >= 0 ? 0 : -1;
    }
  sph_particles_use(p, SPH_ARRAYS_REST); /* rest positions: the present ones */
}

static void build_list(const sph_particles *p, sph_grid *g, sph_nlist *l) {
  sph_error err;
  const double support = 2.0 * 1.3 * DX;
  sph_grid_init(g);
  sph_nlist_init(l);
  CU_ASSERT_FATAL(sph_grid_build(g, (sph_particles *)p, support * (1 + 1e-9), 1u << 20, &err) == 0);
  CU_ASSERT_FATAL(sph_nlist_build(l, g, p, support, 0.0, 0.0, &err) == 0);
}

static void test_extrapolation(void) {
  sph_particles p;
  lattice(&p);
  sph_grid g;
  sph_nlist l;
  build_list(&p, &g, &l);
  /* a piston: the right wall moving by X(t) = (S/2) sin(omega t); at t its acceleration */
  sph_wall_segment seg;
  memset(&seg, 0, sizeof seg);
  seg.motion.kind = SPH_MOTION_PISTON;
  seg.motion.paddle.kind = SPH_PADDLE_PISTON;
  seg.motion.paddle.period = 1.0;
  seg.motion.paddle.stroke = 0.04;
  seg.motion.paddle.depth = 0.2;
  const double t = 0.3, om = 2.0 * M_PI;
  const double ax = -0.5 * 0.04 * om * om * sin(om * t); /* X'' at t */
  sph_walls walls;
  memset(&walls, 0, sizeof walls);
  walls.segments = &seg;
  walls.n_segments = 1;
  walls.moving = 1;
  const double g0[2] = {0.0, -9.81}, vfl[2] = {0.3, -0.2}, p0 = 2000.0;
  for (int moving = 0; moving <= 1; moving++) {
    sph_adami_params ap = {.kernel = SPH_KERNEL_CUBIC_SPLINE,
                           .h = 1.3 * DX,
                           .eos = sph_eos_tait(RHO0, 20.0),
                           .walls = moving ? &walls : NULL,
                           .t = t};
    ap.g[0] = g0[0], ap.g[1] = g0[1];
    /* the field a fluid at rest presses with: grad p = rho0 (g - a), the acceleration a being
     * the moving wall's (the right wall's particles see g - a; the floor's, at rest, g) */
    double *gv[2] = {malloc(p.n * sizeof(double)), malloc(p.n * sizeof(double))};
    for (size_t i = 0; i < p.n; i++) {
      p.vx[i] = p.kind[i] == SPH_KIND_FLUID ? vfl[0] : 0.01;
      p.vy[i] = p.kind[i] == SPH_KIND_FLUID ? vfl[1] : 0.0;
      p.rho[i] = RHO0;
      p.p[i] = p0 + RHO0 * (g0[0] * p.x[i] + g0[1] * p.y[i]);
      gv[0][i] = gv[1][i] = -1.0;
    }
    const size_t wet = sph_wall_adami(&p, &l, &ap, gv);
    double worst = 0.0, worst_v = 0.0;
    size_t dry = 0, walls_n = 0, wet_n = 0;
    for (size_t i = 0; i < p.n; i++) {
      if (p.kind[i] != SPH_KIND_WALL) {
        CU_ASSERT(gv[0][i] == -1.0); /* untouched */
        continue;
      }
      walls_n++;
      /* the field at i with the wall's own g - a: at rest p0 + rho0 g . x; the moving wall's
       * particles read its continuation with the acceleration taken out along x */
      const int mv = moving && p.body[i] >= 0;
      double expect = p.p[i]; /* reset below */
      (void)expect;
      int reach = 0;
      for (size_t j = 0; j < p.n; j++)
        if (p.kind[j] == SPH_KIND_FLUID && hypot(p.x[i] - p.x[j], p.y[i] - p.y[j]) < 2.6 * DX)
          reach = 1;
      if (!reach) {
        dry++;
        CU_ASSERT(p.p[i] == 0.0 && p.rho[i] == RHO0);
        CU_ASSERT(gv[0][i] == p.vx[i] && gv[1][i] == p.vy[i]);
        continue;
      }
      wet_n++;
      /* Adami's sum: each fluid particle's pressure carried to i with g - a: for p_f linear in
       * x_f with gradient rho0 g, sum (p_f + rho0 (g - a) . (x_i - x_f)) W / sum W = p0 +
       * rho0 g . x_i - rho0 a . (x_i - xbar), xbar the W-weighted mean of the fluid's x */
      double sw = 0.0, sxb = 0.0;
      for (size_t j = 0; j < p.n; j++) {
        if (p.kind[j] != SPH_KIND_FLUID) continue;
        const double r = hypot(p.x[i] - p.x[j], p.y[i] - p.y[j]);
        if (r >= 2.6 * DX) continue;
        const double w = sph_kernel_w(SPH_KERNEL_CUBIC_SPLINE, r, 1.3 * DX);
        sw += w;
        sxb += w * (p.x[i] - p.x[j]);
      }
      double want = p0 + RHO0 * (g0[0] * p.x[i] + g0[1] * p.y[i]);
      if (mv) want -= RHO0 * ax * sxb / sw;
      if (want < 0.0) want = 0.0;
      const double e = fabs(p.p[i] - want) / (RHO0 * 9.81 * 0.2);
      if (e > worst) worst = e;
      CU_ASSERT(fabs(p.rho[i] - sph_eos_density(&ap.eos, p.p[i])) <= 1e-12 * RHO0);
      const double ev = fmax(fabs(gv[0][i] - (2.0 * p.vx[i] - vfl[0])),
                             fabs(gv[1][i] - (2.0 * p.vy[i] - vfl[1])));
      if (ev > worst_v) worst_v = ev;
    }
    printf("\n  %s: %zu wall particles, %zu with fluid in reach (the pass says %zu), %zu dry; "
           "largest error %.2e of rho0 g H, no-slip velocity %.2e m/s",
           moving ? "piston at t = 0.3 s" : "at rest", walls_n, wet_n, wet, dry, worst, worst_v);
    CU_ASSERT(wet == wet_n);
    CU_ASSERT(dry > 0 && wet_n > 0);
    CU_ASSERT(worst < 1e-9);
    CU_ASSERT(worst_v < 1e-12);
    free(gv[0]);
    free(gv[1]);
  }
  /* a field below 0 (a fluid in tension) is clipped: the wall pushes, never pulls */
  for (size_t i = 0; i < p.n; i++)
    if (p.kind[i] == SPH_KIND_FLUID) p.p[i] = -500.0;
  sph_adami_params ap = {
      .kernel = SPH_KERNEL_CUBIC_SPLINE, .h = 1.3 * DX, .eos = sph_eos_tait(RHO0, 20.0)};
  sph_wall_adami(&p, &l, &ap, NULL);
  int clipped = 1;
  for (size_t i = 0; i < p.n; i++)
    if (p.kind[i] == SPH_KIND_WALL) clipped &= p.p[i] == 0.0 && p.rho[i] == RHO0;
  CU_ASSERT(clipped);
  sph_nlist_free(&l);
  sph_grid_free(&g);
  sph_particles_free(&p);
}

/* The guard of adami walls (walls.h, sph_walls_keep_off) is the face itself: in a unit tank
 * with an adami box obstacle, a particle 0.004 in front of the floor, or of the box's left face,
 * stays (the guard of other walls at d_min = 0.01 would move it), one 0.004 behind the floor or
 * inside the box's left face is reflected to 0.004 in front of it, its normal velocity turned
 * into the water; and a dynamic tank with the same d_min moves the one in front too. */
/* Two phases: a wall particle takes the phase of the fluid nearest its mirror point and that
 * phase's extrapolation; the liquid's is held at 0 or above (a wall pushes the liquid, never
 * pulls it), the air's is not: the air has no floor, its gauge pressure falls below 0 where it
 * expands, and the wall that mirrors it carries that pressure (held at 0 it pushed air below
 * ambient away from the wall harder than the air pushed back). A uniform field p0 < 0, no body
 * force: the wet walls carry p0
 * (to round-off) when the fluid is air, 0 when it is the liquid. */
static void test_two_phases(void) {
  sph_particles p;
  lattice(&p);
  sph_particles_use(&p, SPH_ARRAYS_PHASE | SPH_ARRAYS_OFFSET);
  sph_grid g;
  sph_nlist l;
  build_list(&p, &g, &l);
  const double p0 = -50.0;
  sph_adami_params ap = {
      .kernel = SPH_KERNEL_CUBIC_SPLINE, .h = 1.3 * DX, .eos = sph_eos_tait(RHO0, 20.0)};
  for (int phase = 0; phase <= 1; phase++) {
    for (size_t i = 0; i < p.n; i++) {
      p.phase[i] = p.kind[i] == SPH_KIND_FLUID ? (uint8_t)phase : 0;
      p.mx[i] = p.my[i] = 0.0;
      p.p[i] = p.kind[i] == SPH_KIND_FLUID ? p0 : 123.0;
    }
    const size_t wet = sph_wall_adami(&p, &l, &ap, NULL);
    size_t at_p0 = 0, off = 0;
    for (size_t i = 0; i < p.n; i++) {
      if (p.kind[i] != SPH_KIND_WALL) continue;
      const int is_p0 = fabs(p.p[i] - p0) < 1e-12 * fabs(p0); /* (a weighted mean of p0) */
      at_p0 += is_p0 && p.wphase[i] == 1;
      off += phase ? !is_p0 && p.p[i] != 0.0 : p.p[i] != 0.0;
    }
    printf("\n  fluid of phase %d at %g Pa: %zu wall particles wet, %zu at %g Pa, %zu off", phase,
           p0, wet, at_p0, p0, off);
    CU_ASSERT(wet > 0);
    CU_ASSERT_EQUAL(at_p0, phase ? wet : 0);
    CU_ASSERT_EQUAL(off, 0);
  }
  sph_nlist_free(&l);
  sph_grid_free(&g);
  sph_particles_free(&p);
}

static void test_guard_at_face(void) {
  static const double cases[][6] = {
      /* x, y, vx, vy; x, y after */
      {0.2, 0.004, 0.3, -1.0, 0.2, 0.004},  /* in front of the floor: stays */
      {0.2, -0.004, 0.3, -1.0, 0.2, 0.004}, /* behind the floor: reflected */
      {0.396, 0.1, 1.0, 0.0, 0.396, 0.1},   /* in front of the box's left face: stays */
      {0.404, 0.1, 1.0, 0.0, 0.396, 0.1},   /* inside it: reflected */
      /* behind the floor and the left wall, in the tank's corner: kept off both */
      {-0.004, -0.003, -0.5, -0.5, 0.004, 0.003},
  };
  for (int adami = 1; adami >= 0; adami--) {
    sph_particles p;
    sph_error err;
    CU_ASSERT_FATAL(sph_particles_init(&p, 8, &err) == 0);
    for (size_t k = 0; k < 5; k++)
      CU_ASSERT_FATAL(sph_particles_add(&p, cases[k][0], cases[k][1], cases[k][2], cases[k][3],
                                        1000, 1, 0.026, SPH_KIND_FLUID, &err) == (long)k);
    const sph_boundary_kind b = adami ? SPH_BOUNDARY_ADAMI : SPH_BOUNDARY_DYNAMIC;
    sph_tank t = {.present = 1, .x1 = 1.0, .y1 = 1.0, .layers = 3, .boundary = b};
    const sph_obstacle o = {.lo = {0.4, 0.0}, .hi = {0.6, 0.2}, .layers = 3, .boundary = b};
    sph_walls w;
    CU_ASSERT_FATAL(sph_walls_create(&w, &p, &t, NULL, 0, &o, 1, 0.02, 1000, 0.026, 0.0, &err) ==
                    0);
    const size_t moved = sph_walls_keep_off(&w, &p, 0.01, 0, NULL);
    if (adami) {
      CU_ASSERT_EQUAL(moved, 4); /* (two for the corner's) */
      for (size_t k = 0; k < 5; k++)
        CU_ASSERT(fabs(p.x[k] - cases[k][4]) < 1e-15 && fabs(p.y[k] - cases[k][5]) < 1e-15);
      CU_ASSERT(p.vy[0] == -1.0 && p.vy[1] == 1.0 && p.vx[1] == 0.3);
      CU_ASSERT(p.vx[2] == 1.0 && p.vx[3] == -1.0);
      CU_ASSERT(p.vx[4] == 0.5 && p.vy[4] == 0.5);
    } else {
      CU_ASSERT_EQUAL(moved, 6); /* the guard at d_min: the particles in front move too */
      CU_ASSERT(fabs(p.y[0] - 0.016) < 1e-15 && fabs(p.x[2] - 0.384) < 1e-15);
      CU_ASSERT(fabs(p.x[4] - 0.024) < 1e-15 && fabs(p.y[4] - 0.023) < 1e-15);
    }
    printf("\n  %s walls: %zu reflections of 5 particles", adami ? "adami" : "dynamic", moved);
    sph_particles_free(&p);
  }
}

/* A 2-D tank's side walls on the fluid's rows: every side-wall particle at y0 + (j + 1/2) dx, dx
 * from the next, the top one on the tank's last row (ny = H/dx rounded), for a height a whole
 * number of dx (the still tank, 0.15 m at 2.5 mm; the Lobovsky tank, 0.6 m at 7.5 mm) and one
 * that is not (0.151 m); and the still water beside them not pulled toward them: at mid-depth
 * its lateral acceleration over the first step below 0.01 m/s^2 (with the side walls run to the
 * tank's top, 59 spacings of 2.52 mm in place of 2.5, it was 0.92 m/s^2). */
static void test_side_walls(void) {
  const struct { double height, dx; } tanks[] = {{0.15, 0.0025}, {0.6, 0.0075}, {0.151, 0.0025}};
  for (size_t t = 0; t < sizeof tanks / sizeof tanks[0]; t++) {
    char tank[160], dx[64];
    snprintf(tank, sizeof tank, "geometry.tank={x: [0.0, 0.2], y: [0.0, %.17g], boundary: adami}",
             tanks[t].height);
    snprintf(dx, sizeof dx, "numerics.dx=%.17g", tanks[t].dx);
    const char *sets[] = {tank, dx, "physics.air=false", "time.end=0.01",
                          "time.output_interval=0.01"};
    sph_case c;
    sph_sim *s;
    sph_error err;
    CU_ASSERT_FATAL(sph_test_open_sim("cases/still_water_air.yaml", sets, 5, &c, &s) == 0);
    const sph_particles *p = sph_sim_particles(s);
    const double h = c.dx, top = (floor(tanks[t].height / h + 0.5) - 0.5) * h;
    double off = 0.0, high = -INFINITY;
    size_t side = 0;
    for (size_t i = 0; i < p->n; i++) {
      if (p->kind[i] != SPH_KIND_WALL || p->y[i] < 0.0 || (p->x[i] > 0.0 && p->x[i] < 0.2))
        continue; /* (the side walls above the floor's face) */
      const double j = p->y[i] / h - 0.5;
      off = fmax(off, fabs(j - floor(j + 0.5)) * h);
      high = fmax(high, p->y[i]);
      side++;
    }
    size_t mid = SIZE_MAX;
    for (size_t i = 0; i < p->n; i++)
      if (p->kind[i] == SPH_KIND_FLUID && fabs(p->x[i] - 0.5 * h) < 1e-9 &&
          (mid == SIZE_MAX || fabs(p->y[i] - 0.05) < fabs(p->y[mid] - 0.05)))
        mid = i;
    CU_ASSERT_FATAL(mid != SIZE_MAX);
    CU_ASSERT_FATAL(sph_sim_step(s, c.t_end, &err) == 0);
    const double ax = p->vx[mid] / sph_sim_time(s);
    printf("\n  tank %.3f m at dx %.4f m: %zu side-wall particles, at most %.1e m off the rows, "
           "the top at %.6f m (row %.6f); mid-depth lateral acceleration %+.2e m/s^2",
           tanks[t].height, h, side, off, high, top, ax);
    CU_ASSERT(off < 1e-12);
    CU_ASSERT(fabs(high - top) < 1e-12);
    CU_ASSERT(fabs(ax) < 0.01);
    sph_sim_free(s);
    sph_case_free(&c);
  }
}

/* Still water in the tank of tests/data/still_tank.yaml with adami walls (and `extra`). */
static void still_water(const char *extra, double start_bound, double bound) {
  const char *sets[] = {"geometry.tank={x: [0.0, 0.2], y: [0.0, 0.15], boundary: adami}",
                        "geometry.fluid=[{x: [0.0, 0.2], y: [0.0, 0.1], hydrostatic: true}]",
                        extra};
  sph_case c;
  sph_sim *s;
  sph_error err;
  CU_ASSERT_FATAL(sph_test_open_sim("tests/data/still_tank.yaml", sets, extra ? 3 : 2, &c, &s) ==
                  0);
  const size_t n0 = sph_sim_particles(s)->n;
  double vmax = 0.0, vstart = 0.0;
  int crossed = 0;
  while (sph_sim_time(s) < c.t_end) {
    const int rc = sph_sim_step(s, c.t_end, &err);
    if (rc) printf("\n%s\n", err.msg);
    CU_ASSERT_FATAL(rc == 0);
    const sph_particles *p = sph_sim_particles(s);
    CU_ASSERT_EQUAL_FATAL(p->n, n0);
    for (size_t i = 0; i < p->n; i++) {
      if (p->kind[i] != SPH_KIND_FLUID) continue;
      const double v = hypot(p->vx[i], p->vy[i]);
      if (sph_sim_time(s) < 0.1 && v > vstart) vstart = v;
      if (sph_sim_time(s) >= 0.1 && v > vmax) vmax = v;
      if (p->x[i] < 0.0 || p->x[i] > 0.2 || p->y[i] < 0.0) crossed++;
    }
  }
  /* the wall particles with fluid in reach: the hydrostatic pressure continued to them */
  const sph_particles *p = sph_sim_particles(s);
  const double dx = c.dx, g = 9.81, H = 0.1, reach = 2.0 * c.h;
  double worst = 0.0, worst_floor = 0.0, row = 0.0;
  int nw = 0, ncol = 0;
  for (size_t i = 0; i < p->n; i++) {
    if (p->kind[i] != SPH_KIND_WALL) continue;
    int in = 0;
    for (size_t j = 0; j < p->n && !in; j++)
      in = p->kind[j] == SPH_KIND_FLUID && hypot(p->x[i] - p->x[j], p->y[i] - p->y[j]) < reach;
    if (!in || p->y[i] > 0.09) continue; /* (the side walls' top: beside the free surface) */
    const double e = (p->p[i] - RHO0 * g * (H - p->y[i])) / (RHO0 * g * H);
    if (fabs(e) > fabs(worst)) worst = e;
    if (p->y[i] < 0.0 && fabs(e) > fabs(worst_floor)) worst_floor = e;
    nw++;
  }
  for (double x0 = 0.05; x0 < 0.15 - 1e-12; x0 += dx) {
    double lo = INFINITY;
    for (size_t i = 0; i < p->n; i++)
      if (p->kind[i] == SPH_KIND_FLUID && p->x[i] >= x0 && p->x[i] < x0 + dx && p->y[i] < lo)
        lo = p->y[i];
    if (isfinite(lo)) row += lo, ncol++;
  }
  row /= ncol * dx;
  const double vref = sqrt(g * H);
  printf("\n  %s: %ld steps, max speed %.3f %% of sqrt(gH) in the first 0.1 s, %.3f %% after; "
         "crossings %d; %d wall particles in reach, largest pressure error %+.3f %% of rho0 g H "
         "(%+.3f %% in the floor); first row %.3f dx above the floor",
         extra ? extra : "predictor-corrector", sph_sim_steps(s), 100 * vstart / vref,
         100 * vmax / vref, crossed, nw, 100 * worst, 100 * worst_floor, row);
  CU_ASSERT_EQUAL(crossed, 0);
  CU_ASSERT(vstart < start_bound * vref);
  CU_ASSERT(vmax < bound * vref);
  CU_ASSERT(nw > 100);
  CU_ASSERT(fabs(worst) < 0.02);
  CU_ASSERT(fabs(worst_floor) < 0.0075);
  CU_ASSERT(fabs(row - 0.5) < 0.05);
  sph_sim_free(s);
  sph_case_free(&c);
}

static void test_still_water(void) { still_water(NULL, 0.01, 0.005); }
static void test_still_water_leapfrog(void) {
  still_water("numerics.integrator=leapfrog", 0.01, 0.005);
}

/* Runs tests/data/piston.yaml with its tank and piston as adami walls (free-slip or not). */
static void piston(int free_slip) {
  char tank[128], wall[320];
  snprintf(tank, sizeof tank, "geometry.tank={x: [0.0, 0.3], y: [0.0, 0.2], boundary: adami%s}",
           free_slip ? ", free_slip: true" : "");
  snprintf(wall, sizeof wall,
           "geometry.walls=[{from: [0.0475, 0.0025], to: [0.0475, 0.2], layers: 3, stagger: "
           "false, boundary: adami%s, motion: {type: translate, velocity: [0.02, 0.0], start: "
           "0.0, stop: 0.2}}]",
           free_slip ? ", free_slip: true" : "");
  const char *sets[] = {tank, wall};
  sph_case c;
  sph_sim *s;
  sph_error err;
  CU_ASSERT_FATAL(sph_test_open_sim("tests/data/piston.yaml", sets, 2, &c, &s) == 0);
  while (sph_sim_time(s) < c.t_end) {
    const int rc = sph_sim_step(s, c.t_end, &err);
    if (rc) printf("\n%s\n", err.msg);
    CU_ASSERT_FATAL(rc == 0);
  }
  sph_diag_row b;
  sph_sim_diag(s, &b);
  const double rho = 1000.0, g = 9.81, H = 0.1, V = 0.02, T = 0.2, eta = V * H / sqrt(g * H);
  const double expect = 0.5 * rho * g * H * H * V * T + rho * g * eta * H * V * T;
  printf("\n  %s: piston work %.6g J (estimate %.6g J), closed deviation %.2e",
         free_slip ? "free slip" : "no slip", b.boundary_work, expect, b.deviation);
  CU_ASSERT(fabs(b.boundary_work - expect) < 0.03 * expect);
  CU_ASSERT(fabs(b.deviation) < 1e-5);
  sph_sim_free(s);
  sph_case_free(&c);
}

static void test_piston(void) {
  piston(0);
  piston(1);
}

/* The 3-D still tank: sph-3d runs it (this test links the 2-D library). */
static void test_still_water_3d(void) {
  char *d = sph_test_tmpdir(), out[4096], args[8192];
  snprintf(args, sizeof args,
           "run --quiet '%s' -o '%s' --set time.end=0.3 --set geometry.tank.boundary=adami "
           "--set numerics.gradient_correction=false --set 'geometry.fluid=[{x: [0.0, 0.2], y: "
           "[0.0, 0.1], z: [0.0, 0.1], hydrostatic: true}]'",
           sph_test_src("tests/data/still_tank_3d.yaml"), d);
  CU_ASSERT_FATAL(sph_test_sph_ok(args, d, out, sizeof out) == 0);
  char path[4200];
  snprintf(path, sizeof path, "%s/probes.csv", d);
  double *v = NULL;
  const long n = sph_test_csv(path, "P_centre (Pa)", &v);
  CU_ASSERT_FATAL(n > 10);
  const double load = RHO0 * 9.81 * 0.1, e = (v[n - 1] - load) / load;
  printf("\n  3-D still tank, adami walls: the floor sensor reads %+.2f %% of rho0 g H at 0.3 s",
         100 * e);
  CU_ASSERT(fabs(e) < 0.025);
  free(v);
  sph_test_rmtree(d);
  free(d);
}

int main(void) {
  CU_TestInfo tests[] = {
      {"the extrapolation: a linear field continued, at rest and moving", test_extrapolation},
      {"two phases: the liquid's wall held at 0, the air's not", test_two_phases},
      {"the guard is the face itself", test_guard_at_face},
      {"a 2-D tank's side walls on the fluid's rows", test_side_walls},
      {"still water: the wall carries the hydrostatic pressure", test_still_water},
      {"still water with the leap-frog", test_still_water_leapfrog},
      {"a piston's work and the closed ledger", test_piston},
      {"still water in 3-D", test_still_water_3d},
      CU_TEST_INFO_NULL};
  return sph_test_main("adami walls", tests);
}
