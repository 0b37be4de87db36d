/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * geometry_record.c - the case's geometry as every snapshot records it
 * (the group /geometry, io/snapshot_geometry.h): the tank's inner box, the
 * obstacles, the walls at t = 0 and the probes, made once by
 * sph_sim_create.
 */
#include "config.h"

#include "solver/sim_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A wall's two ends as corners: (x0, y0, x1, y1) in 2-D; in 3-D (x0, y0,
 * z0, x1, y1, z1), the segment (x0, z0)-(x1, z1) across y0 .. y1. */
static void wall_corners(const sph_wall_segment *w, double out[6]) {
  memset(out, 0, 6 * sizeof *out);
  const double c[2 * SPH_DIM] = {SPH_XYZ(w->x0, w->y0, w->z0), SPH_XYZ(w->x1, w->y1, w->z1)};
  memcpy(out, c, sizeof c);
}

int sph_sim_record_geometry(const sph_case *c, sph_snapshot_geometry *g, sph_error *err) {
  memset(g, 0, sizeof *g);
  g->dim = SPH_DIM;
  if (c->tank.present) {
    g->has_tank = 1;
    const double t[2 * SPH_DIM] = {SPH_XYZ(c->tank.x0, c->tank.y0, c->tank.z0),
                                   SPH_XYZ(c->tank.x1, c->tank.y1, c->tank.z1)};
    for (int a = 0; a < SPH_DIM; a++) { /* x0, x1, y0, y1 (, z0, z1) */
      g->tank[2 * a] = t[a];
      g->tank[2 * a + 1] = t[SPH_DIM + a];
    }
  }
  const size_t no = c->n_obstacles, nw = c->n_walls, nq = c->n_probes;
  g->obstacles = calloc(no ? no : 1, sizeof *g->obstacles);
  g->walls = calloc(nw ? nw : 1, sizeof *g->walls);
  g->probe_position = calloc(nq ? nq : 1, sizeof *g->probe_position);
  g->probe_name = calloc(nq ? nq : 1, sizeof *g->probe_name);
  g->probe_kind = calloc(nq ? nq : 1, sizeof *g->probe_kind);
  if (!g->obstacles || !g->walls || !g->probe_position || !g->probe_name || !g->probe_kind) {
    sph_snapshot_geometry_free(g);
    return sph_error_set(err, "out of memory for the snapshot's geometry");
  }
  g->n_obstacles = 0; /* the boxes: a shaped obstacle is its wall particles only */
  for (size_t k = 0; k < no; k++) {
    if (c->obstacles[k].inside) continue;
    for (int a = 0; a < SPH_DIM; a++) {
      g->obstacles[g->n_obstacles][2 * a] = c->obstacles[k].lo[a];
      g->obstacles[g->n_obstacles][2 * a + 1] = c->obstacles[k].hi[a];
    }
    g->n_obstacles++;
  }
  g->n_walls = nw;
  for (size_t k = 0; k < nw; k++)
    wall_corners(&c->walls[k], g->walls[k]);
  g->n_probes = nq;
  for (size_t k = 0; k < nq; k++) {
    const sph_probe *q = &c->probes[k];
    const double at[SPH_DIM] = {SPH_XYZ(q->x, q->y, q->z)};
    for (int a = 0; a < SPH_DIM; a++)
      g->probe_position[k][a] = at[a];
    if (q->kind == SPH_PROBE_LEVEL) g->probe_position[k][SPH_UP] = 0.0; /* a vertical line */
    snprintf(g->probe_name[k], sizeof g->probe_name[k], "%s", q->name);
    snprintf(g->probe_kind[k], sizeof g->probe_kind[k], "%s", sph_probe_kind_name(q->kind));
  }
  return 0;
}
