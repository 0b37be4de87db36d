/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_render_3d.c - the renderer's 3-D view (render/camera.h,
 * render/spheres.h, render/mesh_gl.h, render/scene3d.h) and sph-render on
 * a 3-D snapshot (issue 38). The surface's geometry is test_isosurface's.
 *
 * 1. The camera against hand-computed projections: a point 1 m right of
 *    and 1 m above the target, 10 m from the eye, at a 90-degree field of
 *    view on a 200 x 100 image lands on pixel (105, 45) in the front view,
 *    and the same point of the side and top views' frames lands there too;
 *    orthographic with a 20 m high view the same at any depth; the OpenGL
 *    matrices give the same pixels (to 1e-3 px); framing a cube puts its
 *    nearest corners exactly on the 5 % margin and none outside it.
 * 2. Spheres (OSMesa): a lone red sphere facing the eye has, at its centre,
 *    the shading of its formula (ambient 0.3, diffuse 0.7 from the light
 *    (-0.35, 0.55, 0.75), specular 0.15 at exponent 40: red 214, green and
 *    blue 3, within 2), the background around it exactly; two overlapping
 *    spheres give the same image whichever is drawn first (the nearer one
 *    shows: depth); the same inputs give the same bytes. A red square mesh
 *    facing the eye is lit as the sphere's centre is, seen from behind the
 *    same, and a sphere before it shows while one behind it does not.
 * 3. sph-render on a 3-D snapshot of tests/data/still_tank_3d.yaml (t = 0):
 *    the front view shows the water as spheres coloured by the field (the
 *    image's plot box holds non-background pixels, its corners do not) and
 *    the tank's edges as faint lines (above the water, a column crosses the
 *    near and the far top edge, a few light pixels);
 *    one and two worker processes, and two runs, give byte-identical
 *    PNGs; every named view renders; --smooth and a 2-D window are
 *    refused with a message naming the file.
 * 4. Obstacles: the boxes of a snapshot's parameter listing (an incomplete
 *    one ignored) and the tank's; their faces a mesh of the boxes' volume
 *    (to 1e-6) wound along their outward normals.
 * 5. --surface: the water block as a mesh coloured by pressure, and as
 *    water (one colour: no colour bar, where the field's frame has one) on
 *    one and two workers (the same bytes) and on llvmpipe's one
 *    and four rasterising threads (LP_NUM_THREADS: the same bytes); the mesh mode writes
 *    a PLY file whose header counts match its size (28 bytes a vertex with
 *    the field, 13 a face), the same bytes twice, the same surface as a
 *    legacy VTK file that meshio reads back as the PLY (points, triangles,
 *    field; also a directory of them with --format vtk), a directory of
 *    surface_NNNN.ply; options that draw, a .obj output, one file for
 *    many snapshots and an unknown --surface are refused.
 * 6. --slice y=0.05 (the interpolated view with the outline): coloured
 *    water under white air down the middle, the same bytes on one and two
 *    workers; discs of a slab across z; panels of slices across x; an
 *    overlay's markers on a slice; a bad
 *    axis, a negative thickness and --slice with --surface are refused.
 * 7. Golden images (golden/render/small3d_*.png, tests/render_testutil.h's
 *    tolerances) of tests/data/still_tank_3d.yaml at dx = 0.02 m after one
 *    step (250 fluid particles): the fluid as spheres (iso view), the
 *    surface and the slice y = 0.05 m, coloured by pressure; the same run's
 *    free-surface flags (the top layer yellow, the rest purple); --compare
 *    of two 3-D runs.
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "gl_context.h"
#include "obstacles.h"
#include "render_testutil.h"
#include "scene3d.h"
#include "spheres.h"
#include "testutil.h"

static char *tmp;

static void near(double got, double want, double tol, const char *what) {
  if (fabs(got - want) > tol) printf("\n    %s: %.9g, expected %.9g", what, got, want);
  CU_ASSERT(fabs(got - want) <= tol);
}

static void test_projection(void) {
  rcamera c = {{0.0, 0.0, 0.0}, 0.0, 0.0, 10.0, 90.0, 0, 0.0};
  double px, py, d;
  const double front[3] = {1.0, 0.0, 1.0}, side[3] = {0.0, 1.0, 1.0}, top[3] = {1.0, 1.0, 0.0};
  CU_ASSERT(rcamera_project(&c, 200, 100, front, &px, &py, &d) == 0);
  near(px, 105.0, 1e-9, "front px");
  near(py, 45.0, 1e-9, "front py");
  near(d, 10.0, 1e-9, "front depth");
  c.azimuth = 90.0; /* from +x: y to the right */
  CU_ASSERT(rcamera_project(&c, 200, 100, side, &px, &py, &d) == 0);
  near(px, 105.0, 1e-9, "side px");
  near(py, 45.0, 1e-9, "side py");
  c.azimuth = 0.0, c.elevation = 90.0; /* from above: x right, y up the image */
  CU_ASSERT(rcamera_project(&c, 200, 100, top, &px, &py, &d) == 0);
  near(px, 105.0, 1e-9, "top px");
  near(py, 45.0, 1e-9, "top py");
  /* orthographic, 20 m high: the same pixel at depth 10 and at depth 5 */
  rcamera o = {{0.0, 0.0, 0.0}, 0.0, 0.0, 10.0, 90.0, 1, 20.0};
  const double deeper[3] = {1.0, -5.0, 1.0};
  CU_ASSERT(rcamera_project(&o, 200, 100, front, &px, &py, &d) == 0);
  near(px, 105.0, 1e-9, "ortho px");
  CU_ASSERT(rcamera_project(&o, 200, 100, deeper, &px, &py, &d) == 0);
  near(px, 105.0, 1e-9, "ortho px at depth 5");
  near(py, 45.0, 1e-9, "ortho py at depth 5");
  near(d, 5.0, 1e-9, "ortho depth");
  /* behind the eye: not projected */
  const double behind[3] = {0.0, -20.0, 0.0};
  c.elevation = 0.0; /* front again: the eye at y = -10 */
  CU_ASSERT(rcamera_project(&c, 200, 100, behind, &px, &py, &d) != 0);
  double az, el;
  CU_ASSERT(rcamera_named("iso", &az, &el) == 0 && az == 30.0 && el == 25.0);
  CU_ASSERT(rcamera_named("isometric", &az, &el) != 0);
}

/* The matrices map points as rcamera_project does. */
static void test_matrices(void) {
  for (int ortho = 0; ortho <= 1; ortho++) {
    rcamera c = {{0.3, -0.2, 0.5}, 37.0, 21.0, 4.0, 35.0, ortho, 3.0};
    float view[16], proj[16];
    const int w = 320, h = 200;
    rcamera_matrices(&c, (double)w / h, 0.5, 20.0, view, proj);
    double worst = 0.0;
    for (int k = 0; k < 27; k++) {
      const double p[4] = {0.3 + 0.4 * (k % 3 - 1), -0.2 + 0.4 * (k / 3 % 3 - 1),
                           0.5 + 0.4 * (k / 9 - 1), 1.0};
      double e[4] = {0, 0, 0, 0}, q[4] = {0, 0, 0, 0};
      for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
          e[i] += view[4 * j + i] * p[j];
      for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
          q[i] += proj[4 * j + i] * e[j];
      const double gx = 0.5 * (q[0] / q[3] + 1.0) * w, gy = 0.5 * (1.0 - q[1] / q[3]) * h;
      double px, py, d;
      CU_ASSERT(rcamera_project(&c, w, h, p, &px, &py, &d) == 0);
      worst = fmax(worst, fmax(fabs(gx - px), fabs(gy - py)));
      CU_ASSERT(q[2] / q[3] > -1.0 && q[2] / q[3] < 1.0); /* between near and far */
    }
    printf("\n    %s: matrices against the projection, largest difference %.2g px",
           ortho ? "orthographic" : "perspective", worst);
    CU_ASSERT(worst < 1e-3);
  }
}

/* Framing a box: every corner inside the image, the outermost on the margin. */
static void test_framing(void) {
  const double lo[3] = {0.0, 0.0, 0.0}, hi[3] = {3.22, 1.0, 1.0};
  const char *names[4] = {"iso", "front", "side", "top"};
  for (int ortho = 0; ortho <= 1; ortho++)
    for (int v = 0; v < 4; v++) {
      rcamera c = {{0, 0, 0}, 0.0, 0.0, 1.0, 30.0, ortho, 1.0};
      CU_ASSERT_FATAL(rcamera_named(names[v], &c.azimuth, &c.elevation) == 0);
      const int w = 1280, h = 640;
      rcamera_frame_box(&c, lo, hi, (double)w / h);
      double widest = 0.0;
      for (int q = 0; q < 8; q++) {
        const double p[3] = {q & 1 ? hi[0] : lo[0], q & 2 ? hi[1] : lo[1], q & 4 ? hi[2] : lo[2]};
        double px, py, d;
        CU_ASSERT(rcamera_project(&c, w, h, p, &px, &py, &d) == 0);
        CU_ASSERT(d > 0.0);
        const double nx = fabs(2.0 * px / w - 1.0), ny = fabs(2.0 * py / h - 1.0);
        widest = fmax(widest, fmax(nx, ny));
      }
      if (fabs(widest - 1.0 / 1.05) > 1e-9)
        printf("\n    %s%s: the outermost corner at %.12f of the half-image", names[v],
               ortho ? " (ortho)" : "", widest);
      CU_ASSERT(fabs(widest - 1.0 / 1.05) <= 1e-9);
    }
}

static rgl_context *context(void) {
  rgl_context *ctx = NULL;
  sph_error err;
  if (rgl_context_create("osmesa", &ctx, &err) != 0) {
    printf("\n    no OSMesa context: %s", err.msg);
    return NULL;
  }
  return ctx;
}

/* n spheres alone in a scene, at 3 x 3 samples. */
static int spheres(rgl_context *ctx, const rcamera *c, int w, int h, const rsphere *s, size_t n,
                   rcolor bg, uint8_t *out, sph_error *err) {
  const rscene3d sc = {s, n, {NULL}, {NULL}, NULL, 0, 0.0, {0, 0, 0, 0}};
  return rscene3d_draw(&ctx->gl, c, w, h, 3, &sc, bg, out, err);
}

static void test_sphere_shading(void) {
  rgl_context *ctx = context();
  CU_ASSERT_PTR_NOT_NULL_FATAL(ctx);
  rcamera c = {{0.0, 0.0, 0.0}, 0.0, 0.0, 10.0, 30.0, 0, 0.0};
  const int w = 101, h = 101;
  const rsphere s = {{0.0f, 0.0f, 0.0f}, 1.0f, {255, 0, 0, 255}};
  uint8_t *a = malloc(w * h * 4), *b = malloc(w * h * 4);
  sph_error err;
  CU_ASSERT_FATAL(spheres(ctx, &c, w, h, &s, 1, (rcolor){20, 30, 40, 255}, a, &err) == 0);
  const uint8_t *mid = a + ((size_t)50 * w + 50) * 4;
  printf("\n    the sphere's centre: %d %d %d", mid[0], mid[1], mid[2]);
  CU_ASSERT(abs(mid[0] - 214) <= 2 && abs(mid[1] - 3) <= 2 && abs(mid[2] - 3) <= 2);
  CU_ASSERT(a[0] == 20 && a[1] == 30 && a[2] == 40 && a[3] == 255); /* a corner: background */
  /* the sphere's radius on the image: 1 m at 10 m under a 30-degree view of 101 px */
  const double r_px = 1.0 / (10.0 * tan(15.0 * M_PI / 180.0)) * 50.5;
  const uint8_t *in = a + ((size_t)50 * w + (size_t)(50 + 0.8 * r_px)) * 4;
  const uint8_t *out = a + ((size_t)50 * w + (size_t)(50 + 1.2 * r_px)) * 4;
  CU_ASSERT(in[0] > 60 && in[2] < 20);                     /* on the sphere */
  CU_ASSERT(out[0] == 20 && out[1] == 30 && out[2] == 40); /* off it */
  CU_ASSERT_FATAL(spheres(ctx, &c, w, h, &s, 1, (rcolor){20, 30, 40, 255}, b, &err) == 0);
  CU_ASSERT(memcmp(a, b, (size_t)w * h * 4) == 0);
  /* depth: a blue sphere in front of a red one shows, in either order */
  const rsphere two[2] = {{{0.5f, 0.0f, 0.0f}, 1.0f, {255, 0, 0, 255}},
                          {{-0.5f, -1.0f, 0.0f}, 1.0f, {0, 0, 255, 255}}};
  const rsphere owt[2] = {two[1], two[0]};
  CU_ASSERT_FATAL(spheres(ctx, &c, w, h, two, 2, (rcolor){0, 0, 0, 255}, a, &err) == 0);
  CU_ASSERT_FATAL(spheres(ctx, &c, w, h, owt, 2, (rcolor){0, 0, 0, 255}, b, &err) == 0);
  CU_ASSERT(memcmp(a, b, (size_t)w * h * 4) == 0);
  const uint8_t *front = a + ((size_t)50 * w + 50) * 4; /* where both overlap */
  CU_ASSERT(front[2] > 100 && front[0] < 20);
  free(a);
  free(b);
  rgl_context_destroy(ctx);
}

/* A red square mesh 2 m wide in the plane y = 0, facing the front view's
 * eye (normal -y), and spheres with it. */
static void test_mesh_shading(void) {
  rgl_context *ctx = context();
  CU_ASSERT_PTR_NOT_NULL_FATAL(ctx);
  rcamera c = {{0.0, 0.0, 0.0}, 0.0, 0.0, 10.0, 30.0, 0, 0.0};
  const int w = 101, h = 101;
  float p[12] = {-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1};
  float n[12] = {0, -1, 0, 0, -1, 0, 0, -1, 0, 0, -1, 0};
  uint32_t tri[6] = {0, 1, 2, 0, 2, 3};
  const rmesh m = {4, 2, p, n, NULL, tri};
  const uint8_t red[16] = {255, 0, 0, 255, 255, 0, 0, 255, 255, 0, 0, 255, 255, 0, 0, 255};
  uint8_t *a = malloc(w * h * 4), *b = malloc(w * h * 4);
  sph_error err;
  rscene3d sc = {NULL, 0, {&m}, {red}, NULL, 0, 0.0, {0, 0, 0, 0}};
  CU_ASSERT_FATAL(rscene3d_draw(&ctx->gl, &c, w, h, 3, &sc, (rcolor){20, 30, 40, 255}, a, &err) ==
                  0);
  const uint8_t *mid = a + ((size_t)50 * w + 50) * 4;
  printf("\n    the square's centre: %d %d %d", mid[0], mid[1], mid[2]);
  /* lit as a sphere's point facing the eye is */
  CU_ASSERT(abs(mid[0] - 214) <= 2 && abs(mid[1] - 3) <= 2 && abs(mid[2] - 3) <= 2);
  CU_ASSERT(a[0] == 20 && a[1] == 30 && a[2] == 40); /* a corner: background */
  /* the square's edge: 1 m at 10 m under a 30-degree view of 101 px */
  const double half_px = 1.0 / (10.0 * tan(15.0 * M_PI / 180.0)) * 50.5;
  CU_ASSERT(a[((size_t)50 * w + (size_t)(50 + 0.9 * half_px)) * 4] > 150);
  CU_ASSERT(a[((size_t)50 * w + (size_t)(50 + 1.1 * half_px)) * 4] == 20);
  /* seen from behind, the normal turns to the eye: the same shading */
  for (int k = 0; k < 4; k++)
    n[3 * k + 1] = 1;
  CU_ASSERT_FATAL(rscene3d_draw(&ctx->gl, &c, w, h, 3, &sc, (rcolor){20, 30, 40, 255}, b, &err) ==
                  0);
  CU_ASSERT(memcmp(a, b, (size_t)w * h * 4) == 0);
  /* depth between the two: a blue sphere before the square shows, one
   * behind it does not */
  rsphere s = {{0.0f, -1.0f, 0.0f}, 0.5f, {0, 0, 255, 255}};
  sc.spheres = &s;
  sc.n_spheres = 1;
  CU_ASSERT_FATAL(rscene3d_draw(&ctx->gl, &c, w, h, 3, &sc, (rcolor){20, 30, 40, 255}, b, &err) ==
                  0);
  CU_ASSERT(b[((size_t)50 * w + 50) * 4 + 2] > 100 && b[((size_t)50 * w + 50) * 4] < 20);
  s.c[1] = 1.0f;
  CU_ASSERT_FATAL(rscene3d_draw(&ctx->gl, &c, w, h, 3, &sc, (rcolor){20, 30, 40, 255}, b, &err) ==
                  0);
  CU_ASSERT(memcmp(a, b, (size_t)w * h * 4) == 0);
  free(a);
  free(b);
  rgl_context_destroy(ctx);
}

/* Boxes from a snapshot's parameter listing, and their faces as a closed
 * outward mesh of the boxes' volume. */
static void test_obstacles(void) {
  const char *listing = "geometry.tank.x: [0, 3.2200000000000002]\n"
                        "geometry.tank.y: [0, 1]\n"
                        "geometry.tank.z: [0, 1]\n"
                        "geometry.obstacles[0].x: [0.66349999999999998, 0.82450000000000001]\n"
                        "geometry.obstacles[0].y: [0.29849999999999999, 0.70150000000000001]\n"
                        "geometry.obstacles[0].z: [0, 0.161]\n"
                        "geometry.obstacles[0].layers: 2\n"
                        "geometry.obstacles[1].x: [1, 2]\n"
                        "geometry.obstacles[1].y: [0, 0.5]\n"
                        "geometry.obstacles[1].z: [0.25, 0.5]\n"
                        "geometry.obstacles[2].x: [1, 2]\n"; /* incomplete: not a box */
  double box[4][6], tank[6];
  CU_ASSERT_EQUAL_FATAL(robstacles_parse(listing, box, 4), 2);
  CU_ASSERT(box[0][0] == 0.66349999999999998 && box[0][3] == 0.70150000000000001 &&
            box[0][4] == 0.0 && box[0][5] == 0.161);
  CU_ASSERT(box[1][4] == 0.25 && box[1][5] == 0.5);
  CU_ASSERT_EQUAL(robstacles_parse(listing, box, 1), 1);
  CU_ASSERT_EQUAL(robstacles_parse(NULL, box, 4), 0);
  CU_ASSERT(robstacles_tank(listing, tank) == 0 && tank[1] == 3.2200000000000002 && tank[5] == 1.0);
  CU_ASSERT(robstacles_tank("geometry.tank.x: [0, 1]\n", tank) != 0);
  rmesh m;
  sph_error err;
  CU_ASSERT_FATAL(robstacles_mesh((const double(*)[6])box, 2, &m, &err) == 0);
  const double want = 0.161 * 0.403 * 0.161 + 1.0 * 0.5 * 0.25;
  printf("\n    two boxes: %zu triangles, volume %.9f (%.9f)", m.nt, rmesh_volume(&m), want);
  CU_ASSERT(m.nt == 24 && m.nv == 48);
  CU_ASSERT(fabs(rmesh_volume(&m) - want) < 1e-6);
  /* each triangle's winding agrees with its vertices' normal */
  int agree = 0;
  for (size_t t = 0; t < m.nt; t++) {
    const float *a = m.p + 3 * m.tri[3 * t], *b = m.p + 3 * m.tri[3 * t + 1],
                *c = m.p + 3 * m.tri[3 * t + 2], *n = m.normal + 3 * m.tri[3 * t];
    const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double x[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                         e1[0] * e2[1] - e1[1] * e2[0]};
    agree += x[0] * n[0] + x[1] * n[1] + x[2] * n[2] > 0.0;
  }
  CU_ASSERT_EQUAL(agree, 24);
  rmesh_free(&m);
}

/* ---- sph-render on a 3-D snapshot ---- */

/* sph-render in tmp (render_testutil.h), with environment assignments
 * env before it or none, and its last stderr. */
static int render_env(const char *env, const char *args) { return rtest_render(tmp, env, args); }
static int render(const char *args) { return rtest_render(tmp, "", args); }
static const char *last_err(void) { return rtest_last_err(tmp); }

/* Whether tmp/a and tmp/b hold the same bytes. */
static int same_file(const char *a, const char *b) {
  char pa[4200], pb[4200];
  snprintf(pa, sizeof pa, "%s/%s", tmp, a);
  snprintf(pb, sizeof pb, "%s/%s", tmp, b);
  return rtest_same_bytes(pa, pb);
}

static int made;

/* Runs tests/data/still_tank_3d.yaml for one step into tmp/dir (with extra
 * --set arguments); whether it ran. */
static int run_hydrostatic(const char *dir, const char *sets) {
  char args[8192], out[4096];
  snprintf(args, sizeof args,
           "run '%s' -o '%s/%s' --quiet --set time.end=0.001 --set time.output_interval=0.001 "
           "--set output.probe_interval=0.001 %s",
           sph_test_src("tests/data/still_tank_3d.yaml"), tmp, dir, sets);
  const int ran = sph_test_sph(args, tmp, out, sizeof out) == 0;
  if (!ran) printf("\n    sph run: %s", out);
  return ran;
}

static void make_snapshot(void) { made = run_hydrostatic("run3", ""); }

static void test_frames(void) {
  make_snapshot();
  CU_ASSERT_FATAL(made);
  const int rc = render("--view front --size 480x270 --jobs 1 run3/snap_0000.h5 -o f1.png");
  if (rc) printf("\n    sph-render: %s", last_err());
  CU_ASSERT_EQUAL_FATAL(rc, 0);
  int w, h;
  char path[4200];
  snprintf(path, sizeof path, "%s/f1.png", tmp);
  uint8_t *img = rtest_read_png(path, &w, &h);
  CU_ASSERT_PTR_NOT_NULL_FATAL(img);
  CU_ASSERT(w == 480 && h == 270);
  CU_ASSERT(img[0] == 255 && img[1] == 255 && img[2] == 255); /* white corners */
  size_t coloured = 0;
  for (int y = h / 4; y < 3 * h / 4; y++)
    for (int x = w / 4; x < 3 * w / 4; x++) {
      const uint8_t *p = img + ((size_t)y * w + x) * 3;
      coloured += !(p[0] == 255 && p[1] == 255 && p[2] == 255);
    }
  printf("\n    front view: %zu of %d central pixels drawn", coloured, w * h / 4);
  CU_ASSERT(coloured > (size_t)(w * h / 16));
  /* above the water only the tank's top edges: thin faint lines */
  int lines = 0, dark = 0;
  for (int y = (int)(0.08 * h); y < (int)(0.35 * h); y++) {
    const uint8_t *q = img + ((size_t)y * w + (size_t)(0.35 * w)) * 3;
    lines += q[0] < 250;
    dark += q[0] < 100;
  }
  printf("; %d edge pixels above the water", lines);
  CU_ASSERT(lines >= 2 && lines <= 8 && dark == 0);
  free(img);
  CU_ASSERT_EQUAL(render("--view front --size 480x270 --jobs 1 run3/snap_0000.h5 -o f2.png"), 0);
  CU_ASSERT(same_file("f1.png", "f2.png"));
  /* a sequence on one and on two worker processes */
  CU_ASSERT_EQUAL(render("--size 320x180 --jobs 1 --field pressure run3 -o seq1"), 0);
  CU_ASSERT_EQUAL(render("--size 320x180 --jobs 2 --field pressure run3 -o seq2"), 0);
  CU_ASSERT(same_file("seq1/frame_0000.png", "seq2/frame_0000.png"));
  CU_ASSERT(same_file("seq1/frame_0001.png", "seq2/frame_0001.png"));
  const char *views[] = {"iso", "side", "top"};
  for (int v = 0; v < 3; v++) {
    char args[512];
    snprintf(args, sizeof args, "--view %s --size 320x180 run3/snap_0000.h5 -o v%d.png", views[v],
             v);
    CU_ASSERT_EQUAL(render(args), 0);
  }
  CU_ASSERT_EQUAL(render("--ortho --azimuth 45 --elevation 30 --size 320x180 run3/snap_0000.h5 "
                         "-o o.png"),
                  0);
}

/* Reads a PLY file's header: the counts of its elements and whether it
 * declares property `field`. */
static int ply_header(const char *name, size_t *nv, size_t *nf, const char *field, int *has) {
  char path[4200], line[512];
  snprintf(path, sizeof path, "%s/%s", tmp, name);
  FILE *fp = fopen(path, "rb");
  if (!fp) return -1;
  *nv = *nf = 0;
  *has = 0;
  int ok = fgets(line, sizeof line, fp) && strcmp(line, "ply\n") == 0;
  while (ok && fgets(line, sizeof line, fp) && strcmp(line, "end_header\n") != 0) {
    sscanf(line, "element vertex %zu", nv);
    sscanf(line, "element face %zu", nf);
    char prop[256];
    if (sscanf(line, "property float %255s", prop) == 1 && strcmp(prop, field) == 0) *has = 1;
  }
  fclose(fp);
  return ok ? 0 : -1;
}

/* Pixels not white in the right tenth of the PNG at tmp/name, between a fifth from the top and
 * a tenth from the bottom (-1 if unreadable). */
static long right_strip_ink(const char *name) {
  char path[4200];
  snprintf(path, sizeof path, "%s/%s", tmp, name);
  int w, h;
  uint8_t *img = rtest_read_png(path, &w, &h);
  if (!img) return -1;
  long ink = 0;
  for (int y = h / 5; y < h - h / 10; y++) /* below the case's name at the top right */
    for (int x = w - w / 10; x < w; x++) {
      const uint8_t *q = img + ((size_t)y * w + x) * 3;
      ink += !(q[0] == 255 && q[1] == 255 && q[2] == 255);
    }
  free(img);
  return ink;
}

static void test_surface(void) {
  CU_ASSERT_FATAL(made);
  /* the water block as a mesh coloured by pressure: drawn in the middle */
  int rc = render("--view front --size 480x270 --jobs 1 --surface field --field pressure "
                  "run3/snap_0000.h5 -o m1.png");
  if (rc) printf("\n    sph-render: %s", last_err());
  CU_ASSERT_EQUAL_FATAL(rc, 0);
  int w, h;
  char path[4200];
  snprintf(path, sizeof path, "%s/m1.png", tmp);
  uint8_t *img = rtest_read_png(path, &w, &h);
  CU_ASSERT_PTR_NOT_NULL_FATAL(img);
  const uint8_t *mid = img + ((size_t)(h / 2) * w + w / 2) * 3;
  printf("\n    the surface's middle: %d %d %d", mid[0], mid[1], mid[2]);
  CU_ASSERT(!(mid[0] == 255 && mid[1] == 255 && mid[2] == 255));
  free(img);
  /* water, and the same bytes on one and two workers and again */
  CU_ASSERT_EQUAL(render("--size 320x180 --jobs 1 --surface water run3 -o ms1"), 0);
  CU_ASSERT_EQUAL(render("--size 320x180 --jobs 2 --surface water run3 -o ms2"), 0);
  CU_ASSERT(same_file("ms1/frame_0000.png", "ms2/frame_0000.png"));
  CU_ASSERT(same_file("ms1/frame_0001.png", "ms2/frame_0001.png"));
  /* one colour, no field: no colour bar in the right tenth of the frame (the field's has one) */
  CU_ASSERT_EQUAL(render("--size 320x180 --jobs 1 --surface field run3/snap_0000.h5 -o mf.png"), 0);
  const long bar_field = right_strip_ink("mf.png"),
             bar_water = right_strip_ink("ms1/frame_0000.png");
  printf("; ink in the right tenth: %ld pixels with the field's colour bar, %ld for water",
         bar_field, bar_water);
  CU_ASSERT(bar_field > 100);
  CU_ASSERT(bar_water == 0);
  /* llvmpipe's rasteriser on one thread and on four: the same bytes */
  CU_ASSERT_EQUAL(render_env("LP_NUM_THREADS=1", "--size 320x180 --jobs 1 --surface field "
                                                 "run3/snap_0001.h5 -o lp1.png"),
                  0);
  CU_ASSERT_EQUAL(render_env("LP_NUM_THREADS=4", "--size 320x180 --jobs 1 --surface field "
                                                 "run3/snap_0001.h5 -o lp4.png"),
                  0);
  CU_ASSERT(same_file("lp1.png", "lp4.png"));
  /* the mesh mode: one file, with the field; a directory, without */
  rc = render("mesh --field pressure run3/snap_0000.h5 -o s.ply");
  if (rc) printf("\n    sph-render mesh: %s", last_err());
  CU_ASSERT_EQUAL_FATAL(rc, 0);
  size_t nv, nf;
  int has;
  CU_ASSERT_FATAL(ply_header("s.ply", &nv, &nf, "p", &has) == 0);
  printf("; s.ply: %zu vertices, %zu faces", nv, nf);
  CU_ASSERT(nv > 100 && nf > 100 && has);
  snprintf(path, sizeof path, "%s/s.ply", tmp);
  size_t size = 0;
  char *bytes = sph_test_read_file(path, &size);
  const char *end = bytes ? strstr(bytes, "end_header\n") : NULL;
  CU_ASSERT(end && size == (size_t)(end - bytes) + 11 + 28 * nv + 13 * nf);
  free(bytes);
  CU_ASSERT_EQUAL(render("mesh --surface-cell 0.02 run3 -o meshes"), 0);
  CU_ASSERT_FATAL(ply_header("meshes/surface_0001.ply", &nv, &nf, "p", &has) == 0);
  CU_ASSERT(nv > 10 && !has);
  CU_ASSERT_EQUAL(render("mesh --field pressure run3/snap_0000.h5 -o s2.ply"), 0);
  CU_ASSERT(same_file("s.ply", "s2.ply"));
  /* the same surface as legacy VTK (an unstructured grid of triangles, the field as point data,
   * which ParaView keeps): meshio reads the PLY's points, triangles and field from it */
  CU_ASSERT_EQUAL(render("mesh --field pressure run3/snap_0000.h5 -o s.vtk"), 0);
  CU_ASSERT_EQUAL(render("mesh --format vtk --surface-cell 0.02 run3 -o vtks"), 0);
  snprintf(path, sizeof path, "%s/vtks/surface_0001.vtk", tmp);
  FILE *vf = fopen(path, "rb");
  CU_ASSERT(vf != NULL);
  if (vf) fclose(vf);
  char cmd[9000];
  snprintf(cmd, sizeof cmd,
           "cd '%s' && /usr/bin/python3 -c \"import meshio, numpy as n; v = meshio.read('s.vtk'); "
           "q = meshio.read('s.ply'); "
           "assert n.array_equal(v.points, q.points); "
           "assert n.array_equal(v.cells_dict['triangle'], q.cells_dict['triangle']); "
           "assert n.array_equal(v.point_data['p'].ravel(), q.point_data['p']); "
           "assert v.point_data['Normals'].shape == (len(q.points), 3)\"",
           tmp);
  const int py = sph_test_system(cmd);
  if (py != 0)
    printf("\n    meshio could not read s.vtk as s.ply (needs /usr/bin/python3 with meshio: "
           "apt-get install python3-meshio)");
  else
    printf("; s.vtk: the PLY's points, triangles and field (meshio)");
  CU_ASSERT_EQUAL(py, 0);
  /* refusals */
  CU_ASSERT_NOT_EQUAL(render("mesh --size 100x100 run3 -o x"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "unknown option --size in mesh mode"));
  CU_ASSERT_NOT_EQUAL(render("mesh run3 -o one.ply"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "give a directory"));
  CU_ASSERT_NOT_EQUAL(render("mesh run3/snap_0000.h5 -o x.obj"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), ".ply"));
  CU_ASSERT_NOT_EQUAL(render("--surface glass run3/snap_0000.h5 -o g.png"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "valid: field, water, none"));
}

/* --slice: the hydrostatic tank cut across y, interpolated (the water
 * coloured by pressure up to the level 1/2, white above) and as discs;
 * the same bytes on one and two workers; refusals. */
static void test_slices(void) {
  CU_ASSERT_FATAL(made);
  int rc = render("--slice y=0.05 --field pressure --size 480x270 --jobs 1 run3 -o sl1");
  if (rc) printf("\n    sph-render: %s", last_err());
  CU_ASSERT_EQUAL_FATAL(rc, 0);
  CU_ASSERT_EQUAL(render("--slice y=0.05 --field pressure --size 480x270 --jobs 2 run3 -o sl2"), 0);
  CU_ASSERT(same_file("sl1/frame_0000.png", "sl2/frame_0000.png"));
  CU_ASSERT(same_file("sl1/frame_0001.png", "sl2/frame_0001.png"));
  int w, h;
  char path[4200];
  snprintf(path, sizeof path, "%s/sl1/frame_0000.png", tmp);
  uint8_t *img = rtest_read_png(path, &w, &h);
  CU_ASSERT_PTR_NOT_NULL_FATAL(img);
  /* down the middle column: white above the water, coloured below, the
   * outline between */
  int first = -1, last = -1;
  for (int y = 0; y < h; y++) {
    const uint8_t *q = img + ((size_t)y * w + w / 2 - 40) * 3;
    const int coloured = !(q[0] == q[1] && q[1] == q[2]);
    if (coloured && first < 0) first = y;
    if (coloured) last = y;
  }
  printf("\n    slice y = 0.05: the water from row %d to %d of %d", first, last, h);
  CU_ASSERT(first > 0 && last > first + 20);
  free(img);
  CU_ASSERT_EQUAL(render("--slice z=0.05,0.01 --discs --size 320x180 run3/snap_0000.h5 -o d.png"),
                  0);
  CU_ASSERT_EQUAL(render("--panels 2x1 --slice x=0.1 --size 640 run3 -o sp.png"), 0);
  /* reference points over a slice, in the plane's coordinates (x, z) */
  char csv[4200];
  snprintf(csv, sizeof csv, "%s/ref.csv", tmp);
  FILE *fp = fopen(csv, "w");
  CU_ASSERT_PTR_NOT_NULL_FATAL(fp);
  fputs("x,z\n0.05,0.1\n0.15,0.1\n", fp);
  fclose(fp);
  CU_ASSERT_EQUAL(
      render("--slice y=0.05 --overlay ref.csv --size 480x270 run3/snap_0000.h5 -o ov.png"), 0);
  CU_ASSERT_EQUAL(render("--slice y=0.05 --size 480x270 run3/snap_0000.h5 -o nov.png"), 0);
  CU_ASSERT(!same_file("ov.png", "nov.png")); /* the markers are drawn */
  /* a cut outside the domain is refused, not drawn blank (issue 61, E11) */
  CU_ASSERT_NOT_EQUAL(render("--slice x=1e9 run3/snap_0000.h5 -o x.png"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "--slice x=1e+09 is outside the domain, x ["));
  CU_ASSERT_NOT_EQUAL(render("--slice w=0.5 run3/snap_0000.h5 -o x.png"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "expected AXIS=POS[,THICKNESS]"));
  CU_ASSERT_NOT_EQUAL(render("--slice y=0.5,-1 run3/snap_0000.h5 -o x.png"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "thickness"));
  CU_ASSERT_NOT_EQUAL(render("--slice y=0.05 --surface water run3/snap_0000.h5 -o x.png"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "--slice and --surface"));
}

/* Golden images of a small 3-D case (tests/data/still_tank_3d.yaml at dx =
 * 0.02 m: 250 fluid particles): spheres, the surface, a slice. */
static void test_golden(void) {
  CU_ASSERT_FATAL(
      run_hydrostatic("small", "--set numerics.dx=0.02 --set output.free_surface=true"));
  char args[8192];
  const char *cases[3][2] = {{"--field pressure", "small3d_spheres.png"},
                             {"--surface field --field pressure", "small3d_surface.png"},
                             {"--slice y=0.05 --field pressure", "small3d_slice.png"}};
  for (int k = 0; k < 3; k++) {
    snprintf(args, sizeof args, "%s --size 480x270 --jobs 1 small/snap_0001.h5 -o g%d.png",
             cases[k][0], k);
    const int rc = render(args);
    if (rc) printf("\n    sph-render %s: %s", cases[k][0], last_err());
    CU_ASSERT_EQUAL_FATAL(rc, 0);
    char path[4200];
    snprintf(path, sizeof path, "%s/g%d.png", tmp, k);
    rtest_check_golden(path, cases[k][1], 1);
  }
  /* free-surface particles highlighted by their flag: the top layer in the
   * colour map's top (yellow), the rest in its bottom (purple) */
  CU_ASSERT_EQUAL_FATAL(
      render("--field free_surface --size 480x270 --jobs 1 small/snap_0001.h5 -o fs.png"), 0);
  char path[4200];
  snprintf(path, sizeof path, "%s/fs.png", tmp);
  int w, h;
  uint8_t *img = rtest_read_png(path, &w, &h);
  CU_ASSERT_PTR_NOT_NULL_FATAL(img);
  size_t top = 0, rest = 0;
  for (int y = 0; y < h; y++)
    for (int x = 0; x < w * 3 / 4; x++) {
      const uint8_t *q = img + ((size_t)y * w + x) * 3;
      top += q[0] > 150 && q[1] > 150 && q[2] < 80;
      rest += q[0] < 90 && q[1] < 40 && q[2] > 50;
    }
  printf("\n    free_surface: %zu yellow and %zu purple pixels", top, rest);
  CU_ASSERT(top > 500 && rest > 500);
  free(img);
  /* two runs side by side */
  CU_ASSERT_EQUAL(render("--compare --surface water --size 640 run3 small -o cmp"), 0);
  snprintf(path, sizeof path, "%s/cmp/compare_0001.png", tmp);
  img = rtest_read_png(path, &w, &h);
  CU_ASSERT_PTR_NOT_NULL(img);
  free(img);
}

static void test_refusals(void) {
  CU_ASSERT_FATAL(made);
  CU_ASSERT_NOT_EQUAL(render("--smooth run3/snap_0000.h5 -o s.png"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "snap_0000.h5 is 3-D"));
  CU_ASSERT_NOT_EQUAL(render("--view 0:1:0:1 run3/snap_0000.h5 -o s.png"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "is for 2-D snapshots"));
  CU_ASSERT_NOT_EQUAL(render("--view diagonal run3/snap_0000.h5 -o s.png"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "unknown view 'diagonal'"));
  CU_ASSERT_NOT_EQUAL(render("--overlay x.csv run3/snap_0000.h5 -o s.png"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "--overlay draws on 2-D snapshots and slices"));
  CU_ASSERT_NOT_EQUAL(render("--fov 200 run3/snap_0000.h5 -o s.png"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "--fov"));
}

int main(void) {
  tmp = sph_test_tmpdir();
  CU_TestInfo tests[] = {
      {"camera: hand-computed projections", test_projection},
      {"camera: the matrices project as the camera does", test_matrices},
      {"camera: a box framed on its margin", test_framing},
      {"spheres: shading, depth, the same bytes", test_sphere_shading},
      {"surface mesh: shading, both sides, depth with spheres", test_mesh_shading},
      {"obstacles: boxes from the parameters, closed outward", test_obstacles},
      {"sph-render: a 3-D snapshot's frames", test_frames},
      {"sph-render: the free surface, drawn and as PLY", test_surface},
      {"sph-render: slices", test_slices},
      {"golden images of a small 3-D case", test_golden},
      {"sph-render: 3-D refusals", test_refusals},
      CU_TEST_INFO_NULL};
  int rc = sph_test_main("render_3d", tests);
  sph_test_rmtree(tmp);
  free(tmp);
  return rc;
}
