/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * cli.c - parses the sph-render command line into roptions.
 *
 * Options take "--name value" or "--name=value". Modifiers (--overlay-x,
 * ... in the snapshot modes; --x, --y, --label, ... in the plot mode)
 * apply to the overlay or series named just before them; given before any
 * series, --x and --y are the defaults for all. Every value is checked
 * here, and an error names the option, the value and what was expected,
 * so the renderer never starts on a half-understood command. Choices are
 * names (backends, colour maps, wall styles, legend corners), never codes.
 */
#include "config.h"

#include "cli.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <sys/stat.h>

#include "camera.h"
#include "core/version.h"
#include "figure.h"
#include "gl_context.h"
#include "inputs.h"
#include "marks.h"

void rcli_usage(FILE *fp) {
  fputs("usage: sph-render [OPTIONS] SNAPSHOT|RUN_DIR... -o OUT\n"
        "       sph-render --panels CxR [OPTIONS] SNAPSHOT|RUN_DIR... -o FIGURE.png|.svg|.pdf\n"
        "       sph-render --compare [OPTIONS] RUN_DIR RUN_DIR... -o OUT\n"
        "       sph-render plot [OPTIONS] FILE.csv [--points FILE.csv]... -o PLOT.png|.svg|.pdf\n"
        "       sph-render mesh [OPTIONS] SNAPSHOT|RUN_DIR... -o SURFACE.ply|SURFACE.vtk|DIR\n"
        "\n"
        "Renders SPH snapshots (HDF5, as written by `sph run`) to PNG images off screen.\n"
        "A directory stands for its snap_*.h5 files. OUT is a directory (one\n"
        "frame_NNNN.png per snapshot, numbered like the input) or, for one image, a .png\n"
        "file, or an .svg or .pdf file (vector, through cairo).\n"
        "\n"
        "Snapshot options:\n"
        "  -o, --output PATH       output directory, or one .png, .svg or .pdf file (required)\n"
        "  --field NAME            colour by speed (default), pressure, density, vx, vy,\n"
        "                          free_surface, kind, or any field of the file\n"
        "  --cmap NAME             viridis (default), coolwarm (default for vx, vy), gray\n"
        "  --range MIN:MAX         fixed colour range (default: over all inputs, fluid only)\n"
        "  --size W[xH]            image size in pixels (frames: 1280x720; figures: 640 per\n"
        "                          panel column, height from the view's aspect), or in cm,\n"
        "                          mm or in (8.5cm: a journal's column; SVG and PDF in\n"
        "                          points, a PNG at --dpi, the text scaled to match)\n"
        "  --dpi N                 pixels per inch of a PNG sized in cm, mm or in, and of\n"
        "                          the interpolated field in an SVG or PDF (300)\n"
        "  --view X0:X1:Y0:Y1      world window in metres (default: the case's tank)\n"
        "  --view NAME             3-D snapshots: iso (default), front, side or top; the\n"
        "                          camera frames the tank and stays the same for every frame\n"
        "  --azimuth DEG, --elevation DEG   3-D: the camera's direction (front: 0, 0; side:\n"
        "                          90, 0; top: 0, 90), replacing the view's\n"
        "  --distance M, --look-at X:Y:Z    3-D: the camera's distance and target (default:\n"
        "                          the tank framed, from its centre)\n"
        "  --fov DEG               3-D: vertical field of view (default 30)\n"
        "  --ortho                 3-D: orthographic projection\n"
        "  --surface field|water   3-D: the fluid as its free surface, a lit mesh (marching\n"
        "                          cubes on the level 1/2 of the SPH kernel sum), coloured\n"
        "                          by the field or as water, instead of its particles\n"
        "  --surface-cell M        3-D: the lattice's cell for the surface (default dx/2)\n"
        "  --slice AXIS=POS[,T]    3-D: the plane AXIS = POS (x, y or z; m) drawn as a 2-D\n"
        "                          snapshot: the field interpolated on it with the free\n"
        "                          surface outlined, or with --discs the particles of a\n"
        "                          slab T thick (default dx)\n"
        "  --background RRGGBB     background colour (default ffffff; also white, black)\n"
        "  --disc-scale F          particle disc diameter = F * dx (default 1; discs smaller\n"
        "                          than 4 pixels then grow to cover their particle's cell)\n"
        "  --disc-size METRES      disc diameter when the snapshot has no dx\n"
        "  --smooth                the field as its SPH interpolation on the pixels\n"
        "                          (Shepard-normalised, blank outside the fluid): the default\n"
        "                          for every field but free_surface and kind\n"
        "  --outline               draw the free surface as a line (default with --smooth)\n"
        "  --discs                 particle discs instead (the default for free_surface, kind)\n"
        "  --walls grey|field|none how to draw wall particles (default grey; 3-D: none)\n"
        "  --air                   a two-phase run's air too (by default the liquid alone,\n"
        "                          its surface drawn as a one-phase run's)\n"
        "  --bare                  particles only: no axes, labels or colour bar\n"
        "  --no-colorbar           no colour bar\n"
        "  --title TEXT            a title line above the figure\n"
        "  --font-scale N          text size multiplier (default: from the image size)\n"
        "  --samples N             anti-aliasing: each pixel is the mean of NxN samples\n"
        "                          (1 to 4, default 3; 1: none)\n"
        "  --compression N         PNG zlib level 0-9 (default 3)\n"
        "  --jobs N                worker processes (default: one per processor)\n"
        "  --backend NAME          osmesa (default) or egl (surfaceless)\n"
        "  --panels CxR            one figure of C columns and R rows of snapshots\n"
        "  --times T1,T2,...       use the snapshots nearest these times (s)\n"
        "  --compare               inputs are runs: one image per matching time\n"
        "  --names A,B,...         run names for --compare panels (default: directory names)\n"
        "  --match-tol SECONDS     --compare: how far times may differ (default: half the\n"
        "                          first run's output interval)\n"
        "  --overlay FILE.csv      reference points in metres (first two columns: x, y)\n"
        "    --overlay-x COL, --overlay-y COL   columns to use (sums with '+')\n"
        "    --overlay-scale SX:SY  multiply x and y (e.g. to turn x/a into metres)\n"
        "    --overlay-time COL     show a point only at frames within --overlay-tol of it\n"
        "    --overlay-style points|line,  --overlay-label TEXT\n"
        "  --overlay-tol SECONDS   default 0.0005\n"
        "  -v, --verbose           list every file written\n"
        "\n"
        "Plot options (after `plot`):\n"
        "  FILE.csv | --line FILE.csv   a series drawn as a line\n"
        "  --points FILE.csv            a series drawn as markers\n"
        "    --x COL, --y COL           columns (names or sums with '+'; before any series:\n"
        "                               the default for all; else columns 1 and 2)\n"
        "    --x-scale F, --y-scale F   multiply the values\n"
        "    --relative                 plot (y - y0) / |y0|\n"
        "    --label TEXT               legend text (default: the file's name)\n"
        "  --xlabel TEXT, --ylabel TEXT, --title TEXT\n"
        "  --xrange MIN:MAX, --yrange MIN:MAX   axis ranges (default: from the data)\n"
        "  --xlog, --ylog               logarithmic axis (values <= 0 are left out; the\n"
        "                               default range is whole decades)\n"
        "  --legend top-left|top-right|bottom-left|bottom-right|none\n"
        "  -o PLOT.png|PLOT.svg|PLOT.pdf  the plot as a PNG image, or as SVG or PDF (vector)\n"
        "  --size W[xH] (default 960x640; pixels, or points for SVG and PDF), --background,\n"
        "  --font-scale, --samples, --compression, --backend\n"
        "\n"
        "Mesh options (after `mesh`; 3-D snapshots): writes each snapshot's free surface\n"
        "(as --surface draws it) as a binary PLY or legacy VTK file: vertices with outward\n"
        "normals and, with --field, that field (ParaView keeps a field from .vtk only);\n"
        "OUT is one .ply or .vtk file or a directory of surface_NNNN.ply (or .vtk)\n"
        "  --field NAME, --times T1,T2,..., --surface-cell M, --format ply|vtk, -v\n"
        "\n"
        "  -h, --help, --version\n",
        fp);
}

static int parse_double(const char *opt, const char *s, double *out, sph_error *err) {
  char *end;
  errno = 0;
  double v = strtod(s, &end);
  if (end == s || *end != '\0' || errno == ERANGE || !isfinite(v))
    return sph_error_set(err, "%s: '%s' is not a number", opt, s);
  *out = v;
  return 0;
}

static int parse_int(const char *opt, const char *s, int lo, int hi, int *out, sph_error *err) {
  char *end;
  errno = 0;
  long v = strtol(s, &end, 10);
  if (end == s || *end != '\0' || errno == ERANGE || v < lo || v > hi)
    return sph_error_set(err, "%s: '%s' is not a whole number from %d to %d", opt, s, lo, hi);
  *out = (int)v;
  return 0;
}

/* n numbers separated by sep (':' or ','); exactly n unless n_out is given. */
static int parse_numbers(const char *opt, const char *s, char sep, double *v, int n, int *n_out,
                         const char *form, sph_error *err) {
  char buf[1024];
  if (snprintf(buf, sizeof buf, "%s", s) >= (int)sizeof buf)
    return sph_error_set(err, "%s: value too long", opt);
  int k = 0;
  char *p = buf;
  for (;;) {
    char *q = strchr(p, sep);
    if (q) *q = '\0';
    if (k == n) return sph_error_set(err, "%s: '%s': expected %s", opt, s, form);
    if (parse_double(opt, p, &v[k], err) != 0)
      return sph_error_set(err, "%s: '%s': expected %s", opt, s, form);
    k++;
    if (!q) break;
    p = q + 1;
  }
  if (n_out)
    *n_out = k;
  else if (k != n)
    return sph_error_set(err, "%s: '%s': expected %s", opt, s, form);
  return 0;
}

static int parse_range(const char *opt, const char *s, double r[2], sph_error *err) {
  if (parse_numbers(opt, s, ':', r, 2, NULL, "MIN:MAX", err) != 0) return -1;
  if (!(r[1] > r[0])) return sph_error_set(err, "%s: '%s': need MIN < MAX", opt, s);
  return 0;
}

/* One side of --size with its unit: inches per unit of a "cm", "mm" or
 * "in" suffix (*per_in), or 0 for pixels. */
static int parse_side(const char *s, double *v, double *inches) {
  static const struct {
    const char *suffix;
    double inches;
  } units[] = {{"cm", 1.0 / 2.54}, {"mm", 1.0 / 25.4}, {"in", 1.0}};
  char *end;
  errno = 0;
  *v = strtod(s, &end);
  if (end == s || errno == ERANGE || !isfinite(*v) || !(*v > 0.0)) return -1;
  *inches = 0.0;
  if (*end == '\0') return 0;
  for (size_t k = 0; k < sizeof units / sizeof units[0]; k++)
    if (strcmp(end, units[k].suffix) == 0) {
      *inches = units[k].inches;
      return 0;
    }
  return -1;
}

/* "WxH" or "W" (height automatic): pixels (whole numbers, 16 to 16384), or
 * both sides in cm, mm or in (o->size_in, turned into pixels or points by
 * resolve_size once the output is known). */
static int parse_size(const char *opt, const char *s, roptions *o, sph_error *err) {
  char buf[64];
  const char *form = "expected W or WxH: pixels (16 to 16384), or lengths in cm, mm or in "
                     "(e.g. 8.5cm or 8.5cmx6cm)";
  if (snprintf(buf, sizeof buf, "%s", s) >= (int)sizeof buf)
    return sph_error_set(err, "%s: '%s': %s", opt, s, form);
  char *x = strchr(buf, 'x');
  if (x) *x = '\0';
  double w, h = 0.0, uw, uh = 0.0;
  if (parse_side(buf, &w, &uw) || (x && parse_side(x + 1, &h, &uh)) || (x && (uw > 0) != (uh > 0)))
    return sph_error_set(err, "%s: '%s': %s", opt, s, form);
  o->size_in[0] = o->size_in[1] = 0.0;
  o->width = o->height = 0;
  if (uw > 0.0) {
    o->size_in[0] = w * uw;
    o->size_in[1] = h * uh;
    return 0;
  }
  if (parse_int(opt, buf, 16, 16384, &o->width, err) != 0 ||
      (x && parse_int(opt, x + 1, 16, 16384, &o->height, err) != 0))
    return sph_error_set(err, "%s: '%s': %s", opt, s, form);
  return 0;
}

/* A --size in cm, mm or in as pixels (a PNG, at o->dpi) or points (SVG
 * and PDF, 72 per inch), and the font scale that goes with it unless
 * --font-scale is given: glyphs 7 units high per scale step, so scale 1 in
 * points and dpi / 72 in pixels print capitals about 2.5 mm high. */
static int resolve_size(roptions *o, sph_error *err) {
  if (!(o->size_in[0] > 0.0)) return 0;
  const int vector = o->output && rcanvas_vector_kind(o->output);
  const double per_in = vector ? 72.0 : (double)o->dpi;
  const double w = o->size_in[0] * per_in, h = o->size_in[1] * per_in;
  if (!(w >= 16.0 && w <= 16384.0) || (h > 0.0 && !(h >= 16.0 && h <= 16384.0))) {
    /* the sides given, in three digits (issue 61, E12: "118110236220 x 0") */
    if (h > 0.0)
      return sph_error_set(err,
                           "--size: %.4g x %.4g in is %.3g x %.3g %s: each side must be 16 to "
                           "16384",
                           o->size_in[0], o->size_in[1], w, h, vector ? "points" : "pixels");
    return sph_error_set(err, "--size: %.4g in wide is %.3g %s: each side must be 16 to 16384",
                         o->size_in[0], w, vector ? "points" : "pixels");
  }
  o->width = (int)lround(w);
  o->height = h > 0.0 ? (int)lround(h) : 0;
  if (o->font_scale == 0) {
    const long sc = vector ? 1 : lround(per_in / 72.0);
    o->font_scale = (int)(sc < 1 ? 1 : sc > 16 ? 16 : sc);
  }
  return 0;
}

static int parse_grid(const char *opt, const char *s, int *cols, int *rows, sph_error *err) {
  char buf[64];
  snprintf(buf, sizeof buf, "%s", s);
  char *x = strchr(buf, 'x');
  if (!x) return sph_error_set(err, "%s: '%s': expected CxR (columns x rows), e.g. 3x2", opt, s);
  *x = '\0';
  if (parse_int(opt, buf, 1, 64, cols, err) != 0 || parse_int(opt, x + 1, 1, 64, rows, err) != 0 ||
      *cols * *rows > 64)
    return sph_error_set(err, "%s: '%s': expected CxR with at most 64 panels", opt, s);
  return 0;
}

static int parse_color(const char *opt, const char *s, rcolor *c, sph_error *err) {
  if (strcmp(s, "white") == 0) s = "ffffff";
  if (strcmp(s, "black") == 0) s = "000000";
  if (*s == '#') s++;
  if (strlen(s) != 6 || strspn(s, "0123456789abcdefABCDEF") != 6)
    return sph_error_set(err, "%s: '%s': expected a colour RRGGBB (hex), white or black", opt, s);
  unsigned long v = strtoul(s, NULL, 16);
  *c = (rcolor){(uint8_t)(v >> 16), (uint8_t)(v >> 8), (uint8_t)v, 255};
  return 0;
}

/* Splits a comma list into o->names (copies kept in a static buffer: the
 * options live for the whole run). */
static int parse_names(const char *opt, const char *s, roptions *o, sph_error *err) {
  static char buf[4096];
  if (snprintf(buf, sizeof buf, "%s", s) >= (int)sizeof buf)
    return sph_error_set(err, "%s: value too long", opt);
  o->n_names = 0;
  for (char *p = buf; p && o->n_names < ROPT_MAX_LIST;) {
    char *q = strchr(p, ',');
    if (q) *q++ = '\0';
    o->names[o->n_names++] = p;
    p = q;
  }
  return 0;
}

static void defaults(roptions *o) {
  memset(o, 0, sizeof *o);
  o->mode = RMODE_FRAMES;
  o->backend = "osmesa";
  o->compression = 3;
  o->bg = (rcolor){255, 255, 255, 255};
  o->field = "speed";
  o->disc_scale = 1.0;
  o->walls = RWALLS_GREY;
  o->colorbar = 1;
  o->match_tol = NAN;
  o->overlay_tol = 0.0005;
  o->legend = RLEGEND_TOP_LEFT;
  o->samples = RCANVAS_DEFAULT_SAMPLES;
  o->dpi = 300;
  o->smooth = o->outline = -1; /* unset: from the field (rcli_parse) */
  o->fov = 30.0;
}

typedef struct args {
  int argc, i;
  char **argv;
  const char *name; /* the option being parsed, without "=value" */
  const char *inline_value;
  char namebuf[64];
} args;

/* The option's value: after '=' or the next argument. */
static const char *value(args *a, sph_error *err) {
  if (a->inline_value) return a->inline_value;
  if (a->i + 1 >= a->argc) {
    sph_error_set(err, "%s needs a value", a->name);
    return NULL;
  }
  return a->argv[++a->i];
}

#define VALUE()                                                                                    \
  const char *v = value(&a, err);                                                                  \
  if (!v) return -1

static int is(const args *a, const char *name) { return strcmp(a->name, name) == 0; }

/* The extension of path's last component ("" if none; a trailing '/'
 * marks a directory, whatever its name). */
static const char *extension(const char *path) {
  size_t n = strlen(path);
  if (n == 0 || path[n - 1] == '/') return "";
  const char *slash = strrchr(path, '/');
  const char *base = slash ? slash + 1 : path;
  const char *dot = strrchr(base, '.');
  return dot && dot != base ? dot : "";
}

/* What -o may name: a plot is a .png, .svg or .pdf file; snapshot images
 * are PNG files in a directory, or one .png, .svg or .pdf figure. Any other extension is
 * refused rather than taken for a directory's name (an existing directory
 * or a path ending in '/' is always a directory). */
static int check_output(const roptions *o, sph_error *err) {
  const char *ext = extension(o->output);
  struct stat st;
  int is_dir = stat(o->output, &st) == 0 && S_ISDIR(st.st_mode);
  if (o->mode == RMODE_MESH) {
    if (!ext[0] || is_dir || strcmp(ext, ".ply") == 0 || strcmp(ext, ".vtk") == 0) return 0;
    return sph_error_set(
        err, "-o %s: a surface is written as a .ply or .vtk file or into a directory", o->output);
  }
  if (o->mode == RMODE_PLOT) {
    if (rinputs_is_png(o->output) || rcanvas_vector_kind(o->output)) return 0;
    return sph_error_set(err, "-o %s: a plot is written as .png, .svg or .pdf%s%s%s", o->output,
                         ext[0] ? " (not " : "", ext, ext[0] ? ")" : "");
  }
  if (ext[0] && !rinputs_is_png(o->output) && !rcanvas_vector_kind(o->output) && !is_dir)
    return sph_error_set(err,
                         "-o %s: unknown extension '%s': give a .png, .svg or .pdf file or a "
                         "directory (end the name with '/' if a directory's name has a dot)",
                         o->output, ext);
  return 0;
}

static int check(const roptions *o, sph_error *err) {
  if (!o->output) return sph_error_set(err, "no output: give -o PATH (see --help)");
  if (!rgl_backend_valid(o->backend))
    return sph_error_set(err, "--backend: unknown '%s' (valid: %s)", o->backend,
                         rgl_backend_names());
  if (check_output(o, err) != 0) return -1;
  if (o->mode == RMODE_PLOT) return 0;
  if (o->n_inputs == 0) return sph_error_set(err, "no snapshots given (see --help)");
  if (o->mode == RMODE_COMPARE && o->n_inputs > ROPT_MAX_LIST)
    return sph_error_set(err, "--compare: too many runs");
  return 0;
}

/* The options the mesh mode takes (the others draw images). */
static int mesh_option(const char *name) {
  static const char *const names[] = {
      "-o",      "--output",       "-v",      "--verbose", "-h", "--help", "--version",
      "--field", "--surface-cell", "--times", "--format"};
  for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
    if (strcmp(name, names[k]) == 0) return 1;
  return 0;
}

#define VALUE_P()                                                                                  \
  const char *v = value(a, err);                                                                   \
  if (!v) return -1

/* Options of every mode: output, size, colours, text, workers; --help and --version return 2
 * (done). Returns 1 if the option was this group's (handled), 0 if not, -1 on error. */
static int common_option(args *a, roptions *o, sph_error *err) {
  if (is(a, "-h") || is(a, "--help")) {
    rcli_usage(stdout);
    return 2;
  } else if (is(a, "--version")) {
    printf("sph-render (%s)\n", sph_version());
    return 2;
  } else if (is(a, "-o") || is(a, "--output")) {
    VALUE_P();
    o->output = v;
  } else if (is(a, "-v") || is(a, "--verbose")) {
    o->verbose = 1;
  } else if (is(a, "--backend")) {
    VALUE_P();
    o->backend = v;
  } else if (is(a, "--jobs")) {
    VALUE_P();
    if (parse_int(a->name, v, 1, 256, &o->jobs, err) != 0) return -1;
  } else if (is(a, "--size")) {
    VALUE_P();
    if (parse_size(a->name, v, o, err) != 0) return -1;
  } else if (is(a, "--dpi")) {
    VALUE_P();
    if (parse_int(a->name, v, 10, 2400, &o->dpi, err) != 0) return -1;
  } else if (is(a, "--font-scale")) {
    VALUE_P();
    if (parse_int(a->name, v, 1, 16, &o->font_scale, err) != 0) return -1;
  } else if (is(a, "--samples")) {
    VALUE_P();
    if (parse_int(a->name, v, 1, RCANVAS_MAX_SAMPLES, &o->samples, err) != 0) return -1;
  } else if (is(a, "--compression")) {
    VALUE_P();
    if (parse_int(a->name, v, 0, 9, &o->compression, err) != 0) return -1;
  } else if (is(a, "--background")) {
    VALUE_P();
    if (parse_color(a->name, v, &o->bg, err) != 0) return -1;
  } else if (is(a, "--title")) {
    VALUE_P();
    o->title = v;
  } else {
    return 0;
  }
  return 1;
}

/* Plot mode: series and axes. Returns 1 if the option was
 * this group's (handled), 0 if not, -1 on error. */
static int plot_option(args *a, roptions *o, rseries_opt **sep, sph_error *err) {
  if ((is(a, "--line") || is(a, "--points"))) {
    VALUE_P();
    if (o->n_series == ROPT_MAX_LIST) return sph_error_set(err, "too many series");
    *sep = &o->series[o->n_series++];
    **sep = (rseries_opt){v, NULL, NULL, 1.0, 1.0, is(a, "--points"), 0, NULL};
  } else if ((is(a, "--x") || is(a, "--y"))) {
    VALUE_P();
    if (*sep && is(a, "--x"))
      (*sep)->xcol = v;
    else if (*sep)
      (*sep)->ycol = v;
    else if (is(a, "--x"))
      o->xcol = v;
    else
      o->ycol = v;
  } else if ((is(a, "--x-scale") || is(a, "--y-scale"))) {
    VALUE_P();
    if (!*sep)
      return sph_error_set(err, "%s applies to the series before it: give a CSV first", a->name);
    if (parse_double(a->name, v, is(a, "--x-scale") ? &(*sep)->xscale : &(*sep)->yscale, err) != 0)
      return -1;
  } else if (is(a, "--relative")) {
    if (!*sep) return sph_error_set(err, "--relative applies to the series before it");
    (*sep)->relative = 1;
  } else if (is(a, "--label")) {
    VALUE_P();
    if (!*sep) return sph_error_set(err, "--label applies to the series before it");
    (*sep)->label = v;
  } else if ((is(a, "--xlabel") || is(a, "--ylabel"))) {
    VALUE_P();
    if (is(a, "--xlabel"))
      o->xlabel = v;
    else
      o->ylabel = v;
  } else if (is(a, "--xrange")) {
    VALUE_P();
    if (parse_range(a->name, v, o->xrange, err) != 0) return -1;
    o->have_xrange = 1;
  } else if (is(a, "--yrange")) {
    VALUE_P();
    if (parse_range(a->name, v, o->yrange, err) != 0) return -1;
    o->have_yrange = 1;
  } else if ((is(a, "--xlog") || is(a, "--ylog"))) {
    if (is(a, "--xlog"))
      o->xlog = 1;
    else
      o->ylog = 1;
  } else if (is(a, "--legend")) {
    VALUE_P();
    o->legend = rlegend_corner(v);
    if (o->legend < 0)
      return sph_error_set(err,
                           "--legend: unknown '%s' (valid: top-left, top-right, "
                           "bottom-left, bottom-right, none)",
                           v);
  } else {
    return 0;
  }
  return 1;
}

/* Snapshot modes: field, colours, view, figure layout, times. Returns 1 if the option was
 * this group's (handled), 0 if not, -1 on error. */
static int snapshot_option(args *a, roptions *o, int *compare, int *panels, sph_error *err) {
  if (is(a, "--field")) {
    VALUE_P();
    o->field = v;
    o->field_given = 1;
  } else if (is(a, "--surface")) {
    VALUE_P();
    if (strcmp(v, "field") == 0)
      o->surface = RSURFACE_FIELD;
    else if (strcmp(v, "water") == 0)
      o->surface = RSURFACE_WATER;
    else if (strcmp(v, "none") == 0)
      o->surface = RSURFACE_NONE;
    else
      return sph_error_set(err, "--surface: unknown '%s' (valid: field, water, none)", v);
  } else if (is(a, "--slice")) {
    VALUE_P();
    if (rslice_parse(v, &o->slice, err) != 0) return -1;
    o->have_slice = 1;
  } else if (is(a, "--surface-cell")) {
    VALUE_P();
    if (parse_double(a->name, v, &o->surface_cell, err) != 0) return -1;
    if (!(o->surface_cell > 0.0))
      return sph_error_set(err, "--surface-cell: '%s': expected metres > 0", v);
  } else if (is(a, "--cmap")) {
    VALUE_P();
    o->cmap = v;
  } else if (is(a, "--range")) {
    VALUE_P();
    if (parse_range(a->name, v, o->range, err) != 0) return -1;
    o->have_range = 1;
  } else if (is(a, "--view")) {
    VALUE_P();
    double az, el;
    if (rcamera_named(v, &az, &el) == 0) {
      o->view3d = v;
      return 1;
    }
    if (isalpha((unsigned char)v[0]))
      return sph_error_set(err, "--view: unknown view '%s' (3-D: %s; 2-D: X0:X1:Y0:Y1)", v,
                           rcamera_names());
    if (parse_numbers(a->name, v, ':', o->view, 4, NULL, "X0:X1:Y0:Y1", err) != 0) return -1;
    if (!(o->view[1] > o->view[0]) || !(o->view[3] > o->view[2]))
      return sph_error_set(err, "--view: '%s': need X0 < X1 and Y0 < Y1", v);
    o->have_view = 1;
  } else if (is(a, "--azimuth") || is(a, "--elevation") || is(a, "--distance") || is(a, "--fov")) {
    VALUE_P();
    double x;
    if (parse_double(a->name, v, &x, err) != 0) return -1;
    if (is(a, "--azimuth")) {
      o->azimuth = x;
      o->have_azimuth = 1;
    } else if (is(a, "--elevation")) {
      if (!(x >= -90.0 && x <= 90.0))
        return sph_error_set(err, "--elevation: '%s': expected -90 to 90 degrees", v);
      o->elevation = x;
      o->have_elevation = 1;
    } else if (is(a, "--distance")) {
      if (!(x > 0.0)) return sph_error_set(err, "--distance: '%s': expected metres > 0", v);
      o->distance = x;
      o->have_distance = 1;
    } else {
      if (!(x > 0.0 && x < 180.0))
        return sph_error_set(err, "--fov: '%s': expected degrees between 0 and 180", v);
      o->fov = x;
    }
  } else if (is(a, "--look-at")) {
    VALUE_P();
    if (parse_numbers(a->name, v, ':', o->look_at, 3, NULL, "X:Y:Z", err) != 0) return -1;
    o->have_look_at = 1;
  } else if (is(a, "--ortho")) {
    o->ortho = 1;
  } else if (is(a, "--disc-scale")) {
    VALUE_P();
    if (parse_double(a->name, v, &o->disc_scale, err) != 0) return -1;
    if (!(o->disc_scale > 0.0)) return sph_error_set(err, "--disc-scale: must be positive");
    o->disc_given = 1;
  } else if (is(a, "--disc-size")) {
    VALUE_P();
    if (parse_double(a->name, v, &o->disc_size, err) != 0) return -1;
    if (!(o->disc_size > 0.0)) return sph_error_set(err, "--disc-size: must be positive");
    o->disc_given = 1;
  } else if (is(a, "--walls")) {
    VALUE_P();
    o->walls_given = 1;
    if (strcmp(v, "grey") == 0 || strcmp(v, "gray") == 0)
      o->walls = RWALLS_GREY;
    else if (strcmp(v, "field") == 0)
      o->walls = RWALLS_FIELD;
    else if (strcmp(v, "none") == 0)
      o->walls = RWALLS_NONE;
    else
      return sph_error_set(err, "--walls: unknown '%s' (valid: grey, field, none)", v);
  } else if (is(a, "--smooth")) {
    o->smooth = 1;
    o->smooth_given = 1;
  } else if (is(a, "--outline")) {
    o->outline = 1;
    o->smooth_given = 1;
  } else if (is(a, "--discs")) {
    o->smooth = 0;
    o->smooth_given = 1;
  } else if (is(a, "--air")) {
    o->air = 1;
  } else if (is(a, "--bare")) {
    o->bare = 1;
  } else if (is(a, "--no-colorbar")) {
    o->colorbar = 0;
  } else if (is(a, "--panels")) {
    VALUE_P();
    if (parse_grid(a->name, v, &o->cols, &o->rows, err) != 0) return -1;
    *panels = 1;
  } else if (is(a, "--compare")) {
    *compare = 1;
  } else if (is(a, "--times")) {
    VALUE_P();
    if (parse_numbers(a->name, v, ',', o->times, ROPT_MAX_LIST, &o->n_times,
                      "times T1,T2,... in seconds", err) != 0)
      return -1;
  } else if (is(a, "--names")) {
    VALUE_P();
    if (parse_names(a->name, v, o, err) != 0) return -1;
  } else if (is(a, "--match-tol")) {
    VALUE_P();
    if (parse_double(a->name, v, &o->match_tol, err) != 0) return -1;
    if (o->match_tol < 0.0) return sph_error_set(err, "--match-tol: must not be negative");
  } else if (is(a, "--overlay-tol")) {
    VALUE_P();
    if (parse_double(a->name, v, &o->overlay_tol, err) != 0) return -1;
  } else {
    return 0;
  }
  return 1;
}

/* Reference points drawn over snapshots. Returns 1 if the option was
 * this group's (handled), 0 if not, -1 on error. */
static int overlay_option(args *a, roptions *o, roverlay_opt **ovp, sph_error *err) {
  if (is(a, "--overlay")) {
    VALUE_P();
    if (o->n_overlays == 16) return sph_error_set(err, "at most 16 overlays");
    *ovp = &o->overlay[o->n_overlays++];
    **ovp = (roverlay_opt){v, NULL, NULL, NULL, 1.0, 1.0, 0, NULL};
  } else if ((is(a, "--overlay-x") || is(a, "--overlay-y") || is(a, "--overlay-time") ||
              is(a, "--overlay-label") || is(a, "--overlay-style") || is(a, "--overlay-scale"))) {
    VALUE_P();
    if (!*ovp) return sph_error_set(err, "%s applies to the --overlay before it", a->name);
    if (is(a, "--overlay-x"))
      (*ovp)->xcol = v;
    else if (is(a, "--overlay-y"))
      (*ovp)->ycol = v;
    else if (is(a, "--overlay-time"))
      (*ovp)->tcol = v;
    else if (is(a, "--overlay-label"))
      (*ovp)->label = v;
    else if (is(a, "--overlay-style")) {
      if (strcmp(v, "points") == 0)
        (*ovp)->line = 0;
      else if (strcmp(v, "line") == 0)
        (*ovp)->line = 1;
      else
        return sph_error_set(err, "--overlay-style: unknown '%s' (valid: points, line)", v);
    } else { /* --overlay-scale */
      double sc[2];
      if (parse_numbers(a->name, v, ':', sc, 2, NULL, "SX:SY", err) != 0) return -1;
      (*ovp)->xscale = sc[0];
      (*ovp)->yscale = sc[1];
    }
  } else {
    return 0;
  }
  return 1;
}

int rcli_parse(int argc, char **argv, roptions *o, sph_error *err) {
  defaults(o);
  args a = {argc, 1, argv, NULL, NULL, ""};
  if (argc > 1 && strcmp(argv[1], "plot") == 0) {
    o->mode = RMODE_PLOT;
    a.i = 2;
  } else if (argc > 1 && strcmp(argv[1], "mesh") == 0) {
    o->mode = RMODE_MESH;
    a.i = 2;
  }
  int plot = o->mode == RMODE_PLOT, mesh = o->mode == RMODE_MESH;
  int compare = 0, panels = 0;
  roverlay_opt *ov = NULL;
  rseries_opt *se = NULL;
  for (; a.i < argc; a.i++) {
    const char *arg = argv[a.i];
    if (arg[0] != '-' || arg[1] == '\0') {
      /* a positional argument: a snapshot, a run, or a plot series */
      if (plot) {
        if (o->n_series == ROPT_MAX_LIST) return sph_error_set(err, "too many series");
        se = &o->series[o->n_series++];
        *se = (rseries_opt){arg, NULL, NULL, 1.0, 1.0, 0, 0, NULL};
      } else {
        if (o->n_inputs == (int)(sizeof o->inputs / sizeof o->inputs[0]))
          return sph_error_set(err, "too many inputs: give directories instead of files");
        o->inputs[o->n_inputs++] = arg;
      }
      continue;
    }
    a.inline_value = NULL;
    const char *eq = strchr(arg, '=');
    if (eq && strncmp(arg, "--", 2) == 0 && (size_t)(eq - arg) < sizeof a.namebuf) {
      memcpy(a.namebuf, arg, (size_t)(eq - arg));
      a.namebuf[eq - arg] = '\0';
      a.name = a.namebuf;
      a.inline_value = eq + 1;
    } else {
      a.name = arg;
    }
    if (mesh && !mesh_option(a.name))
      return sph_error_set(err, "unknown option %s in mesh mode (see --help)", a.name);
    if (mesh && strcmp(a.name, "--format") == 0) { /* the files of a directory */
      const char *v = a.inline_value ? a.inline_value : a.i + 1 < argc ? argv[++a.i] : NULL;
      if (!v || (strcmp(v, "ply") && strcmp(v, "vtk")))
        return sph_error_set(err, "--format: expected ply or vtk, got %s", v ? v : "nothing");
      o->mesh_vtk = strcmp(v, "vtk") == 0;
      continue;
    }
    int r = common_option(&a, o, err);
    if (r == 0) {
      r = plot ? plot_option(&a, o, &se, err) : snapshot_option(&a, o, &compare, &panels, err);
      if (r == 0 && !plot) r = overlay_option(&a, o, &ov, err);
    }
    if (r < 0) return -1;
    if (r == 2) return 1; /* --help or --version: done */
    if (r == 0)
      return sph_error_set(err, "unknown option %s%s (see --help)", a.name,
                           plot ? " in plot mode" : "");
  }
  if (compare && panels && o->cols * o->rows < o->n_inputs)
    return sph_error_set(err, "--panels %dx%d is too small for %d runs", o->cols, o->rows,
                         o->n_inputs);
  if (mesh) return check(o, err);
  if (compare)
    o->mode = RMODE_COMPARE;
  else if (panels)
    o->mode = RMODE_PANELS;
  /* the default look of a fluid field in a frame, panel or comparison: its
   * SPH interpolation with the free surface outlined (issue 39, D10);
   * flags and kinds stay discs, which --discs asks for anywhere */
  const int fluid_field = strcmp(o->field, "free_surface") != 0 && strcmp(o->field, "kind") != 0;
  if (o->smooth < 0) o->smooth = !plot && fluid_field;
  if (o->outline < 0) o->outline = o->smooth;
  if (resolve_size(o, err) != 0) return -1;
  return check(o, err);
}
