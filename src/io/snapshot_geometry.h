/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * snapshot_geometry.h - the case's geometry as data in every snapshot: the
 * group /geometry (doc/snapshot-format.md), written by the run from its
 * case and read back by any reader of snapshots (the renderer draws the
 * tank and the obstacles from it, `sph info` lists it), so that no reader
 * parses the case's text again.
 *
 *   attribute format   1
 *   attribute dimension 2 or 3
 *   tank        float64 [2 dim]: x0, x1, y0, y1 (, z0, z1), the inner box of
 *               the tank's faces (absent: no tank)
 *   obstacles   float64 [n, 2 dim]: each box x0, x1, y0, y1 (, z0, z1)
 *   walls       float64 [n, 2 dim]: each wall's two ends at t = 0, (x0, y0,
 *               x1, y1) in 2-D; in 3-D the plate's corners (x0, y0, z0, x1,
 *               y1, z1): the segment (x0, z0)-(x1, z1) across y0 .. y1
 *   probe_position float64 [n, dim]: each probe's point; a level gauge's
 *               line is vertical, its height component 0
 *   probe_name, probe_kind  fixed-length strings [n] (kind: pressure,
 *               level or velocity)
 * A dataset with no rows is absent. Snapshots written before the group
 * existed have none (sph_snapshot_read_geometry says so).
 *
 * The struct holds every dimension's layout (three axes), so a reader
 * built for 2-D reads a 3-D file's geometry too: dim says how many
 * components of each row count.
 */
#ifndef SPH_SNAPSHOT_GEOMETRY_H
#define SPH_SNAPSHOT_GEOMETRY_H

#include <stddef.h>

#include "core/error.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SPH_GEOMETRY_FORMAT 1
#define SPH_GEOMETRY_NAME 65 /* a probe's name, with its NUL */
#define SPH_GEOMETRY_KIND 16 /* a probe's kind, with its NUL */

typedef struct sph_snapshot_geometry {
  int dim; /* 2 or 3: the first 2 dim (dim) numbers of each row count */
  int has_tank;
  double tank[6];
  size_t n_obstacles;
  double (*obstacles)[6];
  size_t n_walls;
  double (*walls)[6];
  size_t n_probes;
  double (*probe_position)[3];
  char (*probe_name)[SPH_GEOMETRY_NAME];
  char (*probe_kind)[SPH_GEOMETRY_KIND];
} sph_snapshot_geometry;

struct sph_snapshot;

/* The group /geometry of an open snapshot into *g (its arrays malloc'ed:
 * sph_snapshot_geometry_free). Returns 0, 1 if the snapshot has no such
 * group (written by an earlier build; *g is then empty), or -1 with err. */
int sph_snapshot_read_geometry(const struct sph_snapshot *s, sph_snapshot_geometry *g,
                               sph_error *err);
/* Frees what sph_snapshot_read_geometry (or sph_sim's set-up) allocated;
 * leaves *g empty. */
void sph_snapshot_geometry_free(sph_snapshot_geometry *g);

#ifdef __cplusplus
}
#endif

#endif
