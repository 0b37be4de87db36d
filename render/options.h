/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * options.h - the settings of one sph-render invocation, as parsed from the
 * command line by cli.c. Strings point into argv.
 */
#ifndef SPH_RENDER_OPTIONS_H
#define SPH_RENDER_OPTIONS_H

#include "canvas.h"
#include "slice.h"

enum { ROPT_MAX_LIST = 64 };

enum { RMODE_FRAMES, RMODE_PANELS, RMODE_COMPARE, RMODE_PLOT, RMODE_MESH };

/* --surface: 3-D fluid as particles, or as its free-surface mesh coloured
 * by the field or as water. */
enum { RSURFACE_NONE, RSURFACE_FIELD, RSURFACE_WATER };

/* An --overlay and its modifiers. */
typedef struct roverlay_opt {
  const char *path;
  const char *xcol, *ycol, *tcol; /* NULL: first two columns; no time filter */
  double xscale, yscale;
  int line;
  const char *label;
} roverlay_opt;

/* A plot series (a positional CSV, --line or --points) and its modifiers. */
typedef struct rseries_opt {
  const char *path;
  const char *xcol, *ycol; /* NULL: the global --x/--y, else columns 1 and 2 */
  double xscale, yscale;
  int points;   /* markers instead of a line */
  int relative; /* plot (y - y0) / |y0| */
  const char *label;
} rseries_opt;

typedef struct roptions {
  int mode;
  const char *output;
  const char *backend;
  int jobs;          /* 0: one per processor */
  int width, height; /* 0: the mode's default; height 0 with width: automatic */
  double size_in[2]; /* --size in cm, mm or in: width and height in inches (height 0:
                        automatic), turned into width and height by rcli_parse; 0: pixels */
  int dpi;           /* a PNG's pixels per inch for a --size in cm, mm or in (default 300) */
  int font_scale;    /* 0: automatic */
  int samples;       /* sub-pixels per pixel and axis (anti-aliasing), 1 to 4 */
  int compression;
  rcolor bg;
  const char *title;
  int verbose;

  /* snapshot modes */
  const char *inputs[ROPT_MAX_LIST * 4];
  int n_inputs;
  const char *field;
  const char *cmap; /* NULL: viridis, or coolwarm for signed fields */
  int have_range;
  double range[2];
  int have_view;
  double view[4];
  double disc_scale, disc_size;
  int disc_given; /* --disc-scale or --disc-size given: no growth of small discs */
  int walls;
  int smooth;  /* the SPH interpolation of the field on the pixels (interp.h) */
  int outline; /* the free surface as a line (the interpolation's level 1/2) */
  int bare, colorbar;
  int cols, rows; /* --panels */
  double times[ROPT_MAX_LIST];
  int n_times;
  const char *names[ROPT_MAX_LIST]; /* --names for --compare */
  int n_names;
  double match_tol; /* NaN: half the first run's output interval */
  roverlay_opt overlay[16];
  int n_overlays;
  double overlay_tol;
  int walls_given;  /* --walls given (3-D draws no walls unless asked) */
  int smooth_given; /* --smooth, --outline or --discs given */
  int air;          /* --air: a two-phase run's air drawn too (snapdata.h) */

  /* 3-D snapshots: the camera (camera.h) */
  const char *view3d; /* --view NAME (iso, front, side, top); NULL: iso */
  int have_azimuth, have_elevation, have_distance, have_look_at;
  double azimuth, elevation, distance, look_at[3];
  double fov;          /* degrees, default 30 */
  int ortho;           /* --ortho */
  int surface;         /* RSURFACE_* */
  double surface_cell; /* --surface-cell (m); 0: half the particle spacing */
  int mesh_vtk;        /* mesh mode, --format vtk: a directory of legacy VTK files, not PLY */
  int field_given;     /* --field given (the mesh mode writes no field without it) */
  int have_slice;      /* --slice: 3-D snapshots cut by a plane, drawn as 2-D (slice.h) */
  rslice slice;

  /* plot mode (the mesh mode takes the snapshot modes' inputs, --field,
   * --times and --surface-cell) */
  rseries_opt series[ROPT_MAX_LIST];
  int n_series;
  const char *xcol, *ycol;
  const char *xlabel, *ylabel;
  int have_xrange, have_yrange;
  double xrange[2], yrange[2];
  int xlog, ylog; /* logarithmic axes */
  int legend;
} roptions;

#endif
