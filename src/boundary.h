/*
 * boundary.h - wall particles: where they are created.
 *
 * Walls are made of dynamic particles (paper B §2.7; GOST R 57700.6 3.4.7):
 * fixed in place, with density from the continuity equation and pressure
 * from the equation of state. A wall is a line of particles spaced about
 * dx, plus further layers each dx/2 further out and staggered by half a
 * spacing along the wall (paper B: two staggered layers).
 */
#ifndef SPH_BOUNDARY_H
#define SPH_BOUNDARY_H

#include "case.h"
#include "error.h"
#include "particles.h"

/* Adds `layers` staggered layers of wall particles along the segment A->B:
 * layer 0 on the segment (spacing len/round(len/dx)), layer k offset by
 * k dx/2 to the left of the direction A->B; odd layers sit half a spacing
 * along and reach half a spacing past both ends. Each particle gets density
 * rho, mass and smoothing length h. */
int sph_boundary_add_segment(sph_particles *p, double ax, double ay, double bx, double by,
                             int layers, double dx, double rho, double mass, double h,
                             sph_error *err);

/* Adds the walls of a rectangular tank whose inner faces are x0, x1 (sides)
 * and y0 (floor), side walls up to y1. The first wall layer lies dx/2
 * outside each inner face, so it is dx from the first fluid layer of a
 * block filled against that face. */
int sph_boundary_add_tank(sph_particles *p, const sph_tank *t, double dx, double rho,
                          double mass, double h, sph_error *err);

#endif
