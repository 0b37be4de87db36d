/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * snapdata.h - what the renderer needs from one snapshot: positions, one
 * field, which particles are walls, the time, the particle spacing and the
 * default view. Read only through src/io/snapshot.h.
 *
 * Field names are the snapshot's dataset names (x y vx vy rho p mass h u
 * kind id free_surface ...; z and vz in 3-D) plus "speed" = |v| (derived
 * from vx, vy and, in 3-D, vz) and the aliases "pressure" (p) and
 * "density" (rho). Snapshots of either dimension are read.
 */
#ifndef SPH_RENDER_SNAPDATA_H
#define SPH_RENDER_SNAPDATA_H

#include <stddef.h>
#include <stdint.h>

#include "core/error.h"

typedef struct rsnap {
  char *path;
  double time;
  size_t n;            /* particles */
  int dim;             /* 2 or 3 (the file's attribute "dimension") */
  double *x, *y;       /* positions (m) */
  double *z;           /* 3-D: the vertical position (m); NULL in 2-D */
  double *val;         /* the field, or NULL if none was asked for */
  uint8_t *wall;       /* 1 for wall particles (kind != 0) */
  double dx;           /* particle spacing (attribute dx), NaN if absent */
  double view[4];      /* x0, x1, y0, y1 (attribute view), NaN if absent */
  double box[6];       /* 3-D: x0, x1, y0, y1, z0, z1 (attribute view), NaN if absent */
  char case_name[128]; /* "" if absent */
  char units[32];      /* the field's `units` attribute ("m/s"), "" if none */
  double *h, *vol;     /* smoothing length, volume m / rho: NULL until rsnap_load_volumes */
  int kernel;          /* the case's kernel (interp.h), with the volumes */
  double *off;         /* a 3-D slice (slice.h): each particle's distance from the plane,
                          NULL otherwise */
  double slab;         /* with off: discs show the particles with |off| <= slab */
  size_t *rows;        /* a two-phase run's file without its air: the file's row of each
                          particle here (n of them); NULL: every row */
  size_t n_file;       /* the file's particles */
} rsnap;

/* The dataset a field name reads ("pressure" -> "p"); "speed" stays. */
const char *rsnap_canonical(const char *field);
/* The units of a field as a snapshot's `units` attribute gives them
 * ("m/s"; speed has those of vx), into buf; "" if it has none. */
int rsnap_units(const char *path, const char *field, char *buf, size_t size, sph_error *err);
/* Non-zero for fields whose values are signed around zero (vx, vy, vz). */
int rsnap_signed(const char *field);

/* Loads path and, if field is not NULL, that field. Errors name the file
 * and the field (listing the fields the file has). A two-phase run's
 * snapshot (field `phase`) loads without its air (phase 1): the liquid's
 * particles and the walls, its surface drawn as a one-phase run's. */
int rsnap_load(const char *path, const char *field, rsnap *s, sph_error *err);
/* The same, with the air too where `air` (sph-render --air). */
int rsnap_load_phases(const char *path, const char *field, int air, rsnap *s, sph_error *err);
/* Reads only the time (and the view, NaN if absent) of a snapshot. */
int rsnap_peek(const char *path, double *time, double view[4], sph_error *err);
/* Adds each particle's smoothing length and volume and the case's kernel
 * to a loaded snapshot (for the interpolated view, interp.h). */
int rsnap_load_volumes(rsnap *s, sph_error *err);
void rsnap_free(rsnap *s);
/* Minimum and maximum of the field over fluid particles with finite values;
 * returns how many values there were (0: lo, hi untouched). */
size_t rsnap_fluid_range(const rsnap *s, double *lo, double *hi);

#endif
