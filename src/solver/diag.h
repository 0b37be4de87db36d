/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * diag.h - diagnostics: the surge front and the conserved quantities of the
 * fluid, one CSV row per output time (diagnostics.csv).
 *
 * Columns: time,step,dt,n_fluid,front_x,mass,momentum_x,momentum_y,kinetic,potential,
 * each with its units in the header as sph_csv_put_column writes them
 * ("time (s)", "step", ...):
 *   front_x    largest x of fluid particles within `band` (2 dx) of the floor
 *   mass       sum of fluid masses (exact: masses never change)
 *   momentum   sum of m v over fluid particles
 *   kinetic    sum of m |v|^2 / 2 over fluid particles
 *   potential  sum of -m g.(r - r_floor) over fluid particles, r_floor = (0, floor):
 *              zero on the floor, so E0 is a sizeable positive number
 *   n_free_surface  fluid particles flagged on the free surface (a column
 *              only when the case runs free-surface detection)
 *   internal,boundary_work,xsph_drift,total_energy,energy_deviation,
 *   fluid_energy_deviation,momentum_residual_x,momentum_residual_y
 *              the energy ledger and the momentum balance (columns only
 *              with output.energy)
 *   diffusion_energy  the elastic energy the density diffusion added
 *              (ledger.h; a column only with output.energy and density
 *              diffusion on)
 *   n_removed,mass_removed,energy_removed  the fluid particles that left
 *              the domain, their mass and energy (outflow.h; columns only
 *              with geometry.leaving: remove, the last with output.energy;
 *              after the other ledger columns)
 * Numbers are printed with %.17g: a row reads back to the same bits. Sums
 * run serially over the store in its (deterministic) sorted order.
 */
#ifndef SPH_DIAG_H
#define SPH_DIAG_H

#include <stdio.h>

#include "core/particles.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sph_diag_row {
  double time, dt;
  long step;
  size_t n_fluid;
  double front_x, mass, momentum_x, momentum_y, kinetic, potential;
#if SPH_DIM == 3
  double momentum_z; /* (3-D: a column after momentum_y) */
#endif
  long n_surface; /* fluid particles on the free surface; -1: detection is off */
  /* energy ledger (columns only when the case sets output.energy) */
  int ledger;
  double internal;         /* sum m u over fluid and wall particles */
  double boundary_work;    /* work done on the fluid by moving walls, integrated in time */
  double xsph_drift;       /* change of potential energy caused by the XSPH correction */
  int diffusion;           /* write diffusion_energy */
  double diffusion_energy; /* elastic energy added by the density diffusion (ledger.h) */
  int shifting;            /* write shifting_drift */
  double shifting_drift;   /* change of potential energy caused by particle shifting (ledger.h) */
  int repulsion;           /* write wall_potential */
  double wall_potential;   /* Lennard-Jones potential energy of repulsive walls (ledger.h) */
  int outflow;             /* write n_removed, mass_removed (and energy_removed with the ledger) */
  size_t n_removed;        /* fluid particles that left the domain (geometry.leaving: remove) */
  double mass_removed;     /* their mass */
  double energy_removed;   /* their kinetic + potential + internal energy when they left */
  double total;     /* kinetic + potential + internal + wall_potential - boundary_work - xsph_drift
                       - shifting_drift + energy_removed */
  double deviation; /* (total - E0) / E0, E0 the initial total */
  double fluid_deviation; /* the fluid's own kinetic + potential + internal against its start */
  /* momentum balance: P - P0 - integral of the external force (walls,
   * mirror particles, body force) on the fluid; zero but for round-off and
   * time integration if momentum is conserved */
  double momentum_residual_x, momentum_residual_y;
#if SPH_DIM == 3
  double momentum_residual_z;
#endif
} sph_diag_row;

/* m g.(r - r_floor) of particle i, r_floor = (0, floor_y) (the floor along the
 * last axis): minus its share of the `potential` column (outflow.c books a
 * particle that leaves with the same measure). */
static inline double sph_diag_lift(const sph_particles *p, size_t i, const double g[SPH_DIM],
                                   double floor_y) {
#if SPH_DIM == 2
  return p->mass[i] * (g[0] * p->x[i] + g[1] * (p->y[i] - floor_y));
#else
  return p->mass[i] * (g[0] * p->x[i] + g[1] * p->y[i] + g[2] * (p->z[i] - floor_y));
#endif
}

/* Largest x of fluid particles with y < floor_y + band; -inf if none. */
double sph_diag_front(const sph_particles *p, double floor_y, double band);
/* Wave gauge: the highest fluid particle centre with |x_i - x| < half,
 * plus dx/2 (the top of its lattice cell): the free-surface level at x,
 * read as a gauge would. -inf if no fluid particle is there. */
double sph_diag_surface_at(const sph_particles *p, double x, double half, double dx);
#if SPH_DIM == 3
/* The same on the vertical line at (x, y): the highest fluid particle
 * centre with |x_i - x| < half and |y_i - y| < half, plus dx/2. */
double sph_diag_surface_at_xy(const sph_particles *p, double x, double y, double half, double dx);
#endif
/* A wave gauge's level at `at` (x in 2-D, (x, y) in 3-D) as the functions
 * above read it, in a domain periodic along `axis` over range[0]..range[1]
 * (axis < 0: none): a gauge within `half` of the seam also reads the
 * particles across it (the line's image one period away), the highest
 * counting. A gauge away from the seam reads exactly what the functions
 * above give. */
double sph_diag_gauge_level(const sph_particles *p, const double at[SPH_DIM - 1], double half,
                            double dx, int axis, const double range[2]);
/* The same reading among particles [from, to) of p, without the dx/2: the
 * highest fluid centre, -inf if none (a maximum: the readings of a split
 * of the store, the processes' shares under mpirun, give the whole store's
 * as their largest, to which dx/2 is added). */
double sph_diag_gauge_top(const sph_particles *p, size_t from, size_t to,
                          const double at[SPH_DIM - 1], double half, int axis,
                          const double range[2]);
/* Fills every column but time, step and dt. */
void sph_diag_compute(const sph_particles *p, double floor_y, double band, const double g[SPH_DIM],
                      sph_diag_row *row);
/* CSV header line and rows. Return non-zero on a write error. */
int sph_diag_write_header(FILE *f, int free_surface, int ledger, int diffusion, int repulsion,
                          int shifting, int outflow);
int sph_diag_write_row(FILE *f, const sph_diag_row *row);

#ifdef __cplusplus
}
#endif

#endif
