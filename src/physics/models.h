/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * models.h - the named choices of the physical model that a case selects:
 * the smoothing kernel, the laminar viscosity model and the density
 * filter. Types only, so that the case schema (src/case/) can name them
 * without reaching into the physics' functions; the names are listed and
 * parsed by the case reader (sph_kernel_name, ...) and the filter
 * (sph_filter_name).
 */
#ifndef SPH_MODELS_H
#define SPH_MODELS_H

#include "core/error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The smoothing kernel (src/physics/kernel.h); both have support 2h. */
typedef enum {
  SPH_KERNEL_CUBIC_SPLINE = 0, /* paper A eq. (8), paper B §2.1 */
  SPH_KERNEL_WENDLAND_C2 = 1   /* Wendland (1995), C2, 2-D */
} sph_kernel_kind;

/* The laminar viscosity model (src/solver/forces.h). */
typedef enum {
  SPH_VISCOSITY_NONE = 0,
  SPH_VISCOSITY_STRESS_TENSOR = 1, /* paper A eq. (11), (13), (14) */
  SPH_VISCOSITY_MORRIS = 2         /* paper B eq. (4), laminar term */
} sph_viscosity_kind;

/* Density re-initialisation, paper B §2.8 (src/physics/filter.h). */
typedef enum sph_filter_kind {
  SPH_FILTER_NONE = 0,
  SPH_FILTER_MLS = 1,
  SPH_FILTER_SHEPARD = 2
} sph_filter_kind;

/* Density diffusion in the continuity equation (src/physics/
 * density_diffusion.h): none, or one of three published forms. */
typedef enum sph_diffusion_kind {
  SPH_DIFFUSION_NONE = 0,
  SPH_DIFFUSION_MOLTENI = 1,  /* Molteni & Colagrossi 2009 */
  SPH_DIFFUSION_ANTUONO = 2,  /* Antuono, Colagrossi, Marrone & Molteni 2010 (delta-SPH) */
  SPH_DIFFUSION_FOURTAKAS = 3 /* Fourtakas, Dominguez, Vacondio & Rogers 2019 */
} sph_diffusion_kind;

/* A phase's material (doc/method.md, Two phases): what the second phase's
 * rows read, one field a key of physics.air. src/case/air.c reads, lists and
 * writes them into `sph new`'s template from one table of keys; the solver
 * takes the table whole (solver/force_pass.h, phase_mat), so that a term
 * that reads a new field touches its field here, its key's row in air.c,
 * the term and its call. Phase 0, the liquid, is made of physics.rho0,
 * sound_speed and viscosity.mu, with Tait's law. */
typedef struct sph_material {
  double rho0;          /* reference density (kg/m^3) */
  int exponent;         /* equation of state: 1 the linear p = c0^2 (rho - rho0), 7 Tait's */
  double c0;            /* sound speed (m/s); physics.air's by default the liquid's */
  double mu;            /* dynamic viscosity (Pa s), read with Morris' viscosity */
  double density_limit; /* the blow-up band: the run stops where |rho/rho0 - 1| exceeds it
                         * (numerics.density_limit; physics.air's by default the same) */
  double sigma;         /* the surface tension between this phase and the liquid (N/m):
                         * physics.air's surface_tension; 0 none (the liquid's own: 0) */
} sph_material;

/* The names of the choices in enum order, NULL-terminated:
 * {"none", "mls", "shepard", NULL}. */
extern const char *const sph_filter_kind_names[];
/* "none", "mls", "shepard"; "?" for a value outside the enum. */
const char *sph_filter_name(sph_filter_kind k);
/* The kind named `name`; an unknown name is an error listing the valid ones. */
int sph_filter_from_name(const char *name, sph_filter_kind *k, sph_error *err);

/* {"none", "molteni_colagrossi", "antuono", "fourtakas", NULL} */
extern const char *const sph_diffusion_kind_names[];
/* The name of k; "?" for a value outside the enum. */
const char *sph_diffusion_name(sph_diffusion_kind k);

#ifdef __cplusplus
}
#endif

#endif
