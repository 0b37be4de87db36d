/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_walls_3d.c - walls in 3-D (built with -DSPH_DIM=3, linked with
 * src/libsph3.la): the mirror offsets of the box
 * tank and of box obstacles (src/walls/boundary.h), and the linear
 * moving-least-squares fit through them (src/walls/wall_velocity.h: the
 * 4 x 4 system of the 3-D fit) for the ghost velocity and the mdbc density.
 *
 * 1. Offsets. A 3-layer mdbc tank 0.1 x 0.06 x 0.05 m at dx = 0.01 m:
 *    every wall particle's mirror point x + m lies inside the tank, and
 *    along each axis it is the particle reflected in the face it lies
 *    behind (the same distance in front of the face), or the particle's
 *    own coordinate along an axis it does not lie behind: a wall's
 *    particle mirrors through its face, an edge's through the edge, a
 *    corner's through the corner. A box obstacle's particles (two layers
 *    of a 6 x 5 x 4 point box) mirror out of the box through their
 *    nearest face(s): the mirror point lies outside the box, as far from
 *    that face as the particle is behind it; standing on the floor, none
 *    through its bottom. The same tank closed (lid: true): 3 layers of
 *    16 x 12 over the top, each mirroring through it, and a sixth face.
 * 2. The fit. Fluid on the tank's lattice (600 particles) carrying a
 *    density and a velocity linear in x, y and z: every mdbc wall
 *    particle's density is the field at the particle (a field rising
 *    upwards, so that mdbc's limits do not act), and every no-slip
 *    wall particle's ghost velocity 2 v_wall - v(x + m), to 1e-10 of the
 *    field's scale (the fit is exact for linear fields; a Shepard average
 *    would be off by about the gradient times dx/2). Edges and corners
 *    included: their mirror points see a quarter or an eighth of a
 *    sphere of fluid. Periodic along y (the tank open along y, a field
 *    independent of y): the same, with the mirror points near the seam
 *    fitting across it.
 *    A density falling upwards as hydrostatics has it (1010 - 50 z, every
 *    fit's largest density that of its lowest particles): with the
 *    density's hydrostatic gradient given (head = (0, 0, -50)) the floor's
 *    particles take the field too, to 1e-10; without it (head 0) mdbc's
 *    limit to the fit's largest density cuts them (by 50 kg/m^4 times the
 *    height between the wall particle and the fit's lowest particle).
 * 3. Keeping off. sph_walls_keep_off on a tank (open along y) with a box
 *    obstacle standing on its floor: a fluid particle d in front of a face
 *    with d < d_min (or behind it, within the wall's thickness) ends
 *    2 d_min - d in front of it, its normal velocity turned into the fluid
 *    and its tangential velocity kept; one inside the obstacle grown by
 *    d_min leaves through the face it is nearest to (never through the
 *    bottom, which stands on the floor); one above a side wall's top, one
 *    far behind a wall, and ones clear of every face stay where they are;
 *    the kick sums m dr and m dv of the moves; the tank's open axis has
 *    no faces.
 * 4. A repulsive wall particle pushes a fluid particle across the seam of
 *    a domain periodic along y as it does inside it (the minimum image
 *    along y; it was along x only).
 * 5. Mirror planes: a particle near a corner of a mirror tank gets seven
 *    images (faces, edges, the corner), positions reflected and velocities
 *    reversed along those axes, vh = -v; near one face one; above the side
 *    walls' top within the reach the side's; images hold rho0 and 0 at least.
 * 6. Plates across the flume (geometry.walls in 3-D): on the lattice, layers
 *    dx apart on the segment's left, mirror points through the face.
 * 7. Moving plates: translation in three components, a piston along x, a
 *    flap turning about its hinge line along y.
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/particles.h"
#include "fit_lanes.h"
#include "neighbours/grid.h"
#include "testutil.h"
#include "walls/boundary.h"
#include "walls/repulsion.h"
#include "walls/wall_velocity.h"
#include "walls/walls.h"

#if SPH_DIM != 3
#error "test_walls_3d is built with -DSPH_DIM=3"
#endif

#define DX 0.01
#define H (1.3 * DX)
#define RHO0 1000.0

/* The tank of part 1 and 2: x 0..0.1, y 0..0.06, z 0..0.05 (open along y
 * when open_y). */
static sph_tank tank(int open_y) {
  sph_tank t = {0};
  t.present = 1;
  t.x0 = 0.0, t.x1 = 0.1, t.y0 = 0.0, t.y1 = 0.06, t.z0 = 0.0, t.z1 = 0.05;
  t.layers = 3;
  t.boundary = SPH_BOUNDARY_MDBC;
  t.open_along = open_y ? 2 : 0;
  return t;
}

/* A closed tank (geometry.tank.lid): the lid's layers over the whole top, the side walls' rims
 * too (the tank's layers continued upward, a lattice of 3 x 16 x 12 over a 10 x 6 inside), each
 * particle's mirror point inside the tank through the faces it lies behind (the lid's through
 * its top); the keep-off planes gain the lid, which puts back a particle that crossed it. */
static void test_lid(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 1024, &err) == 0);
  sph_tank t = tank(0);
  t.lid = 1;
  CU_ASSERT_FATAL(sph_boundary_add_tank(&p, &t, DX, RHO0, 1e-3, H, SPH_FLAG_MDBC, &err) == 0);
  size_t over = 0;
  double worst = 0.0;
  for (size_t i = 0; i < p.n; i++) {
    if (!(p.z[i] > t.z1)) continue;
    over++;
    const double want = 2.0 * t.z1 - p.z[i]; /* through the top */
    worst = fmax(worst, fabs(p.z[i] + p.mirror_offset[2][i] - want));
  }
  sph_wall_plane planes[6];
  const size_t n = sph_tank_planes(&t, 0.0, planes);
  int lid_plane = 0;
  for (size_t l = 0; l < n; l++)
    lid_plane += planes[l].axis == 2 && planes[l].dir == -1 && planes[l].at == t.z1;
  printf("\n    the lid: %zu particles over the top, mirror points off by at most %.1e m; %zu "
         "planes",
         over, worst, n);
  CU_ASSERT_EQUAL(over, 3 * 16 * 12);
  CU_ASSERT(worst < 1e-15);
  CU_ASSERT_EQUAL(n, 6);
  CU_ASSERT_EQUAL(lid_plane, 1);
  t.lid = 0;
  CU_ASSERT_EQUAL(sph_tank_planes(&t, 0.0, planes), 5);
  sph_particles_free(&p);
}

static void test_tank_offsets(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 1024, &err) == 0);
  const sph_tank t = tank(0);
  CU_ASSERT_FATAL(sph_boundary_add_tank(&p, &t, DX, RHO0, 1e-3, H, SPH_FLAG_MDBC, &err) == 0);
  const double lo[3] = {t.x0, t.y0, t.z0}, hi[3] = {t.x1, t.y1, t.z1};
  size_t behind[4] = {0}; /* particles behind 0 (none), 1 (walls), 2 (edges), 3 (corners) faces */
  double worst = 0.0;
  int inside = 1;
  for (size_t i = 0; i < p.n; i++) {
    int faces = 0;
    for (int a = 0; a < 3; a++) {
      const double x = p.pos[a][i], g = x + p.mirror_offset[a][i];
      double want = x; /* along an axis it is not behind: its own coordinate */
      if (x < lo[a]) want = 2.0 * lo[a] - x, faces++;
      if (x > hi[a]) want = 2.0 * hi[a] - x, faces++;
      worst = fmax(worst, fabs(g - want));
      if (!(g > lo[a] && (a == 2 || g < hi[a]))) inside = 0;
    }
    behind[faces]++;
  }
  printf("\n    %zu wall particles: %zu behind one face, %zu an edge, %zu a corner; "
         "mirror points off by at most %.1e m",
         p.n, behind[1], behind[2], behind[3], worst);
  CU_ASSERT_EQUAL(behind[0], 0);
  CU_ASSERT_EQUAL(behind[3], 4 * 27); /* four lower corners, 3 x 3 x 3 each */
  CU_ASSERT_EQUAL(behind[2], 4 * 9 * 5 + 2 * 9 * 10 + 2 * 9 * 6); /* vertical, x and y edges */
  CU_ASSERT(worst < 1e-15);
  CU_ASSERT(inside);
  sph_particles_free(&p);
}

static void test_obstacle_offsets(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 256, &err) == 0);
  /* 6 x 5 x 4 lattice points, a shell two deep: its inside 2 x 1 x 0 points, so all of it */
  const sph_obstacle o = {
      .lo = {0.2, 0.3, 0.0}, .hi = {0.26, 0.35, 0.04}, .layers = 2, .boundary = SPH_BOUNDARY_MDBC};
  CU_ASSERT_FATAL(sph_boundary_add_box(&p, &o, -INFINITY, DX, RHO0, 1e-3, H, SPH_FLAG_MDBC, &err) ==
                  0);
  CU_ASSERT_EQUAL(p.n, 6 * 5 * 4);
  int outside = 1, mirrored = 1;
  for (size_t i = 0; i < p.n; i++) {
    double dmin = INFINITY; /* the particle's distance to the box's nearest face */
    for (int a = 0; a < 3; a++)
      dmin = fmin(dmin, fmin(p.pos[a][i] - o.lo[a], o.hi[a] - p.pos[a][i]));
    int out = 0;
    for (int a = 0; a < 3; a++) {
      const double g = p.pos[a][i] + p.mirror_offset[a][i];
      if (g < o.lo[a] || g > o.hi[a]) out = 1;
      /* along a mirrored axis: as far in front of the nearest face as behind it */
      if (p.mirror_offset[a][i] != 0.0 &&
          !(fabs(fabs(p.mirror_offset[a][i]) - 2.0 * dmin) < 1e-15 &&
            (fabs(g - o.lo[a]) - dmin < 1e-15 || fabs(g - o.hi[a]) - dmin < 1e-15)))
        mirrored = 0;
    }
    if (!out) outside = 0;
  }
  CU_ASSERT(outside);
  CU_ASSERT(mirrored);
  /* the same box standing on a floor at z = 0: no mirror point below it */
  const size_t first = p.n;
  CU_ASSERT_FATAL(sph_boundary_add_box(&p, &o, 0.5 * DX, DX, RHO0, 1e-3, H, SPH_FLAG_MDBC, &err) ==
                  0);
  int above = 1;
  for (size_t i = first; i < p.n; i++)
    if (!(p.z[i] + p.mz[i] > 0.0)) above = 0;
  CU_ASSERT(above);
  sph_particles_free(&p);
}

/* The linear fields of part 2: density and velocity at x. The density
 * rises upwards (no wall particle's lies above the fluid's largest, where
 * mdbc limits it, nor below rho0), or, hydrostatic, falls upwards. */
static double density_at(const double x[3], int hydrostatic) {
  return hydrostatic ? 1010.0 - 50.0 * x[2] : 1010.0 + 50.0 * x[2];
}
static double velocity_at(int d, const double x[3], int periodic) {
  static const double base[3] = {0.3, -0.2, 0.1},
                      grad[3][3] = {{1.5, -0.7, 2.0}, {0.4, 1.1, -0.9}, {-1.2, 0.6, 0.8}};
  double v = base[d];
  for (int a = 0; a < 3; a++)
    if (!(periodic && a == 1)) v += grad[d][a] * x[a];
  return v;
}

/* The tank (open along y when periodic) with mdbc no-slip walls, fluid on
 * its lattice up to z = 0.05 carrying the linear fields (the hydrostatic
 * density or the rising one); fits both, mdbc's limit raised by the
 * hydrostatic gradient head_z along z, and returns the largest error of
 * the wall densities and of the ghost velocities (relative to 10 kg/m3 and
 * 0.1 m/s). */
static void fit_tank(int periodic, int hydrostatic, double head_z, double *err_rho, double *err_v) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 4096, &err) == 0);
  for (int k = 0; k < 5; k++)
    for (int j = 0; j < 6; j++)
      for (int i = 0; i < 10; i++) {
        const double x[3] = {(i + 0.5) * DX, (j + 0.5) * DX, (k + 0.5) * DX};
        double v[3];
        for (int d = 0; d < 3; d++)
          v[d] = velocity_at(d, x, periodic);
        const long q = sph_particles_add_at(&p, x, v, density_at(x, hydrostatic), 1e-3, H,
                                            SPH_KIND_FLUID, &err);
        CU_ASSERT_FATAL(q >= 0);
      }
  const size_t nf = p.n;
  const sph_tank t = tank(periodic);
  CU_ASSERT_FATAL(sph_boundary_add_tank(&p, &t, DX, RHO0, 1e-3, H, SPH_FLAG_MDBC | SPH_FLAG_NO_SLIP,
                                        &err) == 0);
  const double period = periodic ? 0.06 : 0.0;
  sph_wall_velocity_work w = {0};
  double *g = malloc(3 * p.n * sizeof *g);
  CU_ASSERT_FATAL(g != NULL);
  double *const gv[3] = {g, g + p.n, g + 2 * p.n};
  CU_ASSERT_FATAL(sph_wall_velocity(&p, 2.0 * H, 0.0, period, 1, gv, &w, &err) == 0);
  const double head[3] = {0.0, 0.0, head_z};
  CU_ASSERT_FATAL(sph_wall_mdbc_density(&p, 2.0 * H, 0.0, period, 1, RHO0, head, &w, &err) == 0);
  *err_rho = *err_v = 0.0;
  for (size_t i = 0; i < p.n; i++) {
    const double x[3] = {p.x[i], p.y[i], p.z[i]};
    if (i < nf) { /* the fluid keeps its own */
      CU_ASSERT(p.rho[i] == density_at(x, hydrostatic));
      for (int d = 0; d < 3; d++)
        CU_ASSERT(gv[d][i] == p.vel[d][i]);
      continue;
    }
    *err_rho = fmax(*err_rho, fabs(p.rho[i] - density_at(x, hydrostatic)) / 10.0);
    double m[3];
    for (int a = 0; a < 3; a++)
      m[a] = x[a] + p.mirror_offset[a][i];
    for (int d = 0; d < 3; d++) /* at rest: 2 * 0 - v(mirror point) */
      *err_v = fmax(*err_v, fabs(gv[d][i] + velocity_at(d, m, periodic)) / 0.1);
  }
  printf("\n    %s, %s density%s: %zu wall particles, density off by %.1e, ghost velocity by "
         "%.1e (relative)",
         periodic ? "periodic along y" : "closed tank", hydrostatic ? "hydrostatic" : "rising",
         hydrostatic && head_z == 0.0 ? " (no head)" : "", p.n - nf, *err_rho, *err_v);
  free(g);
  sph_wall_velocity_work_free(&w);
  sph_particles_free(&p);
}

static void test_fit_linear(void) {
  for (int periodic = 0; periodic < 2; periodic++) {
    double er, ev;
    fit_tank(periodic, 0, 0.0, &er, &ev);
    CU_ASSERT(er < 1e-10);
    CU_ASSERT(ev < 1e-10);
    fit_tank(periodic, 1, -50.0, &er, &ev);
    CU_ASSERT(er < 1e-10);
    CU_ASSERT(ev < 1e-10);
  }
  double er, ev; /* the limit without the weight of the fluid: the floor cut by 50 kg/m^4 x dx */
  fit_tank(0, 1, 0.0, &er, &ev);
  CU_ASSERT(er > 0.5 * 50.0 * DX / 10.0);
}

/* ---- 3. keeping off ------------------------------------------------------- */

static void test_keep_off(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 64, &err) == 0);
  /* the fluid particles first: position, velocity, and where they must end up */
  const double dm = 0.25 * DX; /* d_min */
  static const double cases[][9] = {
      /* x, y, z; vx, vy, vz; x, y, z after */
      {0.05, 0.03, 0.001, 0.1, 0.2, -0.3, 0.05, 0.03, 2 * 0.0025 - 0.001}, /* near the floor */
      {0.05, 0.03, -0.004, 0.1, 0.2, 0.3, 0.05, 0.03, 2 * 0.0025 + 0.004}, /* crossed it */
      {0.0005, 0.03, 0.02, -1.0, 0.0, 0.0, 0.0045, 0.03, 0.02},            /* the side at x0 */
      {0.0995, 0.03, 0.02, 1.0, 0.0, 0.0, 0.0955, 0.03, 0.02},             /* the side at x1 */
      {0.0005, 0.03, 0.06, -1.0, 0.0, 0.0, 0.0005, 0.03, 0.06},  /* above the sides' top */
      {-0.05, 0.03, 0.02, 0.0, 0.0, 0.0, -0.05, 0.03, 0.02},     /* far behind the wall */
      {0.05, 0.0005, 0.02, 0.0, -1.0, 0.0, 0.05, 0.0005, 0.02},  /* y is open: no face */
      {0.05, 0.03, 0.03, 0.0, 0.0, 0.0, 0.05, 0.03, 0.03},       /* clear of every face */
      {0.0605, 0.03, 0.005, 0.5, 0.0, 0.0, 0.0545, 0.03, 0.005}, /* inside the box: out at x */
      {0.07, 0.03, 0.0195, 0.0, 0.0, -0.5, 0.07, 0.03, 0.0255},  /* just below its top */
      {0.07, 0.0401, 0.012, 0.0, 0.0, 0.0, 0.07, 0.0399 + 2 * dm, 0.012}, /* out through y */
  };
  const size_t nc = sizeof cases / sizeof cases[0];
  for (size_t k = 0; k < nc; k++) {
    const long q =
        sph_particles_add_at(&p, cases[k], cases[k] + 3, RHO0, 1e-3, H, SPH_KIND_FLUID, &err);
    CU_ASSERT_FATAL(q >= 0);
  }
  const sph_tank t = tank(1);
  /* the box x 0.06..0.08, y 0.02..0.04, z 0..0.02: on the floor */
  const sph_obstacle o = {.lo = {0.06, 0.02, 0.0},
                          .hi = {0.08, 0.04, 0.02},
                          .layers = 2,
                          .boundary = SPH_BOUNDARY_DYNAMIC};
  sph_walls w;
  CU_ASSERT_FATAL(sph_walls_create(&w, &p, &t, NULL, 0, &o, 1, DX, RHO0, H, 0.0, &err) == 0);
  CU_ASSERT_EQUAL(w.n_plane, 3); /* floor, x0, x1 */
  double kick[6] = {0.0};
  const size_t moved = sph_walls_keep_off(&w, &p, dm, 0, kick);
  CU_ASSERT_EQUAL(moved, 7);
  double want[6] = {0.0};
  for (size_t k = 0; k < nc; k++) {
    int ok = 1;
    for (int a = 0; a < 3; a++) {
      const double moved_by = cases[k][6 + a] - cases[k][a];
      want[a] += p.mass[k] * moved_by;
      if (fabs(p.pos[a][k] - cases[k][6 + a]) > 1e-15) ok = 0;
      /* the velocity: the normal component into the fluid where it moved */
      const double v = cases[k][3 + a];
      const double expect = moved_by != 0.0 && v * moved_by < 0.0 ? -v : v;
      want[3 + a] += p.mass[k] * (expect - v);
      if (p.vel[a][k] != expect) ok = 0;
    }
    if (!ok)
      printf("\n    case %zu: at (%.6f, %.6f, %.6f) v (%g, %g, %g)", k, p.x[k], p.y[k], p.z[k],
             p.vx[k], p.vy[k], p.vz[k]);
    CU_ASSERT(ok);
  }
  for (int a = 0; a < 6; a++)
    CU_ASSERT(fabs(kick[a] - want[a]) < 1e-18);
  /* a second pass moves nothing */
  CU_ASSERT_EQUAL(sph_walls_keep_off(&w, &p, dm, 0, NULL), 0);
  sph_particles_free(&p);
}

/* ---- 5. mirror planes ------------------------------------------------------ */

/* A 3-D mirror tank (x 0..0.1, y 0..0.06, z 0..0.05, reach 0.02): a fluid
 * particle near a lower corner gets seven images (three faces, three edges,
 * the corner), each its position reflected in those planes and its velocity
 * reversed along their axes, with vh = -v; one near a single face gets one;
 * one above the side walls' top by less than the reach is mirrored in the
 * side (the plane spans it), one farther away in none; images never below
 * rho0 and 0. */
static void test_mirror_planes(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 64, &err) == 0);
  const double corner[3] = {0.004, 0.003, 0.002}, face[3] = {0.05, 0.03, 0.01},
               above[3] = {0.005, 0.03, 0.06}, far[3] = {0.005, 0.03, 0.08},
               v[3] = {0.1, -0.2, 0.3};
  const double *at[4] = {corner, face, above, far};
  for (int k = 0; k < 4; k++)
    CU_ASSERT_FATAL(sph_particles_add_at(&p, at[k], v, k == 1 ? 990.0 : 1001.0, 1e-3, H,
                                         SPH_KIND_FLUID, &err) == k);
  p.p[0] = 50.0, p.p[1] = -10.0;
  const sph_tank t = tank(0);
  sph_wall_plane pl[6]; /* (room for a lid: sph_tank_planes fills up to 6) */
  const size_t np = sph_tank_planes(&t, 0.02, pl);
  CU_ASSERT_EQUAL(np, 5);
  CU_ASSERT_EQUAL(sph_mirror_add_planes(&p, pl, np, 0.02, RHO0, &err), 7 + 1 + 1);
  CU_ASSERT_EQUAL(p.n, 4 + 9);
  const double lo[3] = {0.0, 0.0, 0.0};
  int seen[8] = {0}, good = 1;
  for (size_t k = 4; k < 11; k++) { /* the corner's images */
    unsigned axes = 0;
    for (int a = 0; a < 3; a++) {
      const int flipped = p.pos[a][k] != corner[a];
      axes |= (unsigned)flipped << a;
      const double want_x = flipped ? 2.0 * lo[a] - corner[a] : corner[a];
      const double want_v = flipped ? -v[a] : v[a];
      if (fabs(p.pos[a][k] - want_x) > 1e-17 || p.vel[a][k] != want_v || p.velh[a][k] != -v[a])
        good = 0;
    }
    seen[axes]++;
    good &= p.kind[k] == SPH_KIND_MIRROR && p.rho[k] == 1001.0 && p.p[k] == 50.0;
  }
  CU_ASSERT(good);
  for (int m = 1; m < 8; m++)
    CU_ASSERT_EQUAL(seen[m], 1); /* each set of the three planes once */
  /* the face's image: below the floor, density and pressure not below rho0 and 0 */
  CU_ASSERT(fabs(p.z[11] + 0.01) < 1e-17 && p.x[11] == 0.05 && p.vz[11] == -0.3);
  CU_ASSERT(p.rho[11] == RHO0 && p.p[11] == 0.0);
  /* above the side's top, within the reach: mirrored in the side x = 0 */
  CU_ASSERT(fabs(p.x[12] + 0.005) < 1e-17 && p.z[12] == 0.06);
  sph_particles_free(&p);
}

/* ---- 4. repulsive walls across a periodic seam ----------------------------- */

/* The acceleration of a fluid particle at y = yf from a repulsive wall
 * particle at y = yw, 0.36 dx further along x, on a domain periodic along y
 * over [0, 0.1), into acc. */
static void repel(double yf, double yw, double acc[3]) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 8, &err) == 0);
  const double xf[3] = {0.05, yf, 0.05}, xw[3] = {0.05 + 0.0036, yw, 0.05}, v[3] = {0.0};
  CU_ASSERT_FATAL(sph_particles_add_at(&p, xf, v, RHO0, 1e-3, H, SPH_KIND_FLUID, &err) >= 0);
  const long w = sph_particles_add_at(&p, xw, v, RHO0, 1e-3, H, SPH_KIND_WALL, &err);
  CU_ASSERT_FATAL(w >= 0);
  p.flags[w] = SPH_FLAG_REPULSIVE;
  sph_grid g;
  sph_nlist l;
  sph_grid_init(&g);
  sph_nlist_init(&l);
  CU_ASSERT_FATAL(sph_grid_build_periodic(&g, &p, 2.0 * H, SPH_AXIS_Y, 0.0, 0.1, 1u << 20, &err) ==
                  0);
  CU_ASSERT_FATAL(sph_nlist_build(&l, &g, &p, 2.0 * H, 0.0, 0.1, &err) == 0);
  for (int a = 0; a < 3; a++)
    p.acc[a][0] = p.acc[a][1] = 0.0;
  sph_repulsion_add(&p, &l, 1.0, DX, NULL);
  for (size_t i = 0; i < p.n; i++)
    if (p.kind[i] == SPH_KIND_FLUID)
      for (int a = 0; a < 3; a++)
        acc[a] = p.acc[a][i];
  sph_nlist_free(&l);
  sph_grid_free(&g);
  sph_particles_free(&p);
}

static void test_repulsion_periodic(void) {
  double inside[3], across[3];
  repel(0.05, 0.05 + 0.0048, inside);           /* 0.6 dx apart, both well inside the period */
  repel(0.0985, 0.0985 + 0.0048 - 0.1, across); /* the same pair across the seam at y = 0.1 */
  printf("\n    repulsion: (%.6g, %.6g, %.6g) inside, (%.6g, %.6g, %.6g) across the seam",
         inside[0], inside[1], inside[2], across[0], across[1], across[2]);
  CU_ASSERT(inside[1] < 0.0 && inside[0] < 0.0); /* pushed away from the wall particle */
  for (int a = 0; a < 3; a++)
    CU_ASSERT(fabs(across[a] - inside[a]) <= 1e-9 * fabs(inside[1]));
}

/* 6. Plates across the flume (3-D wall segments, geometry.walls): a
 * vertical gate from (x, z) = (0.05, 0.005) up to (0.05, 0.045) across the
 * tank's y range and a plate inclined at 45 degrees, two and three layers:
 * the counts, every particle's y on the fluid's lattice, the layers dx
 * apart on the segment's left (x right, z up), and the mdbc plate's mirror
 * points dx/2 + its depth in front of its face, on the fluid's side. */
static void test_plates(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 1024, &err) == 0);
  sph_wall_segment w[2] = {{0}};
  w[0].x0 = 0.05, w[0].z0 = 0.005, w[0].x1 = 0.05, w[0].z1 = 0.045, w[0].y0 = 0.0, w[0].y1 = 0.06;
  w[0].layers = 2, w[0].boundary = SPH_BOUNDARY_DYNAMIC;
  const double r = 0.03 / sqrt(2.0); /* 3 dx long, along (1, 1) / sqrt 2 */
  w[1].x0 = 0.0, w[1].z0 = 0.0, w[1].x1 = r, w[1].z1 = r, w[1].y0 = 0.01, w[1].y1 = 0.05;
  w[1].layers = 3, w[1].boundary = SPH_BOUNDARY_MDBC;
  const size_t n0 = 2 * 5 * 6; /* layers x (4 spacings + 1) x 6 across */
  CU_ASSERT_FATAL(sph_boundary_add_plate(&p, &w[0], DX, RHO0, 1e-3, H, 0, &err) == 0);
  CU_ASSERT_EQUAL_FATAL(p.n, n0);
  CU_ASSERT_FATAL(sph_boundary_add_plate(&p, &w[1], DX, RHO0, 1e-3, H, SPH_FLAG_MDBC, &err) == 0);
  CU_ASSERT_EQUAL_FATAL(p.n, n0 + 3 * 4 * 4);
  double worst = 0.0;
  size_t per_layer[3] = {0};
  for (size_t i = 0; i < p.n; i++) {
    const int k = i >= n0;
    const sph_wall_segment *s = &w[k];
    const double len = hypot(s->x1 - s->x0, s->z1 - s->z0);
    const double tx = (s->x1 - s->x0) / len, tz = (s->z1 - s->z0) / len;
    const double rx = p.x[i] - s->x0, rz = p.z[i] - s->z0;
    const double left = -tz * rx + tx * rz, along = tx * rx + tz * rz; /* left of A->B */
    const double layer = left / DX, j = (p.y[i] - s->y0) / DX - 0.5;
    worst = fmax(worst, fabs(layer - floor(layer + 0.5)));
    worst = fmax(worst, fabs(j - floor(j + 0.5)));
    worst = fmax(worst, fabs(along / DX - floor(along / DX + 0.5)));
    if (!(p.y[i] > s->y0 && p.y[i] < s->y1)) worst = 1.0;
    if (k == 1) {
      per_layer[(int)floor(layer + 0.5)]++;
      /* the mirror point: as far in front of the face (dx/2 right of the segment) as the
       * particle is behind it, along the face's normal; y unchanged */
      const double gx = p.x[i] + p.mx[i] - s->x0, gz = p.z[i] + p.mz[i] - s->z0;
      const double gleft = -tz * gx + tx * gz, galong = tx * gx + tz * gz;
      worst = fmax(worst, fabs((-0.5 * DX - gleft) - (left + 0.5 * DX)));
      worst = fmax(worst, fabs(galong - along) + fabs(p.my[i]));
    }
  }
  printf("\n    %zu plate particles, layers of the inclined one %zu %zu %zu; off the lattice or "
         "the mirror rule by at most %.1e",
         p.n, per_layer[0], per_layer[1], per_layer[2], worst);
  CU_ASSERT(worst < 1e-12);
  CU_ASSERT(per_layer[0] == 16 && per_layer[1] == 16 && per_layer[2] == 16);
  sph_particles_free(&p);
}

/* 7. Moving plates: sph_walls_move puts a translated plate at its rest
 * position plus v (t - start) with v in three components (at rest before
 * start, stopped after stop), a piston moves along x only, and a flap turns
 * in the x-z plane about its hinge line along y: y kept, the distance to
 * the hinge kept, the velocity normal to the radius. */
static void test_moving_plates(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 1024, &err) == 0);
  sph_tank none = {0};
  sph_wall_segment w[3] = {{0}};
  for (int k = 0; k < 3; k++) {
    w[k].x0 = 0.1 * k, w[k].z0 = 0.0, w[k].x1 = 0.1 * k, w[k].z1 = 0.05;
    w[k].y0 = 0.0, w[k].y1 = 0.03, w[k].layers = 2, w[k].boundary = SPH_BOUNDARY_DYNAMIC;
  }
  w[0].motion.kind = SPH_MOTION_TRANSLATE;
  w[0].motion.vx = 0.5, w[0].motion.vy = -0.25, w[0].motion.vz = 1.0;
  w[0].motion.start = 0.1, w[0].motion.stop = 0.3;
  for (int k = 1; k < 3; k++) {
    w[k].motion.kind = k == 1 ? SPH_MOTION_PISTON : SPH_MOTION_FLAP;
    sph_paddle *pd = &w[k].motion.paddle;
    pd->kind = k == 1 ? SPH_PADDLE_PISTON : SPH_PADDLE_FLAP;
    pd->period = 1.0, pd->stroke = 0.02, pd->depth = 0.04, pd->ramp = 0.0;
    pd->hinge_x = w[k].x0, pd->hinge_y = 0.0; /* the hinge's height: z */
    w[k].motion.stop = INFINITY;
  }
  sph_walls walls;
  CU_ASSERT_FATAL(sph_walls_create(&walls, &p, &none, w, 3, NULL, 0, DX, RHO0, H, 0.0, &err) == 0);
  CU_ASSERT_FATAL(walls.moving && (p.live & SPH_ARRAYS_REST));
  const double times[4] = {0.05, 0.2, 0.3, 0.42};
  double worst = 0.0;
  size_t moved[3] = {0};
  for (int n = 0; n < 4; n++) {
    const double t = times[n];
    sph_walls_move(&walls, &p, t);
    for (size_t i = 0; i < p.n; i++) {
      const int k = p.body[i];
      const double dx = p.x[i] - p.xr[i], dy = p.y[i] - p.yr[i], dz = p.z[i] - p.zr[i];
      moved[k] += dx != 0.0 || dz != 0.0;
      if (k == 0) {
        const double te = t < 0.1 ? 0.0 : (t < 0.3 ? t : 0.3) - 0.1, on = t > 0.1 && t < 0.3;
        worst = fmax(worst, fabs(dx - 0.5 * te) + fabs(dy + 0.25 * te) + fabs(dz - te));
        worst = fmax(worst, fabs(p.vx[i] - 0.5 * on) + fabs(p.vy[i] + 0.25 * on) +
                                fabs(p.vz[i] - 1.0 * on));
      } else if (k == 1) {
        worst = fmax(worst, fabs(dy) + fabs(dz) + fabs(p.vy[i]) + fabs(p.vz[i])); /* along x */
      } else {
        const double hx = w[2].x0, rx = p.x[i] - hx, rz = p.z[i];
        const double r0 = hypot(p.xr[i] - hx, p.zr[i]);
        worst = fmax(worst, fabs(dy) + fabs(p.vy[i]) + fabs(hypot(rx, rz) - r0));
        worst = fmax(worst, fabs(p.vx[i] * rx + p.vz[i] * rz));
      }
    }
  }
  printf("\n    moved: translate %zu, piston %zu, flap %zu particle-times; off the laws by %.1e",
         moved[0], moved[1], moved[2], worst);
  CU_ASSERT(worst < 1e-14);
  CU_ASSERT(moved[0] == 3 * 2 * 6 * 3); /* moving or stopped at 0.2, 0.3, 0.42 s */
  CU_ASSERT(moved[1] > 0 && moved[2] > 0);
  sph_particles_free(&p);
}

int main(void) {
  CU_TestInfo tests[] = {
      {"3-D tank: mirror points through faces, edges and corners", test_tank_offsets},
      {"3-D closed tank: the lid's layers, mirror points and face", test_lid},
      {"3-D box obstacle: mirror points out through the nearest faces", test_obstacle_offsets},
      {"3-D linear fit: mdbc density and ghost velocity exact for linear fields, also hydrostatic",
       test_fit_linear},
      {"3-D keeping off: the tank's faces and a box obstacle", test_keep_off},
      {"3-D fits: eight lanes give the two lanes' bits (random cloud)", test_fit_lanes},
      {"3-D repulsive wall across a periodic seam along y", test_repulsion_periodic},
      {"3-D mirror planes: images through faces, edges and corners", test_mirror_planes},
      {"3-D plates across the flume: lattice, layers and mirror points", test_plates},
      {"3-D moving plates: translate, piston and flap", test_moving_plates},
      CU_TEST_INFO_NULL};
  return sph_test_main("walls_3d", tests);
}
