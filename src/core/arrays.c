/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * arrays.c - staggered array blocks (see arrays.h). Array k starts at
 * page boundary + k * 64 bytes (k taken modulo 64, the lines of a page), so
 * up to 64 arrays walked at the same index never share an L1 set.
 */
#include "config.h"

#include "core/arrays.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define SPH_PAGE 4096
#define SPH_LINE 64

static size_t round_up(size_t v, size_t to) { return (v + to - 1) / to * to; }

/* Offset of array k in a block whose arrays 0..k-1 end at `end`. */
static size_t place(size_t end, size_t k) {
  return round_up(end, SPH_PAGE) + SPH_LINE * (k % (SPH_PAGE / SPH_LINE));
}

void *sph_arrays_block(size_t cap, size_t count, const size_t *size, void **start) {
  size_t end = 0;
  for (size_t k = 0; k < count; k++) {
    if (size[k] && cap > ((size_t)-1 - 2 * SPH_PAGE - end) / size[k]) return NULL;
    end = place(end, k) + cap * size[k];
  }
  /* calloc, not an aligned malloc and memset: a large block comes zeroed
   * from the kernel without being touched, so arrays a case never uses (the
   * stress tensor's, the ledger's, ...) take no resident memory */
  char *block = calloc(1, end + SPH_PAGE);
  if (!block) return NULL;
  char *base = block + (SPH_PAGE - (uintptr_t)block % SPH_PAGE) % SPH_PAGE;
  end = 0;
  for (size_t k = 0; k < count; k++) {
    const size_t off = place(end, k);
    start[k] = base + off;
    end = off + cap * size[k];
  }
  return block;
}

int sph_arrays_regrow(void **block, size_t cap, size_t keep, size_t count, const size_t *size,
                      void **const *field, const unsigned char *skip) {
  enum { MAX_ARRAYS = 64 };
  void *start[MAX_ARRAYS];
  if (count > MAX_ARRAYS) return -1;
  void *fresh = sph_arrays_block(cap, count, size, start);
  if (!fresh) return -1;
  for (size_t k = 0; k < count; k++) {
    if (keep && !(skip && skip[k])) memcpy(start[k], *field[k], keep * size[k]);
    *field[k] = start[k];
  }
  free(*block);
  *block = fresh;
  return 0;
}
