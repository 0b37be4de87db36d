/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * outflow.h - fluid particles that leave the domain, taken out of the run
 * (geometry.leaving: remove).
 *
 * A drop thrown over an open tank's wall has left the flow the case
 * models; it is taken out of the run instead of stopping it, as
 * DualSPHysics excludes its "out" particles. What it carried is booked:
 * its mass, momentum and energy (kinetic + potential + internal, the
 * potential measured as the diagnostics measure it: sph_diag_lift) at the moment
 * it is removed, so that the ledger still closes,
 *   mass + mass_removed = M0,
 *   momentum + momentum_removed - P0 - impulse = 0,
 *   total + energy_removed = E0 (ledger.h).
 * The store stays what every reader expects: the surviving particles keep
 * their relative order (in storage and in id), and their ids are
 * renumbered to 0..n-1 by that order (a particle's id drops by the number
 * of removed particles with a smaller id); origin[] keeps, for each id,
 * the id the particle had when the case made it, which a restart needs to
 * take the same particles out of the case it remakes. Sums run serially in
 * storage order: the same bits for any thread count.
 */
#ifndef SPH_OUTFLOW_H
#define SPH_OUTFLOW_H

#include <stddef.h>
#include <stdint.h>

#include "core/error.h"
#include "core/particles.h"

/* The doubles a restart record keeps (sph_outflow_save): count, mass,
 * energy, a momentum per axis. */
#define SPH_OUTFLOW_SAVED (3 + SPH_DIM)

typedef struct sph_outflow {
  size_t count;             /* fluid particles removed so far */
  double mass, energy;      /* their mass and energy when removed */
  double momentum[SPH_DIM]; /* their momentum when removed */
  int64_t *origin;          /* origin[id]: the id at creation; NULL while none was removed */
  size_t n_origin;          /* its length: the particles in the store */
} sph_outflow;

/* Whether fluid particle i of p is outside the domain x0, x1, y0, y1 (,
 * z0, z1) (a NaN position is not: the blow-up check names it). */
static inline int sph_outflow_outside(const sph_particles *p, size_t i, const double *d) {
  return p->kind[i] == SPH_KIND_FLUID &&
         (p->x[i] < d[0] || p->x[i] > d[1] || p->y[i] < d[2] ||
          p->y[i] > d[3] SPH_IF3(|| p->z[i] < d[4] || p->z[i] > d[5]));
}

/* How many fluid particles of p are outside `domain` (sph_outflow_outside). */
long sph_outflow_count(const sph_particles *p, const double domain[2 * SPH_DIM]);

/* Takes the fluid particles outside `domain` out of p and books them in o
 * (g the gravity, floor the height potential energy is measured from).
 * Returns the number removed (0: p untouched), or -1 with err when out of
 * memory (p untouched). */
long sph_outflow_remove(sph_outflow *o, sph_particles *p, const double domain[2 * SPH_DIM],
                        const double g[SPH_DIM], double floor, sph_error *err);

/* Takes out of p, made afresh by the case, the particles a restart record
 * says were removed: origin (n values, increasing) the ids at creation of
 * the particles kept. p's particles must carry their creation ids
 * (0..p->n-1). 0, or -1 with err naming `path`. */
int sph_outflow_restore(sph_outflow *o, sph_particles *p, const int64_t *origin, size_t n,
                        const double saved[SPH_OUTFLOW_SAVED], const char *path, sph_error *err);

void sph_outflow_save(const sph_outflow *o, double out[SPH_OUTFLOW_SAVED]);
void sph_outflow_free(sph_outflow *o);

#endif
