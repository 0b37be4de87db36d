/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * particles.h - the particle store: a structure of arrays.
 *
 * Terms of GOST R 57700.6-2017: fluid particles are "computational particles"
 * (3.4.8); wall particles are "fictitious particles" (3.4.9), here of the
 * "dynamic particles" kind (3.4.7).
 *
 * Invariants: every array holds n valid entries; id is a permutation of
 * 0..n-1 fixed at creation (the order snapshots are written in); the storage
 * order is free to change (the grid sorts particles by cell).
 */
#ifndef SPH_PARTICLES_H
#define SPH_PARTICLES_H

#include <stddef.h>
#include <stdint.h>

#include "core/dim.h"
#include "core/error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Particle kinds, stored as the integer dataset `kind` in snapshots.
 * Mirror particles (GOST R 57700.6 3.4.5) exist only during a force
 * evaluation and are never written. */
enum { SPH_KIND_FLUID = 0, SPH_KIND_WALL = 1, SPH_KIND_MIRROR = 2 };

/* Bits of `flags`. */
enum {
  SPH_FLAG_FREE_SURFACE = 1, /* on the free surface (paper A §7) */
  SPH_FLAG_REPULSIVE = 2,    /* a wall particle of a repulsive wall (paper A eq. 21-22) */
  SPH_FLAG_NO_SLIP = 4,      /* a wall particle with the extrapolated velocity (wall_velocity.h) */
  SPH_FLAG_MDBC = 8, /* a wall particle of an mdbc wall: density from the fluid (wall_velocity.h) */
  SPH_FLAG_FREE_SLIP = 16, /* a wall particle of a free-slip wall: its pressure and artificial-
                              viscosity pair forces act along the wall's normal (pair_terms.h) */
  SPH_FLAG_ADAMI = 32,     /* a wall particle of an adami wall: pressure extrapolated from the
                              fluid, no rates of its own (walls/adami.h) */
  SPH_FLAG_INVISCID = 64,  /* an adami wall particle of a free-slip wall: no viscous pair term
                              with it (walls/adami.h) */
  SPH_FLAG_GHOST = 128     /* in a rank's store: a particle another rank owns, or a mirror
                              particle of one (solver/ranks.c); never in a run's own store */
};
/* The flags of wall particles that carry their mirror offset (mx, my: twice their depth along
 * the wall's normal, boundary.h). */
#define SPH_WALL_NORMAL (SPH_FLAG_NO_SLIP | SPH_FLAG_MDBC | SPH_FLAG_FREE_SLIP | SPH_FLAG_ADAMI)

/* Groups of arrays a case may not use (doc/memory.md). Until a group is
 * live its arrays hold zeros, nothing writes them, and they are neither
 * copied when the store grows nor permuted when it is sorted: their pages
 * stay out of the resident set. Code that writes a group turns it on first
 * (sph_particles_use). */
enum {
  SPH_ARRAYS_HEAT = 1,      /* u, u0, du: the energy ledger's heat */
  SPH_ARRAYS_HALF_STEP = 2, /* vxh, vyh, rhoh, uh: the leap-frog's half step (uh with HEAT
                               only); the velocity mirror particles carry */
  SPH_ARRAYS_REST = 4,      /* xr, yr: the rest positions of moving walls' particles */
  SPH_ARRAYS_OFFSET = 8,    /* mx, my: offsets of mdbc, no-slip and free-slip wall particles */
  SPH_ARRAYS_SAVED = 16,    /* x0, y0, vx0, vy0, rho0: the state at the start of the step (the
                               predictor-corrector's; the leap-frog keeps it in the pass's
                               packed copy instead, solver/sim.c) */
  SPH_ARRAYS_PHASE = 32,    /* phase: each fluid particle's phase, an index into the case's
                               materials (0 the liquid, 1 the air: physics.air); walls 0;
                               wphase: an adami wall particle's mirror phase */
  SPH_ARRAYS_ALL = 63
};

/* The store's axes: a per-axis field is SPH_DIM arrays (core/dim.h), reachable
 * by name (x, y and, in 3-D, z) or by axis (pos[SPH_AXIS_X], ...; the same
 * pointers). A program built on the 3-D library defines SPH_DIM 3 before
 * including this header. */
#define SPH_STORE_DIM SPH_DIM
enum { SPH_AXIS_X = 0, SPH_AXIS_Y = 1, SPH_AXIS_Z = 2 };

/* A per-axis field: names a, b (and c in 3-D) for the axes, arr[axis] for
 * all (an anonymous union: core/dim.h). */
#if SPH_DIM == 2
#define SPH_AXES(arr, a, b, c)                                                                     \
  SPH_ANONYMOUS union {                                                                            \
    SPH_ANONYMOUS struct { double *a, *b; };                                                       \
    double *arr[SPH_STORE_DIM];                                                                    \
  }
#else
#define SPH_AXES(arr, a, b, c)                                                                     \
  SPH_ANONYMOUS union {                                                                            \
    SPH_ANONYMOUS struct { double *a, *b, *c; };                                                   \
    double *arr[SPH_STORE_DIM];                                                                    \
  }
#endif

typedef struct sph_particles {
  size_t n;       /* particles in use */
  size_t cap;     /* allocated length of every array */
  void *block;    /* the one allocation holding every array (particles.c) */
  unsigned live;  /* SPH_ARRAYS_* groups in use; the others hold zeros */
  uint64_t order; /* bumped by every function below that moves particles to other storage
                     indices or changes n (a list built on the store checks it: code that
                     reorders the arrays itself bumps it too) */
  /* state */
  SPH_AXES(pos, x, y, z);    /* position (m) */
  SPH_AXES(vel, vx, vy, vz); /* velocity (m/s) */
  double *rho;               /* density (kg/m^3) */
  double *p;                 /* pressure (Pa), from the equation of state */
  double *mass;              /* mass (kg) */
  double *h;                 /* smoothing length (m) */
  double *u;                 /* thermal energy per unit mass (J/kg) */
  int32_t *kind;             /* SPH_KIND_* */
  int64_t *id;               /* 0..n-1, fixed at creation */
  uint8_t *flags;            /* per-particle flags, SPH_FLAG_* (free surface, wall models) */
  uint8_t *phase;            /* the particle's material (group PHASE; 0 without it) */
  uint8_t *wphase; /* two phases: an adami wall particle's phase, the fluid's beside it, whose
                     pressure its p is and whose material it stands for (walls/adami.h) */
  /* state at the start of the step (predictor-corrector; group SAVED, u0
   * with HEAT), and rates */
  SPH_AXES(pos0, x0, y0, z0);
  SPH_AXES(vel0, vx0, vy0, vz0);
  double *rho0, *u0;
  SPH_AXES(acc, ax, ay, az);     /* dv/dt */
  double *drho, *du;             /* drho/dt, du/dt */
  SPH_AXES(velh, vxh, vyh, vzh); /* leap-frog: velocity at the half step */
  double *rhoh, *uh;             /* leap-frog: density, energy at the half step */
  SPH_AXES(rest, xr, yr, zr);    /* rest position of a wall particle (moving walls) */
  int32_t *body;                 /* index of the moving wall a particle belongs to, or -1 */
  SPH_AXES(xsph, xsx, xsy, xsz); /* XSPH velocity correction */
  /* wall particle: offset to its mirror point across the wall face (walls/wall_velocity.h) */
  SPH_AXES(mirror_offset, mx, my, mz);
} sph_particles;

/* The phase array where the store has phases (group PHASE), else NULL
 * (every particle of phase 0; physics/eos.h, sph_eos_of). */
static inline const uint8_t *sph_particles_phases(const sph_particles *p) {
  return (p->live & SPH_ARRAYS_PHASE) ? p->phase : NULL;
}

/* Whether particle i is of the liquid: a fluid particle of phase 0 (the
 * air of a two-phase run is fluid too, of phase 1). What the surface, the
 * front and the level gauges read. */
static inline int sph_particles_liquid(const sph_particles *p, size_t i) {
  const uint8_t *ph = sph_particles_phases(p);
  return p->kind[i] == SPH_KIND_FLUID && !(ph && ph[i]);
}

/* Allocates room for cap particles (all arrays zeroed); n = 0; every
 * group live but PHASE (every particle then of phase 0), which a store of
 * two phases turns on (sph_particles_limit, sph_particles_use). */
int sph_particles_init(sph_particles *p, size_t cap, sph_error *err);
/* Declares, while the store is empty (n = 0), the only groups in use so
 * far; returns -1 (nothing changed) once particles exist. */
int sph_particles_limit(sph_particles *p, unsigned groups);
/* Turns groups on: a group that was off starts from zeros, except the
 * rest positions, which start at the present positions (as if set when
 * each particle was made). */
void sph_particles_use(sph_particles *p, unsigned groups);
/* Appends one particle at x with velocity v (state arrays set, rates
 * zero); grows if needed. Returns its storage index, or -1 (with err) on
 * allocation failure. */
long sph_particles_add_at(sph_particles *p, const double x[SPH_DIM], const double v[SPH_DIM],
                          double rho, double mass, double h, int32_t kind, sph_error *err);
#if SPH_DIM == 2
/* The same at (x, y) with velocity (vx, vy). */
long sph_particles_add(sph_particles *p, double x, double y, double vx, double vy, double rho,
                       double mass, double h, int32_t kind, sph_error *err);
#endif
/* Copies particle `from` to storage index `to`: every live array (id
 * included: renumber after, if the ids must stay 0..n-1). */
void sph_particles_move(sph_particles *p, size_t to, size_t from);
/* Makes `to` hold the particles i of `from` with mark[i] != 0, in their
 * order, with every array `from` has live (ids kept); grows `to` if
 * needed. 0, or -1 with err out of memory. */
int sph_particles_take(sph_particles *to, const sph_particles *from, const unsigned char *mark,
                       sph_error *err);
/* Makes `to` hold the k particles which[0..k) of `from`, in that order,
 * with the arrays `from` has live (ids kept), array by array: of those in
 * the set `arrays` (bits as sph_particles_array_bits gives them) their
 * values, the others left as they were (stale); grows `to` if needed. 0,
 * or -1 with err out of memory. */
int sph_particles_gather(sph_particles *to, const sph_particles *from, const size_t *which,
                         size_t k, unsigned long long arrays, sph_error *err);
/* For q < k, particle which[q] of `from` into index at[q] of `to`: the
 * arrays of the set `arrays` live in both, array by array. With compare,
 * returns the arrays in which some particle's value was not the one it
 * gets, byte for byte; else 0. */
unsigned long long sph_particles_put(sph_particles *to, const size_t *at, const sph_particles *from,
                                     const size_t *which, size_t k, unsigned long long arrays,
                                     int compare);
/* The set of the arrays named in `names` (field names of sph_particles
 * separated by spaces: "x vx rho"), a bit each in the store's order of
 * arrays; names that are no array are ignored. */
unsigned long long sph_particles_array_bits(const char *names);
/* The bytes of a particle's record (every live array's entry, in the
 * store's order of arrays), for a store that another process holds in the
 * same state (solver/procs.h); and of the arrays in `arrays` alone (bit k:
 * the store's k-th array; SPH_PARTICLES_ALL for every one). */
#define SPH_PARTICLES_ALL (~0ull)
size_t sph_particles_record_size(const sph_particles *p);
size_t sph_particles_record_size_of(const sph_particles *p, unsigned long long arrays);
/* The k particles which[0..k) of p in the arrays of `arrays`, array by
 * array: each array's k entries in turn, in the store's order of arrays
 * (sph_particles_record_size_of(p, arrays) * k bytes in buf); and set from
 * such a block. What a process sends of its own particles (solver/ranks.c):
 * a loop per array, not per particle. */
void sph_particles_pack_block(const sph_particles *p, const size_t *which, size_t k,
                              unsigned long long arrays, unsigned char *buf);
void sph_particles_unpack_block(sph_particles *p, const size_t *which, size_t k,
                                unsigned long long arrays, const unsigned char *buf);
/* Removes the particles i >= first for which drop(ctx, p, i) is true; the
 * others move down in order (sph_particles_move), each id from `first` on
 * renumbered to its new index. drop sees particle i where it was made and
 * every particle after it unmoved (only slots up to i are written before
 * it is asked). Returns how many were removed. */
size_t sph_particles_drop_if(sph_particles *p, size_t first,
                             int (*drop)(const void *ctx, const sph_particles *p, size_t i),
                             const void *ctx);
void sph_particles_free(sph_particles *p);
/* Counts of each kind. */
size_t sph_particles_count_kind(const sph_particles *p, int32_t kind);
/* Reorders every array so that new index i holds old index perm[i]. work must
 * hold n doubles (8 bytes each) of scratch. */
void sph_particles_permute(sph_particles *p, const size_t *perm, void *work);

#ifdef __cplusplus
}
#endif

#endif
