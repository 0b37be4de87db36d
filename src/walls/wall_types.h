/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * wall_types.h - how a case describes its walls: the boundary model of
 * wall particles, the tank, extra wall segments and the prescribed motion
 * of a wall (a gate, a piston or flap paddle). Types only: the case schema
 * (src/case/) fills them in, the wall builder (boundary.h) and the motion
 * law (motion.h) act on them.
 */
#ifndef SPH_WALL_TYPES_H
#define SPH_WALL_TYPES_H

#include "core/dim.h"
#include "walls/wavemaker.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
  SPH_BOUNDARY_DYNAMIC = 0,      /* dynamic particles, GOST R 57700.6 3.4.7; paper B §2.7 */
  SPH_BOUNDARY_FIXED_LAYERS = 1, /* Morris' fixed layers (paper A §6 b): the same particles */
  SPH_BOUNDARY_REPULSIVE = 2,    /* one layer + Lennard-Jones force, paper A eq. (21)-(22) */
  SPH_BOUNDARY_MIRROR = 3,       /* mirror particles, GOST R 57700.6 3.4.5 */
  SPH_BOUNDARY_MDBC = 4,         /* dynamic particles whose density is the fluid's extrapolated
                                    across the face (English et al. 2022; wall_velocity.h) */
  SPH_BOUNDARY_ADAMI = 5         /* particles whose pressure is the fluid's extrapolated with the
                                    hydrostatic term (Adami, Hu & Adams 2012; adami.h) */
} sph_boundary_kind;

/* A rectangular tank: inner faces at x0 (left), x1 (right), y0 (floor); the
 * side walls rise to y1. Wall particles sit outside the inner faces. In 3-D
 * (core/dim.h) a box: faces at x0, x1, y0, y1 (front, back), the floor at
 * z0, the walls rising to z1. */
typedef struct sph_tank {
  int present;
  SPH_COMPONENTS(double, lo, x0, y0, z0); /* the inner box's lower corner (m) */
  SPH_COMPONENTS(double, hi, x1, y1, z1); /* its upper corner: the side walls' top in z (y) */
  int layers;                             /* wall layers, default 2 (staggered) */
  sph_boundary_kind boundary;             /* default dynamic */
  int stagger;      /* layers dx/2 apart and staggered (default), or dx apart */
  int extrapolated; /* no-slip: extrapolated wall velocity (src/wall_velocity.h) */
  int free_slip;    /* pressure and artificial viscosity along the faces' normals */
  int open_along;   /* 3-D: 0, or 1 + the axis (x or y) along which the tank has no
                       faces (the case's periodic axis) */
  int lid;          /* a closed top: the walls' layers over it too (geometry.tank.lid) */
} sph_tank;

/* Prescribed motion of a wall (a gate): translation at a constant velocity
 * from `start` to `stop`, at rest before and after. */
typedef enum {
  SPH_MOTION_NONE = 0,
  SPH_MOTION_TRANSLATE = 1, /* constant velocity from start to stop (a gate) */
  SPH_MOTION_PISTON = 2,    /* wavemaker piston, X(t) = (S/2) sin(omega t), paper B §4.2 */
  SPH_MOTION_FLAP = 3 /* bottom-hinged flap with the same displacement at the still-water level */
} sph_motion_kind;
typedef struct sph_motion {
  sph_motion_kind kind;
  SPH_COMPONENTS(double, v, vx, vy, vz); /* translate: velocity while moving (m/s) */
  double start, stop; /* translate: time interval of the motion (s); stop may be INFINITY */
  sph_paddle paddle;  /* piston and flap (src/wavemaker.h) */
} sph_motion;

/* An extra straight wall from (x0,y0) to (x1,y1): particles spaced dx along
 * it, `layers` staggered layers on its left side (seen from start to end).
 * In 3-D a plate across the flume: the segment from (x0, z0) to (x1, z1) in
 * the x-z plane (its left side seen with x to the right and z up), extruded
 * along y from y0 to y1; its layers dx apart. */
typedef struct sph_wall_segment {
  double x0, y0, x1, y1;
#if SPH_DIM == 3
  double z0, z1;
#endif
  int layers;
  sph_boundary_kind boundary;
  sph_motion motion; /* default none (fixed) */
  int stagger;       /* as sph_tank */
  int extrapolated;  /* as sph_tank */
  int free_slip;     /* as sph_tank */
} sph_wall_segment;

/* A box obstacle (geometry.obstacles): wall particles on the lattice lo[a] + (i + 1/2) dx
 * inside the box, so that its faces lie dx/2 outside the outermost particles as the tank's
 * do, `layers` deep behind every face (solid where the box is thinner). A shaped obstacle (a
 * circle, sphere, cylinder, polygon or mesh of the case, src/case/shape.h) is the box of its
 * bounding box with `inside` set: its particles are the lattice points inside the shape that
 * have a point outside within `layers` spacings along every axis, and no guard keeps the
 * fluid off it (walls.h) but the particles' own forces. */
typedef struct sph_obstacle {
  double lo[SPH_DIM], hi[SPH_DIM]; /* the box's faces (a shape's bounding box, moved out to the
                                      fluid's lattice: case/geometry.c) */
  int layers;                      /* default 2, as a 3-D tank's */
  sph_boundary_kind boundary;      /* dynamic (default), fixed_layers or mdbc */
  int (*inside)(const void *shape, const double *x); /* a shaped obstacle's inside (1; 0
                                                        outside; other: crossing itself) */
  void (*offset)(const void *shape, const double *x, double floor, double *m); /* its mirror
                           offsets (the surface at or below the floor's height no way out) */
  const void *shape;                                                           /* their argument */
  int vessel; /* a vessel (geometry.vessels): the fluid inside the shape, the shell outside it */
} sph_obstacle;

#ifdef __cplusplus
}
#endif

#endif
