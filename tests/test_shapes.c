/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_shapes.c - fluid blocks of other shapes than boxes (src/case/shape.c,
 * doc/case-files.md, Shapes), built twice: test_shapes (2-D: polygons and
 * circles) and test_shapes_3d (-DSPH_DIM=3: polygon prisms, spheres,
 * cylinders and closed surfaces from mesh files).
 *
 * 1. A polygon that is the box's rectangle (either way round) makes the
 *    box's particles bit for bit (in 3-D the prism of that rectangle
 *    across the box's y range).
 * 2. The filled area or volume, N dx^d, against the shape's: a circle or
 *    a sphere 20 particles across within 1 %, a tilted cylinder 20 across
 *    and 40 long within 1 %; a polygon with edges on the lattice's cell
 *    faces exactly.
 * 3. Bad shapes are refused at their key with file, line and what was
 *    expected: a polygon that crosses itself, has fewer than 3 vertices,
 *    repeats a vertex or has no area; a shape beside a box range; two
 *    shapes in one block; a shape outside the tank; a cylinder whose ends
 *    are one point; two shaped blocks that overlap (refused when the
 *    particles are made, naming both blocks and a point).
 * 4. (2-D) Still water over a sloped beach, the water a polygon and the
 *    beach a sloped wall of the default scheme's model (the shipped
 *    cases/sloped_beach.yaml's flume at rest), at dx = 0.02 and 0.01 m:
 *    after 0.5 s no particle is below the beach's surface and the largest
 *    speed is below 10 % of sqrt(g d) (the lattice's staircase along the
 *    1:4 slope settles onto it; a wall of 2 dynamic layers, the segments'
 *    default before they took the scheme's model, let the water through
 *    it at 98 %).
 * 5. (3-D) Closed surfaces from mesh files (src/case/mesh.c, Assimp): a box
 *    written as ASCII STL, binary STL, OBJ and PLY makes the box
 *    primitive's particles bit for bit (dyadic corners and dx, exact in
 *    the files' single precision; a square top whose diagonal lattice
 *    columns run along); a sphere of 1280 triangles fills its mesh's
 *    volume within 2 % at 20 dx across and 1 % at 40 (measured +0.95 %,
 *    -0.20 %; read in millimetres with `scale` and `offset`, its lattice
 *    moved by the single-precision corners: +1.72 %, -0.04 %: at 20
 *    across the lattice's place decides about 1 %); an open surface, an inward one, one with a
 * triangle turned, a missing file, a zero scale, and two boxes overlapping in one file (refused
 * where the surface winds twice, as water and as an obstacle) are refused.
 * 6. Obstacles of a shape: a rectangle (a prism in 3-D) with adami walls
 *    makes the box obstacle's wall particles bit for bit (in 2-D their
 *    mirror offsets too, within 1e-12 dx); a circle (a cylinder standing
 *    on the floor in 3-D) makes a shell of wall particles as deep as its
 *    layers and hollow inside it, no fluid inside, every particle's mirror
 *    offset pointing out of the shape with its midpoint on the surface;
 *    mdbc walls on a shape of fewer layers than fill the kernel's support
 *    are refused. Still water for 0.5 s round a submerged circle of adami
 *    and mdbc walls (2-D, two resolutions) and over a cylinder of mdbc
 *    walls (3-D): none of it into the shape, the largest speed a few per
 *    cent of sqrt(g H) (the bounds and measured values at each test).
 * 7. A wall written as `points` (a polyline) makes the particles of its
 *    segments written one by one, bit for bit; one point, both from/to and
 *    points, and a repeated point are refused at their key.
 */
#include "config.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "case/case.h"
#include "core/particles.h"
#include "solver/sim.h"
#include "testutil.h"

static const double pi = 3.14159265358979323846;

/* The case text head: a tank (x 0..1, y/z 0..0.5; in 3-D y 0..0.3) and dx; blocks follow. */
#if SPH_DIM == 2
#define HEAD                                                                                       \
  "name: shapes\n"                                                                                 \
  "physics: {gravity: [0, -9.81], sound_speed: 20}\n"                                              \
  "numerics: {dx: 0.01}\n"                                                                         \
  "time: {end: 0.01, output_interval: 0.01}\n"                                                     \
  "geometry:\n"                                                                                    \
  "  tank: {x: [0, 1], y: [0, 0.5]}\n"                                                             \
  "  fluid:\n"
#else
#define HEAD                                                                                       \
  "name: shapes\n"                                                                                 \
  "dimension: 3\n"                                                                                 \
  "physics: {gravity: [0, 0, -9.81], sound_speed: 20}\n"                                           \
  "numerics: {dx: 0.01}\n"                                                                         \
  "time: {end: 0.01, output_interval: 0.01}\n"                                                     \
  "geometry:\n"                                                                                    \
  "  tank: {x: [0, 1], y: [0, 0.3], z: [0, 0.5]}\n"                                                \
  "  fluid:\n"
#endif

/* Parses HEAD + blocks; 0 or the error in err. */
static int parse(const char *blocks, const char *const *set, size_t n_set, sph_case *c,
                 sph_error *err) {
  char text[8192];
  snprintf(text, sizeof text, "%s%s", HEAD, blocks);
  return sph_case_parse(text, strlen(text), "shapes.yaml", set, n_set, c, err);
}

/* Opens the sim of a whole case text (asserting it opens). */
static sph_sim *open_text(const char *text, sph_case *c) {
  sph_error err;
  const int rc = sph_case_parse(text, strlen(text), "shapes.yaml", NULL, 0, c, &err);
  if (rc) printf("\n    %s", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  sph_sim *s = NULL;
  const int sc = sph_sim_create(c, &s, &err);
  if (sc) printf("\n    %s", err.msg);
  CU_ASSERT_FATAL(sc == 0);
  return s;
}

/* Opens the sim of HEAD + blocks (asserting it opens). */
static sph_sim *open_sim(const char *blocks, sph_case *c) {
  static char text[8192];
  snprintf(text, sizeof text, "%s%s", HEAD, blocks);
  return open_text(text, c);
}

#if SPH_DIM == 2
/* The distance from the closest fluid particle to the closest wall particle within `radius` of
 * the point (cx, cy) (INFINITY: any wall particle), over every pair (a check, not a pass). */
static double fluid_wall_gap(const sph_particles *p, double cx, double cy, double radius) {
  double gap = INFINITY;
  for (size_t j = 0; j < p->n; j++) {
    if (p->kind[j] != SPH_KIND_WALL || !(hypot(p->pos[0][j] - cx, p->pos[1][j] - cy) < radius))
      continue;
    for (size_t i = 0; i < p->n; i++)
      if (p->kind[i] == SPH_KIND_FLUID)
        gap = fmin(gap, hypot(p->pos[0][i] - p->pos[0][j], p->pos[1][i] - p->pos[1][j]));
  }
  return gap;
}
#endif

/* Whether two sims made the same particles, bit for bit. */
static int same_particles(sph_sim *a, sph_sim *b) {
  const sph_particles *p = sph_sim_particles(a), *q = sph_sim_particles(b);
  if (p->n != q->n) return 0;
  for (int d = 0; d < SPH_DIM; d++)
    if (memcmp(p->pos[d], q->pos[d], p->n * sizeof(double)) ||
        memcmp(p->vel[d], q->vel[d], p->n * sizeof(double)))
      return 0;
  return !memcmp(p->rho, q->rho, p->n * sizeof(double)) &&
         !memcmp(p->mass, q->mass, p->n * sizeof(double)) &&
         !memcmp(p->kind, q->kind, p->n * sizeof *p->kind);
}

/* 1. The rectangle as a polygon, both ways round, is the box. */
static void test_polygon_is_box(void) {
#if SPH_DIM == 2
  const char *box = "    - {x: [0.1, 0.5], y: [0.05, 0.25]}\n";
  const char *ccw = "    - polygon: [[0.1, 0.05], [0.5, 0.05], [0.5, 0.25], [0.1, 0.25]]\n";
  const char *cw = "    - polygon: [[0.1, 0.05], [0.1, 0.25], [0.5, 0.25], [0.5, 0.05]]\n";
#else
  const char *box = "    - {x: [0.1, 0.5], y: [0.05, 0.25], z: [0.05, 0.25]}\n";
  const char *ccw =
      "    - {polygon: [[0.1, 0.05], [0.5, 0.05], [0.5, 0.25], [0.1, 0.25]], y: [0.05, "
      "0.25]}\n";
  const char *cw =
      "    - {polygon: [[0.1, 0.05], [0.1, 0.25], [0.5, 0.25], [0.5, 0.05]], y: [0.05, "
      "0.25]}\n";
#endif
  sph_case c0, c1, c2;
  sph_sim *s0 = open_sim(box, &c0), *s1 = open_sim(ccw, &c1), *s2 = open_sim(cw, &c2);
  printf("\n  box %zu particles; the polygon (anticlockwise, clockwise) the same bits: %s, %s",
         sph_sim_particles(s0)->n, same_particles(s0, s1) ? "yes" : "NO",
         same_particles(s0, s2) ? "yes" : "NO");
  CU_ASSERT(same_particles(s0, s1));
  CU_ASSERT(same_particles(s0, s2));
  sph_sim_free(s0), sph_sim_free(s1), sph_sim_free(s2);
  sph_case_free(&c0), sph_case_free(&c1), sph_case_free(&c2);
}

/* The fluid particles block 0 of the blocks makes, and its measure. */
static long fill(const char *blocks, double *measure) {
  sph_case c;
  sph_error err;
  const int rc = parse(blocks, NULL, 0, &c, &err);
  if (rc) printf("\n    %s", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  const long n = sph_case_block_points(&c.fluid[0], c.dx);
  *measure = sph_case_block_measure(&c.fluid[0]);
  sph_case_free(&c);
  return n;
}

static void report(const char *what, long n, double dx, double measure, double tol) {
  const double filled = (double)n * pow(dx, SPH_DIM), e = (filled - measure) / measure;
  printf("\n  %s: %ld particles, filled %.6g against %.6g: %+.3f %% (at most %.1f %%)", what, n,
         filled, measure, 100 * e, 100 * tol);
  CU_ASSERT(fabs(e) <= tol);
}

/* 2. Filled areas and volumes. */
static void test_filled_measure(void) {
  double m;
  long n;
#if SPH_DIM == 2
  n = fill("    - circle: {centre: [0.5, 0.2], radius: 0.1}\n", &m);
  CU_ASSERT_DOUBLE_EQUAL(m, pi * 0.01, 1e-15);
  report("a circle 20 dx across", n, 0.01, m, 0.01);
  n = fill("    - circle: {centre: [0.5037, 0.2011], radius: 0.1}\n", &m);
  report("the same circle off the lattice", n, 0.01, m, 0.01);
  /* a trapezoid with its slanted edge through cell corners: the cells it cuts in half are
   * counted when their centre is inside, half of them */
  n = fill("    - polygon: [[0, 0], [0.6, 0], [0.6, 0.1], [0, 0.3]]\n", &m);
  CU_ASSERT_DOUBLE_EQUAL(m, 0.12, 1e-15);
  report("a trapezoid (0.12 m2)", n, 0.01, m, 0.01);
  n = fill("    - polygon: [[0.1, 0.1], [0.4, 0.1], [0.4, 0.2], [0.2, 0.2], [0.2, 0.4], [0.1, "
           "0.4]]\n",
           &m);
  CU_ASSERT_EQUAL(n, 500); /* an L of 0.05 m2, its edges on cell faces */
  report("an L on cell faces", n, 0.01, m, 1e-12);
#else
  n = fill("    - sphere: {centre: [0.5, 0.15, 0.2], radius: 0.1}\n", &m);
  CU_ASSERT_DOUBLE_EQUAL(m, 4.0 / 3.0 * pi * 1e-3, 1e-15);
  report("a sphere 20 dx across", n, 0.01, m, 0.01);
  n = fill("    - sphere: {centre: [0.5037, 0.1511, 0.2023], radius: 0.1}\n", &m);
  report("the same sphere off the lattice", n, 0.01, m, 0.01);
  n = fill("    - cylinder: {from: [0.3, 0.15, 0.15], to: [0.6, 0.15, 0.35], radius: 0.1}\n", &m);
  report("a tilted cylinder 20 dx across, 36 long", n, 0.01, m, 0.01);
  n = fill("    - cylinder: {from: [0.3, 0.0, 0.2], to: [0.3, 0.3, 0.2], radius: 0.1}\n", &m);
  report("a cylinder across the tank", n, 0.01, m, 0.01);
#endif
}

/* Parses the blocks and asserts the error holds every one of the NULL-terminated words. */
static void refused(const char *blocks, const char *const *words) {
  sph_case c;
  sph_error err;
  const int rc = parse(blocks, NULL, 0, &c, &err);
  CU_ASSERT(rc != 0);
  if (rc == 0) {
    printf("\n  NOT refused: %s", blocks);
    sph_case_free(&c);
    return;
  }
  printf("\n  %s", err.msg);
  for (const char *const *w = words; *w; w++) {
    const int has = strstr(err.msg, *w) != NULL;
    if (!has) printf("\n    (the message lacks \"%s\")", *w);
    CU_ASSERT(has);
  }
}

/* Parses the blocks (which must read) and asserts that making the particles fails with an
 * error holding every one of the NULL-terminated words. */
static void refused_at_start(const char *blocks, const char *const *words) {
  sph_case c;
  sph_error err;
  CU_ASSERT_FATAL(parse(blocks, NULL, 0, &c, &err) == 0);
  sph_sim *s = NULL;
  const int rc = sph_sim_create(&c, &s, &err);
  CU_ASSERT(rc != 0);
  if (rc == 0)
    sph_sim_free(s);
  else
    printf("\n  %s", err.msg);
  for (const char *const *w = words; rc && *w; w++) {
    const int has = strstr(err.msg, *w) != NULL;
    if (!has) printf("\n    (the message lacks \"%s\")", *w);
    CU_ASSERT(has);
  }
  sph_case_free(&c);
}

/* 3. Bad shapes. */
static void test_refusals(void) {
  /* HEAD has 7 lines (8 in 3-D): the first block is on the next */
  static const char *const crossing[] = {"shapes.yaml:", "geometry.fluid[0].polygon",
                                         "edges 0-1 and 2-3 cross", NULL};
  refused("    - polygon: [[0.1, 0.1], [0.4, 0.4], [0.4, 0.1], [0.1, 0.4]]\n", crossing);
  static const char *const few[] = {"geometry.fluid[0].polygon", "3 to 10000 vertices", "got 2",
                                    NULL};
  refused("    - polygon: [[0.1, 0.1], [0.4, 0.4]]\n", few);
  static const char *const same[] = {"vertices 1 and 2 are the same point", NULL};
  refused("    - polygon: [[0.1, 0.1], [0.4, 0.1], [0.4, 0.1], [0.1, 0.4]]\n", same);
  static const char *const flat[] = {"area is zero", NULL};
  refused("    - polygon: [[0.1, 0.1], [0.2, 0.2], [0.3, 0.3]]\n", flat);
  static const char *const both[] = {"geometry.fluid[0].x", "expected no x range in a block with a",
                                     NULL};
  refused("    - {x: [0.1, 0.2], polygon: [[0.1, 0.1], [0.4, 0.1], [0.1, 0.4]]}\n", both);
  static const char *const outside[] = {"expected a shape inside the tank's inner box", NULL};
  refused("    - polygon: [[0.1, 0.1], [1.4, 0.1], [0.1, 0.4]]\n", outside);
#if SPH_DIM == 2
  static const char *const two[] = {"expected one shape per block, got polygon and circle", NULL};
  refused("    - polygon: [[0.1, 0.1], [0.4, 0.1], [0.1, 0.4]]\n"
          "      circle: {centre: [0.5, 0.2], radius: 0.1}\n",
          two);
  static const char *const radius[] = {"geometry.fluid[0].circle.radius", NULL};
  refused("    - circle: {centre: [0.5, 0.2], radius: -0.1}\n", radius);
  static const char *const wrong_dim[] = {"geometry.fluid[0]", "sphere", NULL};
  refused("    - sphere: {centre: [0.5, 0.2], radius: 0.1}\n", wrong_dim);
  const char *overlap = "    - polygon: [[0.1, 0.1], [0.4, 0.1], [0.1, 0.4]]\n"
                        "    - circle: {centre: [0.3, 0.25], radius: 0.1}\n";
#else
  static const char *const two[] = {"expected one shape per block, got sphere and cylinder", NULL};
  refused("    - sphere: {centre: [0.5, 0.15, 0.2], radius: 0.1}\n"
          "      cylinder: {from: [0.3, 0.15, 0.15], to: [0.6, 0.15, 0.35], radius: 0.1}\n",
          two);
  static const char *const ends[] = {"geometry.fluid[0].cylinder.to", "the same point", NULL};
  refused("    - cylinder: {from: [0.3, 0.15, 0.15], to: [0.3, 0.15, 0.15], radius: 0.1}\n", ends);
  static const char *const wrong_dim[] = {"geometry.fluid[0]", "circle", NULL};
  refused("    - circle: {centre: [0.5, 0.15, 0.2], radius: 0.1}\n", wrong_dim);
  const char *overlap = "    - sphere: {centre: [0.3, 0.15, 0.2], radius: 0.1}\n"
                        "    - {x: [0.35, 0.6], y: [0, 0.3], z: [0, 0.3]}\n";
#endif
  /* overlapping shapes: refused when the particles are made */
  static const char *const apart[] = {
      "geometry.fluid[1]: expected a block apart from geometry.fluid[0]",
      SPH_DIM == 2 ? "shapes.yaml:9:" : "shapes.yaml:10:", NULL};
  refused_at_start(overlap, apart);
}

#if SPH_DIM == 2
/* 4. Still water over a sloped beach: cases/sloped_beach.yaml's flume without its paddle, at
 * dx = 0.02 m and 0.01 m, run for 0.5 s: the largest speed and the lowest fluid particle above
 * the beach's surface (the line of its first wall layer). */
/* The lowest fluid particle over the 1:4 beach from x = 2.5 m: its height above the beach's
 * surface (negative below it). */
static double lowest_over_beach(const sph_particles *p) {
  double lowest = INFINITY;
  for (size_t i = 0; i < p->n; i++)
    if (p->kind[i] == SPH_KIND_FLUID && p->pos[0][i] > 2.5)
      lowest = fmin(lowest, p->pos[1][i] - 0.25 * (p->pos[0][i] - 2.5));
  return lowest;
}

static void still_beach(const char *dx) {
  char text[1024];
  snprintf(text, sizeof text,
           "name: still_beach\n"
           "physics: {gravity: [0, -9.81], sound_speed: {factor: 10, height: 0.25}}\n"
           "numerics: {dx: %s}\n"
           "time: {end: 0.5, output_interval: 0.5}\n"
           "geometry:\n"
           "  tank: {x: [0, 4.1], y: [0, 0.6]}\n"
           "  fluid:\n"
           "    - polygon: [[0, 0], [2.5, 0], [3.5, 0.25], [0, 0.25]]\n"
           "  walls:\n"
           "    - {from: [4.1, 0.4], to: [2.5, 0.0]}\n",
           dx);
  sph_case c;
  sph_error err;
  const int rc = sph_case_parse(text, strlen(text), "still_beach", NULL, 0, &c, &err);
  if (rc) printf("\n    %s", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  CU_ASSERT_EQUAL(c.walls[0].boundary, SPH_BOUNDARY_ADAMI); /* the default scheme's walls */
  sph_sim *s = NULL;
  CU_ASSERT_FATAL(sph_sim_create(&c, &s, &err) == 0);
  const double lowest0 = lowest_over_beach(sph_sim_particles(s));
  while (sph_sim_time(s) < c.t_end)
    CU_ASSERT_FATAL(sph_sim_step(s, c.t_end, &err) == 0);
  const sph_particles *p = sph_sim_particles(s);
  double vmax = 0.0, v2 = 0.0;
  size_t nf = 0;
  for (size_t i = 0; i < p->n; i++)
    if (p->kind[i] == SPH_KIND_FLUID) {
      const double v = hypot(p->vel[0][i], p->vel[1][i]);
      nf++;
      vmax = fmax(vmax, v);
      v2 += v * v;
    }
  const double lowest = lowest_over_beach(p), scale = sqrt(9.81 * 0.25);
  printf("\n  still water over the beach, dx = %s m (%zu fluid particles), t = 0.5 s: largest "
         "speed %.2f %% of sqrt(g d), RMS %.2f %%; the lowest particle over the beach %+.2f dx "
         "from its surface (%+.2f dx at the start, in the wedge at its toe)",
         dx, nf, 100 * vmax / scale, 100 * sqrt(v2 / (double)nf) / scale, lowest / c.dx,
         lowest0 / c.dx);
  CU_ASSERT(vmax < 0.1 * scale);
  /* none went into the beach (at its toe, where the floor's particles stand in for its first
   * layer's, the water fills the corner down to the floor) */
  CU_ASSERT(lowest > -0.5 * c.dx);
  sph_sim_free(s);
  sph_case_free(&c);
}

static void test_still_beach(void) {
  still_beach("0.02");
  still_beach("0.01");
}
#endif

/* ---- 6. obstacles of a shape ---- */

/* A rectangle (a prism in 3-D) as an obstacle makes the box obstacle's wall particles, bit for
 * bit; a circle (a cylinder in 3-D) makes a shell `layers` deep with no fluid inside; mdbc walls
 * of 2 layers on a shape are refused. */
static void test_shaped_obstacles(void) {
#if SPH_DIM == 2
  const char *water = "    - {x: [0, 1], y: [0, 0.3]}\n  obstacles:\n";
  const char *box = "    - {x: [0.4, 0.6], y: [0, 0.2], boundary: adami}\n";
  const char *rect = "    - {polygon: [[0.4, 0], [0.6, 0], [0.6, 0.2], [0.4, 0.2]], boundary: "
                     "adami}\n";
  const char *round = "    - {circle: {centre: [0.5, 0.15], radius: 0.08}, boundary: adami}\n";
  const char *mdbc = "    - {circle: {centre: [0.5, 0.15], radius: 0.08}, boundary: mdbc, "
                     "layers: 2}\n";
#else
  const char *water = "    - {x: [0, 1], y: [0, 0.3], z: [0, 0.3]}\n  obstacles:\n";
  const char *box = "    - {x: [0.4, 0.6], y: [0, 0.3], z: [0, 0.2], boundary: adami}\n";
  const char *rect = "    - {polygon: [[0.4, 0], [0.6, 0], [0.6, 0.2], [0.4, 0.2]], boundary: "
                     "adami}\n";
  const char *round = "    - {cylinder: {from: [0.5, 0.15, 0], to: [0.5, 0.15, 0.25], radius: "
                      "0.08}, boundary: adami}\n";
  const char *mdbc = "    - {cylinder: {from: [0.5, 0.15, 0], to: [0.5, 0.15, 0.25], radius: "
                     "0.08}, boundary: mdbc, layers: 2}\n";
#endif
  char text[1024];
  sph_case c0, c1, c2;
  snprintf(text, sizeof text, "%s%s", water, box);
  sph_sim *s0 = open_sim(text, &c0);
  snprintf(text, sizeof text, "%s%s", water, rect);
  sph_sim *s1 = open_sim(text, &c1);
  const int same = same_particles(s0, s1);
  int same_offsets = 1; /* 2-D: out through the nearest faces, as the box's (to round-off: the
                         * box's from lattice indices, the polygon's from coordinates) */
  const sph_particles *b0 = sph_sim_particles(s0), *b1 = sph_sim_particles(s1);
  for (size_t i = 0; i < b0->n && same && SPH_DIM == 2; i++)
    for (int a = 0; a < SPH_DIM; a++)
      if (fabs(b0->mirror_offset[a][i] - b1->mirror_offset[a][i]) > 1e-12 * 0.01) {
        if (same_offsets)
          printf("\n  the first other offset: particle %zu at (%g, %g): the box's (%g, %g), the "
                 "polygon's (%g, %g)",
                 i, b0->pos[0][i], b0->pos[1][i], b0->mirror_offset[0][i], b0->mirror_offset[1][i],
                 b1->mirror_offset[0][i], b1->mirror_offset[1][i]);
        same_offsets = 0;
      }
  printf("\n  the box obstacle: %zu particles; as a %s, the same bits: %s%s", b0->n,
         SPH_DIM == 2 ? "polygon" : "polygon prism", same ? "yes" : "NO",
         SPH_DIM == 3   ? ""
         : same_offsets ? ", and its mirror offsets within 1e-12 dx"
                        : ", OTHER OFFSETS");
  CU_ASSERT(same);
  if (SPH_DIM == 2) CU_ASSERT(same_offsets);
  /* the round one: its wall particles in the shape within its layers (4, adami) of the side or
   * the top, no fluid inside */
  snprintf(text, sizeof text, "%s%s", water, round);
  sph_sim *s2 = open_sim(text, &c2);
  const sph_particles *p = sph_sim_particles(s2);
  const double r = 0.08, dx = 0.01, L = c2.obstacles[0].layers;
  size_t shell = 0, deep = 0, wet = 0, bad_offsets = 0;
  double inner = INFINITY;
  for (size_t i = 0; i < p->n; i++) {
    const double d = hypot(p->pos[0][i] - 0.5, p->pos[1][i] - 0.15); /* from the axis */
    const double up = SPH_DIM == 3 ? p->pos[SPH_UP][i] : 0.1;
    const int in = d < r && up > 0.0 && up < 0.25;
    if (p->kind[i] == SPH_KIND_FLUID) {
      wet += in;
      continue;
    }
    if (!in) continue; /* the tank's */
    shell++;
    /* its mirror offset (adami walls) out of the shape, halfway on its surface */
    double out[SPH_DIM], half[SPH_DIM], mm = 0.0;
    for (int a = 0; a < SPH_DIM; a++) {
      out[a] = p->pos[a][i] + p->mirror_offset[a][i];
      half[a] = p->pos[a][i] + 0.5 * p->mirror_offset[a][i];
      mm += p->mirror_offset[a][i] * p->mirror_offset[a][i];
    }
    const double dh = hypot(half[0] - 0.5, half[1] - 0.15), uh = SPH_DIM == 3 ? half[SPH_UP] : 0.1;
    const int on = fabs(dh - r) < 1e-12 || fabs(uh) < 1e-12 || fabs(uh - 0.25) < 1e-12;
    bad_offsets += !(mm > 0.0) || c2.obstacles[0].inside(c2.obstacles[0].shape, out) || !on;
    if (SPH_DIM == 2 || (up > (L + 1) * dx && up < 0.25 - (L + 1) * dx)) { /* by the side */
      inner = fmin(inner, d);
      deep += r - d > (L + 1) * dx * sqrt(2.0);
    }
  }
  printf("\n  the %s obstacle: %zu wall particles in it, the innermost by the side %.2f dx from "
         "its axis (%.0f layers), %zu deeper than the layers, %zu fluid particles in it",
         SPH_DIM == 2 ? "circle" : "cylinder", shell, inner / dx, L, deep, wet);
  CU_ASSERT(shell > 0);
  CU_ASSERT(deep == 0);
  CU_ASSERT(inner > r - (L + 1) * dx * sqrt(2.0));
  CU_ASSERT(inner < r - (L - 1) * dx); /* a shell as deep as its layers, hollow inside it */
  CU_ASSERT(wet == 0);
  printf("; %zu mirror offsets not out to its surface", bad_offsets);
  CU_ASSERT(bad_offsets == 0);
  sph_sim_free(s0), sph_sim_free(s1), sph_sim_free(s2);
  sph_case_free(&c0), sph_case_free(&c1), sph_case_free(&c2);
  snprintf(text, sizeof text, "%s%s", water, mdbc);
  static const char *const thin_mdbc[] = {"geometry.obstacles[0].layers",
                                          "expected at least 4 for mdbc walls on a shape", NULL};
  refused(text, thin_mdbc);
}

static int by_position(const void *a, const void *b) {
  const double *p = a, *q = b;
  for (int d = SPH_DIM - 1; d >= 0; d--)
    if (p[d] != q[d]) return p[d] < q[d] ? -1 : 1;
  return 0;
}

/* The positions of the wall particles of s below `top` along the vertical, sorted, into a
 * malloc'd array (SPH_DIM per particle); their count into *n. */
static double *walls_below(sph_sim *s, double top, size_t *n) {
  const sph_particles *p = sph_sim_particles(s);
  double *w = malloc((p->n + 1) * SPH_DIM * sizeof *w);
  *n = 0;
  for (size_t i = 0; w && i < p->n; i++)
    if (p->kind[i] == SPH_KIND_WALL && p->pos[SPH_UP][i] < top) {
      for (int d = 0; d < SPH_DIM; d++)
        w[SPH_DIM * *n + d] = p->pos[d][i];
      (*n)++;
    }
  if (w) qsort(w, *n, SPH_DIM * sizeof *w, by_position);
  return w;
}

/* A vessel (geometry.vessels): the water inside a shape, the wall particles a shell outside its
 * surface. A rectangle (3-D: its prism across y) of adami walls is the tank of adami walls: the
 * same fluid particles bit for bit, and below the tank's top (where the vessel has its lid) the
 * same wall particles (bit for bit in 3-D; in 2-D, whose tank spaces its side walls along them,
 * the floor's, within 1e-12 dx); the fluid of a block reaching outside a round vessel is made
 * inside it only; the round one holds still water with its default (adami) walls and, in 2-D,
 * with mdbc walls; a box range, or repulsive walls, are refused by name. */
static void test_vessel(void) {
#if SPH_DIM == 2
  const char *tank = "  tank: {x: [0, 1], y: [0, 0.5], boundary: adami}\n"
                     "  fluid:\n    - {x: [0, 1], y: [0, 0.3]}\n";
  const char *vessel = "  fluid:\n    - {x: [0, 1], y: [0, 0.3]}\n"
                       "  vessels:\n"
                       "    - {polygon: [[0, 0], [1, 0], [1, 0.5], [0, 0.5]], boundary: adami}\n";
  const char *round = "  fluid:\n    - {x: [0.2, 0.8], y: [0.2, 0.5]}\n"
                      "  vessels:\n    - {circle: {centre: [0.5, 0.5], radius: 0.3}}\n";
  const char *gravity = "[0, -9.81]";
#else
  const char *tank = "  tank: {x: [0, 1], y: [0, 0.3], z: [0, 0.5], boundary: adami}\n"
                     "  fluid:\n    - {x: [0, 1], y: [0, 0.3], z: [0, 0.3]}\n";
  const char *vessel = "  fluid:\n    - {x: [0, 1], y: [0, 0.3], z: [0, 0.3]}\n"
                       "  vessels:\n"
                       "    - {polygon: [[0, 0], [1, 0], [1, 0.5], [0, 0.5]], y: [0, 0.3], "
                       "boundary: adami}\n";
  const char *round = "  fluid:\n    - {x: [0.2, 0.8], y: [0.2, 0.8], z: [0.2, 0.5]}\n"
                      "  vessels:\n    - {sphere: {centre: [0.5, 0.5, 0.5], radius: 0.3}}\n";
  const char *gravity = "[0, 0, -9.81]";
#endif
  char head[512], text[1024];
  snprintf(head, sizeof head,
           "name: vessel\n%s"
           "physics: {gravity: %s, sound_speed: {factor: 10, height: 0.3}}\n"
           "numerics: {dx: %s}\n"
           "time: {end: 0.01, output_interval: 0.01}\n"
           "geometry:\n",
           SPH_DIM == 3 ? "dimension: 3\n" : "", gravity, SPH_DIM == 3 ? "0.02" : "0.01");
  sph_case c0, c1, c2;
  snprintf(text, sizeof text, "%s%s", head, tank);
  sph_sim *s0 = open_text(text, &c0);
  snprintf(text, sizeof text, "%s%s", head, vessel);
  sph_sim *s1 = open_text(text, &c1);
  const sph_particles *p0 = sph_sim_particles(s0), *p1 = sph_sim_particles(s1);
  const size_t nf0 = sph_particles_count_kind(p0, SPH_KIND_FLUID),
               nf1 = sph_particles_count_kind(p1, SPH_KIND_FLUID);
  int same_fluid = nf0 == nf1;
  for (size_t i = 0, j = 0; same_fluid && i < p0->n; i++) { /* the fluid, in order */
    if (p0->kind[i] != SPH_KIND_FLUID) continue;
    while (j < p1->n && p1->kind[j] != SPH_KIND_FLUID)
      j++;
    for (int d = 0; d < SPH_DIM && j < p1->n; d++)
      same_fluid &= p0->pos[d][i] == p1->pos[d][j];
    j++;
  }
  size_t n0, n1;
  /* 3-D: every wall particle below the top; 2-D: the floor's (the 2-D tank spaces its side
   * walls' particles along each wall from its foot to its top, off the lattice) */
  const double below = SPH_DIM == 3 ? 0.5 : 0.0;
  double *w0 = walls_below(s0, below, &n0), *w1 = walls_below(s1, below, &n1);
  /* the same bits in 3-D; in 2-D the tank lays its floor's layers down from the face (y0 - dx/2
   * - k dx), the vessel on its lattice (y0 + (k + 1/2) dx, k < 0): the same to round-off */
  const int same_bits = w0 && w1 && n0 == n1 && !memcmp(w0, w1, n0 * SPH_DIM * sizeof *w0);
  double worst = n0 == n1 ? 0.0 : INFINITY;
  for (size_t i = 0; w0 && w1 && n0 == n1 && i < n0 * SPH_DIM; i++)
    worst = fmax(worst, fabs(w0[i] - w1[i]));
  const int same_walls = SPH_DIM == 3 ? same_bits : worst <= 1e-12 * c0.dx;
  printf("\n  the %s vessel: %zu fluid particles (the tank's %zu), %zu wall particles below the "
         "%s (the tank's %zu), the same bits: fluid %s, walls %s (at most %.1e dx apart)",
         SPH_DIM == 2 ? "rectangle" : "prism", nf1, nf0, n1, SPH_DIM == 3 ? "top" : "floor", n0,
         same_fluid ? "yes" : "NO", same_bits ? "yes" : "no", worst / c0.dx);
  CU_ASSERT(same_fluid);
  CU_ASSERT(same_walls);
  free(w0), free(w1);
  /* the round one: the block's points outside it not made, the shell outside the surface */
  snprintf(text, sizeof text, "%s%s", head, round);
  sph_sim *s2 = open_text(text, &c2);
  const sph_particles *p = sph_sim_particles(s2);
  const double r = 0.3, dx = c2.dx, L = c2.obstacles[0].layers;
  double fluid_out = -INFINITY, wall_in = INFINITY, wall_out = -INFINITY;
  for (size_t i = 0; i < p->n; i++) {
    double d2 = 0.0;
    for (int a = 0; a < SPH_DIM; a++)
      d2 += (p->pos[a][i] - 0.5) * (p->pos[a][i] - 0.5);
    const double d = sqrt(d2) - r; /* outside the surface: positive */
    if (p->kind[i] == SPH_KIND_FLUID)
      fluid_out = fmax(fluid_out, d);
    else
      wall_in = fmin(wall_in, d), wall_out = fmax(wall_out, d);
  }
  printf("\n  the round vessel: %zu fluid particles not made; the fluid reaches %.2f dx past the "
         "surface, the walls from %.2f to %.2f dx past it (%.0f layers)",
         sph_sim_fluid_in_obstacles(s2), fluid_out / dx, wall_in / dx, wall_out / dx, L);
  CU_ASSERT(sph_sim_fluid_in_obstacles(s2) > 0);
  CU_ASSERT(fluid_out < 0.0);
  CU_ASSERT(wall_in >= 0.0 && wall_out <= L * sqrt((double)SPH_DIM) * dx);
#if SPH_DIM == 2
  /* the round tank (the default scheme's adami walls) holds its water still for 0.5 s: the
   * largest speed below 5 % of sqrt(g H), H = 0.3 m its depth (measured 0.89 %), none of it more
   * than dx/4 past the surface */
  sph_error err2;
  int st = 0;
  while (st == 0 && sph_sim_time(s2) < 0.5)
    st = sph_sim_step(s2, 0.5, &err2);
  if (st) printf("\n    %s", err2.msg);
  CU_ASSERT_FATAL(st == 0);
  double fast = 0.0, past = -INFINITY;
  for (size_t i = 0; i < p->n; i++)
    if (p->kind[i] == SPH_KIND_FLUID) {
      fast = fmax(fast, hypot(p->vel[0][i], p->vel[1][i]));
      past = fmax(past, hypot(p->pos[0][i] - 0.5, p->pos[1][i] - 0.5) - r);
    }
  printf("\n  still water in the round vessel at t = %.2f s: largest speed %.2f %% of sqrt(g H), "
         "the fluid up to %.2f dx past the surface",
         sph_sim_time(s2), 100.0 * fast / sqrt(9.81 * 0.3), past / dx);
  CU_ASSERT(fast < 0.05 * sqrt(9.81 * 0.3));
  CU_ASSERT(past < 0.25 * dx);
  /* with mdbc walls (4 layers) too, at dx = 0.01 and 0.02 m (measured 1.60 % and 2.56 %, the
   * fluid -0.09 and -0.01 dx past the surface, 0.97 and 0.93 dx from the closest wall particle) */
  for (int k = 0; k < 2; k++) {
    char mtext[1024];
    sph_case cm;
    snprintf(mtext, sizeof mtext,
             "name: vessel\nphysics: {gravity: %s, sound_speed: {factor: 10, height: 0.3}}\n"
             "numerics: {dx: %s}\ntime: {end: 0.5, output_interval: 0.5}\ngeometry:\n"
             "  fluid:\n    - {x: [0.2, 0.8], y: [0.2, 0.5]}\n"
             "  vessels:\n    - {circle: {centre: [0.5, 0.5], radius: 0.3}, boundary: mdbc}\n",
             gravity, k ? "0.02" : "0.01");
    sph_sim *sm = open_text(mtext, &cm);
    st = 0;
    while (st == 0 && sph_sim_time(sm) < cm.t_end)
      st = sph_sim_step(sm, cm.t_end, &err2);
    CU_ASSERT_FATAL(st == 0);
    const sph_particles *q = sph_sim_particles(sm);
    double mfast = 0.0, mpast = -INFINITY;
    for (size_t i = 0; i < q->n; i++) {
      if (q->kind[i] != SPH_KIND_FLUID) continue;
      mfast = fmax(mfast, hypot(q->vel[0][i], q->vel[1][i]));
      mpast = fmax(mpast, hypot(q->pos[0][i] - 0.5, q->pos[1][i] - 0.5) - r);
    }
    const double near = fluid_wall_gap(q, 0.5, 0.5, INFINITY);
    printf("\n  ... with mdbc walls (%d layers), dx = %g m: largest speed %.2f %% of sqrt(g H), "
           "the fluid up to %.2f dx past the surface, %.2f dx from the closest wall particle",
           cm.obstacles[0].layers, cm.dx, 100.0 * mfast / sqrt(9.81 * 0.3), mpast / cm.dx,
           near / cm.dx);
    CU_ASSERT(mfast < 0.05 * sqrt(9.81 * 0.3));
    CU_ASSERT(mpast < 0.25 * cm.dx);
    CU_ASSERT(near > 0.5 * cm.dx);
    sph_sim_free(sm);
    sph_case_free(&cm);
  }
#endif
  sph_sim_free(s0), sph_sim_free(s1), sph_sim_free(s2);
  sph_case_free(&c0), sph_case_free(&c1), sph_case_free(&c2);
  /* a box range, mdbc walls */
  snprintf(text, sizeof text, "%s%.*s  vessels:\n    - {x: [0, 1], y: [0, 1]%s}\n", head,
           (int)(strstr(round, "  vessels") - round), round, SPH_DIM == 3 ? ", z: [0, 1]" : "");
  sph_case c;
  sph_error err;
  CU_ASSERT(sph_case_parse(text, strlen(text), "vessel.yaml", NULL, 0, &c, &err) != 0);
  printf("\n  %s", err.msg);
  CU_ASSERT(strstr(err.msg, "geometry.vessels[0]") && strstr(err.msg, "expected a shape"));
  snprintf(text, sizeof text, "%s%s", head, round);
  char *at = strstr(text, "radius: 0.3}}\n");
  CU_ASSERT_FATAL(at != NULL);
  at += strlen("radius: 0.3");
  snprintf(at, sizeof text - (size_t)(at - text), "}, boundary: repulsive}\n");
  CU_ASSERT(sph_case_parse(text, strlen(text), "vessel.yaml", NULL, 0, &c, &err) != 0);
  printf("\n  %s", err.msg);
  CU_ASSERT(strstr(err.msg, "geometry.vessels[0].boundary") != NULL);
}

#if SPH_DIM == 2
/* Still water round a submerged circle (the default scheme), 0.5 s: of adami walls at dx = 0.01
 * m, and of mdbc walls (their default layers, ceil(2 h_factor) = 4) at dx = 0.01 and 0.02 m, the
 * circle 16 and 8 dx across: no fluid particle into the circle (at 0.02 m none more than dx/2
 * inside its line, none closer than dx/2 to a wall particle), the largest speed below 2 % of
 * sqrt(g H), 2.5 % at 0.02 m (measured 1.1 %, 1.1 % and 2.1 %: adami at 0.02 m, 2.1 % too); with
 * mdbc the closest
 * fluid particle 1.00 and 0.95 dx from a wall particle (0.88 and 0.80 while mdbc's density limit
 * had no weight of the water, wall_velocity.h), where, on a lattice of the circle's own
 * box (off the fluid's at 0.02 m), one got 1 dx into the circle. mdbc with 2 layers is refused
 * (it let the water in within 0.3 s). */
static void test_still_round_obstacle(void) {
  static const char *const model[3] = {"adami", "mdbc", "mdbc"};
  static const double dx[3] = {0.01, 0.01, 0.02};
  /* the largest speed, in parts of sqrt(g H), and how far (in dx) a fluid particle may stand
   * inside the circle's line: none at dx = 0.01 m; at 0.02 m the circle's wall particles, on the
   * fluid's lattice, stand up to a spacing inside the line, and so may the fluid next to them */
  static const double vbound[3] = {0.02, 0.02, 0.025}, inside[3] = {0.0, 0.0, 0.5};
  for (int k = 0; k < 3; k++) {
    char text[1024];
    snprintf(text, sizeof text,
             "name: still_circle\n"
             "physics: {gravity: [0, -9.81], sound_speed: {factor: 10, height: 0.3}}\n"
             "numerics: {dx: %g}\n"
             "time: {end: 0.5, output_interval: 0.5}\n"
             "geometry:\n"
             "  tank: {x: [0, 1], y: [0, 0.5]}\n"
             "  fluid:\n"
             "    - {x: [0, 1], y: [0, 0.3]}\n"
             "  obstacles:\n"
             "    - {circle: {centre: [0.5, 0.15], radius: 0.08}, boundary: %s}\n",
             dx[k], model[k]);
    sph_case c;
    sph_error err;
    CU_ASSERT_FATAL(sph_case_parse(text, strlen(text), "still_circle", NULL, 0, &c, &err) == 0);
    sph_sim *s = NULL;
    CU_ASSERT_FATAL(sph_sim_create(&c, &s, &err) == 0);
    while (sph_sim_time(s) < c.t_end)
      CU_ASSERT_FATAL(sph_sim_step(s, c.t_end, &err) == 0);
    const sph_particles *p = sph_sim_particles(s);
    double vmax = 0.0, closest = INFINITY;
    for (size_t i = 0; i < p->n; i++) {
      if (p->kind[i] != SPH_KIND_FLUID) continue;
      vmax = fmax(vmax, hypot(p->vel[0][i], p->vel[1][i]));
      closest = fmin(closest, hypot(p->pos[0][i] - 0.5, p->pos[1][i] - 0.15) - 0.08);
    }
    const double wall = fluid_wall_gap(p, 0.5, 0.15, 0.08); /* the circle's wall particles */
    const double scale = sqrt(9.81 * 0.3);
    printf(
        "\n  still water round a circle of %s walls (%d layers), dx = %g m, t = 0.5 s: largest "
        "speed %.2f %% of sqrt(g H); the closest fluid particle %.2f dx from the circle, %.2f dx "
        "from a wall particle",
        model[k], c.obstacles[0].layers, dx[k], 100 * vmax / scale, closest / c.dx, wall / c.dx);
    CU_ASSERT(vmax < vbound[k] * scale);
    CU_ASSERT(closest > -inside[k] * c.dx);
    CU_ASSERT(wall > 0.5 * c.dx);
    sph_sim_free(s);
    sph_case_free(&c);
  }
}
#endif

#if SPH_DIM == 3
/* Still water over a cylinder of mdbc walls standing on the floor (the default scheme, dx =
 * 0.02 m, radius 5 dx, its top 6 dx up under 4 dx of water), 0.5 s: the largest speed below 4 %
 * of sqrt(g H), no fluid particle inside the cylinder's surface by more than dx/4, none closer
 * than 0.75 dx to one of its wall particles (measured 2.41 %, 0.12 dx outside it, 0.93 dx; at
 * dx = 0.01 m, outside make check, 1.51 %, 0.11 dx outside, 0.99 dx). The walls over the axis
 * see in their fits only the water above the top, whose densest particles were mdbc's limit:
 * they took the first row's density where those nearer the rim, whose fits reach the deeper
 * water beside the cylinder, took the hydrostatic one, and the water over the axis sank into
 * the top (11.8 %, a particle 1.18 dx inside, 0.52 dx from a wall particle; at 0.01 m 3.73 %,
 * 0.59 dx). The limit now grants the weight of the water between the fit's densest particle and
 * the wall particle (wall_velocity.h). */
static void test_still_cylinder_mdbc(void) {
  const double dx = 0.02, R = 0.1, top = 0.12, cx = 0.16, cy = 0.16;
  const char *text =
      "name: still_cylinder\n"
      "dimension: 3\n"
      "physics: {sound_speed: {factor: 10, height: 0.2}}\n"
      "numerics: {dx: 0.02}\n"
      "time: {end: 0.5, output_interval: 0.5}\n"
      "geometry:\n"
      "  tank: {x: [0, 0.32], y: [0, 0.32], z: [0, 0.3]}\n"
      "  fluid:\n"
      "    - {x: [0, 0.32], y: [0, 0.32], z: [0, 0.2]}\n"
      "  obstacles:\n"
      "    - {cylinder: {from: [0.16, 0.16, 0], to: [0.16, 0.16, 0.12], radius: 0.1}, "
      "boundary: mdbc}\n";
  sph_case c;
  sph_sim *s = open_text(text, &c);
  sph_error err;
  while (sph_sim_time(s) < c.t_end)
    CU_ASSERT_FATAL(sph_sim_step(s, c.t_end, &err) == 0);
  const sph_particles *p = sph_sim_particles(s);
  double vmax = 0.0, deepest = -INFINITY, gap2 = INFINITY;
  for (size_t i = 0; i < p->n; i++) {
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    vmax = fmax(vmax, sqrt(p->vx[i] * p->vx[i] + p->vy[i] * p->vy[i] + p->vz[i] * p->vz[i]));
    deepest = fmax(deepest, fmin(R - hypot(p->x[i] - cx, p->y[i] - cy), top - p->z[i]));
    for (size_t j = 0; j < p->n; j++) /* the cylinder's wall particles */
      if (p->kind[j] == SPH_KIND_WALL && hypot(p->x[j] - cx, p->y[j] - cy) < R && p->z[j] > 0.0 &&
          p->z[j] < top) {
        const double d[3] = {p->x[i] - p->x[j], p->y[i] - p->y[j], p->z[i] - p->z[j]};
        gap2 = fmin(gap2, d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      }
  }
  const double scale = sqrt(9.81 * 0.2);
  printf("\n  still water over a cylinder of mdbc walls (%d layers), dx = %g m, t = %g s: largest "
         "speed %.2f %% of sqrt(g H); the deepest fluid particle %.2f dx inside its surface, the "
         "closest %.2f dx from one of its wall particles",
         c.obstacles[0].layers, dx, sph_sim_time(s), 100.0 * vmax / scale, deepest / dx,
         sqrt(gap2) / dx);
  CU_ASSERT(vmax < 0.04 * scale);
  CU_ASSERT(deepest < 0.25 * dx);
  CU_ASSERT(sqrt(gap2) > 0.75 * dx);
  sph_sim_free(s);
  sph_case_free(&c);
}
#endif

/* A shape whose bounding box is off the fluid's lattice (a circle, in 3-D a cylinder whose lower
 * end floats 2.5 dx above the floor): its wall particles are put on the fluid's lattice, so that
 * no fluid particle starts closer than dx to one of them. On its own box's lattice they stood
 * half a spacing from fluid particles, and at dx = 0.02 m 16 particles got more than dx into
 * such a floating cylinder of adami walls by 0.5 s (the largest speed 34 % of sqrt(g H)); on
 * the fluid's lattice none (2.2 %, doc/case-files.md). */
static void test_off_lattice(void) {
#if SPH_DIM == 2
  const char *blocks = "    - {x: [0, 1], y: [0, 0.3]}\n  obstacles:\n"
                       "    - {circle: {centre: [0.503, 0.155], radius: 0.08}, boundary: adami}\n";
#else
  const char *blocks = "    - {x: [0, 1], y: [0, 0.3], z: [0, 0.3]}\n  obstacles:\n"
                       "    - {cylinder: {from: [0.503, 0.15, 0.025], to: [0.503, 0.15, 0.225], "
                       "radius: 0.08}, boundary: adami}\n";
#endif
  sph_case c;
  sph_sim *s = open_sim(blocks, &c);
  const sph_particles *p = sph_sim_particles(s);
  const double dx = c.dx;
  size_t walls = 0, off = 0, near = 0;
  double closest = INFINITY;
  for (size_t i = 0; i < p->n; i++) {
    if (p->kind[i] != SPH_KIND_WALL) continue;
    int obstacle = 1; /* inside the tank's inner box: the obstacle's */
    for (int a = 0; a < SPH_DIM; a++)
      obstacle &= p->pos[a][i] > c.tank.lo[a] && p->pos[a][i] < c.tank.hi[a];
    if (!obstacle) continue;
    walls++;
    int on = 1; /* the fluid block's lattice (i + 1/2) dx from 0 */
    for (int a = 0; a < SPH_DIM; a++) {
      const double k = p->pos[a][i] / dx - 0.5;
      on &= fabs(k - floor(k + 0.5)) < 1e-6;
    }
    off += !on;
    for (size_t j = 0; j < p->n; j++) {
      if (p->kind[j] != SPH_KIND_FLUID) continue;
      double r2 = 0.0;
      for (int a = 0; a < SPH_DIM; a++)
        r2 += (p->pos[a][j] - p->pos[a][i]) * (p->pos[a][j] - p->pos[a][i]);
      closest = fmin(closest, r2);
      near += r2 < 0.999 * dx * dx;
    }
  }
  closest = sqrt(closest) / dx;
  printf("\n  %zu wall particles of the shape, %zu off the fluid's lattice; the closest fluid "
         "particle %.3f dx from one (%zu pairs closer than dx)",
         walls, off, closest, near);
  CU_ASSERT(walls > 100);
  CU_ASSERT(off == 0);
  CU_ASSERT(closest > 0.999);
  sph_sim_free(s);
  sph_case_free(&c);
}

/* ---- 7. walls along a polyline ---- */

/* A wall written as `points` is its segments written one by one, bit for bit; bad polylines are
 * refused at their key. */
static void test_polyline_wall(void) {
#if SPH_DIM == 2
  const char *head = "    - {x: [0, 0.3], y: [0, 0.2]}\n  walls:\n";
#else
  const char *head = "    - {x: [0, 0.3], y: [0, 0.3], z: [0, 0.2]}\n  walls:\n";
#endif
  const char *line = "    - {points: [[0.5, 0], [0.7, 0.1], [0.9, 0.1], [0.95, 0.3]], layers: 2}\n";
  const char *apart = "    - {from: [0.5, 0], to: [0.7, 0.1], layers: 2}\n"
                      "    - {from: [0.7, 0.1], to: [0.9, 0.1], layers: 2}\n"
                      "    - {from: [0.9, 0.1], to: [0.95, 0.3], layers: 2}\n";
  char text[1024];
  sph_case c0, c1;
  snprintf(text, sizeof text, "%s%s", head, line);
  sph_sim *s0 = open_sim(text, &c0);
  snprintf(text, sizeof text, "%s%s", head, apart);
  sph_sim *s1 = open_sim(text, &c1);
  const int same = same_particles(s0, s1);
  printf("\n  a polyline of 3 segments: %zu walls, %zu particles; the segments one by one: the "
         "same bits: %s",
         c0.n_walls, sph_sim_particles(s0)->n, same ? "yes" : "NO");
  CU_ASSERT_EQUAL(c0.n_walls, 3);
  CU_ASSERT(same);
  sph_sim_free(s0), sph_sim_free(s1);
  sph_case_free(&c0), sph_case_free(&c1);
  static const char *const one[] = {"geometry.walls[0].points", "at least 2 points", NULL};
  snprintf(text, sizeof text, "%s    - {points: [[0.5, 0]]}\n", head);
  refused(text, one);
  static const char *const both[] = {"geometry.walls[0].from", "either from and to or points",
                                     NULL};
  snprintf(text, sizeof text, "%s    - {from: [0.5, 0], points: [[0.5, 0], [0.6, 0]]}\n", head);
  refused(text, both);
  static const char *const same_point[] = {
      "geometry.walls[0].points[2]", "expected a point different from the point before it", NULL};
  snprintf(text, sizeof text, "%s    - {points: [[0.5, 0], [0.6, 0], [0.6, 0]]}\n", head);
  refused(text, same_point);
}

#if SPH_DIM == 3
/* ---- 5. closed surfaces from mesh files (3-D) ---- */

static char *mesh_dir; /* the mesh files the tests write */

/* The box [lo, hi] as 12 triangles, anticlockwise seen from outside (corner k: x from bit 0,
 * y from bit 1, z from bit 2). */
static const int box_tri[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6},
                                   {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},
                                   {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
static void box_corner(const double lo[3], const double hi[3], int k, double x[3]) {
  for (int a = 0; a < 3; a++)
    x[a] = (k >> a) & 1 ? hi[a] : lo[a];
}

/* Writes n triangles (9 coordinates each) as format "stl" (ASCII), "stlb" (binary), "obj" or
 * "ply" (ASCII) to mesh_dir/name; returns the path (static). */
static const char *write_mesh(const char *name, const char *format, const double *tri, size_t n) {
  static char path[4200];
  snprintf(path, sizeof path, "%s/%s", mesh_dir, name);
  FILE *f = fopen(path, "wb");
  CU_ASSERT_FATAL(f != NULL);
  if (!strcmp(format, "stl")) {
    fprintf(f, "solid test\n");
    for (size_t t = 0; t < n; t++) {
      fprintf(f, " facet normal 0 0 0\n  outer loop\n");
      for (int q = 0; q < 3; q++)
        fprintf(f, "   vertex %.9g %.9g %.9g\n", tri[9 * t + 3 * q], tri[9 * t + 3 * q + 1],
                tri[9 * t + 3 * q + 2]);
      fprintf(f, "  endloop\n endfacet\n");
    }
    fprintf(f, "endsolid test\n");
  } else if (!strcmp(format, "stlb")) {
    char head[80] = "binary STL written by test_shapes";
    fwrite(head, 1, sizeof head, f);
    const uint32_t count = (uint32_t)n;
    fwrite(&count, sizeof count, 1, f);
    for (size_t t = 0; t < n; t++) {
      float v[12] = {0, 0, 0};
      for (int k = 0; k < 9; k++)
        v[3 + k] = (float)tri[9 * t + k];
      const uint16_t attr = 0;
      fwrite(v, sizeof v, 1, f);
      fwrite(&attr, sizeof attr, 1, f);
    }
  } else if (!strcmp(format, "obj")) {
    for (size_t k = 0; k < 3 * n; k++)
      fprintf(f, "v %.9g %.9g %.9g\n", tri[3 * k], tri[3 * k + 1], tri[3 * k + 2]);
    for (size_t t = 0; t < n; t++)
      fprintf(f, "f %zu %zu %zu\n", 3 * t + 1, 3 * t + 2, 3 * t + 3);
  } else { /* ply */
    fprintf(f,
            "ply\nformat ascii 1.0\nelement vertex %zu\nproperty float x\nproperty float y\n"
            "property float z\nelement face %zu\nproperty list uchar int vertex_indices\n"
            "end_header\n",
            3 * n, n);
    for (size_t k = 0; k < 3 * n; k++)
      fprintf(f, "%.9g %.9g %.9g\n", tri[3 * k], tri[3 * k + 1], tri[3 * k + 2]);
    for (size_t t = 0; t < n; t++)
      fprintf(f, "3 %zu %zu %zu\n", 3 * t, 3 * t + 1, 3 * t + 2);
  }
  fclose(f);
  return path;
}

/* The box's triangles (flip: every one turned the other way; keep: how many). */
static size_t box_mesh(const double lo[3], const double hi[3], int flip, double *tri) {
  for (int t = 0; t < 12; t++)
    for (int q = 0; q < 3; q++)
      box_corner(lo, hi, box_tri[t][flip ? 2 - q : q], tri + 9 * t + 3 * q);
  return 12;
}

/* The fluid block "mesh: {file: PATH...}" (extra: more keys of mesh, or "") as blocks text. */
static const char *mesh_block(const char *path, const char *extra) {
  static char b[4600];
  snprintf(b, sizeof b, "    - mesh: {file: '%s'%s}\n", path, extra);
  return b;
}

/* A box in each format is the box primitive, bit for bit: dyadic corners and spacing (exact in
 * the files' single precision), a square top so that lattice columns run along its diagonal. */
static void test_mesh_is_box(void) {
  const double lo[3] = {0.125, 0.03125, 0.0625}, hi[3] = {0.375, 0.28125, 0.3125};
  double tri[12 * 9];
  const size_t n = box_mesh(lo, hi, 0, tri);
  const char *dx[] = {"numerics.dx=0.015625"};
  sph_case c0;
  sph_error err;
  CU_ASSERT_FATAL(parse("    - {x: [0.125, 0.375], y: [0.03125, 0.28125], z: [0.0625, 0.3125]}\n",
                        dx, 1, &c0, &err) == 0);
  sph_sim *s0 = NULL;
  CU_ASSERT_FATAL(sph_sim_create(&c0, &s0, &err) == 0);
  static const char *const formats[][2] = {
      {"box.stl", "stl"}, {"box_binary.stl", "stlb"}, {"box.obj", "obj"}, {"box.ply", "ply"}};
  for (int k = 0; k < 4; k++) {
    const char *path = write_mesh(formats[k][0], formats[k][1], tri, n);
    sph_case c;
    const int rc = parse(mesh_block(path, ""), dx, 1, &c, &err);
    if (rc) printf("\n    %s", err.msg);
    CU_ASSERT_FATAL(rc == 0);
    sph_sim *s = NULL;
    CU_ASSERT_FATAL(sph_sim_create(&c, &s, &err) == 0);
    const int same = same_particles(s0, s);
    printf("\n  %s (%s): %zu particles, the box's bits: %s", formats[k][0], formats[k][1],
           sph_sim_particles(s)->n, same ? "yes" : "NO");
    CU_ASSERT(same);
    sph_sim_free(s);
    sph_case_free(&c);
  }
  sph_sim_free(s0);
  sph_case_free(&c0);
}

/* An icosahedron's triangles subdivided `levels` times onto the sphere (centre, r): 20 4^levels
 * triangles, each with its own three corners (the reader welds them). */
static size_t icosphere(const double centre[3], double r, int levels, double **out) {
  const double g = (1.0 + sqrt(5.0)) / 2.0;
  const double v[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                           {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                           {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  static const int f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                               {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                               {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                               {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  size_t n = 20;
  double *t = malloc(9 * n * sizeof *t);
  for (size_t k = 0; k < n; k++)
    for (int q = 0; q < 3; q++) {
      const double *p = v[f[k][q]];
      const double len = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      for (int a = 0; a < 3; a++)
        t[9 * k + 3 * q + a] = p[a] / len;
    }
  for (int l = 0; l < levels; l++) { /* each triangle into four, the midpoints onto the sphere */
    double *u = malloc(36 * n * sizeof *u);
    for (size_t k = 0; k < n; k++) {
      const double *a = t + 9 * k, *b = a + 3, *c = a + 6;
      double m[3][3];
      const double *pair[3][2] = {{a, b}, {b, c}, {c, a}};
      for (int e = 0; e < 3; e++) {
        double len = 0.0;
        for (int d = 0; d < 3; d++) {
          m[e][d] = pair[e][0][d] + pair[e][1][d];
          len += m[e][d] * m[e][d];
        }
        for (int d = 0; d < 3; d++)
          m[e][d] /= sqrt(len);
      }
      const double *tris[4][3] = {
          {a, m[0], m[2]}, {m[0], b, m[1]}, {m[2], m[1], c}, {m[0], m[1], m[2]}};
      for (int q = 0; q < 4; q++)
        for (int w = 0; w < 3; w++)
          memcpy(u + 36 * k + 9 * q + 3 * w, tris[q][w], 3 * sizeof(double));
    }
    free(t);
    t = u;
    n *= 4;
  }
  for (size_t k = 0; k < 3 * n; k++)
    for (int a = 0; a < 3; a++)
      t[3 * k + a] = centre[a] + r * t[3 * k + a];
  *out = t;
  return n;
}

/* A sphere of 1280 triangles: its filled volume against the mesh's own. */
static void test_mesh_volume(void) {
  const double centre[3] = {0.5, 0.15, 0.2};
  double *tri;
  const size_t n = icosphere(centre, 0.1, 3, &tri);
  const char *path = write_mesh("sphere.obj", "obj", tri, n);
  free(tri);
  double m;
  const long np = fill(mesh_block(path, ""), &m);
  printf("\n  the icosphere: %zu triangles, volume %.6g m3 (the sphere's %.6g)", n, m,
         4.0 / 3.0 * pi * 1e-3);
  report("a mesh sphere 20 dx across", np, 0.01, m, 0.02);
  const char *fine[] = {"numerics.dx=0.005"};
  sph_case c;
  sph_error err;
  CU_ASSERT_FATAL(parse(mesh_block(path, ""), fine, 1, &c, &err) == 0);
  report("the same 40 dx across", sph_case_block_points(&c.fluid[0], 0.005), 0.005, m, 0.01);
  sph_case_free(&c);
  /* scaled from millimetres and moved */
  double *mm;
  const double origin[3] = {0, 0, 0};
  const size_t n2 = icosphere(origin, 100.0, 3, &mm);
  path = write_mesh("sphere_mm.stl", "stlb", mm, n2);
  free(mm);
  const long np2 = fill(mesh_block(path, ", scale: 0.001, offset: [0.5, 0.15, 0.2]"), &m);
  report("the same in millimetres, scale 0.001, moved by offset", np2, 0.01, m, 0.02);
  CU_ASSERT_FATAL(
      parse(mesh_block(path, ", scale: 0.001, offset: [0.5, 0.15, 0.2]"), fine, 1, &c, &err) == 0);
  report("the same 40 dx across", sph_case_block_points(&c.fluid[0], 0.005), 0.005, m, 0.01);
  sph_case_free(&c);
}

/* Bad surfaces. */
static void test_mesh_refusals(void) {
  const double lo[3] = {0.1, 0.05, 0.05}, hi[3] = {0.3, 0.25, 0.25};
  double tri[24 * 9];
  box_mesh(lo, hi, 0, tri);
  static const char *const open[] = {"geometry.fluid[0].mesh.file", "belongs to one triangle only",
                                     "expected a closed surface", NULL};
  refused(mesh_block(write_mesh("open.stl", "stl", tri, 11), ""), open);
  box_mesh(lo, hi, 1, tri);
  static const char *const inward[] = {"turned inward", NULL};
  refused(mesh_block(write_mesh("inward.stl", "stl", tri, 12), ""), inward);
  box_mesh(lo, hi, 0, tri);
  double t[9]; /* one triangle turned */
  memcpy(t, tri + 9, sizeof t);
  memcpy(tri + 9, t + 6, 3 * sizeof(double));
  memcpy(tri + 15, t, 3 * sizeof(double));
  static const char *const turned[] = {"joins two triangles turned opposite ways", NULL};
  refused(mesh_block(write_mesh("turned.stl", "stl", tri, 12), ""), turned);
  static const char *const missing[] = {"geometry.fluid[0].mesh.file", "cannot read", NULL};
  refused(mesh_block("/nonexistent/box.stl", ""), missing);
  static const char *const scale[] = {"geometry.fluid[0].mesh.scale", NULL};
  refused(mesh_block(write_mesh("ok.stl", "stl", tri, 0), ", scale: 0"), scale);
  /* two boxes that overlap, in one file: refused where it winds twice */
  const double lo2[3] = {0.2, 0.1, 0.1}, hi2[3] = {0.4, 0.2, 0.2};
  box_mesh(lo, hi, 0, tri);
  box_mesh(lo2, hi2, 0, tri + 12 * 9);
  static const char *const twice[] = {"shapes.yaml:9: geometry.fluid[0].mesh: expected a surface "
                                      "that does not cross itself, got one that winds 2 times",
                                      NULL};
  const char *two = write_mesh("two.stl", "stl", tri, 24);
  refused_at_start(mesh_block(two, ""), twice);
  /* the same as an obstacle */
  char text[4800];
  snprintf(
      text, sizeof text,
      "    - {x: [0.6, 0.9], y: [0, 0.3], z: [0, 0.2]}\n  obstacles:\n    - mesh: {file: '%s'}\n",
      two);
  static const char *const obstacle[] = {"an obstacle's surface winds 2 times",
                                         "expected a surface that does not cross", NULL};
  refused_at_start(text, obstacle);
}
#endif

int main(void) {
  CU_TestInfo tests[] = {
    {"a rectangle as a polygon is the box, bit for bit", test_polygon_is_box},
    {"filled areas and volumes against the shapes'", test_filled_measure},
    {"bad shapes are refused at their key", test_refusals},
    {"obstacles of a shape: a rectangle is the box; a round one a shell", test_shaped_obstacles},
    {"a shape off the fluid's lattice: its wall particles on it", test_off_lattice},
    {"a wall along a polyline is its segments", test_polyline_wall},
    {"a vessel: a rectangle is the tank, a round one holds the water inside", test_vessel},
#if SPH_DIM == 2
    {"still water over a sloped beach stays still", test_still_beach},
    {"still water round a circle obstacle stays still", test_still_round_obstacle},
#else
    {"a box from STL, binary STL, OBJ and PLY is the box, bit for bit", test_mesh_is_box},
    {"a mesh sphere's filled volume", test_mesh_volume},
    {"still water over a cylinder of mdbc walls stays still", test_still_cylinder_mdbc},
    {"open, inward, mis-turned, missing and self-crossing surfaces are refused",
     test_mesh_refusals},
#endif
    CU_TEST_INFO_NULL
  };
#if SPH_DIM == 3
  mesh_dir = sph_test_tmpdir();
#endif
  const int rc = sph_test_main(SPH_DIM == 2 ? "shapes" : "shapes 3-D", tests);
#if SPH_DIM == 3
  sph_test_rmtree(mesh_dir);
  free(mesh_dir);
#endif
  return rc;
}
