/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * cli_new.c - `sph new NAME`: a case file to start from.
 *
 * Writes NAME.yaml: a small dam break (the Martin & Moyce column of
 * cases/martin_moyce_coarse.yaml, a = 0.05715 m, dx = a/20) that runs as
 * written in a few seconds, with every key of the case schema
 * (doc/case-files.md) either set or shown commented out with its default
 * and its range. The case reader parses the text before it is written (the
 * name's rule is its). tests/check_new holds it to that: the file runs,
 * and every key the schema tables of doc/case-files.md list appears in it.
 * `--dim 3` writes the same dam break in 3-D (a slab of the tank a wide,
 * z up, dx = a/10): the template with its dimension's lines replaced
 * (THREE_D), the rest shared.
 */
#include "config.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/cli.h"

/* The line of TEMPLATE that the air's block (sph_case_air_template: a line
 * for each key of the air's material, from the library's table) replaces. */
#define AIR_BLOCK "  # air\n"

/* The case after its name line (the name comes from the command line). */
static const char *const TEMPLATE =
    "description: \"a dam break to start from: the column of Martin & Moyce (1952), a = 0.05715 "
    "m\"\n"
    "# Every key of a case file is below, set or commented out with its\n"
    "# default and range (doc/case-files.md says more about each). Run it with\n"
    "#   sph run NAME.yaml          and render it with   sph-render out/NAME\n"
    "\n"
    "dimension: 2                 # 2 or 3 (default 2); 3-D cases: doc/case-files.md\n"
    "\n"
    "physics:\n"
    "  rho0: 1000                 # kg/m^3, > 0 (default 1000)\n"
    "  gravity: [0, -9.81]        # m/s^2 (default [0, -9.81])\n"
    "  # body_force: [0, -9.81]   # the same under its general name; not with gravity\n"
    "  # c0: a number (m/s), or factor*sqrt(2|g| height), or factor*speed (all > 0)\n"
    "  sound_speed: {factor: 10, height: 0.1143}\n"
    "  # sound_speed: {factor: 10, speed: 1.5}\n"
    "  # Keys marked (scheme) take numerics.scheme's value when left out; shown\n"
    "  # commented out with the default scheme's (riemann) value.\n"
    "  # artificial_viscosity:    # Monaghan's, paper A eq. (15)-(16)\n"
    "  #   alpha: 0               # >= 0 (scheme; delta_sph 0.02, the papers' cases their own)\n"
    "  #   beta: 0                # >= 0 (default 0)\n"
    "  #   eta: 0.1               # > 0 (default 0.1)\n"
    "  # viscosity:               # laminar viscosity (scheme: none; delta_sph morris 1e-3)\n"
    "  #   model: none            # none, stress_tensor, morris\n"
    "  #   mu: 1.0e-3             # Pa s, > 0: required with a model, an error without\n"
    "  #   gradient_correction: false  # stress_tensor only (default false)\n"
    "  turbulence:\n"
    "    model: none              # none (default), sps\n"
    "    # cs: 0.12               # sps: Smagorinsky C_s, > 0 (default 0.12)\n"
    "    # ci: 0.00066            # sps: C_I, >= 0 (default 0.00066)\n"
    "  # repulsion: 5.6           # repulsive walls' D (J/kg), > 0 (default 5 |g| H)\n"
    "  # xsph: 0                  # XSPH epsilon, [0, 1] (scheme: 0, off)\n"
    "  # riemann:                 # Riemann-solver pressure, Zhang et al. 2017, or off\n"
    "  #   limiter: 3             # (scheme: riemann on; the others off); >= 0 (default 3)\n"
    "  # negative_pressure: false # no tension: density held >= rho0 (scheme: false; others "
    "true)\n" AIR_BLOCK "\n"
    "numerics:\n"
    "  scheme: riemann            # the values of the keys marked (scheme) left out: riemann\n"
    "                             # (default), paper_a, paper_b, delta_sph (doc/method.md,\n"
    "                             # Schemes); a key written out is kept over its scheme\n"
    "  dx: 0.0028575              # m, > 0, smaller than every fluid block (required)\n"
    "  # h_factor: 2              # h = h_factor dx, [0.5, 4] (scheme: 2; the others 1.3)\n"
    "  smoothing_length: constant # constant (default), variable\n"
    "  # kernel: wendland_c2      # cubic_spline, wendland_c2 (scheme: wendland_c2; the others\n"
    "                             # cubic_spline)\n"
    "  # integrator: leapfrog     # predictor_corrector, leapfrog (scheme: leapfrog)\n"
    "  time_step:\n"
    "    # rule: cfl              # cfl, paper_b, fixed (scheme: cfl; the others paper_b)\n"
    "    factor: 0.3              # (0, 1] (default 0.3); unused by fixed\n"
    "    # dt: 1.0e-5             # s, > 0: fixed only (required there)\n"
    "  density_filter:\n"
    "    kind: none               # none (default), mls, shepard\n"
    "    every: 30                # steps, 1..1000000 (default 30)\n"
    "  # density_diffusion:       # (scheme: none; delta_sph antuono 0.1)\n"
    "  #   model: none            # none, molteni_colagrossi, antuono, fourtakas\n"
    "  #   delta: 0.1             # (0, 1] (default 0.1); only with a model\n"
    "  # shifting:                # particle shifting (default off)\n"
    "  #   coefficient: 2         # (0, 10] (default 2)\n"
    "  gradient_correction: false # pressure and continuity with L grad W (default false)\n"
    "  density_limit: 0.3         # stop when |rho/rho0 - 1| exceeds it, (0, 1) (default 0.3)\n"
    "\n"
    "time:\n"
    "  end: 0.5                   # s, > 0 (required)\n"
    "  output_interval: 0.01      # s, end/100000 to end (required unless output_times)\n"
    "  # output_times: [0.1, 0.2] # further output times (s), increasing\n"
    "  stop: front_at_wall        # none (default), front_at_wall (needs a tank)\n"
    "\n"
    "geometry:\n"
    "  tank:                      # a rectangular tank (default none)\n"
    "    x: [0, 0.2286]           # inner faces of the side walls (m), x0 < x1\n"
    "    y: [0, 0.2]              # the floor and the top of the walls (m), y0 < y1\n"
    "    # boundary: adami        # dynamic, fixed_layers, repulsive, mirror, mdbc, adami\n"
    "                             # (scheme: adami; paper_a, paper_b dynamic; delta_sph mdbc)\n"
    "    # layers: 4              # 1..8 (default 2, 3 for mdbc, ceil(2 h_factor) for adami;\n"
    "                             # none for mirror)\n"
    "    # stagger: true          # layers dx/2 apart and staggered (default true; false for "
    "mdbc and adami)\n"
    "    # extrapolated_velocity: false  # no slip on the face (stress_tensor or sps; not "
    "adami)\n"
    "    free_slip: false         # forces along the wall's normal only (default false)\n"
    "    # lid: false             # a closed top: the walls' layers over it too (default false)\n"
    "  fluid:                     # blocks: boxes or shapes (at least one)\n"
    "    - x: [0, 0.05715]\n"
    "      y: [0, 0.1143]\n"
    "      velocity: [0, 0]       # m/s (default [0, 0])\n"
    "      hydrostatic: true      # start from the hydrostatic density (default true)\n"
    "      surface: 0.1143        # the hydrostatic start's surface, >= y1 (default y1)\n"
    "      jitter: 0              # a perturbed start, [0, 0.5) dx (default 0)\n"
    "      # seed: 1              # the jitter's seed, 0..2147483647 (default 1)\n"
    "    # - polygon: [[0.1, 0], [0.2, 0], [0.1, 0.05]]  # instead of x, y: a simple polygon\n"
    "    # - circle: {centre: [0.15, 0.15], radius: 0.02}  # instead of x, y: a disc of water\n"
    "    #                        # (3-D: sphere:, cylinder:, mesh: {file: x.stl, scale, offset})\n"
    "  walls: []                  # extra straight walls (default none), e.g. a gate:\n"
    "  #  - from: [0.06, 0]       # start point (m); the fluid is on the right, seen from it\n"
    "  #    to: [0.06, 0.15]      # end point (m)\n"
    "  #    # points: [[0.06, 0], [0.08, 0.05], [0.1, 0.05]]  # instead of from, to: a polyline\n"
    "  #    boundary: adami       # as the tank's (default the scheme's, as the tank's)\n"
    "  #    layers: 2\n"
    "  #    stagger: true\n"
    "  #    extrapolated_velocity: false\n"
    "  #    free_slip: false\n"
    "  #    motion:               # none (default), translate, piston, flap\n"
    "  #      type: translate\n"
    "  #      velocity: [0, 1.5]  # translate: m/s\n"
    "  #      start: 0            # translate: s, >= 0 (default 0)\n"
    "  #      stop: 0.1           # translate: s, > start (default never)\n"
    "  #      # piston and flap: period (s, > 0), stroke or wave_height (m, > 0),\n"
    "  #      # depth (m, > 0), ramp (s, >= 0; default one period), hinge [x, y] (flap)\n"
    "  #      # period: 1.0\n"
    "  #      # stroke: 0.05\n"
    "  #      # wave_height: 0.03\n"
    "  #      # depth: 0.1\n"
    "  #      # ramp: 1.0\n"
    "  #      # hinge: [0.06, 0]\n"
    "  # obstacles:               # boxes of wall particles (any wall model but mirror)\n"
    "  #   - {x: [0.3, 0.35], y: [0, 0.05], layers: 2, boundary: dynamic}\n"
    "  # vessels:                 # shapes holding the water, a tank of any shape (the fluid\n"
    "  #   - {circle: {centre: [0.5, 0.5], radius: 0.3}}   # blocks cut to them; no tank then)\n"
    "  # periodic_x: [0, 1]       # periodic in x (no tank then), x1 - x0 >= 6 h\n"
    "  # periodic_y: [0, 1]       # 3-D only, as periodic_z: one periodic axis per case\n"
    "  # domain:                  # a fluid particle leaving it: see leaving (default: the\n"
    "  #   x: [-0.1, 0.33]        # geometry's box widened, doc/case-files.md)\n"
    "  #   y: [-0.1, 0.6]\n"
    "  # leaving: stop            # stop (a blow-up) or remove: taken out, booked (default stop)\n"
    "\n"
    "free_surface:                # detection, paper A section 7\n"
    "  radius_factor: 1           # [0.5, 1] (default 1)\n"
    "  # h_factor: 2              # h* = k h on the surface, [1, 4] (default off)\n"
    "\n"
    "output:\n"
    "  snapshots: true            # HDF5 snapshots at the output times (default true)\n"
    "  free_surface: false        # the free_surface field (default false)\n"
    "  energy: false              # the energy ledger's columns (default false)\n"
    "  # gauges: [0.1]            # wave gauges at these x (m): gauges.csv\n"
    "  probes:                    # probes.csv; at most 1000\n"
    "    - name: P1               # [A-Za-z0-9_.-], unique\n"
    "      kind: pressure         # pressure, level, velocity\n"
    "      at: [0.2286, 0.003]    # the point (m); on the right wall's face here\n"
    "      diameter: 0            # the face's width (m; pressure only, default 0: a point)\n"
    "      along: y               # y (default; a wall sensor), x (a floor sensor)\n"
    "      # low_pass: 1000         # Hz: also the sensor's first-order response (pressure only)\n"
    "      # points: 5              # face points, 1..64 (pressure; default 5)\n"
    "      # smoothing: 1           # the interpolation's h over the case's (default 1)\n"
    "      # clip_negative: false   # each particle's pressure below 0 read as 0\n"
    "      # hydrostatic: true      # pressures carried to the point along g (default true)\n"
    "      # wet_sum: 0.1           # the kernel sum below which a point is dry (default 0.1)\n"
    "    - name: H1\n"
    "      kind: level\n"
    "      x: 0.1                 # a level gauge's x (m)\n"
    "      # wetted: false          # true: a wire gauge's wetted length, not the top particle\n"
    "  probe_interval: 0.001      # s, 0 (every step, default) to time.end\n";

/* The lines of TEMPLATE that differ in 3-D: each `from` (a whole line, found
 * exactly once) becomes `to` (one line or more). */
static const struct {
  const char *from, *to;
} THREE_D[] = {
    {"dimension: 2                 # 2 or 3 (default 2); 3-D cases: doc/case-files.md\n",
     "dimension: 3                 # 2 or 3 (default 2); 3-D cases: doc/case-files.md\n"},
    {"  gravity: [0, -9.81]        # m/s^2 (default [0, -9.81])\n",
     "  gravity: [0, 0, -9.81]     # m/s^2, z up (2-D default [0, -9.81])\n"},
    {"  # body_force: [0, -9.81]   # the same under its general name; not with gravity\n",
     "  # body_force: [0, 0, -9.81]  # the same under its general name; not with gravity\n"},
    {"  dx: 0.0028575              # m, > 0, smaller than every fluid block (required)\n",
     "  dx: 0.005715               # m, > 0, smaller than every fluid block (required);\n"
     "                             # a/10: 2000 fluid particles, a quick start\n"},
    {"    y: [0, 0.2]              # the floor and the top of the walls (m), y0 < y1\n",
     "    y: [0, 0.05715]          # its width (m), y0 < y1\n"
     "    z: [0, 0.2]              # the floor and the top of the walls (m), z0 < z1\n"},
    {"    # stagger: true          # layers dx/2 apart and staggered (default true; false for "
     "mdbc and adami)\n",
     "    # stagger: false         # 2-D only so far: 3-D layers are dx apart\n"},
    {"      y: [0, 0.1143]\n", "      y: [0, 0.05715]\n      z: [0, 0.1143]\n"},
    {"      velocity: [0, 0]       # m/s (default [0, 0])\n",
     "      velocity: [0, 0, 0]    # m/s (default [0, 0, 0])\n"},
    {"      surface: 0.1143        # the hydrostatic start's surface, >= y1 (default y1)\n",
     "      surface: 0.1143        # the hydrostatic start's surface, >= z1 (default z1)\n"},
    {"    # - polygon: [[0.1, 0], [0.2, 0], [0.1, 0.05]]  # instead of x, y: a simple polygon\n",
     "    # - {polygon: [[0.1, 0], [0.2, 0], [0.1, 0.05]], y: [0, 0.05715]}  # instead of x, z:\n"
     "    #                        # a prism, the polygon's [x, z] across y (the tank's)\n"},
    {"    # - circle: {centre: [0.15, 0.15], radius: 0.02}  # instead of x, y: a disc of water\n",
     "    # - sphere: {centre: [0.15, 0.028575, 0.15], radius: 0.02}  # instead of x, y, z\n"
     "    # - cylinder: {from: [0.1, 0, 0.1], to: [0.1, 0.05715, 0.1], radius: 0.02}\n"
     "    # - mesh: {file: water.stl, scale: 0.001, offset: [0, 0, 0]}  # a closed STL, OBJ or\n"
     "    #                        # PLY surface, the file relative to this case's folder\n"},
    {"    #                        # (3-D: sphere:, cylinder:, mesh: {file: x.stl, scale, "
     "offset})\n",
     ""},
    {"  #  - from: [0.06, 0]       # start point (m); the fluid is on the right, seen from it\n",
     "  #  - from: [0.06, 0]       # [x, z] (m): a plate across the tank's y range; the fluid\n"
     "  #                          # on its right, seen from it with x right and z up\n"},
    {"  #    stagger: true\n", "  #    stagger: false      # 2-D only so far\n"},
    {"  #      velocity: [0, 1.5]  # translate: m/s\n",
     "  #      velocity: [0, 0, 1.5]  # translate: m/s\n"},
    {"  #      # hinge: [0.06, 0]\n", "  #      # hinge: [0.06, 0]    # [x, z]: a line along y\n"},
    {"  #   - {x: [0.3, 0.35], y: [0, 0.05], layers: 2, boundary: dynamic}\n",
     "  #   - {x: [0.15, 0.2], y: [0, 0.05715], z: [0, 0.05], layers: 2, boundary: dynamic}\n"},
    {"  #   - {circle: {centre: [0.5, 0.5], radius: 0.3}}   # blocks cut to them; no tank then)\n",
     "  #   - {sphere: {centre: [0.5, 0.5, 0.5], radius: 0.3}}  # or a cylinder, a polygon\n"
     "  #                          # prism or a closed mesh; blocks cut to them; no tank then)\n"},
    {"  #   y: [-0.1, 0.6]\n", "  #   y: [-0.1, 0.16]\n  #   z: [-0.1, 0.6]\n"},
    {"  # gauges: [0.1]            # wave gauges at these x (m): gauges.csv\n",
     "  # gauges: [[0.1, 0.028575]]  # wave gauges, vertical lines at these (x, y) (m)\n"},
    {"      at: [0.2286, 0.003]    # the point (m); on the right wall's face here\n",
     "      at: [0.2286, 0.028575, 0.003]  # the disc's centre (m), on the right wall's face\n"
     "      normal: [-1, 0, 0]     # its face's normal, toward the water (3-D, required)\n"},
    {"      along: y               # y (default; a wall sensor), x (a floor sensor)\n",
     "      # along: y             # 2-D only (3-D: normal)\n"},
    {"      # points: 5              # face points, 1..64 (pressure; default 5)\n",
     "      # points: 5              # face points, 1 or 5 in 3-D (pressure; default 5)\n"},
    {"      x: 0.1                 # a level gauge's x (m)\n",
     "      at: [0.1, 0.028575]    # a level gauge's vertical line (x, y) (m)\n"},
};

/* TEMPLATE with the air's block in place of AIR_BLOCK, into a new string;
 * NULL if out of memory. */
static char *template_2d(void) {
  char air[2048];
  const int n = sph_case_air_template(air, sizeof air);
  const char *at = strstr(TEMPLATE, AIR_BLOCK);
  if (n < 0 || n >= (int)sizeof air || !at) return NULL;
  const size_t head = (size_t)(at - TEMPLATE), len = strlen(TEMPLATE) - strlen(AIR_BLOCK) + n + 1;
  char *out = malloc(len);
  if (out) snprintf(out, len, "%.*s%s%s", (int)head, TEMPLATE, air, at + strlen(AIR_BLOCK));
  return out;
}

/* base (TEMPLATE's text) in 3-D (THREE_D's lines replaced) into a new string;
 * NULL if out of memory or a line of THREE_D is not in base once (a defect,
 * said on stderr). */
static char *template_3d(const char *base) {
  const size_t n_sub = sizeof THREE_D / sizeof THREE_D[0];
  size_t len = strlen(base) + 1;
  for (size_t k = 0; k < n_sub; k++)
    len += strlen(THREE_D[k].to);
  char *out = malloc(len), *w = out;
  if (!out) return NULL;
  const char *r = base;
  while (*r) {
    const char *eol = strchr(r, '\n');
    const size_t n = eol ? (size_t)(eol - r) + 1 : strlen(r);
    const char *to = NULL;
    for (size_t k = 0; k < n_sub && !to; k++)
      if (strlen(THREE_D[k].from) == n && !strncmp(r, THREE_D[k].from, n)) to = THREE_D[k].to;
    const size_t m = to ? strlen(to) : n;
    memcpy(w, to ? to : r, m);
    w += m, r += n;
  }
  *w = '\0';
  for (size_t k = 0; k < n_sub; k++) {
    const char *at = strstr(base, THREE_D[k].from);
    if (!at || strstr(at + 1, THREE_D[k].from)) {
      fprintf(stderr, "sph new: the 3-D template's line is not in the 2-D one once: %s",
              THREE_D[k].from);
      free(out);
      return NULL;
    }
  }
  return out;
}

static void new_usage(FILE *f) {
  fprintf(f, "usage: sph new NAME [-o FILE] [--dim 2|3]\n"
             "\n"
             "Writes a case file to start from, NAME.yaml (or FILE): a small dam break\n"
             "that runs as written, with every key of a case file set or shown commented\n"
             "out with its default and range. It will not overwrite a file.\n"
             "\n"
             "  -o, --output FILE  where to write it (default NAME.yaml)\n"
             "      --dim D        2 (default) or 3: the dam break in 3-D (z up, the tank\n"
             "                     one column wide, dx = a/10), its keys in their 3-D form\n");
}

/* The case file for name: its name line, then TEMPLATE (in 3-D when dim
 * is 3); NULL if out of memory. */
static char *case_text(const char *name, int dim) {
  char *base = template_2d();
  char *body = base && dim == 3 ? template_3d(base) : base;
  if (body != base) free(base);
  if (!body) return NULL;
  const size_t n = strlen("name: \n") + strlen(name) + strlen(body) + 1;
  char *text = malloc(n);
  if (text) snprintf(text, n, "name: %s\n%s", name, body);
  free(body);
  return text;
}

int sph_cli_new(int argc, char **argv) {
  const char *name = NULL, *out = NULL;
  int dim = 2;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) {
      new_usage(stdout);
      return 0;
    }
    if (!strcmp(argv[i], "-o") || !strcmp(argv[i], "--output")) {
      if (i + 1 >= argc) {
        fprintf(stderr, "sph new: option %s needs a value\n", argv[i]);
        return 2;
      }
      out = argv[++i];
    } else if (!strcmp(argv[i], "--dim")) {
      if (i + 1 >= argc || (strcmp(argv[i + 1], "2") && strcmp(argv[i + 1], "3"))) {
        fprintf(stderr, "sph new: --dim: expected 2 or 3, got '%s'\n",
                i + 1 < argc ? argv[i + 1] : "");
        return 2;
      }
      dim = argv[++i][0] - '0';
    } else if (argv[i][0] == '-' && argv[i][1]) {
      fprintf(stderr, "sph new: unknown option '%s'\n", argv[i]);
      new_usage(stderr);
      return 2;
    } else if (name) {
      fprintf(stderr, "sph new: one NAME only, got '%s' and '%s'\n", name, argv[i]);
      return 2;
    } else {
      name = argv[i];
    }
  }
  if (!name) {
    new_usage(stderr);
    return 2;
  }
  if (dim != SPH_DIM) return sph_cli_hand_over_dim("new", name, dim); /* (twin.c) */
  char path[4200];
  if (!out) {
    snprintf(path, sizeof path, "%s.yaml", name);
    out = path;
  }
  /* the case reader checks what is written, the name's rule included */
  char *text = case_text(name, dim);
  if (!text) {
    fprintf(stderr, "sph new: out of memory\n");
    return 1;
  }
  sph_case c;
  sph_error err;
  int rc = sph_case_parse(text, strlen(text), out, NULL, 0, &c, &err);
  if (rc == 0 && strcmp(c.name, name) != 0)
    rc = sph_error_set(&err, "%s: NAME '%s' reads as the name '%s': not a case name", out, name,
                       c.name);
  sph_case_free(&c);
  if (rc) {
    /* the name's rule, not a file: nothing was written (issue 61, E12) */
    const char *why = strstr(err.msg, ": name: ");
    if (why)
      fprintf(stderr, "sph new: NAME '%s': %s (nothing written)\n", name, why + 8);
    else
      fprintf(stderr, "sph new: %s\n", err.msg);
    free(text);
    return 2;
  }
  /* never over an existing file: O_EXCL */
  const int fd = open(out, O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) {
    fprintf(stderr, "sph new: cannot create %s: %s\n", out,
            errno == EEXIST ? "it exists (choose another name or -o FILE)" : strerror(errno));
    free(text);
    return 1;
  }
  FILE *f = fdopen(fd, "w");
  int bad = f == NULL;
  if (f) {
    bad |= fputs(text, f) < 0;
    bad |= fclose(f) != 0;
  } else {
    close(fd);
  }
  free(text);
  if (bad) {
    fprintf(stderr, "sph new: cannot write %s: %s\n", out, strerror(errno));
    unlink(out);
    return 1;
  }
  printf("sph new: wrote %s; run it with: sph run %s\n", out, out);
  return 0;
}
