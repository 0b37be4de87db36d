/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * diag.c - front tracking and conserved sums over the fluid (see diag.h).
 */
#include "config.h"

#include "solver/diag.h"

#include "core/exact_sum.h"
#include "core/parallel.h"
#include "io/csv.h"

#include <math.h>

double sph_diag_front(const sph_particles *p, double floor_y, double band) {
  double front = -INFINITY;          /* a maximum: exact in any order */
  const double *up = p->pos[SPH_UP]; /* the vertical: y (z in 3-D) */
  const long n = (long)p->n;
#pragma omp parallel for schedule(static) if (n > SPH_OMP_MIN) reduction(max : front)
  for (long i = 0; i < n; i++)
    if (sph_particles_liquid(p, (size_t)i) && up[i] < floor_y + band && p->x[i] > front)
      front = p->x[i];
  return front;
}

double sph_diag_surface_at(const sph_particles *p, double x, double half, double dx) {
  double top = -INFINITY;
  const double *up = p->pos[SPH_UP];
  for (size_t i = 0; i < p->n; i++)
    if (sph_particles_liquid(p, i) && fabs(p->x[i] - x) < half && up[i] > top) top = up[i];
  return top + 0.5 * dx;
}

#if SPH_DIM == 3
double sph_diag_surface_at_xy(const sph_particles *p, double x, double y, double half, double dx) {
  double top = -INFINITY;
  for (size_t i = 0; i < p->n; i++)
    if (sph_particles_liquid(p, i) && fabs(p->x[i] - x) < half && fabs(p->y[i] - y) < half &&
        p->z[i] > top)
      top = p->z[i];
  return top + 0.5 * dx;
}
#endif

/* The line's reading at `at`, its horizontal coordinates. */
static double line_level(const sph_particles *p, const double at[SPH_DIM - 1], double half,
                         double dx) {
#if SPH_DIM == 2
  return sph_diag_surface_at(p, at[0], half, dx);
#else
  return sph_diag_surface_at_xy(p, at[0], at[1], half, dx);
#endif
}

double sph_diag_gauge_level(const sph_particles *p, const double at[SPH_DIM - 1], double half,
                            double dx, int axis, const double range[2]) {
  double level = line_level(p, at, half, dx);
  if (axis < 0 || axis >= SPH_DIM - 1) return level; /* no horizontal period */
  const double period = range[1] - range[0];
  if (!(period > 0.0)) return level;
  double image[SPH_DIM - 1];
  for (int d = 0; d < SPH_DIM - 1; d++)
    image[d] = at[d];
  if (at[axis] - range[0] < half) { /* the seam at range[0]: the particles near range[1] */
    image[axis] = at[axis] + period;
    level = fmax(level, line_level(p, image, half, dx));
  }
  if (range[1] - at[axis] < half) { /* and the other way */
    image[axis] = at[axis] - period;
    level = fmax(level, line_level(p, image, half, dx));
  }
  return level;
}

/* The sums of a row over the fluid particles, each exact (exact_sum.h):
 * the same bits in any order and for any split of the particles. */
enum { D_MASS, D_MX, D_MY, D_KE, D_PE, D_MZ, D_SUMS };

void sph_diag_compute(const sph_particles *p, double floor_y, double band, const double g[SPH_DIM],
                      sph_diag_row *row) {
  size_t n = 0;
  sph_xsum sum[D_SUMS];
  for (int k = 0; k < D_SUMS; k++)
    sph_xsum_init(&sum[k]);
  for (size_t i = 0; i < p->n; i++) {
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    const double m = p->mass[i];
    n++;
    sph_xsum_add(&sum[D_MASS], m);
    sph_xsum_add(&sum[D_MX], m * p->vx[i]);
    sph_xsum_add(&sum[D_MY], m * p->vy[i]);
#if SPH_DIM == 2
    sph_xsum_add(&sum[D_KE], 0.5 * m * (p->vx[i] * p->vx[i] + p->vy[i] * p->vy[i]));
#else /* the floor along z, the vertical */
    sph_xsum_add(&sum[D_MZ], m * p->vz[i]);
    sph_xsum_add(&sum[D_KE],
                 0.5 * m * (p->vx[i] * p->vx[i] + p->vy[i] * p->vy[i] + p->vz[i] * p->vz[i]));
#endif
    sph_xsum_add(&sum[D_PE], -sph_diag_lift(p, i, g, floor_y));
  }
  SPH_IF3(row->momentum_z = sph_xsum_round(&sum[D_MZ]);)
  row->n_fluid = n;
  row->front_x = sph_diag_front(p, floor_y, band);
  row->mass = sph_xsum_round(&sum[D_MASS]);
  row->momentum_x = sph_xsum_round(&sum[D_MX]);
  row->momentum_y = sph_xsum_round(&sum[D_MY]);
  row->kinetic = sph_xsum_round(&sum[D_KE]);
  row->potential = sph_xsum_round(&sum[D_PE]);
  row->n_surface = -1;
  row->ledger = 0;
  row->diffusion = 0;
  row->shifting = 0;
  row->repulsion = 0;
  row->outflow = 0;
  row->n_removed = 0;
  row->mass_removed = row->energy_removed = 0.0;
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
