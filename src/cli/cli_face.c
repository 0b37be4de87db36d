/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * cli_face.c - `sph face [--help] SNAPSHOT...`: the front face of a
 * breaking wave in each snapshot (wave_face.h), and the first time it
 * stands vertical (paper B §4.3).
 *
 * Prototype (declared in src/cli/cli.h):
 *   int sph_cli_face(int argc, char **argv);
 * argv[0] is "face". The still-water level is the top of the case's
 * highest fluid block, dx the case's spacing, and the window the fluid
 * blocks' x range, all read from the case stored in the snapshot (with its
 * --set overrides). Prints a header line starting with '#', one line
 * "time crest_x crest_y toe_x angle_deg" per file in the order given
 * ("nan" when there is no face to measure), then a line
 * "# first vertical: t = T (FILE)" for the first file whose angle is at
 * least 90 degrees, or "# first vertical: not reached".
 * Exit status: 0 every file was read, 1 a file failed, 2 usage error.
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "sph.h"

static const char USAGE[] =
    "usage: sph face [--help] SNAPSHOT...\n"
    "Measures the front face of the highest wave crest in each snapshot (a wave\n"
    "running towards +x, paper B §4.3). With d the still-water level (top of the\n"
    "case's highest fluid block) and dx the case's spacing:\n"
    "  crest  the highest fluid particle over the fluid blocks' x range;\n"
    "  face   from y_lo = d + (crest_y - d)/4 up to the crest; in each band of\n"
    "         height dx the leading (largest) x of the fluid between the crest\n"
    "         and the toe (the first dx-wide column ahead whose water is below y_lo);\n"
    "  angle  90 + atan(slope of leading x against height), in degrees:\n"
    "         < 90 leaning back, 90 vertical, > 90 overhanging (a jet).\n"
    "Prints one line per file, in the order given:\n"
    "  time crest_x crest_y toe_x angle_deg\n"
    "then the first file whose face is at least vertical:\n"
    "  # first vertical: t = T (FILE)      or      # first vertical: not reached\n"
    "Heights are y in 2-D and z in 3-D (crest_y is then the crest's height), and a\n"
    "3-D snapshot's face is that of the water seen from the side (the whole width).\n"
    "Exit status: 0 all read, 1 a file failed, 2 usage error.\n";

/* Measures one file and prints its line; *angle gets the angle (NaN if
 * none) and *t the time. 0, or -1 with err. */
static int measure(const char *path, double *t, double *angle, sph_error *err) {
  sph_snapshot *s;
  if (sph_snapshot_open(path, &s, err)) return -1;
  sph_case c;
  if (sph_cli_snapshot_case(s, &c, err)) {
    sph_snapshot_close(s);
    return -1;
  }
  double level = -INFINITY, x0 = INFINITY, x1 = -INFINITY;
  for (size_t b = 0; b < c.n_fluid; b++) {
#if SPH_DIM == 3
    const double top = c.fluid[b].z1; /* z up */
#else
    const double top = c.fluid[b].y1;
#endif
    if (top > level) level = top;
    if (c.fluid[b].x0 < x0) x0 = c.fluid[b].x0;
    if (c.fluid[b].x1 > x1) x1 = c.fluid[b].x1;
  }
  const double dx = c.dx;
  sph_case_free(&c);
  sph_particles p;
  if (sph_snapshot_read_particles(s, &p, err)) {
    sph_snapshot_close(s);
    return -1;
  }
  *t = sph_snapshot_time(s);
  sph_snapshot_close(s);
  sph_wave_face f;
  const int rc = sph_wave_face_measure(&p, level, dx, x0, x1, &f, err);
  sph_particles_free(&p);
  if (rc < 0) return -1;
  *angle = f.angle;
  printf("%.9g %.9g %.9g %.9g %.4f\n", *t, f.crest_x, f.crest_y, f.toe_x, f.angle);
  return 0;
}

/* Measures one file; the first one at least vertical is announced.
 * found points to the flag "already announced". */
static int measure_one(const char *path, void *found, sph_error *err) {
  double t, angle;
  if (measure(path, &t, &angle, err)) return -1;
  if (!*(int *)found && angle >= 90.0) {
    printf("# first vertical: t = %.9g (%s)\n", t, path);
    *(int *)found = 1;
  }
  return 0;
}

int sph_cli_face(int argc, char **argv) {
  int n_files;
  const int rc = sph_cli_snapshot_args("face", USAGE, argc, argv, &n_files);
  if (rc != 0) return rc < 0 ? 0 : rc;
  printf("# time crest_x crest_y toe_x angle_deg (front face; see sph face --help)\n");
  int found = 0;
  const int status = sph_cli_each_snapshot("face", argc, argv, measure_one, &found);
  if (!found) printf("# first vertical: not reached\n");
  return status;
}
