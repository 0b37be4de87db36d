/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * diag_sums.h - the sums behind a diagnostics row (diag.h) and the energy
 * ledger's stored heat (ledger.h), taken over a span of the store and
 * merged exactly: partial sums over any split of the particles (the
 * processes of a run under mpirun, each over its share) give a row with
 * the bits of one sum over the whole store (exact_sum.h). Not installed.
 */
#ifndef SPH_DIAG_SUMS_H
#define SPH_DIAG_SUMS_H

#include <stdint.h>

#include "core/exact_sum.h"
#include "core/particles.h"
#include "solver/diag.h"

/* mass, momentum by axis, kinetic and potential energy over the fluid;
 * the stored heat m u of every particle and of the fluid alone */
enum {
  SPH_DS_MASS,
  SPH_DS_MX,
  SPH_DS_MY,
  SPH_DS_MZ,
  SPH_DS_KE,
  SPH_DS_PE,
  SPH_DS_HEAT,
  SPH_DS_HEAT_FLUID,
  SPH_DS_COUNT
};

typedef struct sph_diag_sums {
  sph_xsum s[SPH_DS_COUNT];
  int64_t n_fluid; /* fluid particles */
  double front;    /* the surge front's x (sph_diag_front): a maximum, -inf if none */
} sph_diag_sums;

void sph_diag_sums_init(sph_diag_sums *t);
/* Adds particles [from, to) of p: the fluid's row sums, its front within
 * `band` of floor_y, and with heat != 0 the stored heat's two sums. */
void sph_diag_sums_add(sph_diag_sums *t, const sph_particles *p, size_t from, size_t to,
                       double floor_y, double band, const double g[SPH_DIM], int heat);
/* The surge front (sph_diag_front) among particles [from, to): a maximum,
 * -inf if none there. */
double sph_diag_front_span(const sph_particles *p, size_t from, size_t to, double floor_y,
                           double band);
/* Adds u's sums into t, exactly. */
void sph_diag_sums_merge(sph_diag_sums *t, const sph_diag_sums *u);
/* The row's columns the sums give (every one sph_diag_compute fills). */
void sph_diag_sums_row(const sph_diag_sums *t, sph_diag_row *row);

#endif
