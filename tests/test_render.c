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
 * pixel with a tolerance (tests/render_testutil.h). Regenerate them (after
 * a deliberate change) with `make golden-render`.
 *
 * Bad inputs: a missing file, a snapshot without the requested field and
 * a corrupt HDF5 file each give a non-zero exit status and a message naming
 * the file (and the field), and leave no PNG (and no temporary file).
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "colormap.h"
#include "contour.h"
#include "core/particles.h"
#include "figure.h"
#include "font.h"
#include "inputs.h"
#include "interp.h"
#include "io/csv.h"
#include "io/snapshot.h"
#include "label.h"
#include "layout.h"
#include "marks.h"
#include "render_testutil.h"
#include "snapdata.h"
#include "testutil.h"
#include "ticks.h"

/* The fixture's view and the fixed options every fixture render uses. */
static const double fixture_view[4] = {-0.02, 0.22, -0.02, 0.12};
static const double fixture_dx = 0.01;

static char *tmp;        /* the temporary directory of this run */
static char snap0[4096]; /* fixture snapshot at t = 0 */
static char snap1[4096]; /* fixture snapshot at t = 0.1 */

/* ------------------------------------------------------------------ helpers */

static const char *renderer(void) {
  static char buf[4096];
  snprintf(buf, sizeof buf, "%s", sph_test_build("render/sph-render"));
  return buf;
}

/* Runs sph-render with args (a shell fragment); stderr goes to tmp/err.txt. */
static int render(const char *args) { return rtest_render(tmp, "", args); }

/* The last stderr of render(), in a static buffer. */
static const char *last_err(void) { return rtest_last_err(tmp); }

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

/* Whether the file at path holds the bytes of needle (binary-safe: a PDF
 * has NUL bytes in its streams). */
static int file_has(const char *path, const char *needle) {
  FILE *fp = fopen(path, "rb");
  if (!fp) return 0;
  size_t cap = 1 << 20, n = 0, k = strlen(needle);
  char *buf = malloc(cap);
  while (buf && (n += fread(buf + n, 1, cap - n, fp)) == cap) {
    char *b = realloc(buf, cap * 2);
    if (!b) break;
    buf = b;
    cap *= 2;
  }
  fclose(fp);
  int found = 0;
  for (size_t i = 0; buf && i + k <= n && !found; i++)
    found = memcmp(buf + i, needle, k) == 0;
  free(buf);
  return found;
}

/* Whether python3's XML parser reads path as an SVG document. */
static int svg_parses(const char *path) {
  char cmd[8400];
  snprintf(cmd, sizeof cmd,
           "python3 -c 'import sys, xml.etree.ElementTree as E; "
           "r = E.parse(sys.argv[1]).getroot(); sys.exit(0 if r.tag.endswith(\"svg\") else 1)' "
           "'%s'",
           path);
  return sph_test_system(cmd) == 0;
}

static int same_bytes(const char *a, const char *b) { return rtest_same_bytes(a, b); }

/* How many files in dir end with suffix. */
static int count_files(const char *dir, const char *suffix) {
  char cmd[4400];
  snprintf(cmd, sizeof cmd, "exit $(ls -1 '%s' 2>/dev/null | grep -c -- '%s$')", dir, suffix);
  return sph_test_system(cmd);
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

/* The rows of a bitmap that hold ink (coverage above half). */
static void ink_rows(const rfont_bitmap *b, int *top, int *bottom) {
  *top = b->h;
  *bottom = -1;
  for (int y = 0; y < b->h; y++)
    for (int x = 0; x < b->w; x++)
      if (b->a[(size_t)y * b->w + x] > 127) {
        if (y < *top) *top = y;
        if (y > *bottom) *bottom = y;
      }
}

/* FreeType text: the capitals are RFONT_CAP * scale pixels tall, g reaches
 * below the baseline, widths grow with the text and with the scale, a
 * raster is the same twice, and UTF-8 superscripts are glyphs of the font
 * (not its missing-glyph box). */
static void test_font(void) {
  sph_error err;
  CU_ASSERT_EQUAL_FATAL(rfont_init(&err), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(rfont_path(), ".ttf"));
  rfont_bitmap b, b2;
  CU_ASSERT_EQUAL_FATAL(rfont_raster("H", rfont_em(3), 0.0, &b, &err), 0);
  int top, bottom;
  ink_rows(&b, &top, &bottom);
  CU_ASSERT(abs((bottom - top + 1) - RFONT_CAP * 3) <= 1); /* cap height 21 px */
  CU_ASSERT(abs(bottom + 1 - b.oy) <= 1);                  /* H sits on the baseline */
  CU_ASSERT_EQUAL_FATAL(rfont_raster("H", rfont_em(3), 0.0, &b2, &err), 0);
  CU_ASSERT(b.w == b2.w && b.h == b2.h && memcmp(b.a, b2.a, (size_t)b.w * b.h) == 0);
  int grey = 0; /* anti-aliased: some coverage between ink and paper */
  for (int k = 0; k < b.w * b.h; k++)
    grey += b.a[k] > 20 && b.a[k] < 235;
  CU_ASSERT(grey > 0);
  rfont_bitmap_free(&b);
  rfont_bitmap_free(&b2);
  CU_ASSERT_EQUAL_FATAL(rfont_raster("g", rfont_em(3), 0.0, &b, &err), 0);
  ink_rows(&b, &top, &bottom);
  CU_ASSERT(bottom >= b.oy + 3); /* a descender */
  rfont_bitmap_free(&b);
  CU_ASSERT_EQUAL(rfont_width("", 3), 0);
  CU_ASSERT(rfont_width("ab", 2) > rfont_width("a", 2));
  CU_ASSERT(abs(rfont_width("speed (m/s)", 4) - 2 * rfont_width("speed (m/s)", 2)) <= 1);
  /* the box the font draws for a character it lacks is not what ³ gets */
  CU_ASSERT_EQUAL_FATAL(rfont_raster("\xe2\x81\xb0", rfont_em(4), 0.0, &b, &err), 0); /* U+2070 */
  CU_ASSERT_EQUAL_FATAL(rfont_raster("\xc2\xb3", rfont_em(4), 0.0, &b2, &err), 0);    /* U+00B3 */
  ink_rows(&b2, &top, &bottom);
  CU_ASSERT(bottom < b2.oy - 2 * 4); /* a superscript: above the baseline */
  rfont_bitmap_free(&b);
  rfont_bitmap_free(&b2);
  const char *p = "a\xc2\xb3\xff";
  CU_ASSERT_EQUAL(rfont_utf8_next(&p), 'a');
  CU_ASSERT_EQUAL(rfont_utf8_next(&p), 0xB3u);
  CU_ASSERT_EQUAL(rfont_utf8_next(&p), 0xFFFDu); /* an invalid byte */
  CU_ASSERT_EQUAL(*p, '\0');
}

/* Labels: units from the table of the solver's columns or from the name,
 * powers as superscripts, none where a scale or a sum of unlike terms
 * makes them unknown. */
static void test_labels(void) {
  static const struct {
    const char *expr;
    double scale;
    int relative;
    const char *want;
  } cases[] = {
      {"time", 1.0, 0, "time (s)"},
      {"kinetic+potential", 1.0, 0, "kinetic+potential (J/m)"},
      {"kinetic+front_x", 1.0, 0, "kinetic+front_x"}, /* unlike units */
      {"front_x", 17.5, 0, "front_x"},                /* rescaled */
      {"P1 (Pa)", 1.0, 0, "P1 (Pa)"},                 /* carried in the header */
      {"eta_0.5", 1.0, 0, "eta_0.5 (m)"},             /* a gauge */
      {"T", 1.0, 0, "T"},                             /* someone else's column: no guess */
      {"kinetic", 1.0, 1, "kinetic, relative change"},
  };
  char buf[256];
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    rlabel_column(cases[k].expr, cases[k].scale, cases[k].relative, buf, sizeof buf);
    CU_ASSERT_STRING_EQUAL(buf, cases[k].want);
  }
  rlabel_with_units("density", "kg/m^3", buf, sizeof buf);
  CU_ASSERT_STRING_EQUAL(buf, "density (kg/m\xc2\xb3)");
  rlabel_with_units("rate", "s^-1", buf, sizeof buf);
  CU_ASSERT_STRING_EQUAL(buf, "rate (s\xe2\x81\xbb\xc2\xb9)");
  rlabel_with_units("kind", "1", buf, sizeof buf);
  CU_ASSERT_STRING_EQUAL(buf, "kind");
  /* a snapshot's field: the units attribute of its dataset */
  sph_error err;
  CU_ASSERT_EQUAL(rsnap_units(snap0, "speed", buf, sizeof buf, &err), 0);
  CU_ASSERT_STRING_EQUAL(buf, "m/s");
  CU_ASSERT_EQUAL(rsnap_units(snap0, "density", buf, sizeof buf, &err), 0);
  CU_ASSERT_STRING_EQUAL(buf, "kg/m^3");
}

/* The SPH interpolation against exact answers on a lattice of spacing d
 * (volumes d^2, h = 1.3 d): in the interior the kernel sum is 1 (to 1e-3
 * for the cubic spline, 1e-2 for Wendland C2) and a linear field is
 * reproduced to a hundredth of its change over one spacing (the Shepard
 * division makes a constant exact; the lattice's first moment is not
 * exactly zero off its points); the kernel sum is 1/2 on the block's edge half a spacing
 * beyond its last row (to 0.03); and the outline drawn from it runs along
 * that edge. Both kernels. */
typedef struct seg_stats {
  int n;
  double ymin, ymax;
} seg_stats;

static void collect_segment(void *ctx, double x0, double y0, double x1, double y1) {
  seg_stats *st = ctx;
  if (fmin(x0, x1) < 20.0 || fmax(x0, x1) > 140.0) return; /* the top edge, not the sides */
  st->n++;
  st->ymin = fmin(st->ymin, fmin(y0, y1));
  st->ymax = fmax(st->ymax, fmax(y0, y1));
}

static void test_interp(void) {
  enum { NX = 40, NY = 20 };
  const double d = 0.01;
  static double x[NX * NY], y[NX * NY], h[NX * NY], vol[NX * NY], val[NX * NY];
  static unsigned char wall[NX * NY];
  for (int j = 0; j < NY; j++)
    for (int i = 0; i < NX; i++) {
      int k = j * NX + i;
      x[k] = (i + 0.5) * d;
      y[k] = (j + 0.5) * d;
      h[k] = 1.3 * d;
      vol[k] = d * d;
      val[k] = 2.0 + 3.0 * x[k] - 5.0 * y[k];
      wall[k] = 0;
    }
  for (int kernel = 0; kernel < 2; kernel++) {
    rinterp_in in = {NX * NY, x, y, h, vol, val, wall, kernel, NULL};
    /* points every d/4 over [0, 0.4] x [0, 0.25]: row j at y = 0.25 - (j + 1/2) d/4 */
    rinterp_grid g = {160, 100, 0.0, 0.25, 0.25 * d};
    static double f[160 * 100], sf[160 * 100], sw[160 * 100];
    sph_error err;
    CU_ASSERT_EQUAL_FATAL(rinterp_field(&in, &g, f, sf, sw, &err), 0);
    double worst_f = 0.0, worst_s = 0.0;
    for (int j = 0; j < g.ny; j++)
      for (int i = 0; i < g.nx; i++) {
        double px = (i + 0.5) * g.step, py = g.y1 - (j + 0.5) * g.step;
        size_t q = (size_t)j * g.nx + i;
        CU_ASSERT(sw[q] == 0.0);
        if (px < 3 * d || px > 0.4 - 3 * d || py < 3 * d || py > 0.2 - 3 * d) continue;
        worst_f = fmax(worst_f, fabs(f[q] - (2.0 + 3.0 * px - 5.0 * py)));
        worst_s = fmax(worst_s, fabs(sf[q] - 1.0));
      }
    CU_ASSERT(worst_f < 0.01 * sqrt(3.0 * 3.0 + 5.0 * 5.0) * d);
    CU_ASSERT(worst_s < (kernel == RKERNEL_CUBIC ? 1e-3 : 1e-2));
    /* on the top edge y = 0.2 (grid row 19.5 from the top: between rows 19 and 20) */
    double edge = 0.5 * (sf[19 * g.nx + 80] + sf[20 * g.nx + 80]);
    CU_ASSERT(fabs(edge - 0.5) < 0.03);
    CU_ASSERT(rinterp_is_fluid(sf[25 * g.nx + 80]) && !rinterp_is_fluid(sf[12 * g.nx + 80]));
    /* the outline of the middle part of the top edge */
    static double phi[160 * 100];
    for (size_t q = 0; q < 160 * 100; q++)
      phi[q] = sf[q] - 0.5;
    seg_stats st = {0, INFINITY, -INFINITY};
    rcontour(phi, NULL, g.nx, 40, collect_segment, &st); /* the top 40 rows only */
    CU_ASSERT(st.n > 100);
    CU_ASSERT(st.ymin > 20.0 - 0.5 && st.ymax < 20.0 + 0.5); /* grid units: y = 0.2 is 20 */
    printf("\n  kernel %d: linear field error %.1e, kernel sum %.1e from 1, %.3f on the edge, "
           "outline at %.2f to %.2f (20 exact)",
           kernel, worst_f, worst_s, edge, st.ymin, st.ymax);
  }
  /* the kernel a snapshot names: its kernel attribute, else (a snapshot
   * written before it had one) its parameters' numerics.kernel line */
  struct {
    const char *kernel, *parameters;
    int want;
  } named[] = {{"wendland_c2", NULL, RKERNEL_WENDLAND_C2},
               {"cubic_spline", "numerics.kernel: wendland_c2\n", RKERNEL_CUBIC},
               {NULL, "numerics.kernel: wendland_c2\n", RKERNEL_WENDLAND_C2},
               {NULL, "numerics.kernel: cubic_spline\n", RKERNEL_CUBIC},
               {NULL, NULL, RKERNEL_CUBIC}};
  for (size_t c = 0; c < sizeof named / sizeof named[0]; c++) {
    sph_particles p;
    sph_error err;
    char path[4200];
    snprintf(path, sizeof path, "%s/kernel_%zu.h5", tmp, c);
    CU_ASSERT_EQUAL_FATAL(sph_particles_init(&p, 4, &err), 0);
    sph_particles_add(&p, 0.0, 0.0, 0, 0, 1000, 0.1, 0.013, SPH_KIND_FLUID, &err);
    sph_snapshot_meta m;
    memset(&m, 0, sizeof m);
    m.case_name = "kernel";
    m.kernel = named[c].kernel;
    m.parameters = named[c].parameters;
    m.dx = 0.01;
    m.h = 0.013;
    m.rho0 = 1000;
    CU_ASSERT_EQUAL(sph_snapshot_write(path, &m, &p, &err), 0);
    sph_particles_free(&p);
    sph_snapshot *ss = NULL;
    CU_ASSERT_EQUAL_FATAL(sph_snapshot_open(path, &ss, &err), 0);
    CU_ASSERT_EQUAL(rinterp_kernel_of(ss), named[c].want);
    sph_snapshot_close(ss);
  }
}

static double luminance(const uint8_t c[3]) {
  return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

/* The outline as polylines (rcontour_lines): a circle of radius 20 on a
 * 60 x 60 grid is one closed line through as many points as marching
 * squares has pieces, each point on an edge and within 0.05 of the
 * circle, consecutive points a cell apart at most; a band cut off by the
 * grid's border is open at both ends. Twice the same points, bit for bit. */
typedef struct poly_stats {
  int lines, closed;
  size_t points;
  double worst, step, first[2];
} poly_stats;

static void collect_poly(void *ctx, const double *xy, size_t n, int closed) {
  poly_stats *st = ctx;
  st->lines++;
  st->closed += closed;
  st->points += n;
  if (st->lines == 1) st->first[0] = xy[0], st->first[1] = xy[1];
  for (size_t k = 0; k < n; k++) {
    const double r = hypot(xy[2 * k] - 30.5, xy[2 * k + 1] - 30.5);
    st->worst = fmax(st->worst, fabs(r - 20.0));
    const size_t q = (k + 1) % n;
    if (k + 1 < n || closed)
      st->step = fmax(st->step, hypot(xy[2 * q] - xy[2 * k], xy[2 * q + 1] - xy[2 * k + 1]));
  }
}

static void count_segment(void *ctx, double x0, double y0, double x1, double y1) {
  (void)x0, (void)y0, (void)x1, (void)y1;
  (*(size_t *)ctx)++;
}

static void test_contour_lines(void) {
  static double phi[60 * 60];
  for (int j = 0; j < 60; j++)
    for (int i = 0; i < 60; i++) /* point (i, j) at (i + 1/2, j + 1/2) */
      phi[j * 60 + i] = 20.0 - hypot(i + 0.5 - 30.5, j + 0.5 - 30.5);
  poly_stats a = {0}, b = {0};
  size_t pieces = 0;
  rcontour(phi, NULL, 60, 60, count_segment, &pieces);
  CU_ASSERT_EQUAL(rcontour_lines(phi, NULL, 60, 60, collect_poly, &a), 0);
  CU_ASSERT_EQUAL(rcontour_lines(phi, NULL, 60, 60, collect_poly, &b), 0);
  CU_ASSERT_EQUAL(a.lines, 1);
  CU_ASSERT_EQUAL(a.closed, 1);
  CU_ASSERT_EQUAL(a.points, pieces); /* a closed line: one point per piece */
  CU_ASSERT(a.worst < 0.05);
  CU_ASSERT(a.step <= M_SQRT2 + 1e-12);
  CU_ASSERT(a.first[0] == b.first[0] && a.first[1] == b.first[1] && a.points == b.points);
  /* the circle's top half (rows 31 up): the grid's last row cuts it, open */
  poly_stats h = {0};
  CU_ASSERT_EQUAL(rcontour_lines(phi + 31 * 60, NULL, 60, 29, collect_poly, &h), 0);
  CU_ASSERT_EQUAL(h.lines, 1);
  CU_ASSERT_EQUAL(h.closed, 0);
  printf("\n  circle: %zu pieces, one closed line within %.3f cells of r = 20", pieces, a.worst);
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
  /* a header with units (the convention of every CSV sph writes): the
   * bare name finds its column, the full name too, a prefix does not */
  fp = fopen(bad, "w");
  CU_ASSERT_PTR_NOT_NULL_FATAL(fp);
  fputs("time (s),step,kinetic (J/m),kinetic_x\n0,1,2,3\n", fp);
  fclose(fp);
  CU_ASSERT_EQUAL_FATAL(sph_csv_read(bad, &t, &err), 0);
  CU_ASSERT_EQUAL(sph_csv_column(&t, "time", &err), 0);
  CU_ASSERT_EQUAL(sph_csv_column(&t, "step", &err), 1);
  CU_ASSERT_EQUAL(sph_csv_column(&t, "kinetic", &err), 2);
  CU_ASSERT_EQUAL(sph_csv_column(&t, "kinetic (J/m)", &err), 2);
  CU_ASSERT_EQUAL(sph_csv_column(&t, "kinetic_x", &err), 3);
  CU_ASSERT_EQUAL(sph_csv_column(&t, "kin", &err), -1);
  CU_ASSERT_EQUAL(sph_csv_column(&t, "time (", &err), -1);
  CU_ASSERT_EQUAL(sph_csv_eval(&t, "time+kinetic", v, &err), 0);
  CU_ASSERT_DOUBLE_EQUAL(v[0], 2.0, 1e-15);
  sph_csv_free(&t);
  /* two columns a name could mean are ambiguous, not one picked silently
   * (issue 61, E10); the exact name still picks its own */
  fp = fopen(bad, "w");
  CU_ASSERT_PTR_NOT_NULL_FATAL(fp);
  fputs("time (s),a (m),a (Pa),b,b\n0,1,2,3,4\n", fp);
  fclose(fp);
  CU_ASSERT_EQUAL_FATAL(sph_csv_read(bad, &t, &err), 0);
  CU_ASSERT_EQUAL(sph_csv_column(&t, "a", &err), -1);
  CU_ASSERT_PTR_NOT_NULL(
      strstr(err.msg, "'a' names columns 2 ('a (m)') and 3 ('a (Pa)'): ambiguous"));
  CU_ASSERT_EQUAL(sph_csv_column(&t, "a (Pa)", &err), 2);
  CU_ASSERT_EQUAL(sph_csv_column(&t, "b", &err), -1);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "'b' names columns 4 ('b') and 5 ('b'): ambiguous"));
  sph_csv_free(&t);
  fp = fopen(bad, "w");
  fputs("a,b\n1,2,3\n", fp);
  fclose(fp);
  CU_ASSERT_NOT_EQUAL(sph_csv_read(bad, &t, &err), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "bad.csv:2"));
  /* bounded (issue 39, D4): a stream without newlines stops at the line
   * bound, an endless table at the cell bound, each with its message */
  CU_ASSERT_NOT_EQUAL(sph_csv_read("/dev/zero", &t, &err), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "/dev/zero:1: a line longer than 1024 KiB"));
  char *fifo = path_in(tmp, "endless.csv"), cmd[8192];
  CU_ASSERT_FATAL(mkfifo(fifo, 0600) == 0);
  snprintf(cmd, sizeof cmd, "(yes 1,2 > '%s' 2>/dev/null &)", fifo);
  CU_ASSERT_FATAL(system(cmd) == 0);
  CU_ASSERT_NOT_EQUAL(sph_csv_read(fifo, &t, &err), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "more than 33554432 cells"));
  printf("\n  %s", err.msg);
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
  /* journal sizes in points (font scale 1, 7 pt capitals): at least three
   * labelled ticks on every axis and on the colour bar, their labels apart
   * (y, the bar: 9 pt between ticks; x: the widest label and 3 pt) -
   * six panels of the wet-bed tank (2 x 0.3 m) down a 17 cm page, and
   * one Martin & Moyce view (0.23 x 0.17 m) and three of the wet bed's
   * first 1.4 m in an 8.5 cm column; a view too flat for three gets what
   * fits (the renderer then says so) */
  const struct {
    int width, cols, rows;
    double view[4], hi;
  } journal[] = {{482, 1, 6, {-0.01, 2.01, -0.01, 0.3}, 1.7},
                 {241, 1, 1, {-0.005, 0.232, -0.005, 0.172}, 1.4},
                 {241, 1, 3, {0.0, 1.4, 0.0, 0.2}, 1.7}};
  for (size_t k = 0; k < sizeof journal / sizeof journal[0]; k++) {
    memset(&in, 0, sizeof in);
    in.width = journal[k].width;
    in.cols = journal[k].cols;
    in.rows = journal[k].rows;
    in.scale = 1;
    memcpy(in.view, journal[k].view, sizeof in.view);
    in.colorbar = 1;
    in.hi = journal[k].hi;
    CU_ASSERT_EQUAL_FATAL(rlayout_figure(&in, &L, &err), 0);
    CU_ASSERT(L.xt.n >= 3 && L.yt.n >= 3 && L.bt.n >= 3);
    CU_ASSERT(L.yt.step / (in.view[3] - in.view[2]) * (b->y1 - b->y0) >= 9.0);
    CU_ASSERT(L.bt.step / in.hi * (L.bar.y1 - L.bar.y0) >= 9.0);
    char ticks[1600];
    rlayout_describe_ticks(&L, ticks, sizeof ticks);
    printf("\n  %d pt, %dx%d panels of %.0f x %.0f pt: %s", in.width, in.cols, in.rows,
           b->x1 - b->x0, b->y1 - b->y0, ticks);
  }
  in.cols = 3; /* three across an 8.5 cm column: too flat for three y labels */
  in.rows = 1;
  memcpy(in.view, journal[0].view, sizeof in.view);
  in.width = 482;
  CU_ASSERT_EQUAL_FATAL(rlayout_figure(&in, &L, &err), 0);
  CU_ASSERT(L.yt.n < 3 && L.yt.n >= 1);
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

/* The style whose rfigure_color is the oracle of a rendered colour: map
 * name over [lo, hi] (m receives the map). */
static void oracle_style(const char *map, double lo, double hi, rcolormap *m, rfigure_style *st) {
  sph_error err;
  CU_ASSERT_EQUAL_FATAL(rcolormap_get(map, m, &err), 0);
  memset(st, 0, sizeof *st);
  st->cmap = m;
  st->lo = lo;
  st->hi = hi;
}

static void test_frame_exact(void) {
  CU_ASSERT_EQUAL_FATAL(render("--discs --size 640x360 --range 0:1 --background 203040 --jobs 1 "
                               "--compression 9 run/snap_0001.h5 -o speed.png"),
                        0);
  int w, h;
  uint8_t *img = rtest_read_png(path_in(tmp, "speed.png"), &w, &h);
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
  rfigure_style st;
  oracle_style("viridis", 0.0, 1.0, &m, &st);
  sph_error err;
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
  rtest_check_golden(path_in(tmp, "speed.png"), "fixture_speed.png", 1);
}

static void test_frame_bare(void) {
  /* --bare: the view fills the image; walls grey */
  CU_ASSERT_EQUAL_FATAL(render("--bare --size 480x280 --field pressure --range 0:1000 --jobs 1 "
                               "run/snap_0000.h5 -o bare.png"),
                        0);
  int w, h;
  uint8_t *img = rtest_read_png(path_in(tmp, "bare.png"), &w, &h);
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
  CU_ASSERT_EQUAL_FATAL(render("--discs --size 640x360 --range 0:1 --background 203040 --jobs 1 "
                               "--backend egl run/snap_0001.h5 -o egl.png"),
                        0);
  rtest_check_golden(path_in(tmp, "egl.png"), "fixture_speed.png", 0);
#else
  CU_ASSERT_NOT_EQUAL(render("--backend egl run/snap_0001.h5 -o egl.png"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "without EGL"));
#endif
}

static void test_panels_overlay(void) {
  char args[8192];
  snprintf(args, sizeof args,
           "--discs --panels 2x1 --field vx --range -1:1 --jobs 1 --compression 9 --size 800 "
           "--overlay '%s' --overlay-time time --overlay-style line --overlay-label reference "
           "run -o panels.png",
           sph_test_src("tests/data/render/overlay.csv"));
  CU_ASSERT_EQUAL_FATAL(render(args), 0);
  int w, h;
  uint8_t *img = rtest_read_png(path_in(tmp, "panels.png"), &w, &h);
  CU_ASSERT_PTR_NOT_NULL_FATAL(img);
  CU_ASSERT_EQUAL(w, 800);
  CU_ASSERT_EQUAL(h % 2, 0);
  free(img);
  rtest_check_golden(path_in(tmp, "panels.png"), "fixture_panels.png", 1);
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
  uint8_t *img = rtest_read_png(path_in(tmp, "plot.png"), &w, &h);
  CU_ASSERT_PTR_NOT_NULL_FATAL(img);
  CU_ASSERT_EQUAL(w, 640);
  CU_ASSERT_EQUAL(h, 420);
  CU_ASSERT(img[0] == 255 && img[1] == 255 && img[2] == 255);
  free(img);
  rtest_check_golden(path_in(tmp, "plot.png"), "plot.png", 1);
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
  uint8_t *img = rtest_read_png(path_in(tmp, "log.png"), &w, &h);
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
  rtest_check_golden(path_in(tmp, "log.png"), "plot_log.png", 1);
  /* a linear y axis over the same data is not straight */
  snprintf(args, sizeof args, "plot '%s' --x n --y err --xlog --size 640x420 -o semilog.png", data);
  CU_ASSERT_EQUAL_FATAL(render(args), 0);
  img = rtest_read_png(path_in(tmp, "semilog.png"), &w, &h);
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

/* A lattice of nx x ny fluid particles of spacing d (all with speed 1/2)
 * filling the fixture's view: sub-pixel particles at a frame's size. */
static int write_lattice(const char *path, double d, int nx, int ny) {
  sph_particles p;
  sph_error err;
  if (sph_particles_init(&p, (size_t)nx * ny, &err) != 0) return -1;
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++)
      sph_particles_add(&p, fixture_view[0] + (i + 0.5) * d, fixture_view[2] + (j + 0.5) * d, 0.5,
                        0.0, 1000, 1000 * d * d, 1.3 * d, SPH_KIND_FLUID, &err);
  sph_snapshot_meta m;
  memset(&m, 0, sizeof m);
  m.case_name = "lattice";
  m.dx = d;
  m.h = 1.3 * d;
  m.rho0 = 1000;
  memcpy(m.view, fixture_view, sizeof m.view);
  int rc = sph_snapshot_write(path, &m, &p, &err);
  sph_particles_free(&p);
  return rc;
}

/* How much an image of a uniform field beats into moire: the standard
 * deviation of the mean luminance of 4 x 4 pixel blocks (one colour and
 * its gaps, evenly spread, average to the same grey in every block),
 * over blocks inside [0, xmax) x [0, ymax). */
static double moire(const uint8_t *img, int w, int xmax, int ymax) {
  double sum = 0.0, sum2 = 0.0;
  int n = 0;
  for (int by = 1; by + 1 < ymax / 4; by++)
    for (int bx = 1; bx + 1 < xmax / 4; bx++) {
      double m = 0.0;
      for (int y = 0; y < 4; y++)
        for (int x = 0; x < 4; x++)
          m += luminance(img + 3 * ((size_t)(by * 4 + y) * w + bx * 4 + x));
      m /= 16.0;
      sum += m;
      sum2 += m * m;
      n++;
    }
  double mean = sum / n;
  return sqrt(fmax(sum2 / n - mean * mean, 0.0));
}

/* Anti-aliasing: particles 1.08 pixels apart, drawn as discs of that
 * diameter sampled once per pixel (the renderer before this test:
 * --samples 1 --disc-scale 1), alias into moire bands; with the defaults
 * (3 x 3 samples per pixel, and discs under 4 pixels grown to cover their
 * cell) the block means agree to a fraction of a grey level. The default
 * image is the same bytes from one and two workers. */
static void test_antialias(void) {
  char *lat = path_in(tmp, "lattice/snap_0000.h5");
  char dir[4200];
  snprintf(dir, sizeof dir, "%s/lattice", tmp);
  CU_ASSERT_EQUAL_FATAL(mkdir(dir, 0777), 0);
  /* 240 px over 0.24 m: 1000 px/m; d = 0.00108 m is 1.08 px */
  CU_ASSERT_EQUAL_FATAL(write_lattice(lat, 0.00108, 222, 129), 0);
  CU_ASSERT_EQUAL_FATAL(render("--discs --bare --size 240x140 --range 0:1 --samples 1 "
                               "--disc-scale 1 --jobs 1 lattice/snap_0000.h5 -o aliased.png"),
                        0);
  CU_ASSERT_EQUAL_FATAL(render("--discs --bare --size 240x140 --range 0:1 --jobs 1 "
                               "lattice/snap_0000.h5 -o smooth.png"),
                        0);
  CU_ASSERT_EQUAL_FATAL(render("--discs --bare --size 240x140 --range 0:1 --jobs 2 "
                               "lattice/snap_0000.h5 -o smooth2.png"),
                        0);
  CU_ASSERT_TRUE(same_bytes(path_in(tmp, "smooth.png"), path_in(tmp, "smooth2.png")));
  int w, h, w2, h2;
  uint8_t *a = rtest_read_png(path_in(tmp, "aliased.png"), &w, &h);
  uint8_t *b = rtest_read_png(path_in(tmp, "smooth.png"), &w2, &h2);
  CU_ASSERT_PTR_NOT_NULL_FATAL(a);
  CU_ASSERT_PTR_NOT_NULL_FATAL(b);
  /* the lattice ends 0.2398 m x 0.1397 m from the view's corner: blocks
   * inside it only */
  double ma = moire(a, w, 236, 136), mb = moire(b, w2, 236, 136);
  printf("\n  moire (std of 4x4 block luminance): one sample, discs of dx %.2f; defaults %.2f", ma,
         mb);
  CU_ASSERT(ma > 2.0);
  CU_ASSERT(mb < 0.5);
  free(a);
  free(b);
}

/* The default look (issue 39, D10): a fluid field is drawn as its SPH
 * interpolation with the free surface outlined (the bytes of --smooth
 * --outline), a flag or kind field as discs (the bytes of --discs), and
 * --discs gives the discs of a fluid field. */
static void test_default_look(void) {
  const char *base = "--size 320x180 --range 0:1 --jobs 1 run/snap_0001.h5 -o ";
  char cmd[1024];
  const char *variants[][2] = {{"", "look_default.png"},
                               {"--smooth --outline ", "look_smooth.png"},
                               {"--discs ", "look_discs.png"},
                               {"--field kind ", "look_kind.png"},
                               {"--field kind --discs ", "look_kind_discs.png"}};
  for (int k = 0; k < 5; k++) {
    snprintf(cmd, sizeof cmd, "%s%s%s", variants[k][0], base, variants[k][1]);
    CU_ASSERT_EQUAL_FATAL(render(cmd), 0);
  }
  CU_ASSERT_TRUE(same_bytes(path_in(tmp, "look_default.png"), path_in(tmp, "look_smooth.png")));
  CU_ASSERT_FALSE(same_bytes(path_in(tmp, "look_default.png"), path_in(tmp, "look_discs.png")));
  CU_ASSERT_TRUE(same_bytes(path_in(tmp, "look_kind.png"), path_in(tmp, "look_kind_discs.png")));
}

/* The interpolated view (--smooth) of the fixture at t = 0, whose vx is
 * linear in x: vx = (x / dx - 9) / 9 on the 18 x 11 block. Inside the
 * block, two smoothing lengths from its edges, each pixel has the colour
 * of that line at its centre (within one colour-table entry: the lattice
 * reproduces a linear field to 1e-3 of its change over one spacing);
 * above the block the background shows; with --outline the first ink in
 * a column above the block's middle is the outline, on the block's top
 * y = 0.11 m (within a pixel and a half); golden image with axes. */
static void test_smooth(void) {
  CU_ASSERT_EQUAL_FATAL(render("--bare --size 480x280 --field vx --range -1:1 --smooth --outline "
                               "--jobs 1 run/snap_0000.h5 -o smooth_view.png"),
                        0);
  int w, h;
  uint8_t *img = rtest_read_png(path_in(tmp, "smooth_view.png"), &w, &h);
  CU_ASSERT_PTR_NOT_NULL_FATAL(img);
  rcolormap m;
  rfigure_style st;
  oracle_style("coolwarm", -1.0, 1.0, &m, &st);
  /* 2000 px/m, the view's corner (-0.02, 0.12) at pixel (0, 0) */
  int checked = 0, worst = 0;
  for (double y = 0.03; y <= 0.08; y += 0.005)
    for (double x = 0.03; x <= 0.15; x += 0.005) {
      int px = (int)floor((x + 0.02) * 2000.0), py = (int)floor((0.12 - y) * 2000.0);
      double cx = (px + 0.5) / 2000.0 - 0.02; /* the pixel centre's x */
      uint8_t want[3];
      rfigure_color(&st, (cx / 0.01 - 9.0) / 9.0, want);
      const uint8_t *got = img + 3 * ((size_t)py * w + px);
      for (int c = 0; c < 3; c++)
        worst = abs(got[c] - want[c]) > worst ? abs(got[c] - want[c]) : worst;
      checked++;
    }
  CU_ASSERT(checked > 200);
  CU_ASSERT(worst <= 3);
  /* above the block: white */
  const uint8_t *above = img + 3 * ((size_t)(0.12 - 0.115) * 2000 * w + 220);
  CU_ASSERT(above[0] == 255 && above[1] == 255 && above[2] == 255);
  /* the outline: the first dark pixel from the top in the column x = 0.09 m */
  int col = (int)floor((0.09 + 0.02) * 2000.0), row = -1;
  for (int y = 0; y < h && row < 0; y++) {
    const uint8_t *q = img + 3 * ((size_t)y * w + col);
    if (luminance(q) < 128) row = y;
  }
  double want_row = (0.12 - 0.11) * 2000.0; /* 20 */
  printf("\n  linear field: worst channel difference %d over %d pixels; outline at row %d "
         "(block top at %.1f)",
         worst, checked, row, want_row);
  CU_ASSERT(row >= 0 && fabs(row + 0.5 - want_row) <= 1.5);
  free(img);
  /* the same with axes, text and colour bar: golden */
  CU_ASSERT_EQUAL_FATAL(render("--size 640x360 --field speed --range 0:1 --smooth --outline "
                               "--jobs 1 --compression 9 run/snap_0001.h5 -o smooth_frame.png"),
                        0);
  rtest_check_golden(path_in(tmp, "smooth_frame.png"), "fixture_smooth.png", 1);
}

/* Plots as SVG and PDF through cairo: a page of the requested size in
 * points, glyphs of the font embedded (SVG: as outlines, one symbol per
 * glyph used; PDF: a font subset), the same bytes on a second run, and
 * the XML well-formed (python3 parses it). The units of the columns name
 * the axes; nothing is left beside the file (no .tmp). */
static void test_vector_plot(void) {
  char args[16384], diag[4096];
  snprintf(diag, sizeof diag, "%s", sph_test_src("tests/data/render/diagnostics.csv"));
  for (int run = 0; run < 2; run++) {
    snprintf(args, sizeof args,
             "plot '%s' --x time --y front_x --points '%s' --x T --y Z --size 500x300 "
             "-o plot%d.svg && '%s' plot '%s' --x time --y front_x --size 500x300 -o plot%d.pdf",
             diag, sph_test_src("tests/data/render/experiment.csv"), run, renderer(), diag, run);
    CU_ASSERT_EQUAL_FATAL(render(args), 0);
  }
  CU_ASSERT_TRUE(same_bytes(path_in(tmp, "plot0.svg"), path_in(tmp, "plot1.svg")));
  CU_ASSERT_TRUE(same_bytes(path_in(tmp, "plot0.pdf"), path_in(tmp, "plot1.pdf")));
  CU_ASSERT_EQUAL(count_files(tmp, ".tmp"), 0);
  char *svg = sph_test_read_file(path_in(tmp, "plot0.svg"), NULL);
  CU_ASSERT_PTR_NOT_NULL_FATAL(svg);
  CU_ASSERT_PTR_NOT_NULL(strstr(svg, "<svg"));
  CU_ASSERT_PTR_NOT_NULL(strstr(svg, "width=\"500pt\" height=\"300pt\""));
  CU_ASSERT_PTR_NOT_NULL(strstr(svg, "id=\"glyph0-1\"")); /* text as the font's glyphs */
  free(svg);
  const char *pdf = path_in(tmp, "plot0.pdf");
  CU_ASSERT_TRUE(file_has(pdf, "%PDF-"));
  CU_ASSERT_TRUE(file_has(pdf, "/MediaBox [ 0 0 500 300 ]"));
  CU_ASSERT_TRUE(file_has(pdf, "DejaVuSans")); /* the embedded font subset */
  CU_ASSERT_TRUE(file_has(pdf, "%%EOF"));
  CU_ASSERT_TRUE(svg_parses(path_in(tmp, "plot0.svg")));
}

/* Snapshot figures as SVG and PDF (issue 39, point 10): one snapshot and a
 * panel figure through cairo, the interpolated field as an embedded image
 * and the discs, text and outline as vector shapes; a page of the layout's
 * size in points (1280 x 720 for a frame), or of a --size in cm, mm or in
 * (8.5 cm = 241 pt); the same bytes on a second run; well-formed XML. A
 * PNG with a --size in cm is drawn at --dpi (default 300: 8.5 cm = 1004
 * pixels, 150: 502) with its text scaled to match; bad sizes are refused
 * with what was expected. */
static void test_vector_figures(void) {
  for (int run = 0; run < 2; run++) {
    char args[9216]; /* the renderer's path (up to 4096 bytes) twice */
    snprintf(args, sizeof args,
             "--jobs 1 run/snap_0001.h5 -o fig%d.svg && '%s' --jobs 1 --size 8.5cm "
             "run/snap_0001.h5 -o fig%d.pdf && '%s' --jobs 1 --panels 2x1 --size 17cm "
             "run/snap_0000.h5 run/snap_0001.h5 -o panels%d.svg",
             run, renderer(), run, renderer(), run);
    CU_ASSERT_EQUAL_FATAL(render(args), 0);
  }
  CU_ASSERT_TRUE(same_bytes(path_in(tmp, "fig0.svg"), path_in(tmp, "fig1.svg")));
  CU_ASSERT_TRUE(same_bytes(path_in(tmp, "fig0.pdf"), path_in(tmp, "fig1.pdf")));
  CU_ASSERT_TRUE(same_bytes(path_in(tmp, "panels0.svg"), path_in(tmp, "panels1.svg")));
  CU_ASSERT_EQUAL(count_files(tmp, ".tmp"), 0);
  char *svg = sph_test_read_file(path_in(tmp, "fig0.svg"), NULL);
  CU_ASSERT_PTR_NOT_NULL_FATAL(svg);
  CU_ASSERT_PTR_NOT_NULL(strstr(svg, "width=\"1280pt\" height=\"720pt\""));
  CU_ASSERT_PTR_NOT_NULL(strstr(svg, "<image"));          /* the interpolated field */
  CU_ASSERT_PTR_NOT_NULL(strstr(svg, "id=\"glyph0-1\"")); /* the labels as glyphs */
  free(svg);
  svg = sph_test_read_file(path_in(tmp, "panels0.svg"), NULL);
  CU_ASSERT_PTR_NOT_NULL_FATAL(svg);
  CU_ASSERT_PTR_NOT_NULL(strstr(svg, "width=\"482pt\"")); /* 17 cm */
  free(svg);
  const char *pdf = path_in(tmp, "fig0.pdf");
  CU_ASSERT_TRUE(file_has(pdf, "%PDF-"));
  CU_ASSERT_TRUE(file_has(pdf, "/MediaBox [ 0 0 241 "));
  CU_ASSERT_TRUE(file_has(pdf, "%%EOF"));
  CU_ASSERT_TRUE(svg_parses(path_in(tmp, "panels0.svg")));
  /* at 8.5 cm: three ticks or more on each axis and the colour bar (-v
   * lists them), and the outline one path (the only round-joined stroke),
   * traced at --dpi: a finer page has more points on it */
  for (int dpi = 150; dpi <= 600; dpi *= 4) {
    char a2[5120];
    snprintf(a2, sizeof a2, "-v --jobs 1 --size 8.5cm --dpi %d run/snap_0001.h5 -o col%d.svg", dpi,
             dpi);
    CU_ASSERT_EQUAL_FATAL(render(a2), 0);
    const char *e = last_err();
    const char *axes[3] = {"x ticks [", "y ticks [", "colour bar ticks ["};
    for (int a = 0; a < 3; a++) {
      const char *q = strstr(e, axes[a]);
      CU_ASSERT_PTR_NOT_NULL_FATAL(q);
      int commas = 0;
      for (q += strlen(axes[a]); *q && *q != ']'; q++)
        commas += *q == ',';
      CU_ASSERT(commas >= 2);
    }
    CU_ASSERT_PTR_NULL(strstr(e, "note:"));
    char *col = sph_test_read_file(path_in(tmp, dpi == 150 ? "col150.svg" : "col600.svg"), NULL);
    CU_ASSERT_PTR_NOT_NULL_FATAL(col);
    int round = 0;
    size_t longest = 0, all = 0;
    for (const char *q = col; (q = strstr(q, "stroke-linejoin:round")); q++) {
      const char *d = strstr(q, " d=\""), *end = d ? strchr(d + 4, '"') : NULL;
      size_t pts = 1;
      for (const char *r = d; r && r < end; r++)
        pts += *r == 'L';
      if (pts > longest) longest = pts;
      all += pts;
      round++;
    }
    /* the surface in one path, a few short pieces besides at most (where
     * the fluid's kernel sum dips to 1/2 in a film along the floor) */
    CU_ASSERT(round >= 1 && round <= 6 && longest > 0.5 * all);
    printf("\n  8.5 cm at %d dpi: outline in %d path%s of %zu points, the longest %zu", dpi, round,
           round == 1 ? "" : "s", all, longest);
    static size_t at150;
    if (dpi == 150)
      at150 = longest;
    else
      CU_ASSERT(longest > 2 * at150);
    free(col);
  }
  /* a PNG of a physical size: pixels at --dpi */
  char args[5120]; /* the renderer's path, up to 4096 bytes */
  snprintf(args, sizeof args,
           "--jobs 1 --size 8.5cm run/snap_0001.h5 -o col300.png && '%s' --jobs 1 --size 85mm "
           "--dpi 150 run/snap_0001.h5 -o col150.png",
           renderer());
  CU_ASSERT_EQUAL_FATAL(render(args), 0);
  int w = 0, h = 0;
  uint8_t *img = rtest_read_png(path_in(tmp, "col300.png"), &w, &h);
  CU_ASSERT(img != NULL && w == 1004);
  free(img);
  img = rtest_read_png(path_in(tmp, "col150.png"), &w, &h);
  CU_ASSERT(img != NULL && w == 502);
  free(img);
  CU_ASSERT_NOT_EQUAL(render("--size 8.5cmx6 run/snap_0001.h5 -o bad.png"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "lengths in cm, mm or in"));
  CU_ASSERT_NOT_EQUAL(render("--size 300in run/snap_0001.h5 -o bad.png"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "each side must be 16 to 16384"));
  /* the width alone, in three digits (issue 61, E12) */
  CU_ASSERT_NOT_EQUAL(render("--size 1e9cm run/snap_0001.h5 -o bad.png"), 0);
  CU_ASSERT_PTR_NOT_NULL(
      strstr(last_err(), "--size: 3.937e+08 in wide is 1.18e+11 pixels: each side must be"));
  CU_ASSERT_FALSE(exists(path_in(tmp, "bad.png")));
}

/* What -o may name: a plot's extension picks its format and any other is
 * refused; a snapshot figure is a .png, .svg or .pdf file (several
 * snapshots into one such file is an error), any other extension is
 * refused, not taken for a directory; a directory whose name has a dot is
 * taken with a trailing slash or when it exists. */
static void test_output_names(void) {
  char args[8192];
  snprintf(args, sizeof args, "plot '%s' -o plot.eps",
           sph_test_src("tests/data/render/diagnostics.csv"));
  CU_ASSERT_NOT_EQUAL(render(args), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), ".png, .svg or .pdf"));
  CU_ASSERT_FALSE(exists(path_in(tmp, "plot.eps")));
  CU_ASSERT_NOT_EQUAL(render("run -o one.pdf"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "names one image but there are"));
  CU_ASSERT_FALSE(exists(path_in(tmp, "one.pdf")));
  CU_ASSERT_NOT_EQUAL(render("run/snap_0001.h5 -o one.jpg"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "unknown extension '.jpg'"));
  CU_ASSERT_FALSE(exists(path_in(tmp, "one.jpg")));
  CU_ASSERT_EQUAL(render("--size 200 --jobs 1 run -o frames.v2/"), 0);
  CU_ASSERT_TRUE(exists(path_in(tmp, "frames.v2/frame_0001.png")));
  CU_ASSERT_EQUAL(render("--size 200 --jobs 1 run -o frames.v2"), 0); /* it exists now */
}

/* Without its font the renderer stops before drawing, naming the file and
 * the Debian package to install; SPH_RENDER_FONT picks another font. */
static void test_font_missing(void) {
  char cmd[9000];
  snprintf(cmd, sizeof cmd,
           "cd '%s' && SPH_RENDER_FONT=/no/such/font.ttf '%s' --size 200 run/snap_0001.h5 "
           "-o nofont.png 2> err.txt",
           tmp, renderer());
  CU_ASSERT_NOT_EQUAL(sph_test_system(cmd), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "/no/such/font.ttf"));
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "fonts-dejavu-core"));
  CU_ASSERT_FALSE(exists(path_in(tmp, "nofont.png")));
  snprintf(cmd, sizeof cmd,
           "cd '%s' && SPH_RENDER_FONT=/usr/share/fonts/truetype/dejavu/DejaVuSerif.ttf '%s' "
           "--size 200 run/snap_0001.h5 -o serif.png 2> err.txt",
           tmp, renderer());
  CU_ASSERT_EQUAL(sph_test_system(cmd), 0); /* fonts-dejavu-core has the serif too */
  CU_ASSERT_TRUE(exists(path_in(tmp, "serif.png")));
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
  /* the 3-D options on a 2-D snapshot */
  CU_ASSERT_NOT_EQUAL(render("--slice y=0.5 run/snap_0001.h5 -o out_missing"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "is 2-D: --slice cuts 3-D snapshots"));
  CU_ASSERT_NOT_EQUAL(render("--surface field run/snap_0001.h5 -o out_missing"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "is 2-D: --surface"));
  CU_ASSERT_NOT_EQUAL(render("mesh run/snap_0001.h5 -o out_missing"), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(last_err(), "is 2-D: the mesh mode"));
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
      {"FreeType text", test_font},
      {"labels with units", test_labels},
      {"SPH interpolation and outline, exact", test_interp},
      {"outline as polylines", test_contour_lines},
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
      {"anti-aliasing: no moire", test_antialias},
      {"the default look: a fluid field smooth and outlined, flags as discs", test_default_look},
      {"interpolated view and outline", test_smooth},
      {"plots as SVG and PDF", test_vector_plot},
      {"snapshot figures as SVG and PDF, sizes in cm", test_vector_figures},
      {"output names and extensions", test_output_names},
      {"missing font", test_font_missing},
      {"bad input: missing file", test_missing_file},
      {"bad input: missing field", test_missing_field},
      {"bad input: corrupt HDF5", test_corrupt_file},
      {"bad options", test_bad_options},
      {"cleanup", test_cleanup},
      CU_TEST_INFO_NULL,
  };
  return sph_test_main("render", tests);
}
