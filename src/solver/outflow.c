/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * outflow.c - fluid particles that leave the domain (see outflow.h).
 */
#include "config.h"

#include "solver/outflow.h"

#include <stdlib.h>
#include <string.h>

#include "core/exact_sum.h"
#include "core/parallel.h"
#include "solver/diag.h"

/* Removes the particles whose id (a creation-order id, 0..n-1) has
 * keep_as[id] < 0 and gives every other its new id keep_as[id]; the order
 * of the survivors in storage is kept. */
static void compact(sph_particles *p, const int64_t *keep_as) {
  size_t kept = 0;
  for (size_t i = 0; i < p->n; i++) {
    const int64_t id = keep_as[p->id[i]];
    if (id < 0) continue;
    if (kept != i) sph_particles_move(p, kept, i);
    p->id[kept++] = id;
  }
  p->n = kept;
  p->order++; /* n changed even where nothing moved */
}

long sph_outflow_count(const sph_particles *p, const double domain[2 * SPH_DIM]) {
  const long n = (long)p->n;
  long k = 0;
#pragma omp parallel for reduction(+ : k) if (n > SPH_OMP_MIN)
  for (long i = 0; i < n; i++)
    k += sph_outflow_outside(p, (size_t)i, domain);
  return k;
}

long sph_outflow_remove(sph_outflow *o, sph_particles *p, const double domain[2 * SPH_DIM],
                        const double g[SPH_DIM], double floor, sph_error *err) {
  const long n = (long)p->n, k = sph_outflow_count(p, domain);
  if (k == 0) return 0;
  int64_t *keep_as = calloc((size_t)n, sizeof *keep_as);
  int64_t *origin = malloc((size_t)(n - k > 0 ? n - k : 1) * sizeof *origin);
  if (!keep_as || !origin) {
    free(keep_as);
    free(origin);
    return sph_error_set(err, "out of memory taking %ld particles that left the domain out", k);
  }
  /* book what leaves (each sum exact: exact_sum.h, the same bits in any
   * order), then add it to what left before; mark it by id */
  sph_xsum sm, se, sv[SPH_DIM];
  sph_xsum_init(&sm), sph_xsum_init(&se);
  for (int a = 0; a < SPH_DIM; a++)
    sph_xsum_init(&sv[a]);
  for (size_t i = 0; i < p->n; i++) {
    if (!sph_outflow_outside(p, i, domain)) continue;
    const double m = p->mass[i];
    const double v2 = SPH_NORM2(p->vx[i], p->vy[i], p->vz[i]);
    sph_xsum_add(&sm, m);
    sph_xsum_add(&se, 0.5 * m * v2 - sph_diag_lift(p, i, g, floor) + m * p->u[i]);
    for (int a = 0; a < SPH_DIM; a++)
      sph_xsum_add(&sv[a], m * p->vel[a][i]);
    keep_as[p->id[i]] = -1;
  }
  o->mass += sph_xsum_round(&sm);
  o->energy += sph_xsum_round(&se);
  for (int a = 0; a < SPH_DIM; a++)
    o->momentum[a] += sph_xsum_round(&sv[a]);
  /* the survivors' new ids in their id order, and their creation ids */
  int64_t next = 0;
  for (long id = 0; id < n; id++) {
    if (keep_as[id] < 0) continue;
    origin[next] = o->origin ? o->origin[id] : id;
    keep_as[id] = next++;
  }
  compact(p, keep_as);
  free(keep_as);
  free(o->origin);
  o->origin = origin;
  o->n_origin = p->n;
  o->count += (size_t)k;
  return k;
}

int sph_outflow_restore(sph_outflow *o, sph_particles *p, const int64_t *origin, size_t n,
                        const double saved[SPH_OUTFLOW_SAVED], const char *path, sph_error *err) {
  const size_t made = p->n;
  for (size_t k = 0; k < n; k++)
    if (origin[k] < 0 || (uint64_t)origin[k] >= made || (k > 0 && origin[k] <= origin[k - 1]))
      return sph_error_set(err,
                           "%s: dataset /restart/origin holds %lld at row %zu: expected ids "
                           "of the case's %zu particles in increasing order",
                           path, (long long)origin[k], k, made);
  if (!(saved[0] >= 0.0) || saved[0] != (double)(made - n))
    return sph_error_set(err,
                         "%s: the restart record says %g particles left the domain, its ids "
                         "leave out %zu of the case's %zu",
                         path, saved[0], made - n, made);
  int64_t *keep_as = malloc((made ? made : 1) * sizeof *keep_as);
  int64_t *own = malloc((n ? n : 1) * sizeof *own);
  if (!keep_as || !own) {
    free(keep_as);
    free(own);
    return sph_error_set(err, "out of memory");
  }
  for (size_t id = 0; id < made; id++)
    keep_as[id] = -1;
  for (size_t k = 0; k < n; k++)
    keep_as[origin[k]] = (int64_t)k;
  for (size_t i = 0; i < made; i++)
    if (keep_as[p->id[i]] < 0 && p->kind[i] != SPH_KIND_FLUID) {
      const int64_t id = p->id[i];
      free(keep_as);
      free(own);
      return sph_error_set(err,
                           "%s: the restart record leaves out particle %lld, a wall particle: "
                           "only fluid leaves the domain",
                           path, (long long)id);
    }
  compact(p, keep_as);
  free(keep_as);
  memcpy(own, origin, n * sizeof *own);
  free(o->origin);
  o->origin = own;
  o->n_origin = n;
  o->count = (size_t)saved[0];
  o->mass = saved[1];
  o->energy = saved[2];
  for (int a = 0; a < SPH_DIM; a++)
    o->momentum[a] = saved[3 + a];
  return 0;
}

void sph_outflow_save(const sph_outflow *o, double out[SPH_OUTFLOW_SAVED]) {
  out[0] = (double)o->count;
  out[1] = o->mass;
  out[2] = o->energy;
  for (int a = 0; a < SPH_DIM; a++)
    out[3 + a] = o->momentum[a];
}

void sph_outflow_free(sph_outflow *o) {
  free(o->origin);
  memset(o, 0, sizeof *o);
}
