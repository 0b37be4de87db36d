/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_wall_velocity.c - unstaggered wall layers and the extrapolated
 * (no-slip) velocity of wall particles (src/walls/boundary.h, src/walls/wall_velocity.h).
 *
 * 1. Layers. sph_boundary_add_segment with stagger = 0 puts layer k at k dx
 *    from layer 0, at the same positions along the wall; every particle's
 *    mirror offset is twice its depth below the wall face (dx/2 in front of
 *    layer 0) along the face's normal into the fluid; staggered layers have
 *    depths dx/2 + k dx/2. An unstaggered tank (sph_boundary_add_tank) with
 *    3 layers: the floor's layers reach under the side walls, so the
 *    corner squares are filled on the lattice with no particle twice.
 * 2. Ghost velocity. A 16 x 10 lattice of fluid above a bed of 4
 *    unstaggered no-slip layers, with a velocity field linear in x and y
 *    (u = U + a x + b y, v = V + c x + d y): the linear moving-least-squares
 *    fit is exact for it, so every wall particle gets 2 v_wall - v(mirror
 *    point) to round-off (checked to 1e-12 of the field's scale), also
 *    with the wall moving (v_wall = (0.3, -0.1)), and on a domain periodic
 *    in x with a field u = U + b y (periodic) and the mirror points of the
 *    end particles' neighbours across the seam. A wall particle without
 *    the flag, and the fluid, keep their own velocity (bitwise); a no-slip
 *    wall whose mirror point no fluid reaches keeps its wall velocity.
 *    The Shepard average (what the fit falls back to) would be off by
 *    about b dx / 2 on the first wall row: the test would see that.
 * 3. The shear film is symmetric: for u = b y the ghost velocity of the
 *    wall particle at depth d is -b d (the field continued through y = 0).
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "case/case.h"
#include "core/particles.h"
#include "fit_lanes.h"
#include "testutil.h"
#include "walls/boundary.h"
#include "walls/wall_velocity.h"

#define DX 0.01
#define H (1.3 * DX)

/* ---- 1. layers ------------------------------------------------------------ */

static void test_unstaggered_segment(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 64, &err) == 0);
  /* a bed from x = 0.095 to 0.005 at y = -dx/2: fluid above (right of A->B) */
  CU_ASSERT_FATAL(sph_boundary_add_segment(&p, 0.095, -0.005, 0.005, -0.005, 3, 0, 0, DX, 1000.0,
                                           0.1, H, SPH_FLAG_NO_SLIP, &err) == 0);
  CU_ASSERT_EQUAL(p.n, 30);
  for (size_t i = 0; i < p.n; i++) {
    const int k = (int)(i / 10);
    const double depth = 0.005 + k * DX;
    CU_ASSERT(fabs(p.y[i] + depth) < 1e-15);
    CU_ASSERT(fabs(p.x[i] - (0.095 - (double)(i % 10) * DX)) < 1e-15);
    CU_ASSERT(p.mx[i] == 0.0);
    CU_ASSERT(fabs(p.my[i] - 2.0 * depth) < 1e-15); /* the mirror point is at y = +depth */
    CU_ASSERT(p.flags[i] == SPH_FLAG_NO_SLIP && p.kind[i] == SPH_KIND_WALL);
  }
  /* staggered: depth dx/2 + k dx/2, odd layers count + 2 particles */
  sph_particles q;
  CU_ASSERT_FATAL(sph_particles_init(&q, 64, &err) == 0);
  CU_ASSERT_FATAL(sph_boundary_add_segment(&q, 0.095, -0.005, 0.005, -0.005, 2, 1, 0, DX, 1000.0,
                                           0.1, H, 0, &err) == 0);
  CU_ASSERT_EQUAL(q.n, 10 + 11);
  for (size_t i = 0; i < q.n; i++) {
    const double depth = i < 10 ? 0.005 : 0.01;
    CU_ASSERT(fabs(q.y[i] + depth) < 1e-15);
    CU_ASSERT(fabs(q.my[i] - 2.0 * depth) < 1e-15);
  }
  /* a vertical wall drawn upwards: the fluid on its right (+x) */
  sph_particles v;
  CU_ASSERT_FATAL(sph_particles_init(&v, 64, &err) == 0);
  CU_ASSERT_FATAL(sph_boundary_add_segment(&v, -0.005, 0.0, -0.005, 0.1, 2, 0, 0, DX, 1000.0, 0.1,
                                           H, 0, &err) == 0);
  for (size_t i = 0; i < v.n; i++) {
    const double depth = -v.x[i];
    CU_ASSERT(fabs(v.mx[i] - 2.0 * depth) < 1e-15);
    CU_ASSERT(v.my[i] == 0.0);
  }
  sph_particles_free(&p);
  sph_particles_free(&q);
  sph_particles_free(&v);
}

static int cmp_point(const void *a, const void *b) {
  const double *p = a, *q = b;
  if (p[0] != q[0]) return p[0] < q[0] ? -1 : 1;
  if (p[1] != q[1]) return p[1] < q[1] ? -1 : 1;
  return 0;
}

static void test_unstaggered_tank(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 256, &err) == 0);
  sph_tank t = {.present = 1,
                .x1 = 0.1,
                .y1 = 0.055,
                .layers = 3,
                .boundary = SPH_BOUNDARY_FIXED_LAYERS,
                .extrapolated = 1};
  CU_ASSERT_FATAL(sph_boundary_add_tank(&p, &t, DX, 1000.0, 0.1, H, 0, &err) == 0);
  /* every particle on the lattice (i + 1/2) dx, no two alike */
  double *pts = malloc(2 * p.n * sizeof *pts);
  CU_ASSERT_FATAL(pts != NULL);
  for (size_t i = 0; i < p.n; i++) {
    const double fx = p.x[i] / DX - 0.5, fy = p.y[i] / DX - 0.5;
    CU_ASSERT(fabs(fx - round(fx)) < 1e-9 && fabs(fy - round(fy)) < 1e-9);
    pts[2 * i] = round(fx);
    pts[2 * i + 1] = round(fy);
  }
  qsort(pts, p.n, 2 * sizeof *pts, cmp_point);
  size_t dup = 0;
  for (size_t i = 1; i < p.n; i++)
    dup += cmp_point(pts + 2 * (i - 1), pts + 2 * i) == 0;
  CU_ASSERT_EQUAL(dup, 0);
  /* the corner squares below-left and below-right: 3 x 3 cells each */
  size_t corner = 0;
  for (size_t i = 0; i < p.n; i++)
    if (p.y[i] < 0.0 && (p.x[i] < 0.0 || p.x[i] > 0.1)) corner++;
  CU_ASSERT_EQUAL(corner, 18);
  /* floor: 3 rows of 10 + 2 * 3; side walls: 3 columns of 6, y = dx/2 .. y1 */
  CU_ASSERT_EQUAL(p.n, 3 * 16 + 2 * 3 * 6);
  free(pts);
  sph_particles_free(&p);
}

/* ---- 2. ghost velocity ---------------------------------------------------- */

typedef struct field {
  double U, a, b, V, c, d;
} field;

static void eval(const field *f, double x, double y, double *u, double *v) {
  *u = f->U + f->a * x + f->b * y;
  *v = f->V + f->c * x + f->d * y;
}

/* 16 x 10 fluid lattice on [0, 0.16] x [0, 0.1] above a bed of 4 no-slip
 * unstaggered layers (and, with `extra`, one unflagged wall particle and
 * a no-slip particle far above the fluid). */
static void build(sph_particles *p, const field *f, double wu, double wv, int extra) {
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(p, 512, &err) == 0);
  for (int j = 0; j < 10; j++)
    for (int i = 0; i < 16; i++) {
      const double x = (i + 0.5) * DX, y = (j + 0.5) * DX;
      double u, v;
      eval(f, x, y, &u, &v);
      CU_ASSERT_FATAL(sph_particles_add(p, x, y, u, v, 1000.0, 0.1, H, SPH_KIND_FLUID, &err) >= 0);
    }
  const size_t first = p->n;
  CU_ASSERT_FATAL(sph_boundary_add_segment(p, 0.155, -0.005, 0.005, -0.005, 4, 0, 0, DX, 1000.0,
                                           0.1, H, SPH_FLAG_NO_SLIP, &err) == 0);
  for (size_t i = first; i < p->n; i++) {
    p->vx[i] = wu;
    p->vy[i] = wv;
  }
  if (extra) {
    long k = sph_particles_add(p, 0.08, -0.02, wu, wv, 1000.0, 0.1, H, SPH_KIND_WALL, &err);
    CU_ASSERT_FATAL(k >= 0); /* no flag: keeps its velocity */
    k = sph_particles_add(p, 0.08, 0.5, wu, wv, 1000.0, 0.1, H, SPH_KIND_WALL, &err);
    CU_ASSERT_FATAL(k >= 0);
    p->flags[k] = SPH_FLAG_NO_SLIP;
    p->my[k] = 0.2; /* mirror point at y = 0.7: no fluid there */
  }
}

static double check_ghosts(const sph_particles *p, const field *f, double wu, double wv,
                           const double *gx, const double *gy, size_t *checked) {
  double worst = 0.0;
  *checked = 0;
  for (size_t i = 0; i < p->n; i++) {
    if (!(p->flags[i] & SPH_FLAG_NO_SLIP) || p->y[i] > 0.0) {
      CU_ASSERT(gx[i] == p->vx[i] && gy[i] == p->vy[i]); /* own velocity, bitwise */
      continue;
    }
    double u, v;
    eval(f, p->x[i] + p->mx[i], p->y[i] + p->my[i], &u, &v);
    const double eu = fabs(gx[i] - (2.0 * wu - u)), ev = fabs(gy[i] - (2.0 * wv - v));
    if (eu > worst) worst = eu;
    if (ev > worst) worst = ev;
    (*checked)++;
  }
  return worst;
}

static void test_ghost_linear(void) {
  const field f = {0.2, 1.5, 3.0, -0.1, 0.7, -1.5};
  const double moving[2][2] = {{0.0, 0.0}, {0.3, -0.1}};
  for (int m = 0; m < 2; m++) {
    sph_particles p;
    sph_error err;
    build(&p, &f, moving[m][0], moving[m][1], 1);
    double *g = malloc(2 * p.n * sizeof *g);
    CU_ASSERT_FATAL(g != NULL);
    sph_wall_velocity_work w = {0};
    double *const gv[2] = {g, g + p.n};
    CU_ASSERT_FATAL(sph_wall_velocity(&p, 2.0 * H, 0.0, 0.0, 0, gv, &w, &err) == 0);
    sph_wall_velocity_work_free(&w);
    size_t checked;
    const double worst = check_ghosts(&p, &f, moving[m][0], moving[m][1], g, g + p.n, &checked);
    printf("\n  linear field, wall velocity (%g, %g): %zu ghosts, worst error %.2e m/s",
           moving[m][0], moving[m][1], checked, worst);
    CU_ASSERT_EQUAL(checked, 4 * 16);
    CU_ASSERT(worst < 1e-12);
    /* the far no-slip particle: its own (wall) velocity */
    CU_ASSERT(g[p.n - 1] == moving[m][0] && g[2 * p.n - 1] == moving[m][1]);
    free(g);
    sph_particles_free(&p);
  }
  printf("\n");
}

static void test_ghost_periodic(void) {
  /* periodic in x over [0, 0.16): the field must be periodic, u = b y */
  const field f = {0.0, 0.0, 3.0, 0.05, 0.0, 0.0};
  sph_particles p;
  sph_error err;
  build(&p, &f, 0.0, 0.0, 0);
  double *g = malloc(2 * p.n * sizeof *g);
  CU_ASSERT_FATAL(g != NULL);
  sph_wall_velocity_work w = {0};
  /* twice through the same work: reused buffers give the same result */
  double *const gv[2] = {g, g + p.n};
  for (int pass = 0; pass < 2; pass++) {
    CU_ASSERT_FATAL(sph_wall_velocity(&p, 2.0 * H, 0.0, 0.16, 0, gv, &w, &err) == 0);
    size_t checked;
    const double worst = check_ghosts(&p, &f, 0.0, 0.0, g, g + p.n, &checked);
    CU_ASSERT_EQUAL(checked, 4 * 16);
    CU_ASSERT(worst < 1e-12);
    if (pass == 0) printf("\n  periodic: %zu ghosts, worst error %.2e m/s\n", checked, worst);
  }
  /* shear through the bed: the ghost at y = -d is -b d, u continued */
  for (size_t i = 0; i < p.n; i++)
    if (p.kind[i] == SPH_KIND_WALL) CU_ASSERT(fabs(g[i] - f.b * p.y[i]) < 1e-12);
  sph_wall_velocity_work_free(&w);
  free(g);
  sph_particles_free(&p);
}

/* ---- 3. the case keys ------------------------------------------------------ */

static void test_case_keys(void) {
  const char *base = sph_test_src("cases/inclined_plane.yaml");
  sph_case c;
  sph_error err;
  CU_ASSERT_FATAL(sph_case_load(base, NULL, 0, &c, &err) == 0);
  CU_ASSERT(c.gradient_correction == 1);
  CU_ASSERT_FATAL(c.n_walls == 1);
  CU_ASSERT(c.walls[0].stagger == 0 && c.walls[0].extrapolated == 1 && c.walls[0].layers == 4);
  sph_case_free(&c);
  struct {
    const char *set, *want;
  } bad[] = {
      {"physics.viscosity.model=morris",
       "physics.viscosity.gradient_correction: corrects the stress-tensor viscosity"},
      {"geometry.walls=[{from: [1.0e-3, 0], to: [0, 0], boundary: repulsive, stagger: false}]",
       "geometry.walls[0].stagger: only for 'dynamic', 'fixed_layers', 'mdbc' and 'adami' walls"},
      {"geometry.walls=[{from: [1.0e-3, 0], to: [0, 0], stagger: maybe}]",
       "geometry.walls[0].stagger: expected"},
      {"geometry.walls=[{from: [1.0e-3, 0], to: [0, 0], extrapolated_velocity: true, "
       "motion: {type: flap, period: 1, stroke: 0.1, depth: 1}}]",
       "geometry.walls[0].extrapolated_velocity: not on a turning wall"},
  };
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    const char *set[] = {bad[k].set};
    int rc = sph_case_load(base, set, 1, &c, &err);
    printf("\n  --set %s: %s", bad[k].set, rc ? err.msg : "(accepted)");
    CU_ASSERT(rc != 0);
    if (rc) CU_ASSERT(strstr(err.msg, bad[k].want) != NULL);
  }
  /* extrapolated velocity without a strain-rate pass */
  const char *set2[] = {"physics.viscosity.gradient_correction=false",
                        "physics.viscosity.model=morris"};
  int rc = sph_case_load(base, set2, 2, &c, &err);
  printf("\n  morris viscosity with extrapolated_velocity: %s\n", rc ? err.msg : "(accepted)");
  CU_ASSERT(rc != 0);
  if (rc)
    CU_ASSERT(
        strstr(err.msg, "geometry.walls[0].extrapolated_velocity: acts in the strain-rate pass") !=
        NULL);
}

int main(void) {
  CU_TestInfo tests[] = {
      {"unstaggered and staggered layers, mirror offsets", test_unstaggered_segment},
      {"unstaggered tank: corners filled, no duplicates", test_unstaggered_tank},
      {"ghost velocity of a linear field, walls at rest and moving", test_ghost_linear},
      {"ghost velocity across a periodic seam; shear continued", test_ghost_periodic},
      {"case keys: stagger, extrapolated_velocity, gradient_correction", test_case_keys},
      {"the fits' eight lanes give the two lanes' bits (random cloud)", test_fit_lanes},
      CU_TEST_INFO_NULL};
  return sph_test_main("wall velocity", tests);
}
