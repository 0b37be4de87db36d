/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_render.c - tests of the off-screen renderer sph-render (render/).
 *
 * Fixtures are made here: two small snapshots (200 fluid particles in a
 * sheared block, 48 wall particles, fixed values) written with
 * sph_snapshot_write into a temporary directory, and the CSV files in
 * tests/data/render/. The renderer runs as a program, as a user runs it.
 *
 * Checks that hold on any OpenGL driver, exactly:
 *  - the background colour at a corner;
 *  - the pixel under a fluid particle's centre has the colour its value
 *    maps to (the disc interior is stored unblended);
 *  - the colour bar's top and bottom rows are the colour map's ends;
 *  - the same inputs give byte-identical PNGs, run after run and for one
 *    or two worker processes.
 * Golden images (the PNG files in golden/render/) are compared pixel by
 * pixel with a tolerance, because other Mesa drivers than llvmpipe
 * rasterise edges slightly differently: a pixel differs if a channel is off by more than
 * GOLDEN_CHANNEL_TOL; at most GOLDEN_PIXEL_FRACTION of the pixels may
 * differ, and the mean absolute channel difference must stay below
 * GOLDEN_MEAN_TOL. With llvmpipe the images match exactly.
 * Regenerate the golden images (after a deliberate change) with
 * `make golden-render`, which runs this program with SPH_RENDER_REGEN=1.
 *
 * Bad inputs: a missing file, a snapshot without the requested field and
 * a corrupt HDF5 file each give a non-zero exit status and a message naming
 * the file (and the field), and leave no PNG (and no temporary file).
 */
#include "config.h"

#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "colormap.h"
#include "core/particles.h"
#include "figure.h"
#include "font.h"
#include "inputs.h"
#include "io/csv.h"
#include "io/snapshot.h"
#include "layout.h"
#include "marks.h"
#include "snapdata.h"
#include "testutil.h"
#include "ticks.h"

#define GOLDEN_CHANNEL_TOL 8
#define GOLDEN_PIXEL_FRACTION 0.002
#define GOLDEN_MEAN_TOL 0.5

/* The fixture's view and the fixed options every fixture render uses. */
static const double fixture_view[4] = {-0.02, 0.22, -0.02, 0.12};
static const double fixture_dx = 0.01;

static char *tmp;        /* the temporary directory of this run */
static char snap0[4096]; /* fixture snapshot at t = 0 */
static char snap1[4096]; /* fixture snapshot at t = 0.1 */

/* ------------------------------------------------------------------ helpers */

static int regen(void) {
  const char *r = getenv("SPH_RENDER_REGEN");
  return r && strcmp(r, "1") == 0;
}

static const char *renderer(void) {
  static char buf[4096];
  snprintf(buf, sizeof buf, "%s", sph_test_build("render/sph-render"));
  return buf;
}

/* Runs sph-render with args (a shell fragment); stderr goes to tmp/err.txt. */
static int render(const char *args) {
  char cmd[16384];
  snprintf(cmd, sizeof cmd, "cd '%s' && '%s' %s 2> '%s/err.txt'", tmp, renderer(), args, tmp);
  return sph_test_system(cmd);
}

/* The last stderr of render(), in a static buffer. */
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

static int exists(const char *path) {
  struct stat st;
  return stat(path, &st) == 0;
}

static char *path_in(const char *dir, const char *name) {
  static char buf[4][4200];
  static int k;
  k = (k + 1) % 4;
  snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name);
  return buf[k];
}

/* Reads a PNG as 8-bit RGB; NULL if it cannot. */
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

static int same_bytes(const char *a, const char *b) {
  char cmd[9000];
  snprintf(cmd, sizeof cmd, "cmp -s '%s' '%s'", a, b);
  return sph_test_system(cmd) == 0;
}

/* How many files in dir end with suffix. */
static int count_files(const char *dir, const char *suffix) {
  char cmd[4400];
  snprintf(cmd, sizeof cmd, "exit $(ls -1 '%s' 2>/dev/null | grep -c -- '%s$')", dir, suffix);
  return sph_test_system(cmd);
}

/* Compares an image with golden/render/<name> within the tolerances above,
 * or, when regenerating and may_regen is set, copies it there. */
static void check_golden(const char *image, const char *name, int may_regen) {
  char golden[4096];
  snprintf(golden, sizeof golden, "%s", sph_test_src("golden/render/"));
  strncat(golden, name, sizeof golden - strlen(golden) - 1);
  if (regen() && may_regen) {
    char cmd[9000];
    snprintf(cmd, sizeof cmd, "cp '%s' '%s'", image, golden);
    CU_ASSERT_EQUAL_FATAL(sph_test_system(cmd), 0);
    printf("\n  regenerated %s\n", golden);
    return;
  }
  int w, h, gw, gh;
  uint8_t *a = read_png(image, &w, &h);
  uint8_t *b = read_png(golden, &gw, &gh);
  CU_ASSERT_PTR_NOT_NULL_FATAL(a);
  if (!b) {
    printf("\n  missing golden image %s (make golden-render)\n", golden);
    free(a);
    CU_FAIL_FATAL("golden image missing");
  }
  CU_ASSERT_EQUAL(w, gw);
  CU_ASSERT_EQUAL(h, gh);
  if (w == gw && h == gh) {
    size_t n = (size_t)w * h, differ = 0;
    double sum = 0.0;
    for (size_t i = 0; i < n; i++) {
      int worst = 0;
      for (int c = 0; c < 3; c++) {
        int d = abs((int)a[3 * i + c] - (int)b[3 * i + c]);
        sum += d;
        if (d > worst) worst = d;
      }
      if (worst > GOLDEN_CHANNEL_TOL) differ++;
    }
    double mean = sum / (3.0 * n);
    if (differ > GOLDEN_PIXEL_FRACTION * n || mean > GOLDEN_MEAN_TOL)
      printf("\n  %s vs %s: %zu of %zu pixels differ, mean difference %.3f\n", image, golden,
             differ, n, mean);
    CU_ASSERT(differ <= GOLDEN_PIXEL_FRACTION * n);
    CU_ASSERT(mean <= GOLDEN_MEAN_TOL);
  }
  free(a);
  free(b);
}

/* --------------------------------------------------------------- fixtures */

/* 198 fluid particles (an 18 x 11 block, sheared in proportion to t so
 * frames differ, staying inside the tank) and 48 walls. */
static int write_fixture(const char *path, double t, int free_surface) {
  sph_particles p;
  sph_error err;
  if (sph_particles_init(&p, 256, &err) != 0) return -1;
  const double dx = fixture_dx;
  for (int i = 0; i < 24; i++)
    sph_particles_add(&p, -0.015 + i * dx, -0.005, 0, 0, 1000, 0.1, 1.3 * dx, SPH_KIND_WALL, &err);
  for (int j = 0; j < 12; j++) {
    sph_particles_add(&p, -0.005, 0.005 + j * dx, 0, 0, 1000, 0.1, 1.3 * dx, SPH_KIND_WALL, &err);
    sph_particles_add(&p, 0.205, 0.005 + j * dx, 0, 0, 1000, 0.1, 1.3 * dx, SPH_KIND_WALL, &err);
  }
  for (int j = 0; j < 11; j++)
    for (int i = 0; i < 18; i++) {
      double x = (i + 0.5) * dx + t * 2.0 * j * dx, y = (j + 0.5) * dx;
      double vx = (i - 8.5) / 9.0, vy = (j - 5.0) / 10.0;
      long k = sph_particles_add(&p, x, y, vx, vy, 1000 + j, 0.1, 1.3 * dx, SPH_KIND_FLUID, &err);
      p.p[k] = 100.0 * (10 - j);
      p.flags[k] = j == 10;
    }
  sph_snapshot_meta m;
  memset(&m, 0, sizeof m);
  m.time = t;
  m.dt = 1e-4;
  m.step = (int64_t)(t * 1e4);
  m.case_name = "render_fixture";
  m.dx = dx;
  m.h = 1.3 * dx;
  m.rho0 = 1000;
  memcpy(m.view, fixture_view, sizeof m.view);
  m.free_surface = free_surface;
  int rc = sph_snapshot_write(path, &m, &p, &err);
  if (rc) printf("\n  fixture: %s\n", err.msg);
  sph_particles_free(&p);
  return rc;
}

static int setup(void) {
  tmp = sph_test_tmpdir();
  snprintf(snap0, sizeof snap0, "%s/run/snap_0000.h5", tmp);
  snprintf(snap1, sizeof snap1, "%s/run/snap_0001.h5", tmp);
  char dir[4200];
  snprintf(dir, sizeof dir, "%s/run", tmp);
  if (mkdir(dir, 0777) != 0) return -1;
  if (write_fixture(snap0, 0.0, 0) != 0 || write_fixture(snap1, 0.1, 0) != 0) return -1;
  return 0;
}

/* ------------------------------------------------------------ unit tests */

static void test_font(void) {
  CU_ASSERT_EQUAL(rfont_check(), 0);
  uint8_t rows[RFONT_ROWS];
  for (int c = '!'; c <= '~'; c++) { /* every visible glyph lights something */
    rfont_glyph((unsigned char)c, rows);
    int lit = 0;
    for (int r = 0; r < RFONT_ROWS; r++)
      lit |= rows[r];
    CU_ASSERT(lit != 0);
  }
  rfont_glyph('g', rows); /* g has a descender */
  CU_ASSERT(rows[7] != 0 || rows[8] != 0);
  CU_ASSERT_EQUAL(rfont_width("ab", 2), (2 * RFONT_ADVANCE - 1) * 2);
  CU_ASSERT_EQUAL(rfont_width("", 3), 0);
}

static double luminance(const uint8_t c[3]) {
  return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

static void test_colormap(void) {
  rcolormap m;
  sph_error err;
  CU_ASSERT_EQUAL_FATAL(rcolormap_get("viridis", &m, &err), 0);
  /* the ends are viridis' published end colours, exactly */
  CU_ASSERT(m.lut[0][0] == 0x44 && m.lut[0][1] == 0x01 && m.lut[0][2] == 0x54);
  CU_ASSERT(m.lut[255][0] == 0xfd && m.lut[255][1] == 0xe7 && m.lut[255][2] == 0x25);
  CU_ASSERT_FALSE(m.diverging);
  /* lightness never falls along a sequential map (one 8-bit step of slack) */
  for (int i = 1; i < RCMAP_SIZE; i++)
    CU_ASSERT(luminance(m.lut[i]) >= luminance(m.lut[i - 1]) - 1.0);
  CU_ASSERT_EQUAL(rcolormap_index(0.0), 0);
  CU_ASSERT_EQUAL(rcolormap_index(1.0), 255);
  CU_ASSERT_EQUAL(rcolormap_index(-3.0), 0);
  CU_ASSERT_EQUAL(rcolormap_index(0.5), 128);
  CU_ASSERT_EQUAL(rcolormap_index(NAN), -1);
  uint8_t rgb[3];
  rcolormap_map(&m, NAN, rgb);
  CU_ASSERT(rgb[0] == 255 && rgb[1] == 0 && rgb[2] == 255);
  CU_ASSERT_EQUAL_FATAL(rcolormap_get("coolwarm", &m, &err), 0);
  CU_ASSERT_TRUE(m.diverging);
  CU_ASSERT(m.lut[0][2] > m.lut[0][0]);     /* blue end */
  CU_ASSERT(m.lut[255][0] > m.lut[255][2]); /* red end */
  CU_ASSERT_NOT_EQUAL(rcolormap_get("jet", &m, &err), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "viridis"));
}

/* The ticks of a logarithmic axis over [lo, hi] are labelled want[0..n). */
static void check_log_labels(double lo, double hi, int target, const char *const *want, int n) {
  rticks t;
  char buf[64];
  rticks_make_log(lo, hi, target, &t);
  CU_ASSERT_EQUAL_FATAL(t.n, n);
  for (int i = 0; i < n; i++) {
    rticks_label(&t, t.v[i], buf, sizeof buf);
    CU_ASSERT_STRING_EQUAL(buf, want[i]);
  }
}

static void test_ticks(void) {
  rticks t;
  char buf[64];
  rticks_make(0.0, 1.0, 6, &t);
  CU_ASSERT_EQUAL(t.n, 6);
  CU_ASSERT_DOUBLE_EQUAL(t.step, 0.2, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(t.v[3], 0.6000000000000001, 1e-15);
  rticks_label(&t, t.v[3], buf, sizeof buf);
  CU_ASSERT_STRING_EQUAL(buf, "0.6");
  rticks_make(-0.3, 0.3, 4, &t); /* no "-0.0" */
  for (int i = 0; i < t.n; i++) {
    rticks_label(&t, t.v[i], buf, sizeof buf);
    CU_ASSERT(strcmp(buf, "-0.0") != 0 && strcmp(buf, "-0") != 0);
  }
  rticks_make(0.0, 2.0e5, 5, &t); /* large values in exponent form */
  rticks_label(&t, t.v[1], buf, sizeof buf);
  CU_ASSERT_STRING_EQUAL(buf, "0.5e5");
  double lo = 0.13, hi = 3.94;
  rticks_expand(&lo, &hi, 6);
  CU_ASSERT_DOUBLE_EQUAL(lo, 0.0, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(hi, 4.0, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(rticks_nice(0.23, 1), 0.2, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(rticks_nice(0.23, 0), 0.5, 1e-15);
  /* logarithmic: decades over a wide range, fixed notation inside [1e-3, 1e4] */
  const char *wide[4] = {"1", "10", "100", "1000"};
  check_log_labels(0.5, 2000.0, 6, wide, 4);
  /* 1, 2, 5 over fewer than target / 3 decades */
  const char *narrow[4] = {"0.02", "0.05", "0.1", "0.2"};
  check_log_labels(0.015, 0.3, 9, narrow, 4);
  /* small values: every label in exponent form */
  rticks_make_log(2e-6, 0.05, 6, &t);
  CU_ASSERT_EQUAL_FATAL(t.n, 4);
  rticks_label(&t, t.v[0], buf, sizeof buf);
  CU_ASSERT_STRING_EQUAL(buf, "1e-5");
  rticks_label(&t, t.v[3], buf, sizeof buf);
  CU_ASSERT_STRING_EQUAL(buf, "1e-2");
  lo = 0.13;
  hi = 3.94;
  rticks_expand_log(&lo, &hi);
  CU_ASSERT_DOUBLE_EQUAL(lo, 0.1, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(hi, 10.0, 1e-15);
  lo = hi = 7.0; /* one value: its decade */
  rticks_expand_log(&lo, &hi);
  CU_ASSERT_DOUBLE_EQUAL(lo, 1.0, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(hi, 10.0, 1e-15);
}

static void test_csv(void) {
  sph_csv t;
  sph_error err;
  CU_ASSERT_EQUAL_FATAL(sph_csv_read(sph_test_src("tests/data/render/experiment.csv"), &t, &err),
                        0);
  CU_ASSERT_EQUAL(t.ncol, 2);
  CU_ASSERT_EQUAL(t.nrow, 8);
  CU_ASSERT_STRING_EQUAL(t.names[1], "Z");
  CU_ASSERT_EQUAL(sph_csv_column(&t, "Z", &err), 1);
  CU_ASSERT_EQUAL(sph_csv_column(&t, "front_x", &err), -1);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "front_x"));
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "experiment.csv"));
  double v[8];
  CU_ASSERT_EQUAL(sph_csv_eval(&t, "T+Z", v, &err), 0);
  CU_ASSERT_DOUBLE_EQUAL(v[0], 1.5, 1e-12);
  sph_csv_free(&t);
  /* a cell that is not a number: file, line and column in the message */
  char *bad = path_in(tmp, "bad.csv");
  FILE *fp = fopen(bad, "w");
  CU_ASSERT_PTR_NOT_NULL_FATAL(fp);
  fputs("# comment\r\na,b\r\n1,2\r\n\r\n3,x\r\n", fp);
  fclose(fp);
  CU_ASSERT_NOT_EQUAL(sph_csv_read(bad, &t, &err), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "bad.csv:5"));
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "'b'"));
  fp = fopen(bad, "w");
  fputs("a,b\n1,2,3\n", fp);
  fclose(fp);
  CU_ASSERT_NOT_EQUAL(sph_csv_read(bad, &t, &err), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "bad.csv:2"));
}

static void test_inputs(void) {
  char buf[256];
  rinputs_number("out/run/snap_0012.h5", buf, sizeof buf);
  CU_ASSERT_STRING_EQUAL(buf, "0012");
  rinputs_number("fixture.h5", buf, sizeof buf);
  CU_ASSERT_STRING_EQUAL(buf, "");
  rinputs_stem("a/b/diagnostics.csv", buf, sizeof buf);
  CU_ASSERT_STRING_EQUAL(buf, "diagnostics");
  rinputs_stem("out/run_fine/", buf, sizeof buf); /* a run directory names its panel */
  CU_ASSERT_STRING_EQUAL(buf, "run_fine");
  CU_ASSERT_TRUE(rinputs_is_png("x/Frame.PNG"));
  CU_ASSERT_FALSE(rinputs_is_png("frames"));
  rinputs l = {0, 0, NULL};
  sph_error err;
  CU_ASSERT_EQUAL_FATAL(rinputs_add(&l, path_in(tmp, "run"), &err), 0);
  CU_ASSERT_EQUAL_FATAL(l.n, 2);
  CU_ASSERT_STRING_EQUAL(l.v[0].path, snap0); /* name order */
  CU_ASSERT_EQUAL_FATAL(rinputs_times(&l, &err), 0);
  CU_ASSERT_EQUAL(rinputs_nearest(&l, 0.07), 1);
  CU_ASSERT_DOUBLE_EQUAL(rinputs_min_spacing(&l), 0.1, 1e-12);
  rinputs_free(&l);
  CU_ASSERT_NOT_EQUAL(rinputs_add(&l, path_in(tmp, "no-such-dir"), &err), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "no-such-dir"));
}

static void test_layout(void) {
  rlayout L;
  sph_error err;
  rlayout_in in;
  memset(&in, 0, sizeof in);
  in.width = 1280;
  in.height = 720;
  in.rows = in.cols = 1;
  memcpy(in.view, fixture_view, sizeof in.view);
  in.colorbar = 1;
  in.lo = 0.0;
  in.hi = 1.0;
  CU_ASSERT_EQUAL_FATAL(rlayout_figure(&in, &L, &err), 0);
  const rrect *b = &L.panel[0].plot;
  /* one scale for both axes: the box has the view's aspect within a pixel */
  CU_ASSERT(fabs((b->x1 - b->x0) - 0.24 * L.px_per_m) <= 0.5 + 1e-9);
  CU_ASSERT(fabs((b->y1 - b->y0) - 0.14 * L.px_per_m) <= 0.5 + 1e-9);
  CU_ASSERT(b->x0 >= 0 && b->x1 <= L.bar.x0 && b->y0 >= 0 && b->y1 <= 720);
  CU_ASSERT_EQUAL(b->x0, floor(b->x0)); /* whole pixels */
  double px, py;
  rlayout_to_px(&L, 0, fixture_view[0], fixture_view[3], &px, &py);
  CU_ASSERT(fabs(px - b->x0) <= 0.5 && fabs(py - b->y0) <= 0.5);
  /* automatic height: even, and the plot keeps its aspect */
  in.height = 0;
  in.cols = 3;
  in.rows = 2;
  CU_ASSERT_EQUAL_FATAL(rlayout_figure(&in, &L, &err), 0);
  CU_ASSERT_EQUAL(L.height % 2, 0);
  CU_ASSERT_EQUAL(L.panels, 6);
  CU_ASSERT(L.panel[5].plot.y1 <= L.height);
  in.view[1] = in.view[0];
  CU_ASSERT_NOT_EQUAL(rlayout_figure(&in, &L, &err), 0);
}

/* ------------------------------------------------------ rendering checks */

/* The layout sph-render uses for one fixture frame of the given size. */
static void fixture_layout(int w, int h, double lo, double hi, int bare, rlayout *L) {
  rlayout_in in;
  memset(&in, 0, sizeof in);
  in.width = w;
  in.height = h;
  in.rows = in.cols = 1;
  memcpy(in.view, fixture_view, sizeof in.view);
  in.bare = bare;
  in.colorbar = 1;
  in.lo = lo;
  in.hi = hi;
  sph_error err;
  CU_ASSERT_EQUAL_FATAL(rlayout_figure(&in, L, &err), 0);
}

static void test_frame_exact(void) {
  CU_ASSERT_EQUAL_FATAL(render("--size 640x360 --range 0:1 --background 203040 --jobs 1 "
                               "--compression 9 run/snap_0001.h5 -o speed.png"),
                        0);
  int w, h;
  uint8_t *img = read_png(path_in(tmp, "speed.png"), &w, &h);
  CU_ASSERT_PTR_NOT_NULL_FATAL(img);
  CU_ASSERT_EQUAL(w, 640);
  CU_ASSERT_EQUAL(h, 360);
  /* background at the corners */
  CU_ASSERT(img[0] == 0x20 && img[1] == 0x30 && img[2] == 0x40);
  size_t last = ((size_t)h * w - 1) * 3;
  CU_ASSERT(img[last] == 0x20 && img[last + 1] == 0x30 && img[last + 2] == 0x40);

  rlayout L;
  fixture_layout(640, 360, 0.0, 1.0, 0, &L);
  rcolormap m;
  sph_error err;
  CU_ASSERT_EQUAL_FATAL(rcolormap_get("viridis", &m, &err), 0);
  rfigure_style st;
  memset(&st, 0, sizeof st);
  st.cmap = &m;
  st.lo = 0.0;
  st.hi = 1.0;
  /* disc centres of fluid particles: the exact colour of their speed */
  rsnap s;
  CU_ASSERT_EQUAL_FATAL(rsnap_load(snap1, "speed", &s, &err), 0);
  int checked = 0;
  for (size_t i = 0; i < s.n; i += 7) {
    if (s.wall[i]) continue;
    double px, py;
    rlayout_to_px(&L, 0, s.x[i], s.y[i], &px, &py);
    if (px < L.panel[0].plot.x0 || px >= L.panel[0].plot.x1) continue;
    uint8_t want[3];
    rfigure_color(&st, s.val[i], want);
    const uint8_t *got = img + ((size_t)floor(py) * w + (size_t)floor(px)) * 3;
    CU_ASSERT(got[0] == want[0] && got[1] == want[1] && got[2] == want[2]);
    checked++;
  }
  CU_ASSERT(checked > 20);
  rsnap_free(&s);
  /* the colour bar: top row = the map's high end, bottom row = its low end */
  int bx = (int)floor(0.5 * (L.bar.x0 + L.bar.x1));
  const uint8_t *top = img + ((size_t)L.bar.y0 * w + bx) * 3;
  const uint8_t *bottom = img + ((size_t)(L.bar.y1 - 1) * w + bx) * 3;
  CU_ASSERT(memcmp(top, m.lut[255], 3) == 0);
  CU_ASSERT(memcmp(bottom, m.lut[0], 3) == 0);
  free(img);
  check_golden(path_in(tmp, "speed.png"), "fixture_speed.png", 1);
}

static void test_frame_bare(void) {
  /* --bare: the view fills the image; walls grey */
  CU_ASSERT_EQUAL_FATAL(render("--bare --size 480x280 --field pressure --range 0:1000 --jobs 1 "
                               "run/snap_0000.h5 -o bare.png"),
                        0);
  int w, h;
  uint8_t *img = read_png(path_in(tmp, "bare.png"), &w, &h);
  CU_ASSERT_PTR_NOT_NULL_FATAL(img);
  rlayout L;
  fixture_layout(480, 280, 0.0, 1000.0, 1, &L);
  CU_ASSERT_DOUBLE_EQUAL(L.px_per_m, 2000.0, 1e-9); /* 480 px for 0.24 m */
  double px, py;
  rlayout_to_px(&L, 0, -0.005, 0.055, &px, &py); /* a wall particle of the left wall */
  const uint8_t *got = img + ((size_t)floor(py) * w + (size_t)floor(px)) * 3;
  CU_ASSERT(got[0] == 150 && got[1] == 150 && got[2] == 150);
  CU_ASSERT(img[0] == 255 && img[1] == 255 && img[2] == 255);
  free(img);
}

static void test_deterministic(void) {
  CU_ASSERT_EQUAL_FATAL(render("--size 400x240 --jobs 1 run -o seq1"), 0);
  CU_ASSERT_EQUAL_FATAL(render("--size 400x240 --jobs 2 run -o seq2"), 0);
  CU_ASSERT_EQUAL_FATAL(render("--size 400x240 --jobs 1 run -o seq3"), 0);
  const char *names[] = {"frame_0000.png", "frame_0001.png"};
  for (int i = 0; i < 2; i++) {
    char a[4200], b[4200], c[4200];
    snprintf(a, sizeof a, "%s/seq1/%s", tmp, names[i]);
    snprintf(b, sizeof b, "%s/seq2/%s", tmp, names[i]);
    snprintf(c, sizeof c, "%s/seq3/%s", tmp, names[i]);
    CU_ASSERT_TRUE(same_bytes(a, b));
    CU_ASSERT_TRUE(same_bytes(a, c));
  }
  /* no time stamp or text chunk in the file */
  char cmd[4400];
  snprintf(cmd, sizeof cmd, "grep -q -a -e tIME -e tEXt -e iTXt '%s/seq1/frame_0000.png'", tmp);
  CU_ASSERT_NOT_EQUAL(sph_test_system(cmd), 0);
}

static void test_backend_egl(void) {
#ifdef HAVE_EGL
  /* the surfaceless EGL back end draws the same image as OSMesa (exact on
   * llvmpipe), so it is held to the OSMesa golden image, never written */
  CU_ASSERT_EQUAL_FATAL(render("--size 640x360 --range 0:1 --background 203040 --jobs 1 "
                               "--backend egl run/snap_0001.h5 -o egl.png"),
                        0);
  check_golden(path_in(tmp, "egl.png"), "fixture_speed.png", 0);
#else
  CU_ASSERT_NOT_EQUAL(render("--backend egl run/snap_0001.h5 -o egl.png"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "without EGL"));
#endif
}

static void test_panels_overlay(void) {
  char args[8192];
  snprintf(args, sizeof args,
           "--panels 2x1 --field vx --range -1:1 --jobs 1 --compression 9 --size 800 "
           "--overlay '%s' --overlay-time time --overlay-style line --overlay-label reference "
           "run -o panels.png",
           sph_test_src("tests/data/render/overlay.csv"));
  CU_ASSERT_EQUAL_FATAL(render(args), 0);
  int w, h;
  uint8_t *img = read_png(path_in(tmp, "panels.png"), &w, &h);
  CU_ASSERT_PTR_NOT_NULL_FATAL(img);
  CU_ASSERT_EQUAL(w, 800);
  CU_ASSERT_EQUAL(h % 2, 0);
  free(img);
  check_golden(path_in(tmp, "panels.png"), "fixture_panels.png", 1);
  /* --times picks the nearest snapshots; more times than panels is an error */
  CU_ASSERT_EQUAL(render("--panels 2x1 --times 0.09,0.01 --jobs 1 run -o t.png"), 0);
  CU_ASSERT_NOT_EQUAL(render("--panels 1x1 --times 0,0.1 run -o t2.png"), 0);
  CU_ASSERT_FALSE(exists(path_in(tmp, "t2.png")));
}

static void test_compare(void) {
  char cmd[9000];
  snprintf(cmd, sizeof cmd, "mkdir -p '%s/runb' && cp '%s' '%s' '%s/runb/'", tmp, snap0, snap1,
           tmp);
  CU_ASSERT_EQUAL_FATAL(sph_test_system(cmd), 0);
  CU_ASSERT_EQUAL_FATAL(render("--compare --names coarse,fine --size 800 --jobs 2 run runb "
                               "-o cmp"),
                        0);
  CU_ASSERT_TRUE(exists(path_in(tmp, "cmp/compare_0000.png")));
  CU_ASSERT_TRUE(exists(path_in(tmp, "cmp/compare_0001.png")));
  CU_ASSERT_EQUAL(render("--compare --times 0.1 run runb -o cmp1.png"), 0);
  CU_ASSERT_TRUE(exists(path_in(tmp, "cmp1.png")));
  CU_ASSERT_NOT_EQUAL(render("--compare run -o cmp2"), 0); /* one run is not a comparison */
}

static void test_plot(void) {
  char args[8192], diag[4096];
  /* sph_test_src returns one static buffer: copy before the next call */
  snprintf(diag, sizeof diag, "%s", sph_test_src("tests/data/render/diagnostics.csv"));
  snprintf(args, sizeof args,
           "plot '%s' --x time --y front_x --x-scale 18.53 --y-scale 17.4978 --label SPH "
           "--points '%s' --label 'Martin & Moyce (fixture)' --xlabel 'T = t sqrt(2g/a)' "
           "--ylabel 'Z = x/a' --size 640x420 --compression 9 -o plot.png",
           diag, sph_test_src("tests/data/render/experiment.csv"));
  CU_ASSERT_EQUAL_FATAL(render(args), 0);
  int w, h;
  uint8_t *img = read_png(path_in(tmp, "plot.png"), &w, &h);
  CU_ASSERT_PTR_NOT_NULL_FATAL(img);
  CU_ASSERT_EQUAL(w, 640);
  CU_ASSERT_EQUAL(h, 420);
  CU_ASSERT(img[0] == 255 && img[1] == 255 && img[2] == 255);
  free(img);
  check_golden(path_in(tmp, "plot.png"), "plot.png", 1);
  /* energy deviation of a sum of columns */
  snprintf(args, sizeof args, "plot '%s' --x time --y kinetic+potential --relative -o dev.png",
           sph_test_src("tests/data/render/diagnostics.csv"));
  CU_ASSERT_EQUAL(render(args), 0);
  /* a missing column names the file and the column */
  snprintf(args, sizeof args, "plot '%s' --x time --y nosuch -o bad.png",
           sph_test_src("tests/data/render/diagnostics.csv"));
  CU_ASSERT_NOT_EQUAL(render(args), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "diagnostics.csv"));
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "nosuch"));
  CU_ASSERT_FALSE(exists(path_in(tmp, "bad.png")));
}

/* The row of the topmost pixel of colour (r, g, b) in column x, or -1. */
static int first_row_of(const uint8_t *img, int w, int h, int x, int r, int g, int b) {
  for (int y = 0; y < h; y++) {
    const uint8_t *q = img + 3 * ((size_t)y * w + x);
    if (abs(q[0] - r) < 40 && abs(q[1] - g) < 40 && abs(q[2] - b) < 40) return y;
  }
  return -1;
}

/* Logarithmic axes: a power law err = 10 n^-1 is a straight line of slope
 * -1 on log-log axes (so the line's pixel rows, where it crosses three
 * columns, are equally spaced for equally spaced log n); golden image;
 * values <= 0 are left out; a log axis refuses a range reaching 0 and data
 * with nothing above 0. */
static void test_plot_log(void) {
  char args[8192], data[4096];
  snprintf(data, sizeof data, "%s", sph_test_src("tests/data/render/loglog.csv"));
  snprintf(args, sizeof args,
           "plot '%s' --x n --y err --label 'err = 10/n' --xlog --ylog --xlabel particles "
           "--ylabel 'error (%%)' --legend none --size 640x420 --compression 9 -o log.png",
           data);
  CU_ASSERT_EQUAL_FATAL(render(args), 0);
  int w, h;
  uint8_t *img = read_png(path_in(tmp, "log.png"), &w, &h);
  CU_ASSERT_PTR_NOT_NULL_FATAL(img);
  /* the line is series 0's colour (marks.c); find it in three columns a
   * quarter of the box apart and compare the spacing of the rows */
  const rcolor c0 = rmark_palette(0);
  int rows[3], cols[3] = {w / 4, w / 2, 3 * w / 4};
  for (int k = 0; k < 3; k++)
    rows[k] = first_row_of(img, w, h, cols[k], c0.r, c0.g, c0.b);
  CU_ASSERT(rows[0] > 0 && rows[1] > rows[0] && rows[2] > rows[1]);
  CU_ASSERT(abs((rows[1] - rows[0]) - (rows[2] - rows[1])) <= 2); /* straight */
  free(img);
  check_golden(path_in(tmp, "log.png"), "plot_log.png", 1);
  /* a linear y axis over the same data is not straight */
  snprintf(args, sizeof args, "plot '%s' --x n --y err --xlog --size 640x420 -o semilog.png", data);
  CU_ASSERT_EQUAL_FATAL(render(args), 0);
  img = read_png(path_in(tmp, "semilog.png"), &w, &h);
  CU_ASSERT_PTR_NOT_NULL_FATAL(img);
  for (int k = 0; k < 3; k++)
    rows[k] = first_row_of(img, w, h, cols[k], c0.r, c0.g, c0.b);
  CU_ASSERT(abs((rows[1] - rows[0]) - (rows[2] - rows[1])) > 10);
  free(img);
  /* errors */
  snprintf(args, sizeof args, "plot '%s' --x n --y err --ylog --yrange 0:10 -o bad.png", data);
  CU_ASSERT_NOT_EQUAL(render(args), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "min > 0"));
  snprintf(args, sizeof args, "plot '%s' --x n --y neg --ylog -o bad.png", data);
  CU_ASSERT_NOT_EQUAL(render(args), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "--ylog"));
  CU_ASSERT_FALSE(exists(path_in(tmp, "bad.png")));
}

/* -------------------------------------------------------------- bad inputs */

static void no_png_in(const char *dir) {
  CU_ASSERT_EQUAL(count_files(dir, ".png"), 0);
  CU_ASSERT_EQUAL(count_files(dir, ".tmp"), 0);
}

static void test_missing_file(void) {
  CU_ASSERT_NOT_EQUAL(render("run/snap_0009.h5 -o out_missing"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "run/snap_0009.h5"));
  no_png_in(path_in(tmp, "out_missing"));
}

static void test_missing_field(void) {
  CU_ASSERT_NOT_EQUAL(render("--field free_surface run -o out_field"), 0);
  const char *e = last_err();
  CU_ASSERT_PTR_NOT_NULL(strstr(e, "snap_0000.h5"));
  CU_ASSERT_PTR_NOT_NULL(strstr(e, "free_surface"));
  no_png_in(path_in(tmp, "out_field"));
  /* with a fixed range the check happens per frame: still no PNG */
  CU_ASSERT_NOT_EQUAL(render("--field free_surface --range 0:1 run -o out_field2"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "free_surface"));
  no_png_in(path_in(tmp, "out_field2"));
  /* a snapshot that has it renders */
  char *fs = path_in(tmp, "fs.h5");
  CU_ASSERT_EQUAL_FATAL(write_fixture(fs, 0.0, 1), 0);
  CU_ASSERT_EQUAL(render("--field free_surface fs.h5 -o fs.png"), 0);
}

static void test_corrupt_file(void) {
  char cmd[9000];
  /* garbage, and a real snapshot cut in half */
  snprintf(cmd, sizeof cmd,
           "mkdir -p '%s/bad' && printf 'not an HDF5 file' > '%s/bad/snap_0000.h5' && "
           "head -c $(($(wc -c < '%s') / 2)) '%s' > '%s/bad/snap_0001.h5'",
           tmp, tmp, snap0, snap0, tmp);
  CU_ASSERT_EQUAL_FATAL(sph_test_system(cmd), 0);
  CU_ASSERT_NOT_EQUAL(render("bad/snap_0000.h5 -o out_bad"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "bad/snap_0000.h5"));
  no_png_in(path_in(tmp, "out_bad"));
  CU_ASSERT_NOT_EQUAL(render("bad/snap_0001.h5 -o out_bad"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "bad/snap_0001.h5"));
  no_png_in(path_in(tmp, "out_bad"));
  /* one bad file among good ones: nothing is written */
  snprintf(cmd, sizeof cmd, "cp '%s' '%s/bad/snap_0002.h5'", snap0, tmp);
  CU_ASSERT_EQUAL_FATAL(sph_test_system(cmd), 0);
  CU_ASSERT_NOT_EQUAL(render("bad -o out_bad"), 0);
  no_png_in(path_in(tmp, "out_bad"));
}

static void test_bad_options(void) {
  CU_ASSERT_NOT_EQUAL(render("run"), 0); /* no -o */
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "-o"));
  CU_ASSERT_NOT_EQUAL(render("--cmap rainbow run -o x"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "viridis"));
  CU_ASSERT_NOT_EQUAL(render("--backend vulkan run -o x"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "osmesa"));
  CU_ASSERT_NOT_EQUAL(render("--range 1:0 run -o x"), 0);
  CU_ASSERT_NOT_EQUAL(render("--view 0:1:0 run -o x"), 0);
  CU_ASSERT_NOT_EQUAL(render("--size 10x10 run -o x"), 0);
  CU_ASSERT_NOT_EQUAL(render("--walls pink run -o x"), 0);
  CU_ASSERT_NOT_EQUAL(render("--frobnicate run -o x"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "--frobnicate"));
  CU_ASSERT_NOT_EQUAL(render("run -o one.png"), 0); /* two snapshots, one file */
  CU_ASSERT_FALSE(exists(path_in(tmp, "one.png")));
  CU_ASSERT_EQUAL(render("--help > /dev/null"), 0);
}

static void test_cleanup(void) {
  if (tmp) sph_test_rmtree(tmp);
  free(tmp);
  tmp = NULL;
  CU_PASS("cleaned up");
}

int main(void) {
  if (setup() != 0) {
    fprintf(stderr, "test_render: cannot write the fixture snapshots\n");
    return 1;
  }
  CU_TestInfo tests[] = {
      {"font glyph table", test_font},
      {"colour maps", test_colormap},
      {"nice ticks", test_ticks},
      {"CSV reader", test_csv},
      {"inputs and names", test_inputs},
      {"layout", test_layout},
      {"frame: exact pixels and golden", test_frame_exact},
      {"frame: bare view mapping and walls", test_frame_bare},
      {"byte-identical for 1 and 2 workers", test_deterministic},
      {"EGL back end", test_backend_egl},
      {"panels with overlay, golden", test_panels_overlay},
      {"compare two runs", test_compare},
      {"plot mode, golden", test_plot},
      {"plot mode, logarithmic axes", test_plot_log},
      {"bad input: missing file", test_missing_file},
      {"bad input: missing field", test_missing_field},
      {"bad input: corrupt HDF5", test_corrupt_file},
      {"bad options", test_bad_options},
      {"cleanup", test_cleanup},
      CU_TEST_INFO_NULL,
  };
  return sph_test_main("render", tests);
}
