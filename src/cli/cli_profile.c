/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * cli_profile.c - `sph profile [--help] SNAPSHOT...`: the error of a film
 * flow down an inclined plane against its steady profile, paper A eq. (26).
 *
 * Prototype (declared in src/cli/cli.h):
 *   int sph_cli_profile(int argc, char **argv);
 * argv[0] is "profile". Each snapshot carries the text of the case it was
 * run from and the --set overrides of the run (one per line); they are
 * parsed again with sph_case_parse, so the physics is exactly the run's:
 *   g  = the body force along x (physics.body_force[0], g sin(alpha)),
 *   nu = mu / rho0 (physics.viscosity.mu, physics.rho0),
 *   L  = the height of the (single) fluid block, y0 = its bottom (the bed),
 *        heights along the vertical axis: y in 2-D, z in 3-D.
 * Then, over the fluid particles of the snapshot (analytic.h),
 *   max  = 100 max_i |vx_i - v(y_i - y0)| / v_max,
 *   L2   = 100 sqrt(mean_i (vx_i - v(y_i - y0))^2) / v_max,
 * with v(y) = (g/nu)(L - y/2) y and v_max = g L^2/(2 nu), and one line
 * "time max L2" is printed per file (%.9g), in the order given, after a
 * header line starting with '#'.
 *
 * Invariants: uses only the public reading API (snapshot.h, case.h), like
 * any other reader. A file that fails (unreadable, no case text, a case
 * without laminar viscosity, without a positive body force along x, or with
 * other than one fluid block) is reported on stderr as
 * "sph profile: <message>" (the message names the file) and the others are still processed; the
 * exit status is 0 if every file was measured, 1 if any failed, 2 for a
 * usage error.
 */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "sph.h"

static const char USAGE[] =
    "usage: sph profile [--help] SNAPSHOT...\n"
    "Measures the velocity of a film flow down an inclined plane (paper A §7)\n"
    "against the steady profile of paper A eq. (26),\n"
    "  v(y) = (g/nu) (L - y/2) y,  v_max = g L^2 / (2 nu),\n"
    "with g the body force along x, nu = mu/rho0 and L the height of the fluid\n"
    "block above its bottom y0 (the bed), all read from the case stored in the\n"
    "snapshot (with its --set overrides). For each file prints one line\n"
    "  time max_rel_error_pct l2_rel_error_pct\n"
    "over the N fluid particles i (y_i measured from the bed):\n"
    "  max = 100 max_i |vx_i - v(y_i)| / v_max\n"
    "  L2  = 100 sqrt( sum_i (vx_i - v(y_i))^2 / N ) / v_max\n"
    "Heights are y in 2-D and z in 3-D (the vertical axis).\n"
    "Exit status: 0 all measured, 1 a file failed, 2 usage error.\n";

/* g, nu, L and y0 of the case stored in s; 0, or -1 with err. */
static int film_parameters(const sph_snapshot *s, double *g, double *nu, double *L, double *y0,
                           sph_error *err) {
  sph_case c;
  if (sph_cli_snapshot_case(s, &c, err)) return -1;
  int rc = 0;
  if (c.viscosity == SPH_VISCOSITY_NONE || !(c.mu > 0.0))
    rc = sph_error_set(err,
                       "%s: the case has no laminar viscosity (physics.viscosity): no film flow",
                       sph_snapshot_path(s));
  else if (!(c.gravity[0] > 0.0))
    rc = sph_error_set(err, "%s: the case's body force along x is %g, not positive: no film flow",
                       sph_snapshot_path(s), c.gravity[0]);
  else if (c.n_fluid != 1)
    rc = sph_error_set(err, "%s: the case has %zu fluid blocks; the film is one block",
                       sph_snapshot_path(s), c.n_fluid);
  if (rc == 0) {
    *g = c.gravity[0];
    *nu = c.mu / c.rho0;
#if SPH_DIM == 2
    *y0 = c.fluid[0].y0;
    *L = c.fluid[0].y1 - c.fluid[0].y0;
#else /* the vertical axis is z (doc/dimensions.md) */
    *y0 = c.fluid[0].z0;
    *L = c.fluid[0].z1 - c.fluid[0].z0;
#endif
  }
  sph_case_free(&c);
  return rc;
}

/* Measures one file and prints its line; 0, or -1 with err. */
static int measure(const char *path, void *ctx, sph_error *err) {
  (void)ctx;
  sph_snapshot *s;
  if (sph_snapshot_open(path, &s, err)) return -1;
  double g = 0.0, nu = 0.0, L = 0.0, y0 = 0.0;
  if (film_parameters(s, &g, &nu, &L, &y0, err)) {
    sph_snapshot_close(s);
    return -1;
  }
  sph_particles p;
  if (sph_snapshot_read_particles(s, &p, err)) {
    sph_snapshot_close(s);
    return -1;
  }
  double emax, el2;
  const long nf = sph_film_error(&p, g, nu, L, y0, &emax, &el2);
  const double t = sph_snapshot_time(s);
  sph_particles_free(&p);
  sph_snapshot_close(s);
  if (nf < 0) return sph_error_set(err, "%s: no fluid particles", path);
  printf("%.9g %.9g %.9g\n", t, 100.0 * emax, 100.0 * el2);
  return 0;
}

int sph_cli_profile(int argc, char **argv) {
  int n_files;
  const int rc = sph_cli_snapshot_args("profile", USAGE, argc, argv, &n_files);
  if (rc != 0) return rc < 0 ? 0 : rc;
  printf("# time max_rel_error_pct l2_rel_error_pct (paper A eq. 26; see sph profile --help)\n");
  return sph_cli_each_snapshot("profile", argc, argv, measure, NULL);
}
