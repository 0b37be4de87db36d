/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_freesurface_3d.c - free-surface detection in 3-D (built with
 * -DSPH_DIM=3, linked with src/libsph3.la): a particle is on the surface
 * when part of its sphere (radius h) is not covered by its neighbours'
 * balls (src/physics/sphere_cover.h).
 *
 * 1. The caps: a ball's cap by the rules (apart, tangent, inside, containing,
 *    a cap of the law of cosines); the exact test on hand-made sets: six
 *    caps on the axes cover the sphere when wider than 54.7356 degrees (the
 *    angle from an axis to a cube corner; 55 degrees covers, 54.5 leaves
 *    the eight corner directions open), two closed hemispheres cover it,
 *    one cap never does, a cap and its duplicate do not.
 * 2. Lattices (dx = 1, h = 1.3): a block 7 x 6 x 5 alone: exactly its
 *    outer layer is flagged (its faces, edges and corners); the same block
 *    in a box of wall particles open at the top (3 layers): exactly its top
 *    layer (a flat surface); on a floor only: its top and its four sides
 *    (the edges where they meet); a droplet (the lattice points within 5.5
 *    of a centre): no particle deeper than 1.5 below its radius is flagged,
 *    the outermost shell (within 0.5 of the farthest) and the 30 points at
 *    radius 5 (the six extremes among them) are; the lattice's interior
 *    never.
 * 3. Exactness of the fast paths: on the lattices and on a lattice jittered
 *    by 0.3 dx (with a vacancy and a duplicate), the flags with the two
 *    certificates equal those of the exact test alone, bit for bit, and are
 *    the same on one and two threads; periodic along y, a slab's flags are
 *    those of the same slab extended far along y, away from its ends.
 * 4. A run: still water in a 3-D tank with output.free_surface and
 *    free_surface.h_factor 1.5: at every step exactly the top layer is
 *    flagged, and its particles carry 1.5 h.
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "case/case.h"
#include "core/particles.h"
#include "neighbours/grid.h"
#include "physics/freesurface.h"
#include "physics/sphere_cover.h"
#include "solver/diag.h"
#include "solver/sim.h"
#include "testutil.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#if SPH_DIM != 3
#error "test_freesurface_3d is built with -DSPH_DIM=3"
#endif

#define H 1.3

/* ---- 1. the caps ---------------------------------------------------------- */

static void test_caps(void) {
  sph_cap c;
  const double far[3] = {3.0, 0.0, 0.0}, touch[3] = {0.0, 2.6, 0.0}, mid[3] = {0.0, 0.0, 1.0};
  const double zero[3] = {0.0, 0.0, 0.0};
  CU_ASSERT_EQUAL(sph_sphere_cap(far, H, H, &c), SPH_DISC_NONE);
  CU_ASSERT_EQUAL(sph_sphere_cap(touch, H, H, &c), SPH_DISC_NONE); /* tangent: a point */
  CU_ASSERT_EQUAL(sph_sphere_cap(zero, H, H, &c), SPH_DISC_NONE);  /* a duplicate */
  CU_ASSERT_EQUAL(sph_sphere_cap(mid, H, 0.2, &c), SPH_DISC_NONE); /* inside the sphere */
  CU_ASSERT_EQUAL(sph_sphere_cap(mid, H, 2.5, &c), SPH_DISC_FULL); /* contains it */
  CU_ASSERT_EQUAL(sph_sphere_cap(mid, H, H, &c), SPH_DISC_ARC);
  CU_ASSERT(c.u[0] == 0.0 && c.u[1] == 0.0 && c.u[2] == 1.0);
  CU_ASSERT(fabs(c.c - 1.0 / (2.0 * H)) < 1e-15); /* cos a = d / (2 R) */
  CU_ASSERT(fabs(c.s - sqrt(1.0 - c.c * c.c)) < 1e-15);

  /* six caps on the axes, half-angle a */
  sph_arc arcs[8];
  for (int wide = 0; wide < 2; wide++) {
    const double a = (wide ? 55.0 : 54.5) * 3.14159265358979323846 / 180.0;
    sph_cap six[6];
    for (int k = 0; k < 6; k++) {
      memset(&six[k], 0, sizeof six[k]);
      six[k].u[k / 2] = k % 2 ? -1.0 : 1.0;
      six[k].c = cos(a);
      six[k].s = sin(a);
    }
    CU_ASSERT_EQUAL(sph_sphere_caps_cover(six, 6, arcs), wide);
  }
  sph_cap two[2] = {{{0.0, 0.0, 1.0}, 0.0, 1.0}, {{0.0, 0.0, -1.0}, 0.0, 1.0}};
  CU_ASSERT_EQUAL(sph_sphere_caps_cover(two, 2, arcs), 1);
  CU_ASSERT_EQUAL(sph_sphere_caps_cover(two, 1, arcs), 0);
  two[1] = two[0];
  CU_ASSERT_EQUAL(sph_sphere_caps_cover(two, 2, arcs), 0);
  CU_ASSERT_EQUAL(sph_sphere_caps_cover(two, 0, arcs), 0);
}

/* ---- 2. and 3. particles ---------------------------------------------------- */

/* Adds a particle of `kind` at (x, y, z). */
static void add(sph_particles *p, double x, double y, double z, int kind) {
  sph_error err;
  const double pos[3] = {x, y, z}, v[3] = {0.0, 0.0, 0.0};
  CU_ASSERT_FATAL(sph_particles_add_at(p, pos, v, 1000.0, 1.0, H, kind, &err) >= 0);
}

/* The flags by id after detection on a grid of p (periodic along y over
 * [0, py) when py > 0), with the certificates or the exact test alone. */
static unsigned char *flags_of(sph_particles *p, double py, int exact_only, size_t *count) {
  sph_error err;
  sph_grid g;
  sph_grid_init(&g);
  int rc = py > 0.0 ? sph_grid_build_periodic(&g, p, 2.0 * H, SPH_AXIS_Y, 0.0, py, 1u << 24, &err)
                    : sph_grid_build(&g, p, 2.0 * H, 1u << 24, &err);
  CU_ASSERT_FATAL(rc == 0);
  sph_freesurface_params fp = SPH_FREESURFACE_DEFAULTS;
  fp.exact_only = exact_only;
  fp.period = py;
  fp.paxis = 1;
  rc = sph_freesurface_detect(p, &g, &fp, count, &err);
  if (rc) printf("\n    %s", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  unsigned char *f = calloc(p->n, 1);
  for (size_t i = 0; i < p->n; i++)
    f[p->id[i]] = (p->flags[i] & SPH_FLAG_FREE_SURFACE) != 0;
  sph_grid_free(&g);
  return f;
}

/* Detects on p with the certificates, checks the exact test alone and one
 * thread give the same flags; returns the flags by id. */
static unsigned char *detect_checked(sph_particles *p, double py, size_t *count) {
  size_t n_exact = 0;
#ifdef _OPENMP
  const int saved = omp_get_max_threads(); /* (make check runs tests on one thread) */
  omp_set_num_threads(2);
#endif
  unsigned char *f = flags_of(p, py, 0, count);
  unsigned char *e = flags_of(p, py, 1, &n_exact);
  CU_ASSERT(memcmp(f, e, p->n) == 0 && *count == n_exact);
#ifdef _OPENMP
  omp_set_num_threads(1);
  size_t n1 = 0;
  unsigned char *one = flags_of(p, py, 0, &n1);
  omp_set_num_threads(saved);
  CU_ASSERT(memcmp(f, one, p->n) == 0);
  free(one);
#endif
  free(e);
  return f;
}

enum { NX = 7, NY = 6, NZ = 5 };

/* The block's particles first (ids 0 .. NX NY NZ - 1, x fastest); walls:
 * 0 none, 1 a floor of 3 layers, 2 a box of 3 layers open at the top. */
static void block(sph_particles *p, int walls) {
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(p, 4096, &err) == 0);
  for (int k = 0; k < NZ; k++)
    for (int j = 0; j < NY; j++)
      for (int i = 0; i < NX; i++)
        add(p, i, j, k, SPH_KIND_FLUID);
  if (!walls) return;
  const int L = walls == 2 ? 3 : 0;
  for (int k = -3; k < NZ + 2; k++)
    for (int j = -L; j < NY + L; j++)
      for (int i = -L; i < NX + L; i++) {
        const int inside = i >= 0 && i < NX && j >= 0 && j < NY && k >= 0;
        if (inside || (walls == 1 && k >= 0)) continue;
        add(p, i, j, k, SPH_KIND_WALL);
      }
}

/* 1 if block particle id (x fastest) lies on one of the faces in `faces`
 * (bits: 1 x-, 2 x+, 4 y-, 8 y+, 16 z-, 32 z+). */
static int on_face(size_t id, unsigned faces) {
  const int i = (int)(id % NX), j = (int)(id / NX % NY), k = (int)(id / (NX * NY));
  return ((faces & 1) && i == 0) || ((faces & 2) && i == NX - 1) || ((faces & 4) && j == 0) ||
         ((faces & 8) && j == NY - 1) || ((faces & 16) && k == 0) || ((faces & 32) && k == NZ - 1);
}

static void check_block(int walls, unsigned faces, const char *what) {
  sph_particles p;
  block(&p, walls);
  size_t count = 0, wrong = 0, want = 0;
  unsigned char *f = detect_checked(&p, 0.0, &count);
  for (size_t id = 0; id < (size_t)(NX * NY * NZ); id++) {
    const int expect = on_face(id, faces);
    want += (size_t)expect;
    wrong += f[id] != expect;
  }
  for (size_t id = NX * NY * NZ; id < p.n; id++)
    wrong += f[id] != 0; /* walls are never flagged */
  printf("\n    %s: %zu flagged (%zu expected), %zu wrong", what, count, want, wrong);
  CU_ASSERT_EQUAL(wrong, 0);
  CU_ASSERT_EQUAL(count, want);
  free(f);
  sph_particles_free(&p);
}

static void test_blocks(void) {
  check_block(0, 63, "block alone: its outer layer");
  check_block(2, 32, "block in a box open at the top: its top layer");
  check_block(1, 32 | 1 | 2 | 4 | 8, "block on a floor: its top and its sides");
}

static void test_droplet(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 1024, &err) == 0);
  const double rd = 5.5;
  for (int k = -6; k <= 6; k++)
    for (int j = -6; j <= 6; j++)
      for (int i = -6; i <= 6; i++)
        if (i * i + j * j + k * k <= rd * rd) add(&p, i, j, k, SPH_KIND_FLUID);
  double *r = malloc(p.n * sizeof *r);
  for (size_t i = 0; i < p.n; i++)
    r[p.id[i]] = sqrt(p.x[i] * p.x[i] + p.y[i] * p.y[i] + p.z[i] * p.z[i]);
  size_t count = 0, deep = 0, shell = 0, shell_flagged = 0, extremes = 0;
  unsigned char *f = detect_checked(&p, 0.0, &count);
  double rmax = 0.0;
  for (size_t id = 0; id < p.n; id++)
    rmax = fmax(rmax, r[id]);
  for (size_t id = 0; id < p.n; id++) {
    if (r[id] < rd - 1.5) deep += f[id];
    if (r[id] > rmax - 0.5) shell++, shell_flagged += f[id];
    if (r[id] == 5.0 && f[id]) extremes++; /* (+-5, 0, 0), (3, 4, 0), ...: 30 points */
  }
  printf("\n    droplet of %zu particles (radius %.1f): %zu flagged; deeper than 1.5: %zu; "
         "outermost shell %zu of %zu; at radius 5 (the six extremes among them) %zu of 30",
         p.n, rd, count, deep, shell_flagged, shell, extremes);
  CU_ASSERT_EQUAL(deep, 0);
  CU_ASSERT(shell > 0 && shell_flagged == shell);
  CU_ASSERT_EQUAL(extremes, 30);
  free(f);
  free(r);
  sph_particles_free(&p);
}

/* A jittered lattice 8 x 8 x 8 (0.3 dx), with a vacancy and a duplicate: the
 * certificates' flags are the exact test's (detect_checked); fewer than a
 * tenth of the inner particles (1.5 from every face) are flagged (none, as
 * measured), and more than 200 of the 512 (the outer layer holds 296). */
static void test_jittered(void) {
  sph_particles p;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 1024, &err) == 0);
  unsigned s = 12345u;
  for (int k = 0; k < 8; k++)
    for (int j = 0; j < 8; j++)
      for (int i = 0; i < 8; i++) {
        if (i == 4 && j == 4 && k == 4) continue; /* a vacancy */
        double e[3];
        for (int a = 0; a < 3; a++) {
          s = s * 1103515245u + 12345u;
          e[a] = 0.3 * ((double)(s >> 8) / 16777216.0 - 0.5) * 2.0;
        }
        add(&p, i + e[0], j + e[1], k + e[2], SPH_KIND_FLUID);
      }
  add(&p, p.x[100], p.y[100], p.z[100], SPH_KIND_FLUID); /* a duplicate */
  size_t count = 0;
  unsigned char *f = detect_checked(&p, 0.0, &count);
  size_t inner = 0, inner_flagged = 0;
  for (size_t i = 0; i < p.n; i++) {
    const size_t id = p.id[i];
    const int in = p.x[i] > 1.5 && p.x[i] < 5.5 && p.y[i] > 1.5 && p.y[i] < 5.5 && p.z[i] > 1.5 &&
                   p.z[i] < 5.5;
    inner += in;
    inner_flagged += in && f[id];
  }
  printf("\n    jittered lattice: %zu particles, %zu flagged; %zu of the %zu inner ones", p.n,
         count, inner_flagged, inner);
  CU_ASSERT(inner_flagged < inner / 10);
  CU_ASSERT(count > 200 && count < p.n);
  free(f);
  sph_particles_free(&p);
}

/* A slab periodic along y (period 8): the flags of the particles are those
 * of the middle of a slab 24 long that is not periodic. */
static void test_periodic(void) {
  unsigned char *f[2];
  size_t n[2], count;
  for (int per = 0; per < 2; per++) {
    sph_particles p;
    sph_error err;
    CU_ASSERT_FATAL(sph_particles_init(&p, 4096, &err) == 0);
    const int ny = per ? 8 : 24;
    for (int k = 0; k < 4; k++)
      for (int j = 0; j < ny; j++)
        for (int i = 0; i < 6; i++)
          add(&p, i + 0.5, j + 0.5, k + (i == 2 && j % 8 == 3 ? 0.3 : 0.0), SPH_KIND_FLUID);
    f[per] = detect_checked(&p, per ? 8.0 : 0.0, &count);
    n[per] = p.n;
    sph_particles_free(&p);
  }
  size_t differ = 0;
  for (size_t id = 0; id < n[1]; id++) { /* (i, j, k) of the short slab = (i, j + 8, k) */
    const size_t i = id % 6, j = id / 6 % 8, k = id / 48;
    differ += f[1][id] != f[0][i + 6 * (j + 8) + 6 * 24 * k];
  }
  printf("\n    periodic slab: %zu of %zu flags differ from the long slab's middle", differ, n[1]);
  CU_ASSERT_EQUAL(differ, 0);
  free(f[0]);
  free(f[1]);
}

/* A run: still water in a 3-D tank with output.free_surface and h* = 1.5 h
 * (free_surface.h_factor): at every step exactly the top layer (20 x 10
 * particles) is flagged, and those particles carry h = 1.5 h0. */
static void test_run(void) {
  static const char *const text = "name: fs3\n"
                                  "dimension: 3\n"
                                  "physics: {sound_speed: {factor: 10, height: 0.1}}\n"
                                  "numerics: {dx: 0.01, scheme: paper_b}\n"
                                  "time: {end: 0.02, output_interval: 0.02}\n"
                                  "geometry:\n"
                                  "  tank: {x: [0.0, 0.2], y: [0.0, 0.1], z: [0.0, 0.15]}\n"
                                  "  fluid: [{x: [0.0, 0.2], y: [0.0, 0.1], z: [0.0, 0.1]}]\n"
                                  "free_surface: {h_factor: 1.5}\n"
                                  "output: {snapshots: false, free_surface: true}\n";
  sph_case c;
  sph_error err;
  int rc = sph_case_parse(text, strlen(text), "fs3.yaml", NULL, 0, &c, &err);
  if (rc) printf("\n    %s", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  sph_sim *s = NULL;
  CU_ASSERT_FATAL(sph_sim_create(&c, &s, &err) == 0);
  long steps = 0, wrong = 0;
  while (sph_sim_time(s) < c.t_end) {
    CU_ASSERT_FATAL(sph_sim_step(s, c.t_end, &err) == 0);
    sph_diag_row d;
    sph_sim_diag(s, &d);
    wrong += d.n_surface != 200;
    steps++;
  }
  const sph_particles *p = sph_sim_particles(s);
  size_t top = 0, big = 0;
  for (size_t i = 0; i < p->n; i++) {
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    const int flagged = (p->flags[i] & SPH_FLAG_FREE_SURFACE) != 0;
    top += flagged && p->z[i] > 0.09;
    big += flagged ? p->h[i] == 1.5 * c.h : p->h[i] == c.h;
  }
  printf("\n    %ld steps, %ld with other than 200 flagged; at the end %zu flagged in the top "
         "layer, %zu of 2000 with the h their flag gives",
         steps, wrong, top, big);
  CU_ASSERT(steps > 10 && wrong == 0 && top == 200 && big == 2000);
  sph_sim_free(s);
  sph_case_free(&c);
}

int main(void) {
  CU_TestInfo tests[] = {
      {"3-D caps: the rules and the exact covering test", test_caps},
      {"3-D lattices: block alone, in a box, on a floor", test_blocks},
      {"3-D droplet", test_droplet},
      {"3-D jittered lattice: certificates = exact test, threads", test_jittered},
      {"3-D periodic along y", test_periodic},
      {"3-D run: the top layer of still water, h* = 1.5 h", test_run},
      CU_TEST_INFO_NULL};
  return sph_test_main("freesurface_3d", tests);
}
