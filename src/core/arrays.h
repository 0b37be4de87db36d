/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * arrays.h - several arrays of one length in one allocation, each starting
 * at a different offset modulo the page size.
 *
 * Arrays of one length allocated one by one all start at the same offset
 * past a page boundary (glibc maps large blocks page by page, 16 bytes in).
 * A loop reading or writing many of them at the same index (an integrator
 * stage touches up to 22) then sends every stream to the same L1 cache set,
 * which holds 8-12 lines, and makes loads wait on earlier stores to other
 * arrays with the same low 12 address bits ("4K aliasing"). Here array k
 * starts k cache lines past a page boundary, so the streams use distinct
 * sets. Measured on the a/100 dam break (leap-frog, 1 thread): the stage
 * went from 28 % of a 71 s run to 6.5 % of 51 s.
 */
#ifndef SPH_ARRAYS_H
#define SPH_ARRAYS_H

#include <stddef.h>

/* One block holding count arrays of cap elements, element k of `size`
 * bytes each; start[k] receives the address of array k. Every array is
 * zero (calloc: pages of a large block stay untouched, and out of the
 * resident set, until an array is used). Returns the block (release it
 * with free()), or NULL when out of memory. */
void *sph_arrays_block(size_t cap, size_t count, const size_t *size, void **start);

/* Moves a set of arrays to a new block of cap elements each: *field[k]
 * (size[k] bytes per element) points into the new block, with the first
 * `keep` elements copied from where it pointed, unless skip (NULL for none)
 * has skip[k] nonzero: such an array (one known to hold only zeros) is left
 * zero and untouched in the new block. The old *block is freed and
 * replaced. Returns 0, or -1 when out of memory (nothing changed). */
int sph_arrays_regrow(void **block, size_t cap, size_t keep, size_t count, const size_t *size,
                      void **const *field, const unsigned char *skip);

#endif
