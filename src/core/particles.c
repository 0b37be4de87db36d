/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * particles.c - the particle store (structure of arrays).
 *
 * All arrays live in one block (arrays.h), with the same capacity, and
 * grow by doubling. Storage order is free to change (the grid sorts by
 * cell); the id array keeps each particle's creation index so output can
 * be written in id order. Permutation goes through one scratch buffer,
 * field by field, so it costs one extra array of memory, not a copy of the
 * whole store.
 */
#include "config.h"

#include "core/particles.h"

#include "core/arrays.h"
#include "core/parallel.h"

#include <stdlib.h>
#include <string.h>

/* Every array of the store, with its element size, for allocation and
 * permutation written once. */
/* (left as written: clang-format 14 does not settle on one layout of it) */
/* clang-format off */
#define SPH_PARTICLE_DOUBLES(X) \
  X(x) X(y) X(vx) X(vy) X(rho) X(p) X(mass) X(h) X(u) \
  X(x0) X(y0) X(vx0) X(vy0) X(rho0) X(u0) \
  X(ax) X(ay) X(drho) X(du) X(xsx) X(xsy) \
  X(vxh) X(vyh) X(rhoh) X(uh) X(xr) X(yr) X(mx) X(my)
/* clang-format on */
#define SPH_PARTICLE_OTHERS(X) X(kind) X(body) X(id) X(flags)
#define SPH_PARTICLE_ONE(f) +1
enum {
  SPH_PARTICLE_ARRAYS =
      0 SPH_PARTICLE_DOUBLES(SPH_PARTICLE_ONE) SPH_PARTICLE_OTHERS(SPH_PARTICLE_ONE)
};

/* The block of arrays is reallocated whole (arrays.h: staggered starts) and
 * the first p->cap entries of every array copied over. */
static int grow(sph_particles *p, size_t cap, sph_error *err) {
  size_t size[SPH_PARTICLE_ARRAYS];
  void **field[SPH_PARTICLE_ARRAYS];
  size_t k = 0;
#define LIST(f) size[k] = sizeof *p->f, field[k++] = (void **)&p->f;
  SPH_PARTICLE_DOUBLES(LIST)
  SPH_PARTICLE_OTHERS(LIST)
#undef LIST
  if (sph_arrays_regrow(&p->block, cap, p->cap, k, size, field))
    return sph_error_set(err, "out of memory for %zu particles", cap);
  p->cap = cap;
  return 0;
}

int sph_particles_init(sph_particles *p, size_t cap, sph_error *err) {
  memset(p, 0, sizeof *p);
  if (cap < 16) cap = 16;
  if (grow(p, cap, err)) {
    sph_particles_free(p);
    return -1;
  }
  return 0;
}

long sph_particles_add(sph_particles *p, double x, double y, double vx, double vy, double rho,
                       double mass, double h, int32_t kind, sph_error *err) {
  if (p->n == p->cap && grow(p, p->cap ? 2 * p->cap : 16, err)) return -1;
  size_t i = p->n++;
  p->x[i] = x;
  p->y[i] = y;
  p->vx[i] = vx;
  p->vy[i] = vy;
  p->rho[i] = rho;
  p->p[i] = 0.0;
  p->mass[i] = mass;
  p->h[i] = h;
  p->u[i] = 0.0;
  p->kind[i] = kind;
  p->body[i] = -1;
  p->xr[i] = x;
  p->yr[i] = y;
  p->mx[i] = p->my[i] = 0.0;
  p->id[i] = (int64_t)i;
  p->flags[i] = 0;
  return (long)i;
}

void sph_particles_free(sph_particles *p) {
  free(p->block);
  memset(p, 0, sizeof *p);
}

size_t sph_particles_count_kind(const sph_particles *p, int32_t kind) {
  size_t c = 0;
  for (size_t i = 0; i < p->n; i++)
    c += p->kind[i] == kind;
  return c;
}

void sph_particles_permute(sph_particles *p, const size_t *perm, void *work) {
  size_t n = p->n;
  if (n == 0) return;
  const long ln = (long)n;
  /* one parallel region; each field's gather and copy-back split by index */
#define PERMUTE(field)                                                                             \
  {                                                                                                \
    __typeof__(p->field) tmp = work;                                                               \
    _Pragma("omp for schedule(static)") for (long i = 0; i < ln; i++) tmp[i] = p->field[perm[i]];  \
    _Pragma("omp for schedule(static)") for (long i = 0; i < ln; i++) p->field[i] = tmp[i];        \
  }
#pragma omp parallel if (ln > SPH_OMP_MIN)
  {
    SPH_PARTICLE_DOUBLES(PERMUTE)
    SPH_PARTICLE_OTHERS(PERMUTE)
  }
#undef PERMUTE
}
