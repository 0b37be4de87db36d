/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * boundary.h - wall particles: where they are created.
 *
 * Walls are made of dynamic particles (paper B §2.7; GOST R 57700.6 3.4.7):
 * fixed in place, with density from the continuity equation and pressure
 * from the equation of state. A wall is a line of particles spaced about
 * dx, plus further layers each dx/2 further out and staggered by half a
 * spacing along the wall (paper B: two staggered layers), or, unstaggered,
 * layers dx apart on the fluid's lattice continued into the wall (Morris
 * et al. 1997, paper A's "Morris particles").
 */
#ifndef SPH_BOUNDARY_H
#define SPH_BOUNDARY_H

#include "core/error.h"
#include "core/particles.h"
#include "walls/wall_types.h"

#include <stdint.h>

/* Adds `layers` layers of wall particles along the segment A->B, layer 0
 * on the segment (spacing len/round(len/dx)). Staggered (stagger != 0):
 * layer k is offset by k dx/2 to the left of the direction A->B, and odd
 * layers sit half a spacing along and reach half a spacing past both ends.
 * Unstaggered: layer k is offset by k dx, at the same positions along the
 * wall as layer 0 (the fluid's lattice continued), every layer reaching
 * `extend` spacings past both ends (a tank floor under its side walls;
 * ignored when staggered).
 * Each particle gets density rho, mass, smoothing length h, `flags`, and
 * its mirror offset (mx, my): twice its distance to the wall face, which
 * lies dx/2 in front of layer 0 on the right of A->B (the fluid side),
 * along the face's normal into the fluid. */
#if SPH_DIM == 2
int sph_boundary_add_segment(sph_particles *p, double ax, double ay, double bx, double by,
                             int layers, int stagger, int extend, double dx, double rho,
                             double mass, double h, uint8_t flags, sph_error *err);
#else
/* The 3-D wall segment w (wall_types.h), a plate across the flume: the
 * segment A = (x0, z0) -> B = (x1, z1) in the x-z plane with its points
 * spaced len/round(len/dx) along it, each repeated along y at
 * y0 + (j + 1/2) s_y, j = 0 .. n_y - 1, n_y = round((y1 - y0)/dx) (at least
 * 1), s_y = (y1 - y0)/n_y (the fluid's lattice across a tank or period of
 * a whole number of dx); w->layers layers dx apart on the left of A->B
 * seen with x to the right and z up (the segment's rule in 2-D, unstaggered).
 * Each particle gets density rho, mass, smoothing length h, `flags`, and
 * its mirror offset (mx, 0, mz) through the face dx/2 on the right of the
 * segment. */
int sph_boundary_add_plate(sph_particles *p, const sph_wall_segment *w, double dx, double rho,
                           double mass, double h, uint8_t flags, sph_error *err);
#endif

/* Adds the walls of a rectangular tank whose inner faces are x0, x1 (sides)
 * and y0 (floor), side walls up to y1. The first wall layer lies dx/2
 * outside each inner face, so it is dx from the first fluid layer of a
 * block filled against that face. */
int sph_boundary_add_tank(sph_particles *p, const sph_tank *t, double dx, double rho, double mass,
                          double h, uint8_t flags, sph_error *err);

/* Adds a box obstacle (wall_types.h): the points lo[a] + (i + 1/2) dx, i = 0 .. n_a - 1 with
 * n_a = round((hi[a] - lo[a]) / dx) (at least 1), that lie fewer than o->layers points from
 * one of the box's faces, in lattice order (the first axis fastest). Walls with a normal
 * (flags & SPH_WALL_NORMAL) carry mirror offsets out through the nearest face(s); a box whose
 * bottom lies at or below floor_level (-INFINITY: none) stands on the floor, and its bottom is not
 * one of those faces. */
int sph_boundary_add_box(sph_particles *p, const sph_obstacle *o, double floor_level, double dx,
                         double rho, double mass, double h, uint8_t flags, sph_error *err);

/* A straight mirror wall (GOST R 57700.6 3.4.5): the line through (px, py)
 * with unit normal (nx, ny) pointing into the fluid, used for particles
 * whose position along the line, (r - P).t with t = (ny, -nx), lies in
 * [t0, t1]. */
#define SPH_MIRROR_MAX_LINES 64

typedef struct sph_mirror_line {
  double px, py, nx, ny, t0, t1;
} sph_mirror_line;

/* The mirror lines of a tank (floor and both side walls, and its lid if it has one; faces as
 * given). */
size_t sph_mirror_tank_lines(const sph_tank *t, double reach, sph_mirror_line out[4]);
/* The mirror line of a wall segment: the fluid is on the right of A -> B,
 * as for a segment of wall particles. */
sph_mirror_line sph_mirror_segment_line(double ax, double ay, double bx, double by);

/* Appends a mirror particle for every fluid particle closer than `reach` to
 * a line in front of it: reflected position, the same density, pressure,
 * mass and smoothing length. Its velocity is two (GOST R 57700.6 3.4.5
 * gives the opposite velocity, no slip): in vx, vy the velocity reflected
 * in the line (the normal component reversed), which the continuity and
 * the step rule read, so the wall is impermeable but a particle sliding
 * along it sees no spurious divergence; in vxh, vyh the opposite velocity
 * -v, which the viscous terms read (artificial and laminar viscosity, the
 * strain rate), so the wall is no-slip. Its density and pressure are the
 * source's, but never below rho0 and 0: as dynamic and mdbc walls (dbc.h),
 * a mirror wall pushes the fluid, it never pulls it. (With the opposite
 * velocity in the
 * continuity too, the surge tip of tests/data/energy_box.yaml thinned to
 * 0.7 rho0 and stopped the run at t = 0.048 s: the images of the particles
 * behind a tip running along the floor move the other way.) A particle
 * near two perpendicular lines (a tank corner) also gets the image through
 * both, whose reflected velocity is -v too. Mirror particles have kind
 * SPH_KIND_MIRROR and ids from n up, in the storage order of their
 * sources. Returns the number added, or -1. */
long sph_mirror_add(sph_particles *p, const sph_mirror_line *lines, size_t n_lines, double reach,
                    double rho0, sph_error *err);
#if SPH_DIM == 3
/* A face of a box tank in 3-D: the plane x[axis] = at, its normal into the
 * fluid along +axis (dir 1) or -axis (dir -1), spanning [lo, hi] along the
 * other axes. */
typedef struct sph_wall_plane {
  int axis, dir;
  double at, lo[3], hi[3];
} sph_wall_plane;

/* The inner faces of a 3-D tank: the floor and the sides, but for the two
 * normal to the axis the tank is open along; each spans the tank's inner
 * box grown by `reach` along the other axes (0: the faces as they are).
 * Into out (room for 6); their number. */
size_t sph_tank_planes(const sph_tank *t, double reach, sph_wall_plane out[6]);

/* sph_mirror_add with mirror planes (a 3-D mirror tank): a fluid particle
 * closer than `reach` to a plane in front of it, within its span, gets its
 * image through it; one near two or three planes of different axes (an
 * edge, a corner) also the images through each pair and through all three,
 * their reflected velocity reversed along each of those axes. */
long sph_mirror_add_planes(sph_particles *p, const sph_wall_plane *planes, size_t n_planes,
                           double reach, double rho0, sph_error *err);
#endif

/* Removes every mirror particle, keeping the others in order. perm needs
 * n entries, work n doubles. */
void sph_mirror_remove(sph_particles *p, size_t *perm, void *work);

#endif
