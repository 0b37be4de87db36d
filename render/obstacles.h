/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * obstacles.h - the boxes of a 3-D snapshot's obstacles as a lit mesh of
 * their faces for a 3-D view (scene3d.h). A snapshot records them in its
 * group /geometry (io/snapshot_geometry.h); for snapshots written before
 * it, robstacles_parse and robstacles_tank read the boxes (the case's
 * `geometry.obstacles`, each x, y and z a range) and the tank's box from
 * the snapshot's `parameters` listing.
 */
#ifndef SPH_RENDER_OBSTACLES_H
#define SPH_RENDER_OBSTACLES_H

#include "core/error.h"
#include "isosurface.h"

#define ROBSTACLES_MAX 64

/* The boxes (x0, x1, y0, y1, z0, z1) listed in parameters as
 * "geometry.obstacles[K].x: [a, b]" (and .y, .z) for K = 0, 1, ...; how
 * many (at most max), 0 if none or parameters is NULL. */
int robstacles_parse(const char *parameters, double (*box)[6], int max);

/* The tank's box (its inner faces, "geometry.tank.x: [a, b]", .y, .z);
 * -1 if not listed. */
int robstacles_tank(const char *parameters, double box[6]);

/* The faces of the n boxes as a mesh: two triangles a face, four
 * vertices with the face's outward normal. */
int robstacles_mesh(const double (*box)[6], int n, rmesh *m, sph_error *err);

#endif
