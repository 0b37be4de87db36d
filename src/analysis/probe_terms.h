/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * probe_terms.h - a probe's reading (probes.h) split over shares of the
 * store: each share's terms (what each particle adds to the probe's sums:
 * a pressure or velocity probe's kernel weight and weighted values at each
 * point, a wire gauge's wetted length, a level probe's candidate tops), in
 * storage order, and the reading folded from the shares' terms taken in
 * storage order: the bits of sph_probe_read over the whole store, since
 * the terms are added in the same order. Under mpirun each process lists
 * the terms of its share (src/solver/run.c). Not installed.
 */
#ifndef SPH_PROBE_TERMS_H
#define SPH_PROBE_TERMS_H

#include <stddef.h>
#include <stdint.h>

#include "analysis/probes.h"

typedef struct sph_probe_term {
  int32_t k;             /* the point (a pressure sensor's face point; else 0) */
  double v[2 + SPH_DIM]; /* its values (a level probe's: v[0]) */
} sph_probe_term;

/* Probe q's terms among particles [from, to) of p, appended to *t (n of
 * cap, grown with realloc): 0, or -1 out of memory (*t keeps what it had). */
int sph_probe_terms(const sph_probe *q, const sph_particles *p, size_t from, size_t to,
                    sph_kernel_kind kernel, double h, double dx, const double g[SPH_DIM],
                    sph_probe_term **t, size_t *n, size_t *cap);
/* Probe q's reading (sph_probe_read's out) from n_pieces lists of terms,
 * pieces[r] holding counts[r], taken in that order (the store's). */
void sph_probe_fold(const sph_probe *q, const sph_probe_term *const *pieces, const size_t *counts,
                    int n_pieces, double h, double dx, double floor_y, double *out);

#endif
