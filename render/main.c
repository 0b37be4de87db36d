/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * main.c - sph-render: SPH snapshots to PNG frames, figures and plots,
 * and 3-D free surfaces to PLY meshes, off screen (OSMesa or surfaceless EGL).
 *
 * Only main decides what to print and the exit status: 0 when every image
 * was written, 1 when anything failed (a bad command line, an unreadable
 * snapshot, a missing field...). Errors name the file and the field or
 * option at fault. Images are written atomically (png_out.c), so a failure
 * never leaves a partial PNG.
 */
#include "config.h"

#include <stdio.h>

#include "cli.h"
#include "mesh_run.h"
#include "plot.h"
#include "sequence.h"

int main(int argc, char **argv) {
  const char *prog = "sph-render";
  roptions o;
  sph_error err = {""};
  int rc = rcli_parse(argc, argv, &o, &err);
  if (rc == 1) return 0;
  if (rc != 0) {
    fprintf(stderr, "%s: %s\n", prog, err.msg);
    return 1;
  }
  if (o.mode == RMODE_PLOT)
    rc = rplot_run(&o, &err);
  else if (o.mode == RMODE_MESH)
    rc = rmesh_run(&o, prog, &err);
  else
    rc = rsequence_run(&o, prog, &err);
  if (rc != 0) {
    fprintf(stderr, "%s: %s\n", prog, err.msg);
    return 1;
  }
  return 0;
}
