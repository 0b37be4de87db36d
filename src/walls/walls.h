/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * walls.h - the walls of a run as a whole: the tank and the wall segments
 * of a case turned into wall particles (boundary.h) or mirror lines, the
 * flags each boundary model gives its particles, and the prescribed motion
 * of the moving ones (motion.h) at every stage of a step.
 *
 * Boundary models (GOST R 57700.6-2017 terms): dynamic wall particles
 * (3.4.7; paper B §2.7) and Morris' fixed layers (paper A §6 b) are wall
 * particles with continuity; repulsive walls (paper A eq. 21-22) are one
 * layer acting by the Lennard-Jones force; mirror walls (3.4.5) are lines
 * whose mirror particles are made for each pass (boundary.h).
 */
#ifndef SPH_WALLS_H
#define SPH_WALLS_H

#include <stddef.h>

#include "core/error.h"
#include "core/particles.h"
#include "walls/boundary.h"
#include "walls/wall_types.h"

typedef struct sph_walls {
  sph_mirror_line mirror[SPH_MIRROR_MAX_LINES]; /* mirror walls */
  size_t n_mirror;
  double mirror_reach;     /* how far behind a mirror line particles are mirrored */
  sph_mirror_line face[4]; /* a tank of wall particles: its inner faces (floor, sides, lid) */
  size_t n_face;
  double face_reach; /* the tank's wall thickness: how far behind a face a particle is put back */
  int moving;        /* some wall particles follow a prescribed motion */
  int repulsive;     /* some wall particles are repulsive (Lennard-Jones) */
  int no_slip;       /* some wall particles carry SPH_FLAG_NO_SLIP */
  int free_slip;     /* some wall particles carry SPH_FLAG_FREE_SLIP */
  int mdbc;          /* some wall particles carry SPH_FLAG_MDBC */
  int adami;         /* some wall particles carry SPH_FLAG_ADAMI (adami.h) */
  int adami_tank;    /* the tank is an adami wall: its faces' guard is at the face itself */
  int dbc;           /* some wall particles are dynamic or fixed_layers (dbc.h) */
  const sph_wall_segment *segments; /* the case's segments (their motions), not owned */
  size_t n_segments;
#if SPH_DIM == 3
  sph_wall_plane plane[6]; /* the tank's inner faces (floor, sides, lid); a mirror tank's mirror
                              planes (then n_mirror = n_plane) */
  size_t n_plane;
#endif
  const sph_obstacle *obstacles; /* the case's box obstacles, kept off as boxes, not owned */
  size_t n_obstacles;
  double obstacle_floor; /* an obstacle face at or below this height stands on the floor */
  size_t n_dropped;      /* a segment's particles not made: closer than dx/2 to an earlier wall's */
} sph_walls;

/* Adds the wall particles of the tank (if present), of the segments and of
 * the box obstacles to p (mass, density rho0, smoothing length h, spacing
 * dx), and records the mirror walls as lines with reach mirror_reach. A
 * moving segment's particles get body = the segment's index. A segment's
 * or obstacle's particle closer than dx/2 to one of an earlier wall (the
 * tank, or a segment or obstacle before it) is not made, and counted in
 * n_dropped. */
int sph_walls_create(sph_walls *w, sph_particles *p, const sph_tank *tank,
                     const sph_wall_segment *segments, size_t n_segments,
                     const sph_obstacle *obstacles, size_t n_obstacles, double dx, double rho0,
                     double h, double mirror_reach, sph_error *err);

/* Positions and velocities of the moving wall particles at time t: rest
 * position plus the prescribed displacement (never accumulated, so a wall
 * is exactly where its law puts it). */
void sph_walls_move(const sph_walls *w, sph_particles *p, double t);

/* Mirror walls, and the inner faces of a tank of wall particles, are
 * impermeable (GOST R 57700.6 3.4.5 gives the images; this keeps the
 * particles off the line the images are taken across). A fluid particle
 * closer than d_min to a mirror line or tank face in front of it, or
 * behind it by less than the mirror reach or the tank's wall thickness
 * (it crossed within a step), is reflected specularly about the line's
 * parallel at d_min: its distance becomes 2 d_min - d and the normal
 * component of its velocity (and of its half-step velocity vxh, vyh when
 * half_step is set: the leap-frog) points into the fluid. Without it a
 * particle drawn onto a mirror line by negative pressure meets its own
 * image at r -> 0, where the kernel gradient is 0/0 (the coarse Martin &
 * Moyce case blew up at t = 0.16 s); and a particle of the disordered
 * bottom row after a dam break's impact, pressed onto an mdbc floor
 * closer than the kernel gradient's peak (0.87 dx for the cubic spline at
 * h = 1.3 dx), is pushed back less the closer it comes, the wall's
 * pressure being the fluid's extrapolated one: it crept through the floor
 * in 0.9 s (the coarse case run on to 2 s stopped at t = 1.33 s). Dynamic
 * walls, whose density rises as fluid approaches, keep it at their gap:
 * for them this never acts.
 * The faces of adami walls (a tank's, an obstacle's) are kept at the face
 * itself instead (distance 0): only a particle that crossed one is
 * reflected, to as far in front of it as it was behind. Their pressure
 * holds the fluid off by itself, and the guard at dx/4 kicked a dozen
 * particles a step back into the water at the corner of TrixiParticles'
 * dam break (bench/peers_trixi): the impulses rang through the wall
 * sensors (the reading's 27 ms high-frequency part 0.34 rho g H against
 * the peer's 0.086; at the face 0.15; a build with no guard read 0.095,
 * and let particles 0.9 dx into the wall).
 * In 3-D the tank's faces are planes (a box's floor and sides) treated
 * the same way. A box obstacle (either dimension) keeps the fluid off as a
 * box: a fluid particle inside the box grown by d_min is reflected about
 * the grown box's face it is nearest to (its least penetration), a bottom
 * standing on the tank's floor excepted.
 * The positions it sets depend on the particle alone: bitwise the same for
 * any thread count. Returns the number of particles reflected; kick (NULL,
 * or 2 SPH_DIM sums the caller has set) gains sum m dx, sum m dy (, sum m
 * dz), then sum m dvx, sum m dvy (, sum m dvz) over them, in storage order
 * (the energy ledger books the lift as the walls' work, the velocity
 * change as their impulse). */
size_t sph_walls_keep_off(const sph_walls *w, sph_particles *p, double d_min, int half_step,
                          double kick[2 * SPH_DIM]);

#endif
