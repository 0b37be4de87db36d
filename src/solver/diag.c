/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * diag.c - front tracking and conserved sums over the fluid (see diag.h).
 */
#include "config.h"

#include "solver/diag.h"
#include "solver/diag_sums.h"

#include "core/exact_sum.h"
#include "core/parallel.h"
#include "io/csv.h"

#include <math.h>

/* The highest fluid centre on the line at `at` among particles [from, to)
 * (a maximum: exact in any order), -inf if none. */
static double top_in(const sph_particles *p, size_t from, size_t to, const double at[SPH_DIM - 1],
                     double half) {
  double top = -INFINITY;
  const double *up = p->pos[SPH_UP];
  for (size_t i = from; i < to; i++)
    if (sph_particles_liquid(p, i) && fabs(p->x[i] - at[0]) < half &&
        SPH_IF3(fabs(p->y[i] - at[1]) < half &&) up[i] > top)
      top = up[i];
  return top;
}

double sph_diag_surface_at(const sph_particles *p, double x, double half, double dx) {
#if SPH_DIM == 2
  const double at[1] = {x};
  return top_in(p, 0, p->n, at, half) + 0.5 * dx;
#else /* every y */
  double top = -INFINITY;
  for (size_t i = 0; i < p->n; i++)
    if (sph_particles_liquid(p, i) && fabs(p->x[i] - x) < half && p->z[i] > top) top = p->z[i];
  return top + 0.5 * dx;
#endif
}

#if SPH_DIM == 3
double sph_diag_surface_at_xy(const sph_particles *p, double x, double y, double half, double dx) {
  const double at[2] = {x, y};
  return top_in(p, 0, p->n, at, half) + 0.5 * dx;
}
#endif

double sph_diag_gauge_top(const sph_particles *p, size_t from, size_t to,
                          const double at[SPH_DIM - 1], double half, int axis,
                          const double range[2]) {
  double top = top_in(p, from, to, at, half);
  if (axis < 0 || axis >= SPH_DIM - 1) return top; /* no horizontal period */
  const double period = range[1] - range[0];
  if (!(period > 0.0)) return top;
  double image[SPH_DIM - 1];
  for (int d = 0; d < SPH_DIM - 1; d++)
    image[d] = at[d];
  if (at[axis] - range[0] < half) { /* the seam at range[0]: the particles near range[1] */
    image[axis] = at[axis] + period;
    top = fmax(top, top_in(p, from, to, image, half));
  }
  if (range[1] - at[axis] < half) { /* and the other way */
    image[axis] = at[axis] - period;
    top = fmax(top, top_in(p, from, to, image, half));
  }
  return top;
}

double sph_diag_gauge_level(const sph_particles *p, const double at[SPH_DIM - 1], double half,
                            double dx, int axis, const double range[2]) {
  return sph_diag_gauge_top(p, 0, p->n, at, half, axis, range) + 0.5 * dx;
}

/* A maximum, exact in any order (diag_sums.h). */
double sph_diag_front_span(const sph_particles *p, size_t from, size_t to, double floor_y,
                           double band) {
  double front = -INFINITY;
  const double *up = p->pos[SPH_UP]; /* the vertical: y (z in 3-D) */
  const long lo = (long)from, hi = (long)to;
#pragma omp parallel for schedule(static) if (hi - lo > SPH_OMP_MIN) reduction(max : front)
  for (long i = lo; i < hi; i++)
    if (sph_particles_liquid(p, (size_t)i) && up[i] < floor_y + band && p->x[i] > front)
      front = p->x[i];
  return front;
}

double sph_diag_front(const sph_particles *p, double floor_y, double band) {
  return sph_diag_front_span(p, 0, p->n, floor_y, band);
}

void sph_diag_sums_init(sph_diag_sums *t) {
  for (int k = 0; k < SPH_DS_COUNT; k++)
    sph_xsum_init(&t->s[k]);
  t->n_fluid = 0;
  t->front = -INFINITY;
}

void sph_diag_sums_add(sph_diag_sums *t, const sph_particles *p, size_t from, size_t to,
                       double floor_y, double band, const double g[SPH_DIM], int heat) {
  sph_xsum *sum = t->s;
  for (size_t i = from; i < to; i++) {
    if (heat) sph_xsum_add(&sum[SPH_DS_HEAT], p->mass[i] * p->u[i]);
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    const double m = p->mass[i];
    t->n_fluid++;
    if (heat) sph_xsum_add(&sum[SPH_DS_HEAT_FLUID], m * p->u[i]);
    sph_xsum_add(&sum[SPH_DS_MASS], m);
    sph_xsum_add(&sum[SPH_DS_MX], m * p->vx[i]);
    sph_xsum_add(&sum[SPH_DS_MY], m * p->vy[i]);
#if SPH_DIM == 2
    sph_xsum_add(&sum[SPH_DS_KE], 0.5 * m * (p->vx[i] * p->vx[i] + p->vy[i] * p->vy[i]));
#else /* the floor along z, the vertical */
    sph_xsum_add(&sum[SPH_DS_MZ], m * p->vz[i]);
    sph_xsum_add(&sum[SPH_DS_KE],
                 0.5 * m * (p->vx[i] * p->vx[i] + p->vy[i] * p->vy[i] + p->vz[i] * p->vz[i]));
#endif
    sph_xsum_add(&sum[SPH_DS_PE], -sph_diag_lift(p, i, g, floor_y));
  }
  const double f = sph_diag_front_span(p, from, to, floor_y, band);
  if (f > t->front) t->front = f;
}

void sph_diag_sums_merge(sph_diag_sums *t, const sph_diag_sums *u) {
  for (int k = 0; k < SPH_DS_COUNT; k++)
    sph_xsum_merge(&t->s[k], &u->s[k]);
  t->n_fluid += u->n_fluid;
  if (u->front > t->front) t->front = u->front;
}

void sph_diag_sums_row(const sph_diag_sums *t, sph_diag_row *row) {
  const sph_xsum *sum = t->s;
  SPH_IF3(row->momentum_z = sph_xsum_round(&sum[SPH_DS_MZ]);)
  row->n_fluid = (size_t)t->n_fluid;
  row->front_x = t->front;
  row->mass = sph_xsum_round(&sum[SPH_DS_MASS]);
  row->momentum_x = sph_xsum_round(&sum[SPH_DS_MX]);
  row->momentum_y = sph_xsum_round(&sum[SPH_DS_MY]);
  row->kinetic = sph_xsum_round(&sum[SPH_DS_KE]);
  row->potential = sph_xsum_round(&sum[SPH_DS_PE]);
  row->n_surface = -1;
  row->ledger = 0;
  row->diffusion = 0;
  row->shifting = 0;
  row->repulsion = 0;
  row->outflow = 0;
  row->n_removed = 0;
  row->mass_removed = row->energy_removed = 0.0;
}

/* Each sum exact (exact_sum.h): the same bits in any order and for any
 * split of the particles. */
void sph_diag_compute(const sph_particles *p, double floor_y, double band, const double g[SPH_DIM],
                      sph_diag_row *row) {
  sph_diag_sums t;
  sph_diag_sums_init(&t);
  sph_diag_sums_add(&t, p, 0, p->n, floor_y, band, g, 0);
  sph_diag_sums_row(&t, row);
}

int sph_diag_write_header(FILE *f, int free_surface, int ledger, int diffusion, int repulsion,
                          int shifting, int outflow) {
  static const char *const base[] = {
    "time",
    "step",
    "dt",
    "n_fluid",
    "front_x",
    "mass",
    "momentum_x",
    "momentum_y",
#if SPH_DIM == 3
    "momentum_z",
#endif
    "kinetic",
    "potential",
    NULL
  };
  static const char *const surface[] = {"n_free_surface", NULL};
  static const char *const ledger_cols[] = {
    "internal",
    "boundary_work",
    "xsph_drift",
    "total_energy",
    "energy_deviation",
    "fluid_energy_deviation",
    "momentum_residual_x",
    "momentum_residual_y",
#if SPH_DIM == 3
    "momentum_residual_z",
#endif
    NULL
  };
  static const char *const diffusion_cols[] = {"diffusion_energy", NULL};
  static const char *const repulsion_cols[] = {"wall_potential", NULL};
  static const char *const shifting_cols[] = {"shifting_drift", NULL};
  static const char *const outflow_cols[] = {"n_removed", "mass_removed", NULL};
  static const char *const outflow_energy[] = {"energy_removed", NULL};
  int bad = sph_csv_put_columns(f, base, 1);
  if (!bad && free_surface) bad = sph_csv_put_columns(f, surface, 0);
  if (!bad && ledger) bad = sph_csv_put_columns(f, ledger_cols, 0);
  if (!bad && ledger && diffusion) bad = sph_csv_put_columns(f, diffusion_cols, 0);
  if (!bad && ledger && repulsion) bad = sph_csv_put_columns(f, repulsion_cols, 0);
  if (!bad && ledger && shifting) bad = sph_csv_put_columns(f, shifting_cols, 0);
  if (!bad && outflow) bad = sph_csv_put_columns(f, outflow_cols, 0);
  if (!bad && ledger && outflow) bad = sph_csv_put_columns(f, outflow_energy, 0);
  return bad || fputc('\n', f) == EOF;
}

int sph_diag_write_row(FILE *f, const sph_diag_row *r) {
  if (fprintf(f, "%.17g,%ld,%.17g,%zu,%.17g,%.17g,%.17g,%.17g", r->time, r->step, r->dt, r->n_fluid,
              r->front_x, r->mass, r->momentum_x, r->momentum_y) < 0)
    return 1;
  SPH_IF3(if (fprintf(f, ",%.17g", r->momentum_z) < 0) return 1;)
  if (fprintf(f, ",%.17g,%.17g", r->kinetic, r->potential) < 0) return 1;
  if (r->n_surface >= 0 && fprintf(f, ",%ld", r->n_surface) < 0) return 1;
  if (r->ledger && fprintf(f, ",%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", r->internal,
                           r->boundary_work, r->xsph_drift, r->total, r->deviation,
                           r->fluid_deviation, r->momentum_residual_x, r->momentum_residual_y) < 0)
    return 1;
  SPH_IF3(if (r->ledger && fprintf(f, ",%.17g", r->momentum_residual_z) < 0) return 1;)
  if (r->ledger && r->diffusion && fprintf(f, ",%.17g", r->diffusion_energy) < 0) return 1;
  if (r->ledger && r->repulsion && fprintf(f, ",%.17g", r->wall_potential) < 0) return 1;
  if (r->ledger && r->shifting && fprintf(f, ",%.17g", r->shifting_drift) < 0) return 1;
  if (r->outflow && fprintf(f, ",%zu,%.17g", r->n_removed, r->mass_removed) < 0) return 1;
  if (r->ledger && r->outflow && fprintf(f, ",%.17g", r->energy_removed) < 0) return 1;
  return fputc('\n', f) == EOF;
}
