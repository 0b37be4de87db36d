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
#include "core/dim.h"
#include "core/parallel.h"

#include <stdlib.h>
#include <string.h>

/* Every array of the store, with the group it belongs to (0: always
 * live), for allocation and permutation written once. */
/* (left as written: clang-format 14 does not settle on one layout of it) */
/* clang-format off */
#define HEAT SPH_ARRAYS_HEAT
#define HALF SPH_ARRAYS_HALF_STEP
#define HALF_HEAT (SPH_ARRAYS_HALF_STEP | SPH_ARRAYS_HEAT) /* uh: both groups */
#define REST SPH_ARRAYS_REST
#define OFFSET SPH_ARRAYS_OFFSET
#define SAVED SPH_ARRAYS_SAVED
#define PHASE SPH_ARRAYS_PHASE
#define SPH_PARTICLE_DOUBLES(X) \
  X(x, 0) X(y, 0) X(vx, 0) X(vy, 0) X(rho, 0) X(p, 0) X(mass, 0) X(h, 0) X(u, HEAT) \
  X(x0, SAVED) X(y0, SAVED) X(vx0, SAVED) X(vy0, SAVED) X(rho0, SAVED) X(u0, HEAT) \
  X(ax, 0) X(ay, 0) X(drho, 0) X(du, HEAT) X(xsx, 0) X(xsy, 0) \
  X(vxh, HALF) X(vyh, HALF) X(rhoh, HALF) X(uh, HALF_HEAT) X(xr, REST) X(yr, REST) \
  X(mx, OFFSET) X(my, OFFSET) SPH_PARTICLE_DOUBLES_Z(X)
#if SPH_DIM == 2
#define SPH_PARTICLE_DOUBLES_Z(X)
#else
#define SPH_PARTICLE_DOUBLES_Z(X) \
  X(z, 0) X(vz, 0) X(z0, SAVED) X(vz0, SAVED) X(az, 0) X(xsz, 0) X(vzh, HALF) X(zr, REST) X(mz, OFFSET)
#endif
/* clang-format on */
#define SPH_PARTICLE_OTHERS(X)                                                                     \
  X(kind, 0) X(body, 0) X(id, 0) X(flags, 0) X(phase, PHASE) X(wphase, PHASE)
#define SPH_PARTICLE_ONE(f, g) +1
enum {
  SPH_PARTICLE_ARRAYS =
      0 SPH_PARTICLE_DOUBLES(SPH_PARTICLE_ONE) SPH_PARTICLE_OTHERS(SPH_PARTICLE_ONE)
};

/* The store's axes are the solver's. */
typedef char sph_store_dim_check[SPH_STORE_DIM == SPH_DIM ? 1 : -1];

/* Whether an array of group g is in use. */
static inline int live(const sph_particles *p, unsigned g) { return (p->live & g) == g; }

/* The block of arrays is reallocated whole (arrays.h: staggered starts) and
 * the first p->cap entries of every live array copied over. */
static int grow(sph_particles *p, size_t cap, sph_error *err) {
  size_t size[SPH_PARTICLE_ARRAYS];
  void **field[SPH_PARTICLE_ARRAYS];
  unsigned char skip[SPH_PARTICLE_ARRAYS];
  size_t k = 0;
#define LIST(f, g) size[k] = sizeof *p->f, skip[k] = !live(p, g), field[k++] = (void **)&p->f;
  SPH_PARTICLE_DOUBLES(LIST)
  SPH_PARTICLE_OTHERS(LIST)
#undef LIST
  if (sph_arrays_regrow(&p->block, cap, p->cap, k, size, field, skip))
    return sph_error_set(err, "out of memory for %zu particles", cap);
  p->cap = cap;
  return 0;
}

int sph_particles_init(sph_particles *p, size_t cap, sph_error *err) {
  memset(p, 0, sizeof *p);
  p->live = SPH_ARRAYS_ALL & ~SPH_ARRAYS_PHASE; /* (phases change the physics: asked for) */
  if (cap < 16) cap = 16;
  if (grow(p, cap, err)) {
    sph_particles_free(p);
    return -1;
  }
  return 0;
}

long sph_particles_add_at(sph_particles *p, const double x[SPH_DIM], const double v[SPH_DIM],
                          double rho, double mass, double h, int32_t kind, sph_error *err) {
  if (p->n == p->cap && grow(p, p->cap ? 2 * p->cap : 16, err)) return -1;
  size_t i = p->n++;
  p->order++;
  for (int d = 0; d < SPH_DIM; d++) {
    p->pos[d][i] = x[d];
    p->vel[d][i] = v[d];
  }
  p->rho[i] = rho;
  p->p[i] = 0.0;
  p->mass[i] = mass;
  p->h[i] = h;
  if (p->live & SPH_ARRAYS_HEAT) p->u[i] = 0.0;
  p->kind[i] = kind;
  p->body[i] = -1;
  if (p->live & SPH_ARRAYS_REST)
    for (int d = 0; d < SPH_DIM; d++)
      p->rest[d][i] = x[d];
  if (p->live & SPH_ARRAYS_OFFSET)
    for (int d = 0; d < SPH_DIM; d++)
      p->mirror_offset[d][i] = 0.0;
  p->id[i] = (int64_t)i;
  p->flags[i] = 0;
  if (p->live & SPH_ARRAYS_PHASE) p->phase[i] = 0;
  return (long)i;
}

#if SPH_DIM == 2
long sph_particles_add(sph_particles *p, double x, double y, double vx, double vy, double rho,
                       double mass, double h, int32_t kind, sph_error *err) {
  const double at[2] = {x, y}, v[2] = {vx, vy};
  return sph_particles_add_at(p, at, v, rho, mass, h, kind, err);
}
#endif

int sph_particles_limit(sph_particles *p, unsigned groups) {
  if (p->n) return -1;
  p->live = groups & SPH_ARRAYS_ALL;
  return 0;
}

void sph_particles_use(sph_particles *p, unsigned groups) {
  const unsigned on = groups & SPH_ARRAYS_ALL & ~p->live;
  if (on & SPH_ARRAYS_REST)
    for (int d = 0; d < SPH_STORE_DIM; d++)
      for (size_t i = 0; i < p->n; i++)
        p->rest[d][i] = p->pos[d][i];
  p->live |= on;
}

void sph_particles_move(sph_particles *p, size_t to, size_t from) {
  p->order++;
#define MOVE(field, g)                                                                             \
  if (live(p, g)) p->field[to] = p->field[from];
  SPH_PARTICLE_DOUBLES(MOVE)
  SPH_PARTICLE_OTHERS(MOVE)
#undef MOVE
}

int sph_particles_take(sph_particles *to, const sph_particles *from, const unsigned char *mark,
                       sph_error *err) {
  size_t *which = malloc((from->n ? from->n : 1) * sizeof *which);
  if (!which) return sph_error_set(err, "out of memory for a store's %zu indices", from->n);
  size_t k = 0;
  for (size_t i = 0; i < from->n; i++)
    if (mark[i]) which[k++] = i;
  const int rc = sph_particles_gather(to, from, which, k, SPH_PARTICLES_ALL, err);
  free(which);
  return rc;
}

int sph_particles_gather(sph_particles *to, const sph_particles *from, const size_t *which,
                         size_t k, unsigned long long arrays, sph_error *err) {
  to->n = 0;
  to->live = from->live;
  to->order++;
  if (to->cap < k && grow(to, k, err)) return -1;
  /* array by array: each a stream of reads and one of writes */
  int b = 0;
#define GATHER(field, g)                                                                           \
  if (live(from, g) && (arrays >> b & 1))                                                          \
    for (size_t q = 0; q < k; q++)                                                                 \
      to->field[q] = from->field[which[q]];                                                        \
  b++;
  SPH_PARTICLE_DOUBLES(GATHER)
  SPH_PARTICLE_OTHERS(GATHER)
#undef GATHER
  to->n = k;
  return 0;
}

unsigned long long sph_particles_put(sph_particles *to, const size_t *at, const sph_particles *from,
                                     const size_t *which, size_t k, unsigned long long arrays,
                                     int compare) {
  unsigned long long d = 0;
  int b = 0;
  /* array by array; a value differs if one of its bytes does, and those
   * before the first that differs are not written again (an array the
   * pass left as it was is only read) */
#define PUT(field, g)                                                                              \
  if (live(from, g) && live(to, g) && (arrays >> b & 1)) {                                         \
    size_t q = 0;                                                                                  \
    if (compare) {                                                                                 \
      while (q < k && memcmp(&to->field[at[q]], &from->field[which[q]], sizeof *to->field) == 0)   \
        q++;                                                                                       \
      if (q < k) d |= 1ull << b;                                                                   \
    }                                                                                              \
    for (; q < k; q++)                                                                             \
      to->field[at[q]] = from->field[which[q]];                                                    \
  }                                                                                                \
  b++;
  SPH_PARTICLE_DOUBLES(PUT)
  SPH_PARTICLE_OTHERS(PUT)
#undef PUT
  return d;
}

unsigned long long sph_particles_array_bits(const char *names) {
  unsigned long long d = 0;
  int b = 0;
  /* each name of the list that is a whole word of it */
#define NAMED(field, g)                                                                            \
  for (const char *at = strstr(names, #field); at; at = strstr(at + 1, #field)) {                  \
    const char after = at[sizeof #field - 1];                                                      \
    if ((at == names || at[-1] == ' ') && (after == ' ' || after == '\0')) d |= 1ull << b;         \
  }                                                                                                \
  b++;
  SPH_PARTICLE_DOUBLES(NAMED)
  SPH_PARTICLE_OTHERS(NAMED)
#undef NAMED
  return d;
}

size_t sph_particles_record_size_of(const sph_particles *p, unsigned long long arrays) {
  size_t n = 0;
  int k = 0;
#define SIZE(field, g)                                                                             \
  if (live(p, g) && (arrays >> k & 1)) n += sizeof *p->field;                                      \
  k++;
  SPH_PARTICLE_DOUBLES(SIZE)
  SPH_PARTICLE_OTHERS(SIZE)
#undef SIZE
  return n;
}

size_t sph_particles_record_size(const sph_particles *p) {
  return sph_particles_record_size_of(p, SPH_PARTICLES_ALL);
}

void sph_particles_pack_block(const sph_particles *p, const size_t *which, size_t k,
                              unsigned long long arrays, unsigned char *buf) {
  int b = 0;
#define PACK_BLOCK(field, g)                                                                       \
  if (live(p, g) && (arrays >> b & 1)) {                                                           \
    for (size_t q = 0; q < k; q++)                                                                 \
      memcpy(buf + q * sizeof *p->field, &p->field[which[q]], sizeof *p->field);                   \
    buf += k * sizeof *p->field;                                                                   \
  }                                                                                                \
  b++;
  SPH_PARTICLE_DOUBLES(PACK_BLOCK)
  SPH_PARTICLE_OTHERS(PACK_BLOCK)
#undef PACK_BLOCK
}

void sph_particles_unpack_block(sph_particles *p, const size_t *which, size_t k,
                                unsigned long long arrays, const unsigned char *buf) {
  int b = 0;
#define UNPACK_BLOCK(field, g)                                                                     \
  if (live(p, g) && (arrays >> b & 1)) {                                                           \
    for (size_t q = 0; q < k; q++)                                                                 \
      memcpy(&p->field[which[q]], buf + q * sizeof *p->field, sizeof *p->field);                   \
    buf += k * sizeof *p->field;                                                                   \
  }                                                                                                \
  b++;
  SPH_PARTICLE_DOUBLES(UNPACK_BLOCK)
  SPH_PARTICLE_OTHERS(UNPACK_BLOCK)
#undef UNPACK_BLOCK
}

/* The store's arrays fit the bits of an array set. */
typedef char sph_arrays_fit_check[SPH_PARTICLE_ARRAYS <= 64 ? 1 : -1];

size_t sph_particles_drop_if(sph_particles *p, size_t first,
                             int (*drop)(const void *ctx, const sph_particles *p, size_t i),
                             const void *ctx) {
  size_t kept = first;
  for (size_t i = first; i < p->n; i++) {
    if (drop(ctx, p, i)) continue;
    if (kept != i) sph_particles_move(p, kept, i);
    p->id[kept] = (int64_t)kept;
    kept++;
  }
  const size_t removed = p->n - kept;
  p->n = kept;
  return removed;
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
  p->order++;
  const long ln = (long)n;
  /* one parallel region; each field's gather and copy-back split by index */
#define PERMUTE(field, g)                                                                          \
  if (live(p, g)) {                                                                                \
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
#undef HEAT
#undef HALF
#undef HALF_HEAT
#undef REST
#undef OFFSET
