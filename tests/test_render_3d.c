/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_render_3d.c - the renderer's 3-D view (render/camera.h,
 * render/spheres.h) and sph-render on a 3-D snapshot (issue 38).
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
 *    shows: depth); the same inputs give the same bytes.
 * 3. sph-render on a 3-D snapshot of cases/hydrostatic_3d.yaml (t = 0):
 *    the front view shows the water as spheres coloured by the field (the
 *    image's plot box holds non-background pixels, its corners do not) and
 *    the tank's edges as faint lines (above the water, a column crosses the
 *    near and the far top edge, a few light pixels);
 *    one and two worker processes, and two runs, give byte-identical
 *    PNGs; every named view renders; --smooth and a 2-D window are
 *    refused with a message naming the file.
 */
#include "config.h"

#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "gl_context.h"
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

static void test_sphere_shading(void) {
  rgl_context *ctx = context();
  CU_ASSERT_PTR_NOT_NULL_FATAL(ctx);
  rcamera c = {{0.0, 0.0, 0.0}, 0.0, 0.0, 10.0, 30.0, 0, 0.0};
  const int w = 101, h = 101;
  const rsphere s = {{0.0f, 0.0f, 0.0f}, 1.0f, {255, 0, 0, 255}};
  uint8_t *a = malloc(w * h * 4), *b = malloc(w * h * 4);
  sph_error err;
  CU_ASSERT_FATAL(rspheres_draw(&ctx->gl, &c, w, h, 3, &s, 1, (rcolor){20, 30, 40, 255}, a, &err) ==
                  0);
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
  CU_ASSERT_FATAL(rspheres_draw(&ctx->gl, &c, w, h, 3, &s, 1, (rcolor){20, 30, 40, 255}, b, &err) ==
                  0);
  CU_ASSERT(memcmp(a, b, (size_t)w * h * 4) == 0);
  /* depth: a blue sphere in front of a red one shows, in either order */
  const rsphere two[2] = {{{0.5f, 0.0f, 0.0f}, 1.0f, {255, 0, 0, 255}},
                          {{-0.5f, -1.0f, 0.0f}, 1.0f, {0, 0, 255, 255}}};
  const rsphere owt[2] = {two[1], two[0]};
  CU_ASSERT_FATAL(rspheres_draw(&ctx->gl, &c, w, h, 3, two, 2, (rcolor){0, 0, 0, 255}, a, &err) ==
                  0);
  CU_ASSERT_FATAL(rspheres_draw(&ctx->gl, &c, w, h, 3, owt, 2, (rcolor){0, 0, 0, 255}, b, &err) ==
                  0);
  CU_ASSERT(memcmp(a, b, (size_t)w * h * 4) == 0);
  const uint8_t *front = a + ((size_t)50 * w + 50) * 4; /* where both overlap */
  CU_ASSERT(front[2] > 100 && front[0] < 20);
  free(a);
  free(b);
  rgl_context_destroy(ctx);
}

/* ---- sph-render on a 3-D snapshot ---- */

static int render(const char *args) {
  char cmd[16384], *prog = realpath(sph_test_build("render/sph-render"), NULL);
  snprintf(cmd, sizeof cmd, "cd '%s' && '%s' %s 2> '%s/err.txt'", tmp,
           prog ? prog : "render/sph-render", args, tmp);
  free(prog);
  return sph_test_system(cmd);
}

static const char *last_err(void) {
  static char buf[8192];
  char path[4200];
  snprintf(path, sizeof path, "%s/err.txt", tmp);
  buf[0] = '\0';
  FILE *fp = fopen(path, "r");
  if (fp) {
    size_t n = fread(buf, 1, sizeof buf - 1, fp);
    buf[n] = '\0';
    fclose(fp);
  }
  return buf;
}

static uint8_t *read_png(const char *path, int *w, int *h) {
  png_image img;
  memset(&img, 0, sizeof img);
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&img, path)) return NULL;
  img.format = PNG_FORMAT_RGB;
  uint8_t *buf = malloc(PNG_IMAGE_SIZE(img));
  if (!buf || !png_image_finish_read(&img, NULL, buf, 0, NULL)) {
    free(buf);
    png_image_free(&img);
    return NULL;
  }
  *w = (int)img.width;
  *h = (int)img.height;
  return buf;
}

static int same_file(const char *a, const char *b) {
  size_t na, nb;
  char pa[4200], pb[4200];
  snprintf(pa, sizeof pa, "%s/%s", tmp, a);
  snprintf(pb, sizeof pb, "%s/%s", tmp, b);
  char *x = sph_test_read_file(pa, &na), *y = sph_test_read_file(pb, &nb);
  const int same = x && y && na == nb && memcmp(x, y, na) == 0;
  free(x);
  free(y);
  return same;
}

static int made;

static void make_snapshot(void) {
  char args[8192], out[4096];
  snprintf(args, sizeof args,
           "run '%s' -o '%s/run3' --quiet --set time.end=0.001 --set time.output_interval=0.001 "
           "--set output.probe_interval=0.001",
           sph_test_src("cases/hydrostatic_3d.yaml"), tmp);
  made = sph_test_sph(args, tmp, out, sizeof out) == 0;
  if (!made) printf("\n    sph run: %s", out);
}

static void test_frames(void) {
  make_snapshot();
  CU_ASSERT_FATAL(made);
  const int rc = render("--view front --size 480x270 --jobs 1 run3/snap_0000.h5 -o f1.png");
  if (rc) printf("\n    sph-render: %s", last_err());
  CU_ASSERT_EQUAL_FATAL(rc, 0);
  int w, h;
  char path[4200];
  snprintf(path, sizeof path, "%s/f1.png", tmp);
  uint8_t *img = read_png(path, &w, &h);
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

static void test_refusals(void) {
  CU_ASSERT_FATAL(made);
  CU_ASSERT_NOT_EQUAL(render("--smooth run3/snap_0000.h5 -o s.png"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "snap_0000.h5 is 3-D"));
  CU_ASSERT_NOT_EQUAL(render("--view 0:1:0:1 run3/snap_0000.h5 -o s.png"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "is for 2-D snapshots"));
  CU_ASSERT_NOT_EQUAL(render("--view diagonal run3/snap_0000.h5 -o s.png"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "unknown view 'diagonal'"));
  CU_ASSERT_NOT_EQUAL(render("--fov 200 run3/snap_0000.h5 -o s.png"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "--fov"));
}

int main(void) {
  tmp = sph_test_tmpdir();
  CU_TestInfo tests[] = {{"camera: hand-computed projections", test_projection},
                         {"camera: the matrices project as the camera does", test_matrices},
                         {"camera: a box framed on its margin", test_framing},
                         {"spheres: shading, depth, the same bytes", test_sphere_shading},
                         {"sph-render: a 3-D snapshot's frames", test_frames},
                         {"sph-render: 3-D refusals", test_refusals},
                         CU_TEST_INFO_NULL};
  int rc = sph_test_main("render_3d", tests);
  sph_test_rmtree(tmp);
  free(tmp);
  return rc;
}
