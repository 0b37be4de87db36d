/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * decomp.h - the domain decomposition: which rank owns a particle, and which
 * particles each rank needs beside its own (its ghosts).
 *
 * Space is cut into cubic decomposition cells of a fixed side from the
 * origin 0 (cell k along an axis holds floor(x / side) = k), so a cell's
 * coordinates are a function of a position alone. The cells are ordered
 * along a Hilbert curve (Skilling 2004, doc/method.md, Ranks), whose
 * consecutive cells are neighbours in space: a contiguous range of the curve
 * is a compact region. The ranks own contiguous ranges of the curve,
 * balanced by particle count: rank r owns the cells from the key of the
 * particle at position floor(r N / R) of the particles sorted by key (N
 * particles, R ranks) up to the next rank's first key, a whole cell always
 * to one rank. The cut is a pure function of the particles' positions, so a
 * restart from any snapshot, on any rank count, cuts the same state the same
 * way.
 *
 * A rank's ghosts are the particles it does not own whose cell lies within
 * `depth` cells (in every direction, the 3^D block and beyond) of a cell it
 * owns: with depth x side at least the reach of every chain of neighbour
 * passes a step makes, a rank that holds its own particles and its ghosts
 * computes its own particles' rates exactly as the whole set would, bit for
 * bit (the storage order and every row are functions of position and id:
 * neighbours/grid.h).
 */
#ifndef SPH_DECOMP_H
#define SPH_DECOMP_H

#include <stddef.h>
#include <stdint.h>

#include "core/dim.h"
#include "core/error.h"
#include "core/particles.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The decomposition's grid: cells of side `side` from the origin; a
 * periodic axis (1 + its store axis, or 0) wraps its cells over
 * [period_lo, period_lo + ncell_periodic side). */
typedef struct sph_decomp_grid {
  double side;
  int periodic;
  double period_lo;
  long ncell_periodic;
} sph_decomp_grid;

/* The Hilbert key of the cell with coordinates c (each in [0, 2^bits),
 * bits <= 21 in 3-D, 31 in 2-D): its position along the curve that fills
 * the 2^bits-cube. */
uint64_t sph_decomp_hilbert(const uint32_t c[SPH_DIM], int bits);

/* The bits per axis of the keys (the curve fills a cube of 2^bits cells
 * per side, centred on the origin). */
#define SPH_DECOMP_BITS (SPH_DIM == 2 ? 31 : 21)

/* The cell coordinates (offset so that they are non-negative: cell k is
 * stored as k + 2^(bits-1)) of a position; -1 if a coordinate is outside
 * the curve's cube or not finite. */
int sph_decomp_cell(const sph_decomp_grid *g, const double x[SPH_DIM], uint32_t c[SPH_DIM]);

/* The key of each particle of p (keys[i] for storage index i). */
int sph_decomp_keys(const sph_decomp_grid *g, const sph_particles *p, uint64_t *keys,
                    sph_error *err);

/* The cut of n keys (any order) into ranks ranges: first[r] is the first key
 * of rank r (first[0] = 0), rank r owns the keys in [first[r], first[r + 1])
 * (the last rank up to UINT64_MAX). Pure: the same keys in any order give
 * the same cut. Fails only out of memory. */
int sph_decomp_cut(const uint64_t *keys, size_t n, int ranks, uint64_t *first, sph_error *err);

/* The same cut balanced by weight: the particle of key keys[i] weighs
 * w[i] (the cost of its rows); rank r from the first key at which the
 * weights of the keys below it reach r / ranks of the whole. Pure, as
 * sph_decomp_cut. */
int sph_decomp_cut_weighted(const uint64_t *keys, const uint32_t *w, size_t n, int ranks,
                            uint64_t *first, sph_error *err);

/* The same cut with rank r's share of the whole weight share[r] (the
 * shares sum to 1; NULL: 1 / ranks each, sph_decomp_cut_weighted's cut):
 * rank r from the first key at which the weights below it reach the
 * shares of the ranks before it. Pure in the keys, weights and shares. */
int sph_decomp_cut_shares(const uint64_t *keys, const uint32_t *w, size_t n, int ranks,
                          const double *share, uint64_t *first, sph_error *err);

/* The rank that owns key k under the cut. */
int sph_decomp_owner(const uint64_t *first, int ranks, uint64_t k);

/* The particles rank `rank` needs beside its own: mark[i] = 1 for its own
 * particles, 2 for its ghosts within row_depth cells of a cell it owns
 * whose kind k is in row_kinds (bit 1 << k), 3 for the others within depth
 * cells, 0 for the rest. A pass needs the rows (the neighbours) of its own
 * particles and of the ghosts that a chain of passes reads a row's result
 * at (within one support, row_depth 1, and only the kinds whose rows give
 * a result: solver/ranks.c); the ghosts marked 3 are there as neighbours
 * only. A row_depth of depth or more marks every ghost of those kinds 2.
 * Returns the number of ghosts, or -1 out of memory. */
long sph_decomp_halo(const sph_decomp_grid *g, const sph_particles *p, const uint64_t *keys,
                     const uint64_t *first, int ranks, int rank, int depth, int row_depth,
                     unsigned row_kinds, unsigned char *mark, sph_error *err);

/* For each particle i, the particles in the 3^D cells around its cell (its
 * own included; wrapping on the periodic axis, each cell once): all[i] of
 * every kind, of_kind[i] of `kind`. With cells one support wide, what a
 * particle's rows cost grows with them (the candidates of its neighbour
 * row; solver/ranks.c weighs the cut by them). 0, or -1 out of memory. */
int sph_decomp_block_counts(const sph_decomp_grid *g, const sph_particles *p, int32_t kind,
                            uint32_t *all, uint32_t *of_kind, sph_error *err);

#ifdef __cplusplus
}
#endif

#endif
